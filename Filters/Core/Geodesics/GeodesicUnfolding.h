// Geodesic triangle unfolding (GTU, Wang et al. 2016, Section 3.2): the geodesic distance from a
// source to a point inside a face, from the source's distances to the face's corners. For each
// edge, the geodesic triangle (source, edge end points) is unfolded into the face's plane beside
// the edge; the straight line from the unfolded source to the point, when it crosses the edge,
// gives a candidate. Corner paths (corner distance plus the straight segment) are candidates too;
// the smallest candidate wins. Exact on developable surfaces whenever the corner distances are.
#pragma once

#include "TriangleMesh.h"

#include <array>

namespace gs
{

// Distance at barycentric point `bary` of face f, given the source's distances to the face's
// corners (corner order of mesh.Face(f); infinite corners are ignored). Infinite when all three
// corners are.
double UnfoldedDistance(const TriangleMesh& mesh, int f, const std::array<double, 3>& bary,
  const std::array<double, 3>& cornerDistances);

// The same, with the geometry behind the winning candidate, in the face's plane laid out with
// corner 0 at the origin and corner 1 on the +x axis: the point, the corners, and the unfolded
// source (for a corner candidate, that corner; FromEdge tells which kind won).
struct UnfoldedTriangle
{
  double Distance;
  Vec2 Point;
  Vec2 Corners[3];
  Vec2 Source;
  bool FromEdge = false;
  int Edge = -1; // FromEdge: the edge (corners Edge, Edge + 1) the source was unfolded across
};
UnfoldedTriangle UnfoldTriangle(const TriangleMesh& mesh, int f, const std::array<double, 3>& bary,
  const std::array<double, 3>& cornerDistances);

// One face unfolded for many points of it: the face's layout and each edge's unfolded source,
// which depend on the corner distances only, set up once (UnfoldTriangle sets them up at every
// call). At(bary) is UnfoldTriangle(mesh, f, bary, cornerDistances), to the bit.
class FaceUnfolding
{
public:
  FaceUnfolding() = default;
  FaceUnfolding(const TriangleMesh& mesh, int f, const std::array<double, 3>& cornerDistances);
  UnfoldedTriangle At(const std::array<double, 3>& bary) const;

private:
  Vec2 P[3];                       // the corners laid out
  std::array<double, 3> D{ {} };   // their distances
  // Edge i (corners i, i + 1): its vector and the unfolded source across it (Valid: both corner
  // distances finite and within the triangle inequality).
  struct EdgeSource
  {
    bool Valid = false;
    Vec2 Edge, Source;
  };
  EdgeSource Edges[3];
};

} // namespace gs
