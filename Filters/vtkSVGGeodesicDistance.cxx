#include "vtkSVGGeodesicDistance.h"

#include "vtkCachedSurface.h"
#include "vtkDistributedSurface.h"
#include "vtkSaddleVertexGraphCache.h"
#include "vtkSurfacePieces.h"
#include "vtkSurfacePointLocator.h"

#include "GeodesicEngine.h"
#include "SaddleVertexGraph.h"
#include "SurfacePoint.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>

vtkStandardNewMacro(vtkSVGGeodesicDistance);

// The converted mesh and what is derived from it (vtkCachedSurface), kept while the input mesh
// is unchanged, so that changing only the sources or parameters does not redo them, and the
// engines over it.
struct vtkSVGGeodesicDistance::Cache : vtkCachedSurface
{
  // Per Solver, made on demand over Mesh.Build.Mesh (and Graph(): one graph engine at a time).
  std::unique_ptr<gs::GeodesicEngine> Engines[gs::NumberOfGeodesicSolvers];
};

// One Execute's sources, step to step.
struct vtkSVGGeodesicDistance::Run
{
  std::vector<gs::SurfacePoint> PointSources;
  std::vector<std::vector<gs::SurfacePoint>> CurveSources;
  vtkSaddleVertexGraphCache::Origin GraphOrigin = vtkSaddleVertexGraphCache::Origin::Memory;
};

//------------------------------------------------------------------------------
vtkSVGGeodesicDistance::vtkSVGGeodesicDistance()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkSVGGeodesicDistance::~vtkSVGGeodesicDistance() = default;

//------------------------------------------------------------------------------
const char* vtkSVGGeodesicDistance::GetSolverName(int solver)
{
  if (solver < 0 || solver >= gs::NumberOfGeodesicSolvers)
  {
    return "unknown";
  }
  return gs::GeodesicSolverName(static_cast<gs::GeodesicSolver>(solver));
}

//------------------------------------------------------------------------------
bool vtkSVGGeodesicDistance::UsesGraph() const
{
  return gs::GeodesicSolverUsesGraph(static_cast<gs::GeodesicSolver>(this->Solver));
}

//------------------------------------------------------------------------------
void vtkSVGGeodesicDistance::AddSourceVertexId(vtkIdType id)
{
  this->SourceVertexIds.push_back(id);
  this->Modified();
}

//------------------------------------------------------------------------------
void vtkSVGGeodesicDistance::RemoveAllSourceVertexIds()
{
  if (!this->SourceVertexIds.empty())
  {
    this->SourceVertexIds.clear();
    this->Modified();
  }
}

//------------------------------------------------------------------------------
int vtkSVGGeodesicDistance::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkSVGGeodesicDistance::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Under MPI, the distances from vertex ids are computed on the pieces when they hold triangles
  // only (the same decision on every process: it depends on properties and on CanUse, which is
  // collective); everything else gathers the surface.
  const vtkDistributedSurface distributed(outputVector->GetInformationObject(0));
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  // Source points and curves too.
  const gs::GeodesicSolver solver = static_cast<gs::GeodesicSolver>(this->Solver);
  const bool noGraph =
    solver == gs::GeodesicSolver::Exact || solver == gs::GeodesicSolver::VirtualSources;
  const bool sourcesPort = inputVector[1]->GetNumberOfInformationObjects() > 0;
  if (distributed && input && output && (this->UsesGraph() || noGraph) &&
    this->CacheFileName.empty())
  {
    std::vector<double> xyz;
    vtkSmartPointer<vtkPolyData> curves;
    if (sourcesPort)
    {
      // Points and curves (line cells): the Sources whole on every process.
      vtkSmartPointer<vtkPolyData> all =
        distributed.GatherAuxiliaryEverywhere(vtkPointSet::GetData(inputVector[1], 0));
      if (all)
      {
        vtkDistributedSurface::SplitPointsAndCurves(all, xyz, curves);
      }
    }
    vtkSmartPointer<vtkPolyData> own =
      vtkSurfacePieces::OwnCellsInPlace(this, distributed, this->Pieces, input);
    if (own)
    {
      return this->ExecutePieces(input, own, output, sourcesPort ? &xyz : nullptr, curves);
    }
  }
  return vtkDistributedSurface::RequestData(this, inputVector, outputVector,
    [this](vtkPolyData* whole, const std::vector<vtkPointSet*>& auxiliaries, vtkPolyData* result) {
      return this->Execute(whole, auxiliaries[0], result);
    });
}

//------------------------------------------------------------------------------
int vtkSVGGeodesicDistance::ExecutePieces(vtkPolyData* input, vtkPolyData* own,
  vtkPolyData* output, const std::vector<double>* sourceXyz, vtkPolyData* curves)
{
  output->Initialize(); // empty unless everything succeeds
  this->UpdateProgress(0.0);
  // (Property checks: the same outcome on every process.)
  if (!vtkCachedSurface::CheckEngine(this, this->Solver,
        { gs::GeodesicSolver::Exact, gs::GeodesicSolver::SVGLabelCorrecting,
          gs::GeodesicSolver::SVGDijkstra, gs::GeodesicSolver::DGG,
          gs::GeodesicSolver::VirtualSources },
        this->K))
  {
    return 1;
  }
  const gs::GeodesicSolver solver = static_cast<gs::GeodesicSolver>(this->Solver);
  const bool noGraph =
    solver == gs::GeodesicSolver::Exact || solver == gs::GeodesicSolver::VirtualSources;
  // Source points (the Sources port) replace the vertex ids, as serially.
  std::vector<gs::Vec3> sourcePoints;
  for (std::size_t i = 0; sourceXyz && i + 2 < sourceXyz->size(); i += 3)
  {
    sourcePoints.emplace_back((*sourceXyz)[i], (*sourceXyz)[i + 1], (*sourceXyz)[i + 2]);
  }
  const std::vector<vtkIdType> sourceIds =
    sourceXyz ? std::vector<vtkIdType>() : this->SourceVertexIds;
  const bool noSource = sourceXyz ? sourcePoints.empty() && !curves : sourceIds.empty();
  if (this->ResultArrayName.empty() || !(this->MaximumDistance >= 0.0) || noSource)
  {
    vtkErrorMacro(<< (this->ResultArrayName.empty() ? "ResultArrayName is empty."
                        : noSource
                        ? "No source: set SourceVertexIds or connect source points or lines to "
                          "the Sources port (with at least one point)."
                        : "MaximumDistance must be at least 0 (0 or infinity: unlimited)."));
    return 1;
  }
  bool built = false;
  std::vector<double> distances;
  if (noGraph)
  {
    if (!this->Pieces->DistancesWithoutGraph(this, solver, own, input->GetMTime(), sourceIds,
          sourcePoints, curves, this->MaximumDistance, distances))
    {
      return 1;
    }
  }
  else if (!this->Pieces->UseGraph(this, own, input->GetMTime(),
             vtkCachedSurface::GraphOptions(
               this->Solver, this->K, this->GraphAccuracy, this->ReachedStencil),
             0.1, 0.8, built) ||
    !this->Pieces->Distances(this, own, sourceIds, sourcePoints, curves, this->MaximumDistance,
      this->UnfoldingRefinement, distances))
  {
    return 1;
  }
  vtkNew<vtkDoubleArray> distance;
  distance->SetName(this->ResultArrayName.c_str());
  distance->SetNumberOfTuples(static_cast<vtkIdType>(distances.size()));
  for (size_t i = 0; i < distances.size(); ++i)
  {
    distance->SetValue(static_cast<vtkIdType>(i), distances[i]);
  }
  output->ShallowCopy(own);
  output->GetPointData()->AddArray(distance);
  output->GetPointData()->SetActiveScalars(distance->GetName());

  // The graph as the serial field data describes it, and this process's share of the work.
  const gs::PieceGraph& graph = this->Pieces->Graph();
  const gs::SurfacePiece& piece = this->Pieces->Piece();
  vtkNew<vtkFieldData> fieldData;
  fieldData->ShallowCopy(own->GetFieldData());
  auto addDouble = [&fieldData](const char* name, double value) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fieldData->AddArray(a);
  };
  auto addInt = [&fieldData](const char* name, int value) {
    vtkNew<vtkIntArray> a;
    a->SetName(name);
    a->InsertNextValue(value);
    fieldData->AddArray(a);
  };
  if (!noGraph)
  {
    addDouble("SVGMeanDegree",
      piece.GlobalNumberOfVertices() > 0
        ? static_cast<double>(graph.GlobalNumberOfEntries()) /
          static_cast<double>(piece.GlobalNumberOfVertices())
        : 0.0);
    addDouble("SVGBuildSeconds", graph.BuildSeconds());
    vtkNew<vtkStringArray> origin;
    origin->SetName("SVGGraphOrigin");
    origin->InsertNextValue(built ? "built" : "memory");
    fieldData->AddArray(origin);
    addInt("PieceRefinementRounds", this->Pieces->RefinementRounds());
  }
  else if (solver == gs::GeodesicSolver::Exact)
  {
    addDouble("PieceWindowsPropagated", static_cast<double>(this->Pieces->WindowsPropagated()));
    addDouble("PieceWindowsSent", static_cast<double>(this->Pieces->WindowsSent()));
  }
  else
  {
    addDouble("PieceCrossings", static_cast<double>(this->Pieces->WindowsPropagated()));
    addDouble("PieceSourcesSent", static_cast<double>(this->Pieces->WindowsSent()));
  }
  addInt("PieceFaces", piece.Mesh().NumberOfFaces());
  addInt("PieceOwnedVertices", static_cast<int>(piece.NumberOfOwnedVertices()));
  addInt("PieceBandRings", piece.Rings());
  addInt("PieceSolveRounds", this->Pieces->SolveRounds());
  output->SetFieldData(fieldData);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkSVGGeodesicDistance::Execute(vtkPolyData* input, vtkPointSet* sources, vtkPolyData* output)
{
  output->Initialize(); // empty unless everything succeeds
  this->UpdateProgress(0.0);

  if (!vtkCachedSurface::CheckEngine(this, this->Solver,
        { gs::GeodesicSolver::Exact, gs::GeodesicSolver::SVGLabelCorrecting,
          gs::GeodesicSolver::SVGDijkstra, gs::GeodesicSolver::DGG, gs::GeodesicSolver::VirtualSources },
        this->K))
  {
    return 1;
  }
  if (this->ResultArrayName.empty())
  {
    vtkErrorMacro("ResultArrayName is empty.");
    return 1;
  }
  if (!(this->MaximumDistance >= 0.0))
  {
    vtkErrorMacro("MaximumDistance must be at least 0 (0 or infinity: unlimited); it is "
      << this->MaximumDistance << ".");
    return 1;
  }
  Run run;

  // 1. The core mesh, converted once while the input is unchanged.
  Cache& cache = vtkSurfaceMeshConverter::Update(this->MeshCache, input);
  if (!vtkSurfaceMeshConverter::Report(cache.Mesh, this))
  {
    return 1;
  }
  this->UpdateProgress(0.1);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 2. Sources: curves (line cells of port 1) and points (its other points), or the listed
  //    point ids.
  if (!this->FindSources(cache, sources, run))
  {
    return 1;
  }

  // 3. The saddle vertex graph (SVG solvers): from this process's cache, the cache file, or
  //    built now with progress 0.1 .. 0.8.
  if (this->UsesGraph() && !this->UseGraph(cache, run))
  {
    return 1;
  }
  this->UpdateProgress(0.8);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 4. Solve.
  if (!this->Solve(cache, run))
  {
    return 1;
  }
  this->UpdateProgress(0.9);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 5. Map back to every input point (welded points share their vertex's distance).
  this->WriteOutput(cache, run, output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkSVGGeodesicDistance::FindSources(Cache& cache, vtkPointSet* sources, Run& run)
{
  std::vector<gs::SurfacePoint>& pointSources = run.PointSources;
  std::vector<std::vector<gs::SurfacePoint>>& curveSources = run.CurveSources;
  if (sources)
  {
    auto snap = [&](const double x[3], gs::SurfacePoint& p, vtkIdType pointId) {
      const gs::Result<gs::SurfacePoint> snapped = cache.Locator().Snap(x);
      if (!snapped.Ok())
      {
        vtkErrorMacro("Source point " << pointId << ": " << snapped.Message() << ".");
        return false;
      }
      p = *snapped;
      return true;
    };
    std::vector<unsigned char> onCurve(static_cast<size_t>(sources->GetNumberOfPoints()), 0);
    vtkPolyData* polySources = vtkPolyData::SafeDownCast(sources);
    if (polySources && polySources->GetNumberOfLines() > 0)
    {
      auto it = vtk::TakeSmartPointer(polySources->GetLines()->NewIterator());
      vtkIdType npts;
      const vtkIdType* pts;
      for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
      {
        it->GetCurrentCell(npts, pts);
        gs::Result<std::vector<gs::SurfacePoint>> curve =
          cache.SnapCurve(sources->GetPoints(), npts, pts);
        if (!curve.Ok())
        {
          vtkErrorMacro("Source curve: " << curve.Message() << ".");
          return false;
        }
        for (vtkIdType i = 0; i < npts; ++i)
        {
          onCurve[static_cast<size_t>(pts[i])] = 1;
        }
        if (!curve->empty())
        {
          curveSources.push_back(std::move(*curve));
        }
      }
    }
    for (vtkIdType i = 0; i < sources->GetNumberOfPoints(); ++i)
    {
      if (onCurve[static_cast<size_t>(i)])
      {
        continue;
      }
      double x[3];
      sources->GetPoint(i, x);
      gs::SurfacePoint p;
      if (!snap(x, p, i))
      {
        return false;
      }
      pointSources.push_back(p);
    }
  }
  else
  {
    for (vtkIdType id : this->SourceVertexIds)
    {
      const gs::Result<int> v = cache.VertexOfPoint(id);
      if (!v.Ok())
      {
        vtkErrorMacro("Source vertex id " << v.Message() << ".");
        return false;
      }
      pointSources.push_back(gs::SurfacePoint::AtVertex(*v));
    }
  }
  if (pointSources.empty() && curveSources.empty())
  {
    vtkErrorMacro("No source: set SourceVertexIds or connect source points or lines to the "
                  "Sources port (with at least one point).");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkSVGGeodesicDistance::UseGraph(Cache& cache, Run& run)
{
  bool graphChanged = false;
  const gs::SaddleVertexGraphOptions options =
    vtkCachedSurface::GraphOptions(this->Solver, this->K, this->GraphAccuracy, this->ReachedStencil);
  if (!cache.UseSaddleVertexGraph(this, options, this->CacheFileName, 0.1, 0.7, graphChanged, &run.GraphOrigin))
  {
    return false; // aborted, or the error is reported
  }
  std::unique_ptr<gs::GeodesicEngine>& engine = cache.Engines[this->Solver];
  if (graphChanged || !engine)
  {
    for (auto& other : cache.Engines)
    {
      if (other && gs::GeodesicSolverUsesGraph(other->Solver()))
      {
        other.reset(); // (over the previous graph, or a second copy of the per-node data)
      }
    }
    gs::Result<std::unique_ptr<gs::GeodesicEngine>> made = gs::MakeGeodesicEngine(
      static_cast<gs::GeodesicSolver>(this->Solver), cache.Mesh.Build.Mesh, cache.Graph());
    if (!made.Ok())
    {
      vtkErrorMacro("The geodesic solver cannot use the graph: " << made.Message() << ".");
      return false;
    }
    engine = std::move(*made);
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkSVGGeodesicDistance::Solve(Cache& cache, Run& run)
{
  std::unique_ptr<gs::GeodesicEngine>& engine = cache.Engines[this->Solver];
  if (!engine) // (graph engines are made with their graph, UseGraph)
  {
    gs::Result<std::unique_ptr<gs::GeodesicEngine>> made =
      gs::MakeGeodesicEngine(static_cast<gs::GeodesicSolver>(this->Solver), cache.Mesh.Build.Mesh);
    if (!made.Ok())
    {
      vtkErrorMacro("The geodesic solver cannot be made: " << made.Message() << ".");
      return false;
    }
    engine = std::move(*made);
  }
  gs::GeodesicSources sources;
  sources.Points = std::move(run.PointSources);
  sources.Curves = std::move(run.CurveSources);
  gs::GeodesicSolveOptions options;
  options.MaximumDistance = this->MaximumDistance;
  options.UnfoldingRefinement = this->UnfoldingRefinement;
  options.NumberOfThreads = 0; // (graph refinement of large solves on every core: the same bits)
  options.Progress = [this](double fraction) {
    this->UpdateProgress(0.1 + 0.8 * fraction);
    return !this->CheckAbort();
  };
  const gs::Status solved = engine->Solve(sources, options);
  if (solved.IsAborted())
  {
    return false;
  }
  if (!solved.Ok())
  {
    vtkErrorMacro("The geodesic solver rejected the sources: " << solved.Message());
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkSVGGeodesicDistance::WriteOutput(const Cache& cache, const Run& run, vtkPolyData* output)
{
  const std::vector<int>& pointToVertex = cache.Mesh.Build.PointToVertex;
  const bool useGraph = this->UsesGraph();
  const gs::GeodesicEngine& engine = *cache.Engines[this->Solver];
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vtkNew<vtkDoubleArray> distance;
  distance->SetName(this->ResultArrayName.c_str());
  distance->SetNumberOfComponents(1);
  distance->SetNumberOfTuples(static_cast<vtkIdType>(pointToVertex.size()));
  for (size_t i = 0; i < pointToVertex.size(); ++i)
  {
    const int v = pointToVertex[i];
    double d = nan;
    if (v >= 0)
    {
      d = engine.Distance(v);
    }
    if (!std::isfinite(d) || (this->MaximumDistance > 0.0 && d > this->MaximumDistance))
    {
      d = nan;
    }
    distance->SetValue(static_cast<vtkIdType>(i), d);
  }

  output->ShallowCopy(cache.Mesh.Surface);
  output->GetPointData()->AddArray(distance);
  output->GetPointData()->SetActiveScalars(distance->GetName());
  if (useGraph)
  {
    // A fresh field data object: the surface's own (shallow-copied) one is left untouched.
    vtkNew<vtkFieldData> fieldData;
    if (vtkFieldData* inputFieldData = output->GetFieldData())
    {
      fieldData->ShallowCopy(inputFieldData);
    }
    vtkNew<vtkDoubleArray> meanDegree;
    meanDegree->SetName("SVGMeanDegree");
    meanDegree->InsertNextValue(cache.Graph()->MeanDegree());
    vtkNew<vtkDoubleArray> buildSeconds;
    buildSeconds->SetName("SVGBuildSeconds");
    buildSeconds->InsertNextValue(cache.Graph()->BuildSeconds());
    vtkNew<vtkStringArray> origin;
    origin->SetName("SVGGraphOrigin");
    origin->InsertNextValue(vtkSaddleVertexGraphCache::OriginName(run.GraphOrigin));
    fieldData->AddArray(meanDegree);
    fieldData->AddArray(buildSeconds);
    fieldData->AddArray(origin);
    output->SetFieldData(fieldData);
  }
}

//------------------------------------------------------------------------------
void vtkSVGGeodesicDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Solver: " << this->Solver << " (" << GetSolverName(this->Solver) << ")\n";
  os << indent << "SourceVertexIds (" << this->SourceVertexIds.size() << "):";
  for (vtkIdType id : this->SourceVertexIds)
  {
    os << " " << id;
  }
  os << "\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance
     << (this->MaximumDistance > 0.0 ? "" : " (unlimited)") << "\n";
  os << indent << "ResultArrayName: " << this->ResultArrayName << "\n";
  os << indent << "K: " << this->K << "\n";
  os << indent << "GraphAccuracy: " << this->GraphAccuracy << "\n";
  os << indent << "ReachedStencil: " << this->ReachedStencil << "\n";
  os << indent << "CacheFileName: "
     << (this->CacheFileName.empty() ? "(none)" : this->CacheFileName) << "\n";
  os << indent << "UnfoldingRefinement: " << (this->UnfoldingRefinement ? "on" : "off") << "\n";
}
