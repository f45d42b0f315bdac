#include "vtkCachedSurface.h"

#include "vtkSurfacePointLocator.h"

#include "SaddleVertexGraph.h"

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
gs::SaddleVertexGraphOptions vtkCachedSurface::GraphOptions(int k, double accuracy)
{
  gs::SaddleVertexGraphOptions options;
  options.K = k;
  if (accuracy != 0.0)
  {
    options.Construction = gs::GraphConstruction::DiscreteGeodesic;
    options.Accuracy = accuracy;
  }
  return options;
}

//------------------------------------------------------------------------------
bool vtkCachedSurface::UseNoSaddleVertexGraph()
{
  const bool changed = this->GraphInUse != nullptr;
  this->GraphInUse.reset();
  return changed;
}
