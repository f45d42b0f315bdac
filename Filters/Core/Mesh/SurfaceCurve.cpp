#include "SurfaceCurve.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

FaceExit FindFaceExit(const TriangleMesh& M, int f, const Vec3& x, const Vec3& d, int entry)
{
  const Vec3 n = M.FaceNormal(f);
  FaceExit best;
  best.T = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
  {
    const int e = 3 * f + k;
    if (e == entry)
    {
      continue;
    }
    const Vec3 A = M.Position(M.Origin(e)), B = M.Position(M.Destination(e));
    // Only edges the ray leaves through (den < 0 for counter-clockwise faces).
    const double den = Dot(Cross(B - A, d), n);
    if (!(den < 0.0))
    {
      continue;
    }
    const double t = Dot(Cross(x - A, B - A), n) / den;
    const double s = Dot(Cross(x - A, d), n) / den;
    if (t > -1e-9 * std::max(M.EdgeLength(e), 1e-300) && s >= -1e-9 && s <= 1.0 + 1e-9 && t < best.T)
    {
      best.Edge = e;
      best.T = std::max(t, 0.0);
      best.S = s;
    }
  }
  return best;
}

namespace
{
// Appends the pieces of the straight surface path from `from` to `to`.
void TraceSegment(const TriangleMesh& M, const SurfacePoint& from, const SurfacePoint& to,
  std::vector<CurvePiece>& out)
{
  auto addPiece = [&](int f, const Vec3& a, const Vec3& b) { out.push_back({ f, a, b }); };
  const Vec3 q = M.Position(to);
  Vec3 x = M.Position(from);
  auto hasCorner = [&](int f, int v) {
    const auto& t = M.Face(f);
    return t[0] == v || t[1] == v || t[2] == v;
  };
  // The face to start in: from's face, or for a vertex the face around it that points at q.
  int target = to.IsVertex() ? -1 : to.Face;
  int f = from.Face;
  if (from.IsVertex())
  {
    if (target >= 0 && hasCorner(target, from.Vertex))
    {
      f = target;
    }
    else
    {
      double best = std::numeric_limits<double>::infinity();
      for (int h : M.OutgoingHalfedges(from.Vertex))
      {
        const int g = h / 3;
        const Vec3 c = M.Interpolate(g, { { 1.0 / 3, 1.0 / 3, 1.0 / 3 } });
        if (Norm(c - q) < best)
        {
          best = Norm(c - q);
          f = g;
        }
      }
    }
  }
  // The walk is over in a face that holds the end point: its own face, a face around it when it
  // is a vertex, or any face whose closure contains it (an end point on an edge, reached from
  // the face on the other side).
  auto holds = [&](int g) {
    const auto& t = M.Face(g);
    const Vec3 P0 = M.Position(t[0]), P1 = M.Position(t[1]), P2 = M.Position(t[2]);
    const Vec3 n = Cross(P1 - P0, P2 - P0);
    const double n2 = Dot(n, n);
    const double eps = 1e-9;
    if (std::abs(Dot(q - P0, n)) > eps * std::sqrt(n2) * M.MeanEdgeLength())
    {
      return false;
    }
    const double u0 = Dot(Cross(P1 - q, P2 - q), n) / n2, u1 = Dot(Cross(P2 - q, P0 - q), n) / n2;
    return u0 >= -eps && u1 >= -eps && 1.0 - u0 - u1 >= -eps;
  };
  auto done = [&](int g) {
    return g == target || (to.IsVertex() && hasCorner(g, to.Vertex)) || holds(g);
  };
  int entry = -1; // half-edge of f through which the walk entered
  // Walk straight towards q across faces, re-aiming in each face's plane; a segment between
  // nearby points crosses a few faces. Give up (keeping the end points) if it wanders.
  for (int step = 0; step < 256; ++step)
  {
    if (done(f))
    {
      addPiece(f, x, q);
      return;
    }
    const Vec3 n = M.FaceNormal(f);
    Vec3 dir = q - x;
    dir = dir - n * Dot(n, dir);
    if (Norm(dir) <= 1e-14 * M.MeanEdgeLength())
    {
      break;
    }
    const FaceExit out = FindFaceExit(M, f, x, dir, entry);
    const int exit = out.Edge;
    double bestS = out.S;
    if (exit < 0)
    {
      break;
    }
    // Stay off the vertices, where the next face would be ambiguous.
    bestS = std::min(1.0 - 1e-9, std::max(1e-9, bestS));
    const Vec3 y = M.Position(M.Origin(exit)) * (1.0 - bestS) + M.Position(M.Destination(exit)) * bestS;
    addPiece(f, x, y);
    x = y;
    entry = M.Twin(exit);
    if (entry < 0)
    {
      break; // the boundary
    }
    f = entry / 3;
  }
  // The walk did not reach the end point's face: keep the end point itself.
  addPiece(to.IsVertex() ? M.VertexHalfedge(to.Vertex) / 3 : to.Face, q, q);
}
} // namespace

std::vector<CurvePiece> TraceSurfaceCurve(const TriangleMesh& M, const std::vector<SurfacePoint>& curve)
{
  std::vector<CurvePiece> out;
  if (curve.size() == 1)
  {
    const Vec3 p = M.Position(curve[0]);
    out.push_back({ curve[0].IsVertex() ? M.VertexHalfedge(curve[0].Vertex) / 3 : curve[0].Face, p, p });
  }
  for (std::size_t i = 0; i + 1 < curve.size(); ++i)
  {
    TraceSegment(M, curve[i], curve[i + 1], out);
  }
  return out;
}

void AppendStraightRuns(const TriangleMesh& mesh, const std::vector<SurfacePoint>& curve,
  std::vector<std::vector<CurvePiece>>& runs)
{
  std::size_t i = 0;
  while (i + 1 < curve.size())
  {
    const Vec3 p = mesh.Position(curve[i]);
    std::size_t j = i + 1;
    while (j + 1 < curve.size())
    {
      const Vec3 d = mesh.Position(curve[j]) - p, e = mesh.Position(curve[j + 1]) - p;
      const double nd = Norm(d), ne = Norm(e);
      if (!(nd > 0.0 && ne > nd && Norm(Cross(d, e)) <= 1e-9 * nd * ne))
      {
        break;
      }
      ++j;
    }
    runs.push_back(TraceSurfaceCurve(mesh, { curve[i], curve[j] }));
    i = j;
  }
}

std::vector<SurfacePoint> SampleCurvePieces(
  const TriangleMesh& M, const std::vector<CurvePiece>& pieces, double spacing)
{
  std::vector<SurfacePoint> samples;
  for (const CurvePiece& piece : pieces)
  {
    const double length = Norm(piece.B - piece.A);
    const int steps = spacing > 0.0 ? std::max(1, static_cast<int>(std::ceil(length / spacing))) : 1;
    for (int i = 0; i <= steps; ++i)
    {
      const Vec3 x = piece.A + (piece.B - piece.A) * (static_cast<double>(i) / steps);
      SurfacePoint sample = SurfacePoint::InFace(piece.Face, 0, 0, 0);
      sample.Bary = M.ClampedBarycentric(piece.Face, x);
      samples.push_back(sample);
      if (length == 0.0)
      {
        break;
      }
    }
  }
  return samples;
}

} // namespace gs
