// Curves on the surface: a polyline given as surface points, traced across faces into pieces
// (straight segments inside one face each), and sampled.
#pragma once

#include "SurfacePoint.h"
#include "TriangleMesh.h"

#include <vector>

namespace gs
{

struct CurvePiece
{
  int Face;
  Vec3 A, B; // a straight segment inside Face (A == B: a single point)
};

// Consecutive points are joined by the straight surface path between them: a walk across
// faces, re-aimed at the next point in each face's plane (exact on developable patches). A
// walk that cannot reach the next point (boundary, more than 256 faces) keeps that point alone.
std::vector<CurvePiece> TraceSurfaceCurve(const TriangleMesh& mesh, const std::vector<SurfacePoint>& curve);

// Surface points along the pieces, at most `spacing` apart within each piece (both ends kept).
std::vector<SurfacePoint> SampleCurvePieces(
  const TriangleMesh& mesh, const std::vector<CurvePiece>& pieces, double spacing);

} // namespace gs
