#include "vtkSurfacePointLocator.h"

#include <vtkGenericCell.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <array>
#include <cmath>

//------------------------------------------------------------------------------
vtkSurfacePointLocator::vtkSurfacePointLocator(const vtkSurfaceMeshConverter::Result& mesh)
  : Mesh(mesh)
  , Locator(vtkSmartPointer<vtkStaticCellLocator>::New())
  , Cell(vtkSmartPointer<vtkGenericCell>::New())
{
  this->Locator->SetDataSet(mesh.Triangles);
  this->Locator->BuildLocator();
}

//------------------------------------------------------------------------------
vtkSurfacePointLocator::~vtkSurfacePointLocator() = default;

//------------------------------------------------------------------------------
bool vtkSurfacePointLocator::Snap(const double x[3], gs::SurfacePoint& point, std::string& error)
{
  if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
  {
    error = "non-finite coordinates";
    return false;
  }
  const gs::TriangleMesh& mesh = this->Mesh.Build.Mesh;
  const std::vector<int>& pointToVertex = this->Mesh.Build.PointToVertex;
  double closest[3], pcoords[3], weights[3], dist2 = 0.0;
  vtkIdType cellId = -1;
  int subId = 0;
  this->Locator->FindClosestPoint(x, closest, this->Cell, cellId, subId, dist2);
  if (cellId < 0 || cellId >= mesh.NumberOfFaces())
  {
    error = "could not be snapped to the surface";
    return false;
  }
  // Barycentric coordinates in the triangle's point order, then matched to the core face's
  // corners by vertex (the mesh builder may have re-oriented the face). The locator used
  // Cell as scratch space: fetch the closest triangle itself.
  this->Mesh.Triangles->GetCell(cellId, this->Cell);
  double snapped[3];
  this->Cell->EvaluatePosition(closest, snapped, subId, pcoords, dist2, weights);
  const std::array<int, 3>& face = mesh.Face(static_cast<int>(cellId));
  std::array<double, 3> bary{ { 0.0, 0.0, 0.0 } };
  int matched = 0;
  for (int k = 0; k < 3; ++k)
  {
    const int v = pointToVertex[static_cast<size_t>(this->Cell->GetPointId(k))];
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
    error = "internal error: triangle " + std::to_string(cellId) + " does not match its core face";
    return false;
  }
  point = gs::SurfacePoint::InFace(
    static_cast<int>(cellId), bary[0] / sum, bary[1] / sum, bary[2] / sum);
  return true;
}
