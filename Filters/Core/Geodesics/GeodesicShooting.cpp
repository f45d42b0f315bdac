#include "GeodesicShooting.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

namespace
{
// Rotates v about the unit axis k by the angle whose cosine and sine are c and s.
Vec3 Rotate(const Vec3& v, const Vec3& k, double c, double s)
{
  return v * c + Cross(k, v) * s + k * (Dot(k, v) * (1.0 - c));
}

// Unit direction in face f's plane at angle a (counter-clockwise about the face normal) from
// the unit in-plane direction `zero`.
Vec3 InFaceDirection(const TriangleMesh& m, int f, const Vec3& zero, double a)
{
  return RotateTangent(zero, m.FaceNormal(f), a);
}

} // namespace

double TangentAngle(const TriangleMesh& m, const SurfacePoint& at, const Vec3& direction)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (at.IsVertex())
  {
    // The face of the fan whose plane holds the projected direction inside its corner.
    double fan = 0.0, bestAngle = nan, bestMiss = std::numeric_limits<double>::infinity();
    for (int h : m.OutgoingHalfedges(at.Vertex))
    {
      const int f = h / 3;
      const Vec3 n = m.FaceNormal(f);
      const Vec3 d = direction - n * Dot(n, direction);
      const Vec3 e1 = Unit(m.Position(m.Destination(h)) - m.Position(at.Vertex));
      const double beta = m.CornerAngle(h);
      if (Norm(d) > 1e-12 * Norm(direction))
      {
        const double a = std::atan2(Dot(Cross(e1, d), n), Dot(e1, d)); // from e1, CCW
        // Distance outside the corner [0, beta] (0 when inside).
        const double miss = a < 0.0 ? -a : (a > beta ? a - beta : 0.0);
        if (miss < bestMiss)
        {
          bestMiss = miss;
          bestAngle = fan + std::min(std::max(a, 0.0), beta);
        }
      }
      fan += beta;
    }
    return bestAngle;
  }
  const int f = at.Face;
  const Vec3 n = m.FaceNormal(f);
  const Vec3 d = direction - n * Dot(n, direction);
  if (!(Norm(d) > 1e-12 * Norm(direction)))
  {
    return nan;
  }
  const Vec3 e0 = Unit(m.Position(m.Face(f)[1]) - m.Position(m.Face(f)[0]));
  return std::atan2(Dot(Cross(e0, d), n), Dot(e0, d));
}

GeodesicShot ShootGeodesic(const TriangleMesh& m, const SurfacePoint& from, double angle, double length)
{
  GeodesicShot shot;
  int f = -1;
  Vec3 x, d;
  if (from.IsVertex())
  {
    // The fan corner holding the angle (taken modulo the total angle).
    const double theta = m.TotalAngle(from.Vertex);
    double a = std::fmod(angle, theta);
    if (a < 0.0)
    {
      a += theta;
    }
    x = m.Position(from.Vertex);
    double fan = 0.0;
    const std::vector<int> out = m.OutgoingHalfedges(from.Vertex);
    for (std::size_t i = 0; i < out.size(); ++i)
    {
      const int h = out[i];
      const double beta = m.CornerAngle(h);
      if (a <= fan + beta || i + 1 == out.size())
      {
        f = h / 3;
        const Vec3 e1 = Unit(m.Position(m.Destination(h)) - x);
        d = InFaceDirection(m, f, e1, std::min(std::max(a - fan, 0.0), beta));
        break;
      }
      fan += beta;
    }
  }
  else
  {
    f = from.Face;
    x = m.Interpolate(f, from.Bary);
    const Vec3 e0 = Unit(m.Position(m.Face(f)[1]) - m.Position(m.Face(f)[0]));
    d = InFaceDirection(m, f, e0, angle);
  }
  double remaining = std::max(0.0, length);
  int entry = -1;
  // A geodesic of length L crosses at most about L / (shortest altitude) faces; the bound only
  // guards against loops caused by rounding.
  const int maxSteps = 1000000;
  for (int step = 0; step < maxSteps; ++step)
  {
    const Vec3 n = m.FaceNormal(f);
    const FaceExit out = FindFaceExit(m, f, x, d, entry);
    const int exit = out.Edge;
    const double bestT = out.T;
    double bestS = out.S;
    if (exit < 0 || bestT >= remaining)
    {
      // Ends inside this face (or, by rounding, found no way out: stay here).
      const Vec3 y = exit < 0 ? x : x + d * remaining;
      shot.Pieces.push_back({ f, x, y });
      shot.Length += exit < 0 ? 0.0 : remaining;
      shot.End = SurfacePoint::InFace(f, 0, 0, 0);
      shot.End.Bary = m.ClampedBarycentric(f, y);
      return shot;
    }
    // Cross the edge, off its end points (a vertex would leave the next face ambiguous).
    bestS = std::min(1.0 - 1e-9, std::max(1e-9, bestS));
    const Vec3 A = m.Position(m.Origin(exit)), B = m.Position(m.Destination(exit));
    const Vec3 y = A + (B - A) * bestS;
    shot.Pieces.push_back({ f, x, y });
    shot.Length += bestT;
    remaining -= bestT;
    const int t = m.Twin(exit);
    if (t < 0)
    {
      shot.ReachedBoundary = true;
      shot.End = SurfacePoint::InFace(f, 0, 0, 0);
      shot.End.Bary = m.ClampedBarycentric(f, y);
      return shot;
    }
    // Unfold: turn the direction about the edge from this face's plane into the next one's.
    const int g = t / 3;
    const Vec3 axis = Unit(B - A);
    const Vec3 ng = m.FaceNormal(g);
    const double c = Dot(n, ng);
    const double sn = Dot(Cross(n, ng), axis);
    d = Unit(Rotate(d, axis, c, sn));
    x = y;
    f = g;
    entry = t;
  }
  shot.End = SurfacePoint::InFace(f, 0, 0, 0);
  shot.End.Bary = m.ClampedBarycentric(f, x);
  return shot;
}

} // namespace gs
