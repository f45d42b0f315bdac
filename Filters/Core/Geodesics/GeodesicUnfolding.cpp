#include "GeodesicUnfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

double UnfoldedDistance(const TriangleMesh& mesh, int f, const std::array<double, 3>& bary,
  const std::array<double, 3>& d)
{
  return UnfoldTriangle(mesh, f, bary, d).Distance;
}

UnfoldedTriangle UnfoldTriangle(const TriangleMesh& mesh, int f, const std::array<double, 3>& bary,
  const std::array<double, 3>& d)
{
  return FaceUnfolding(mesh, f, d).At(bary);
}

FaceUnfolding::FaceUnfolding(const TriangleMesh& mesh, int f, const std::array<double, 3>& d)
  : D(d)
{
  // The face laid out in its plane: corner 0 at the origin, corner 1 on the x axis.
  const double l01 = mesh.EdgeLength(3 * f);
  const double l02 = mesh.EdgeLength(3 * f + 2);
  const double a0 = mesh.CornerAngle(3 * f);
  P[0] = Vec2(0.0, 0.0);
  P[1] = Vec2(l01, 0.0);
  P[2] = Vec2(l02 * std::cos(a0), l02 * std::sin(a0));
  for (int i = 0; i < 3; ++i)
  {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    if (!std::isfinite(d[i]) || !std::isfinite(d[j]))
    {
      continue;
    }
    const Vec2 e = P[j] - P[i];
    const double L = Norm(e);
    const Vec2 u = e * (1.0 / L);
    Vec2 n(-u.y, u.x);
    if (Dot(n, P[k] - P[i]) > 0.0)
    {
      n = n * -1.0; // the unfolded source lies across the edge from the third corner
    }
    const double x = (d[i] * d[i] - d[j] * d[j] + L * L) / (2.0 * L);
    const double y2 = d[i] * d[i] - x * x;
    if (y2 < 0.0)
    {
      continue; // the distances violate the triangle inequality: no geodesic triangle
    }
    Edges[i].Valid = true;
    Edges[i].Edge = e;
    Edges[i].Source = P[i] + u * x + n * std::sqrt(y2);
  }
}

UnfoldedTriangle FaceUnfolding::At(const std::array<double, 3>& bary) const
{
  const Vec2 q = P[0] * bary[0] + P[1] * bary[1] + P[2] * bary[2];
  UnfoldedTriangle out;
  out.Point = q;
  for (int i = 0; i < 3; ++i)
  {
    out.Corners[i] = P[i];
  }
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i)
  {
    if (!std::isfinite(D[i]) || D[i] >= best)
    {
      continue; // (D[i] + a length is never below best)
    }
    const double viaCorner = D[i] + Norm(q - P[i]);
    if (viaCorner < best)
    {
      best = viaCorner;
      out.Source = P[i];
    }
  }
  for (int i = 0; i < 3; ++i)
  {
    if (!Edges[i].Valid)
    {
      continue;
    }
    // The line from the unfolded source to q must cross the edge between its end points.
    const Vec2& s = Edges[i].Source;
    const Vec2 sq = q - s;
    const double den = Cross(sq, Edges[i].Edge);
    if (std::abs(den) < 1e-300)
    {
      continue;
    }
    const double t = Cross(P[i] - s, sq) / den; // position along the edge, 0..1
    if (t < -1e-9 || t > 1.0 + 1e-9)
    {
      continue;
    }
    if (best < std::numeric_limits<double>::infinity() && NormExceeds(sq, best))
    {
      continue; // (longer than the best: its hypot spared)
    }
    const double straight = Norm(sq);
    if (straight < best)
    {
      best = straight;
      out.Source = s;
      out.FromEdge = true;
      out.Edge = i;
    }
  }
  out.Distance = best;
  return out;
}

} // namespace gs
