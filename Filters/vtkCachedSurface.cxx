#include "vtkCachedSurface.h"

#include "vtkSurfacePointLocator.h"

#include "SaddleVertexGraph.h"

#include <vtkAlgorithm.h>

//------------------------------------------------------------------------------
vtkCachedSurface::vtkCachedSurface() = default;

//------------------------------------------------------------------------------
vtkCachedSurface::~vtkCachedSurface() = default;

//------------------------------------------------------------------------------
vtkSurfacePointLocator& vtkCachedSurface::Locator()
{
  if (!this->PointLocator)
  {
    this->PointLocator.reset(new vtkSurfacePointLocator(this->Mesh));
  }
  return *this->PointLocator;
}

//------------------------------------------------------------------------------
gs::Result<std::vector<gs::SurfacePoint>> vtkCachedSurface::SnapCurve(
  vtkPoints* points, vtkIdType n, const vtkIdType* ids)
{
  return this->Locator().SnapCurve(points, n, ids);
}

//------------------------------------------------------------------------------
gs::Result<int> vtkCachedSurface::VertexOfPoint(vtkIdType pointId) const
{
  const std::vector<int>& pointToVertex = this->Mesh.Build.PointToVertex;
  const vtkIdType numberOfPoints = static_cast<vtkIdType>(pointToVertex.size());
  if (pointId < 0 || pointId >= numberOfPoints)
  {
    return gs::Status::Error(std::to_string(pointId) + " is out of range [0, " +
      std::to_string(numberOfPoints) + ")");
  }
  int v = pointToVertex[static_cast<size_t>(pointId)];
  if (v < 0)
  {
    return gs::Status::Error(std::to_string(pointId) + " is not used by any triangle");
  }
  return v;
}

//------------------------------------------------------------------------------
std::uint64_t vtkCachedSurface::MeshHash()
{
  if (!this->HashValid)
  {
    this->Hash = gs::SaddleVertexGraph::HashMesh(this->Mesh.Build.Mesh);
    this->HashValid = true;
  }
  return this->Hash;
}

//------------------------------------------------------------------------------
bool vtkCachedSurface::UseSaddleVertexGraph(vtkAlgorithm* algorithm,
  const gs::SaddleVertexGraphOptions& options, const std::string& fileName, double progressStart, double progressSpan, bool& changed,
  vtkSaddleVertexGraphCache::Origin* origin)
{
  changed = false;
  const vtkSaddleVertexGraphCache::Result found = vtkSaddleVertexGraphCache::GetFor(algorithm,
    this->Mesh.Build.Mesh, this->MeshHash(), options, fileName, progressStart, progressSpan);
  if (!found.Graph)
  {
    return false; // aborted, or the error is reported
  }
  if (origin)
  {
    *origin = found.From;
  }
  changed = found.Graph != this->GraphInUse;
  this->GraphInUse = found.Graph;
  return true;
}

//------------------------------------------------------------------------------
bool vtkCachedSurface::CheckEngine(vtkAlgorithm* algorithm, int solver,
  const std::vector<gs::GeodesicSolver>& allowed, int k)
{
  bool known = false;
  std::string names;
  for (gs::GeodesicSolver a : allowed)
  {
    known = known || static_cast<int>(a) == solver;
    names += (names.empty() ? "" : ", ") + std::to_string(static_cast<int>(a)) + " = " +
      gs::GeodesicSolverName(a);
  }
  if (!known)
  {
    vtkErrorWithObjectMacro(algorithm, "Unknown Solver " << solver << " (" << names << ").");
    return false;
  }
  if (gs::GeodesicSolverUsesGraph(static_cast<gs::GeodesicSolver>(solver)) && k < 1)
  {
    vtkErrorWithObjectMacro(algorithm, "K must be at least 1 for the "
        << gs::GeodesicSolverName(static_cast<gs::GeodesicSolver>(solver)) << " solver; it is " << k
        << ".");
    return false;
  }
  return true;
}

gs::SaddleVertexGraphOptions vtkCachedSurface::GraphOptions(
  int solver, int k, double graphAccuracy, bool reachedStencil)
{
  gs::SaddleVertexGraphOptions options;
  options.K = k;
  if (solver == static_cast<int>(gs::GeodesicSolver::DGG))
  {
    options.Construction = gs::GraphConstruction::DiscreteGeodesic;
    options.Accuracy = graphAccuracy;
    options.ReachedStencil = reachedStencil;
  }
  return options;
}

bool vtkCachedSurface::UseEngineGraph(vtkAlgorithm* algorithm, int solver, int k,
  double graphAccuracy, const std::string& fileName, double progressStart, double progressSpan,
  bool& changed, vtkSaddleVertexGraphCache::Origin* origin)
{
  if (!gs::GeodesicSolverUsesGraph(static_cast<gs::GeodesicSolver>(solver)))
  {
    changed = this->UseNoSaddleVertexGraph();
    return true;
  }
  return this->UseSaddleVertexGraph(algorithm, GraphOptions(solver, k, graphAccuracy), fileName,
    progressStart, progressSpan, changed, origin);
}

//------------------------------------------------------------------------------
bool vtkCachedSurface::UseNoSaddleVertexGraph()
{
  const bool changed = this->GraphInUse != nullptr;
  this->GraphInUse.reset();
  return changed;
}
