#include "vtkSurfacePointLocator.h"

#include <vtkGenericCell.h>
#include <vtkMath.h>
#include <vtkPoints.h>
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
  this->MaximumDistance = MaximumDistanceFraction * mesh.Triangles->GetLength();
}

//------------------------------------------------------------------------------
vtkSurfacePointLocator::~vtkSurfacePointLocator() = default;

//------------------------------------------------------------------------------
bool vtkSurfacePointLocator::Snap(
  const double x[3], gs::SurfacePoint& point, std::string& error, bool anyDistance)
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
  if (!anyDistance && std::sqrt(dist2) > this->MaximumDistance)
  {
    error = "it lies " + std::to_string(std::sqrt(dist2)) +
      " from the surface, more than a quarter of the mesh's bounding box diagonal (" +
      std::to_string(this->MaximumDistance) + "): check its coordinates";
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

//------------------------------------------------------------------------------
bool vtkSurfacePointLocator::SnapCurve(vtkPoints* points, vtkIdType n, const vtkIdType* ids,
  std::vector<gs::SurfacePoint>& curve, std::string& error)
{
  const double spacing = CurveSampleSpacing * this->Mesh.Build.Mesh.MeanEdgeLength();
  // At most this many samples per segment (a segment far longer than the mesh).
  constexpr vtkIdType MaximumSamplesPerSegment = 1 << 20;
  curve.clear();
  // The polyline's own points must be near the surface; the samples between them (a chord of a
  // curved surface) may be farther.
  auto add = [&](const double x[3], vtkIdType pointId, bool sample) {
    gs::SurfacePoint p;
    std::string reason;
    if (!this->Snap(x, p, reason, sample))
    {
      error = "point " + std::to_string(pointId) + ": " + reason;
      return false;
    }
    const gs::SurfacePoint& last = curve.empty() ? p : curve.back();
    if (curve.empty() || last.Vertex != p.Vertex || last.Face != p.Face || last.Bary != p.Bary)
    {
      curve.push_back(p);
    }
    return true;
  };
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (ids[i] < 0 || ids[i] >= points->GetNumberOfPoints())
    {
      error = "a line cell refers to point " + std::to_string(ids[i]) + ", out of range";
      return false;
    }
    double a[3];
    points->GetPoint(ids[i], a);
    if (!add(a, ids[i], false))
    {
      return false;
    }
    if (i + 1 == n)
    {
      break;
    }
    double b[3];
    points->GetPoint(ids[i + 1], b);
    const double length = std::sqrt(vtkMath::Distance2BetweenPoints(a, b));
    if (!std::isfinite(length))
    {
      error = "point " + std::to_string(ids[i + 1]) + ": non-finite coordinates";
      return false;
    }
    const vtkIdType steps = static_cast<vtkIdType>(
      std::min<double>(MaximumSamplesPerSegment, std::ceil(length / spacing)));
    for (vtkIdType s = 1; s < steps; ++s)
    {
      const double t = static_cast<double>(s) / static_cast<double>(steps);
      const double x[3] = { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]),
        a[2] + t * (b[2] - a[2]) };
      if (!add(x, ids[i], true))
      {
        return false;
      }
    }
  }
  return true;
}
