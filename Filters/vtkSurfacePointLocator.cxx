#include "vtkSurfacePointLocator.h"

#include <vtkGenericCell.h>
#include <vtkMath.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

//------------------------------------------------------------------------------
vtkSurfacePointLocator::vtkSurfacePointLocator(const vtkSurfaceMeshConverter::Result& mesh)
  : Mesh(mesh)
  , Locator(vtkSmartPointer<vtkStaticCellLocator>::New())
  , Cell(vtkSmartPointer<vtkGenericCell>::New())
{
  this->Locator->SetDataSet(mesh.Triangles);
  this->Locator->BuildLocator();
  this->Diagonal = mesh.Triangles->GetLength();
}

//------------------------------------------------------------------------------
vtkSurfacePointLocator::~vtkSurfacePointLocator() = default;

//------------------------------------------------------------------------------
gs::Result<gs::SurfacePoint> vtkSurfacePointLocator::Snap(const double x[3], double maximumFraction)
{
  if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
  {
    return gs::Status::Error("non-finite coordinates");
  }
  const gs::TriangleMesh& mesh = this->Mesh.Build.Mesh;
  const std::vector<int>& pointToVertex = this->Mesh.Build.PointToVertex;
  double closest[3], dist2 = 0.0;
  vtkIdType cellId = -1;
  int subId = 0;
  this->Locator->FindClosestPoint(x, closest, this->Cell, cellId, subId, dist2);
  if (cellId < 0 || cellId >= mesh.NumberOfFaces())
  {
    return gs::Status::Error("could not be snapped to the surface");
  }
  if (std::sqrt(dist2) > maximumFraction * this->Diagonal)
  {
    return gs::Status::Error(TooFar(std::sqrt(dist2), maximumFraction, this->Diagonal));
  }
  // The locator used Cell as scratch space: fetch the closest triangle itself.
  this->Mesh.Triangles->GetCell(cellId, this->Cell);
  return OnFace(this->Cell, closest, static_cast<int>(cellId), mesh.Face(static_cast<int>(cellId)),
    [&pointToVertex](vtkIdType p) { return pointToVertex[static_cast<size_t>(p)]; });
}

//------------------------------------------------------------------------------
std::string vtkSurfacePointLocator::TooFar(
  double distance, double maximumFraction, double diagonal)
{
  std::ostringstream message;
  message << "it lies " << distance << " from the surface, more than " << maximumFraction
          << " times the mesh's bounding box diagonal (" << diagonal
          << "): check its coordinates";
  return message.str();
}

//------------------------------------------------------------------------------
gs::Result<gs::SurfacePoint> vtkSurfacePointLocator::OnFace(vtkGenericCell* triangle,
  double closest[3], int face, const std::array<int, 3>& corners,
  const std::function<int(vtkIdType)>& vertexOf)
{
  // Barycentric coordinates in the triangle's point order, then matched to the face's corners.
  double snapped[3], pcoords[3], weights[3], dist2 = 0.0;
  int subId = 0;
  triangle->EvaluatePosition(closest, snapped, subId, pcoords, dist2, weights);
  std::array<double, 3> bary{ { 0.0, 0.0, 0.0 } };
  int matched = 0;
  for (int k = 0; k < 3; ++k)
  {
    const int v = vertexOf(triangle->GetPointId(k));
    for (int c = 0; c < 3; ++c)
    {
      if (corners[c] == v)
      {
        bary[c] = std::max(0.0, weights[k]);
        ++matched;
      }
    }
  }
  const double sum = bary[0] + bary[1] + bary[2];
  if (matched != 3 || !(sum > 0.0))
  {
    return gs::Status::Error(
      "internal error: triangle " + std::to_string(face) + " does not match its core face");
  }
  return gs::SurfacePoint::InFace(face, bary[0] / sum, bary[1] / sum, bary[2] / sum);
}

//------------------------------------------------------------------------------
gs::Result<std::vector<gs::SurfacePoint>> vtkSurfacePointLocator::SnapCurve(
  vtkPoints* points, vtkIdType n, const vtkIdType* ids)
{
  const double spacing = CurveSampleSpacing * this->Mesh.Build.Mesh.MeanEdgeLength();
  // At most this many samples per segment (a segment far longer than the mesh).
  constexpr vtkIdType MaximumSamplesPerSegment = 1 << 20;
  std::vector<gs::SurfacePoint> curve;
  // The polyline's own points must be near the surface; the samples between them (a chord of a
  // curved surface) may be farther.
  auto add = [&](const double x[3], vtkIdType pointId, bool sample) {
    const gs::Result<gs::SurfacePoint> snapped =
      this->Snap(x, sample ? std::numeric_limits<double>::infinity() : MaximumDistanceFraction);
    if (!snapped.Ok())
    {
      return gs::Status::Error("point " + std::to_string(pointId) + ": " + snapped.Message());
    }
    const gs::SurfacePoint& p = *snapped;
    const gs::SurfacePoint& last = curve.empty() ? p : curve.back();
    if (curve.empty() || last.Vertex != p.Vertex || last.Face != p.Face || last.Bary != p.Bary)
    {
      curve.push_back(p);
    }
    return gs::Status();
  };
  for (vtkIdType i = 0; i < n; ++i)
  {
    if (ids[i] < 0 || ids[i] >= points->GetNumberOfPoints())
    {
      return gs::Status::Error(
        "a line cell refers to point " + std::to_string(ids[i]) + ", out of range");
    }
    double a[3];
    points->GetPoint(ids[i], a);
    if (gs::Status added = add(a, ids[i], false); !added.Ok())
    {
      return added;
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
      return gs::Status::Error(
        "point " + std::to_string(ids[i + 1]) + ": non-finite coordinates");
    }
    const vtkIdType steps = static_cast<vtkIdType>(
      std::min<double>(MaximumSamplesPerSegment, std::ceil(length / spacing)));
    for (vtkIdType s = 1; s < steps; ++s)
    {
      const double t = static_cast<double>(s) / static_cast<double>(steps);
      const double x[3] = { a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]),
        a[2] + t * (b[2] - a[2]) };
      if (gs::Status added = add(x, ids[i], true); !added.Ok())
      {
        return added;
      }
    }
  }
  return curve;
}
