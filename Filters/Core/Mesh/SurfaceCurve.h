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

// Where a ray from x (in face f) with in-plane direction d leaves the face: the edge (a
// half-edge of f other than `entry`, -1 if none), the ray parameter t and the position s along
// the edge (0 at its origin). A start on the edge it leaves through counts (t = 0).
struct FaceExit
{
  int Edge = -1;
  double T = 0.0, S = 0.0;
};
FaceExit FindFaceExit(const TriangleMesh& mesh, int f, const Vec3& x, const Vec3& d, int entry);

// Spacing of the samples of a curve source seeding the exact geodesic solver, in mean edge
// lengths: the exact reference for distances to a curve and for curve coordinates.
constexpr double ExactCurveSampleSpacing = 1.0 / 16.0;

// The curve as runs, each as long as the curve goes straight in space (consecutive points on one
// line, going on), traced on the surface (TraceSurfaceCurve of the run's ends): how virtual
// source propagation carries a curve (a straight line snapped onto a flat part of the mesh is
// one run). Appended to `runs`.
void AppendStraightRuns(const TriangleMesh& mesh, const std::vector<SurfacePoint>& curve,
  std::vector<std::vector<CurvePiece>>& runs);

// Surface points along the pieces, at most `spacing` apart within each piece (both ends kept).
std::vector<SurfacePoint> SampleCurvePieces(
  const TriangleMesh& mesh, const std::vector<CurvePiece>& pieces, double spacing);

} // namespace gs
