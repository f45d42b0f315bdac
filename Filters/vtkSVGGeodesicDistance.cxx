#include "vtkSVGGeodesicDistance.h"

#include "vtkSurfaceMeshConverter.h"

#include "ExactGeodesic.h"
#include "SurfacePoint.h"

#include <vtkCell.h>
#include <vtkDoubleArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <array>
#include <cmath>
#include <limits>
#include <sstream>

vtkStandardNewMacro(vtkSVGGeodesicDistance);

// The converted mesh and its solver, kept while the input mesh is unchanged (same object, same
// modification time), so that changing only the sources or parameters does not rebuild them.
struct vtkSVGGeodesicDistance::Cache
{
  vtkPolyData* Input = nullptr;
  vtkMTimeType InputTime = 0;
  vtkSurfaceMeshConverter::Result Mesh;
  std::unique_ptr<gs::ExactGeodesicSolver> Exact; // refers to Mesh.Build.Mesh
  vtkSmartPointer<vtkStaticCellLocator> Locator;  // over Mesh.Triangles, built on demand
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
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPointSet* sources =
    inputVector[1]->GetNumberOfInformationObjects() > 0 ? vtkPointSet::GetData(inputVector[1], 0)
                                                        : nullptr;
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!input || !output)
  {
    vtkErrorMacro("Missing input or output mesh.");
    return 0;
  }
  output->Initialize(); // empty unless everything succeeds
  this->UpdateProgress(0.0);

  if (this->Solver != EXACT)
  {
    vtkErrorMacro("Unknown Solver " << this->Solver << " (0 = Exact).");
    return 1;
  }
  if (this->ResultArrayName.empty())
  {
    vtkErrorMacro("ResultArrayName is empty.");
    return 1;
  }

  // 1. The core mesh, converted once while the input is unchanged.
  if (!this->MeshCache || this->MeshCache->Input != input ||
    this->MeshCache->InputTime != input->GetMTime())
  {
    this->MeshCache.reset(new Cache);
    this->MeshCache->Input = input;
    this->MeshCache->InputTime = input->GetMTime();
    this->MeshCache->Mesh = vtkSurfaceMeshConverter::Convert(input);
    if (this->MeshCache->Mesh.Ok)
    {
      this->MeshCache->Exact.reset(new gs::ExactGeodesicSolver(this->MeshCache->Mesh.Build.Mesh));
    }
  }
  Cache& cache = *this->MeshCache;
  for (const std::string& warning : cache.Mesh.Warnings)
  {
    vtkWarningMacro("Input mesh: " << warning);
  }
  if (!cache.Mesh.Ok)
  {
    vtkErrorMacro("Invalid input mesh: " << cache.Mesh.Error);
    return 1;
  }
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  const std::vector<int>& pointToVertex = cache.Mesh.Build.PointToVertex;
  this->UpdateProgress(0.2);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 2. Sources: snapped points of port 1, or the listed point ids.
  std::vector<gs::SurfacePoint> surfaceSources;
  if (sources)
  {
    if (!cache.Locator)
    {
      cache.Locator = vtkSmartPointer<vtkStaticCellLocator>::New();
      cache.Locator->SetDataSet(cache.Mesh.Triangles);
      cache.Locator->BuildLocator();
    }
    for (vtkIdType i = 0; i < sources->GetNumberOfPoints(); ++i)
    {
      double x[3], closest[3], pcoords[3], weights[3], dist2;
      vtkIdType cellId = -1;
      int subId = 0;
      sources->GetPoint(i, x);
      if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      {
        vtkErrorMacro("Source point " << i << " has non-finite coordinates.");
        return 1;
      }
      cache.Locator->FindClosestPoint(x, closest, cellId, subId, dist2);
      if (cellId < 0 || cellId >= mesh.NumberOfFaces())
      {
        vtkErrorMacro("Source point " << i << " could not be snapped to the surface.");
        return 1;
      }
      // Barycentric coordinates in the triangle's point order; then matched to the core face's
      // corners by vertex (the builder may have re-oriented the face).
      vtkCell* triangle = cache.Mesh.Triangles->GetCell(cellId);
      double snapped[3];
      triangle->EvaluatePosition(closest, snapped, subId, pcoords, dist2, weights);
      const std::array<int, 3>& face = mesh.Face(static_cast<int>(cellId));
      std::array<double, 3> bary{ { 0.0, 0.0, 0.0 } };
      int matched = 0;
      for (int k = 0; k < 3; ++k)
      {
        const int v = pointToVertex[static_cast<size_t>(triangle->GetPointId(k))];
        for (int c = 0; c < 3; ++c)
        {
          if (face[c] == v)
          {
            bary[c] = std::max(0.0, weights[k]);
            ++matched;
          }
        }
      }
      const double sum = bary[0] + bary[1] + bary[2];
      if (matched != 3 || !(sum > 0.0))
      {
        vtkErrorMacro("Internal error: triangle " << cellId << " does not match core face.");
        return 1;
      }
      surfaceSources.push_back(
        gs::SurfacePoint::InFace(static_cast<int>(cellId), bary[0] / sum, bary[1] / sum,
          bary[2] / sum));
    }
  }
  else
  {
    const vtkIdType numberOfPoints = static_cast<vtkIdType>(pointToVertex.size());
    for (vtkIdType id : this->SourceVertexIds)
    {
      if (id < 0 || id >= numberOfPoints)
      {
        vtkErrorMacro("Source vertex id " << id << " is out of range [0, " << numberOfPoints
                                          << ").");
        return 1;
      }
      const int v = pointToVertex[static_cast<size_t>(id)];
      if (v < 0)
      {
        vtkErrorMacro("Source vertex id " << id << " is not used by any triangle.");
        return 1;
      }
      surfaceSources.push_back(gs::SurfacePoint::AtVertex(v));
    }
  }
  if (surfaceSources.empty())
  {
    vtkErrorMacro("No source: set SourceVertexIds or connect source points to the Sources "
                  "port (with at least one point).");
    return 1;
  }

  // 3. Solve.
  gs::ExactGeodesicOptions options;
  options.MaximumDistance = this->MaximumDistance;
  if (!cache.Exact->Solve(surfaceSources, options))
  {
    vtkErrorMacro("The geodesic solver rejected the sources.");
    return 1;
  }
  this->UpdateProgress(0.9);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 4. Map back to every input point (welded points share their vertex's distance).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vtkNew<vtkDoubleArray> distance;
  distance->SetName(this->ResultArrayName.c_str());
  distance->SetNumberOfComponents(1);
  distance->SetNumberOfTuples(static_cast<vtkIdType>(pointToVertex.size()));
  for (size_t i = 0; i < pointToVertex.size(); ++i)
  {
    const int v = pointToVertex[i];
    double d = v >= 0 ? cache.Exact->Distance(v) : nan;
    if (!std::isfinite(d) ||
      (this->MaximumDistance > 0.0 && d > this->MaximumDistance))
    {
      d = nan;
    }
    distance->SetValue(static_cast<vtkIdType>(i), d);
  }

  output->ShallowCopy(cache.Mesh.Surface);
  output->GetPointData()->AddArray(distance);
  output->GetPointData()->SetActiveScalars(distance->GetName());
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkSVGGeodesicDistance::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Solver: " << this->Solver << (this->Solver == EXACT ? " (Exact)" : "") << "\n";
  os << indent << "SourceVertexIds (" << this->SourceVertexIds.size() << "):";
  for (vtkIdType id : this->SourceVertexIds)
  {
    os << " " << id;
  }
  os << "\n";
  os << indent << "MaximumDistance: " << this->MaximumDistance
     << (this->MaximumDistance > 0.0 ? "" : " (unlimited)") << "\n";
  os << indent << "ResultArrayName: " << this->ResultArrayName << "\n";
}
