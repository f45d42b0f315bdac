// Straightest geodesics: from a surface point, walk in a tangent direction for a given length,
// crossing edges by unfolding the next face about the shared edge (the inverse of the log map
// for directions whose geodesic passes through no vertex). Used to draw shapes given in geodesic
// polar coordinates onto the surface.
#pragma once

#include "SurfaceCurve.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"

#include <vector>

namespace gs
{

struct GeodesicShot
{
  SurfacePoint End;                 // a face point (with barycentric coordinates)
  double Length = 0.0;              // length walked (less than asked at a boundary)
  bool ReachedBoundary = false;     // stopped at the mesh boundary
  std::vector<CurvePiece> Pieces;   // the path, one straight piece per face
};

// The tangent angle at a surface point of a 3D direction (projected onto the tangent plane),
// in the convention of ExactGeodesicSolver::DepartureAngle: for a vertex, counter-clockwise from
// its VertexHalfedge in its fan (0 .. total angle); for a face point, from the face's first edge.
// NaN when the direction is (nearly) normal to the surface there.
double TangentAngle(const TriangleMesh& mesh, const SurfacePoint& at, const Vec3& direction);

// Walks `length` from `from` leaving at tangent angle `angle` (same convention). Stops early at
// the boundary. Passing exactly through a vertex, the walk continues on one side of it.
GeodesicShot ShootGeodesic(const TriangleMesh& mesh, const SurfacePoint& from, double angle, double length);

} // namespace gs
