// Iso-curve arc-length angles (angles that do not fold past saddles) and their inverse.
#include "GeodesicPolarCoordinatesImpl.h"

#include "GeodesicShooting.h"
#include "SurfaceCurve.h"
#include "GeodesicUnfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

namespace
{
// Whether segments [p, q] and [a, b], lying in one face's plane with normal n, cross; the
// crossing's parameter along [p, q] in t.
bool SegmentsCross(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& n, double& t)
{
  const Vec3 r = q - p, s = b - a;
  const double den = Dot(Cross(r, s), n);
  if (den == 0.0)
  {
    return false;
  }
  t = Dot(Cross(a - p, s), n) / den;
  const double u = Dot(Cross(a - p, r), n) / den;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}
} // namespace

bool GeodesicPolarCoordinates::TraceIsoCurve(int v,
  const std::vector<std::vector<std::pair<Vec3, Vec3>>>& reference, double& toReference,
  double& length) const
{
  const double c = VertexRho[v];
  // Distances just beyond the radius come from an exact solve a few edges further.
  auto rho = [&](int w) { return std::isfinite(VertexRho[w]) ? VertexRho[w] : BeyondRho(w); };
  // Below the level: strictly closer than v (vertices at exactly the level count as above; v
  // itself is where the loop starts and ends).
  auto below = [&](int w) { return w != v && rho(w) < c; };
  // Point on half-edge h where the level is reached (one end below, the other above).
  auto crossing = [&](int h) {
    const int a = Mesh.Origin(h), b = Mesh.Destination(h);
    const double ra = a == v ? c : rho(a), rb = b == v ? c : rho(b);
    const double t = std::isfinite(rb) && std::abs(rb - ra) > 0.0 ? (c - ra) / (rb - ra) : 1.0;
    return Mesh.Position(a) + (Mesh.Position(b) - Mesh.Position(a)) * std::min(1.0, std::max(0.0, t));
  };
  // Start: the face around v whose far edge goes from above to below counter-clockwise, so that
  // the walk keeps the source (below) on its left.
  int h0 = -1;
  for (int h : Mesh.OutgoingHalfedges(v))
  {
    const int a = Mesh.Destination(h), b = Mesh.Opposite(h);
    if (!below(a) && below(b))
    {
      h0 = TriangleMesh::Next(h); // edge a -> b, crossed from v
      break;
    }
  }
  if (h0 < 0)
  {
    return false;
  }
  Vec3 x = Mesh.Position(v);
  int h = h0; // the edge the walk leaves its current face through
  length = 0.0;
  toReference = -1.0;
  const int maxSteps = 4 * Mesh.NumberOfFaces() + 8;
  for (int step = 0; step < maxSteps; ++step)
  {
    const int f = h / 3;
    // Every edge the walk leaves through runs from above to below; when its upper end is v, the
    // level is reached at v itself: the loop is closed.
    const bool closing = Mesh.Origin(h) == v && step > 0;
    const Vec3 y = closing ? Mesh.Position(v) : crossing(h);
    const double piece = Norm(y - x);
    double t = 0.0;
    for (const auto& seg : reference[f])
    {
      if (toReference < 0.0 && SegmentsCross(x, y, seg.first, seg.second, Mesh.FaceNormal(f), t))
      {
        toReference = length + t * piece;
      }
    }
    length += piece;
    x = y;
    if (closing)
    {
      return toReference >= 0.0 && length > 0.0;
    }
    const int twin = Mesh.Twin(h);
    if (twin < 0)
    {
      return false; // the iso-curve meets the mesh boundary: not a loop
    }
    // In the next face, leave through the other edge that changes side.
    const int e1 = TriangleMesh::Next(twin), e2 = TriangleMesh::Prev(twin);
    const int third = Mesh.Destination(e1);
    // twin runs from the shared edge's lower end to its upper end; the level leaves through e1
    // (upper end to third) when third is below, through e2 (third to the lower end) otherwise.
    h = below(third) == below(Mesh.Origin(e1)) ? e2 : e1;
  }
  return false;
}

Result<int> GeodesicPolarCoordinates::UseIsoCurveAngles()
{
  if (!Solved || CurveMode)
  {
    return Status::Error("iso-curve angles need the coordinates about a point (a successful "
                         "Compute, not ComputeCurve)");
  }
  IsoAngles = true;
  // The reference geodesic: from the source in direction theta = 0 to the radius.
  std::vector<std::vector<std::pair<Vec3, Vec3>>> reference(Mesh.NumberOfFaces());
  double radius = 0.0;
  for (int v : InsideList)
  {
    radius = std::max(radius, VertexRho[v]);
  }
  const GeodesicShot ray = ShootGeodesic(Mesh, Source, Reference, radius * 1.01 + MeanEdge);
  // (A chart the exact engine solved in parts goes a few edges further the same way.)
  BeyondInParts = Engine && Engine == WideExact.get();
  const double beyond = radius + 3.0 * MeanEdge;
  if (BeyondInParts)
  {
    GeodesicSources sources;
    sources.Points = { Source };
    GeodesicSolveOptions further;
    further.MaximumDistance = beyond;
    static_cast<void>(WideExact->Solve(sources, further)); // Compute accepted Source
  }
  else
  {
    ExactGeodesicOptions further;
    further.MaximumDistance = beyond;
    static_cast<void>(Solver.Solve({ Source }, further)); // Compute accepted Source
  }
  for (const CurvePiece& piece : ray.Pieces)
  {
    reference[piece.Face].push_back({ piece.A, piece.B });
  }
  int kept = 0;
  for (int v : InsideList)
  {
    if (!(VertexRho[v] > 0.0))
    {
      continue;
    }
    double toReference = 0.0, length = 0.0;
    if (TraceIsoCurve(v, reference, toReference, length))
    {
      VertexTheta[v] = std::fmod(TwoPi * (length - toReference) / length, TwoPi);
    }
    else
    {
      ++kept;
    }
  }
  return kept;
}


SurfacePoint GeodesicPolarCoordinates::InverseIsoCurve(double c, double theta) const
{
  // The level loop at rho = c, traced counter-clockwise from where it crosses the reference
  // geodesic (as UseIsoCurveAngles measured it), walked to the fraction theta / 2 pi of its length.
  auto rho = [&](int w) { return std::isfinite(VertexRho[w]) ? VertexRho[w] : BeyondRho(w); };
  auto below = [&](int w) { return rho(w) < c; };
  auto crossing = [&](int h) {
    const int a = Mesh.Origin(h), b = Mesh.Destination(h);
    const double ra = rho(a), rb = rho(b);
    const double t = std::isfinite(rb) && std::abs(rb - ra) > 0.0 ? (c - ra) / (rb - ra) : 1.0;
    return Mesh.Position(a) + (Mesh.Position(b) - Mesh.Position(a)) * std::min(1.0, std::max(0.0, t));
  };
  auto toSurface = [&](int f, const Vec3& x) {
    SurfacePoint p = SurfacePoint::InFace(f, 0, 0, 0);
    p.Bary = Mesh.ClampedBarycentric(f, x);
    return p;
  };
  // 1. Where the reference geodesic reaches the level.
  const GeodesicShot ray = ShootGeodesic(Mesh, Source, Reference, c * 1.01 + MeanEdge);
  int f0 = -1;
  Vec3 start;
  for (const CurvePiece& piece : ray.Pieces)
  {
    const auto& t = Mesh.Face(piece.Face);
    auto interpolated = [&](const Vec3& x) {
      const SurfacePoint p = toSurface(piece.Face, x);
      return p.Bary[0] * rho(t[0]) + p.Bary[1] * rho(t[1]) + p.Bary[2] * rho(t[2]);
    };
    const double ra = interpolated(piece.A), rb = interpolated(piece.B);
    if (std::isfinite(ra) && std::isfinite(rb) && (ra - c) * (rb - c) <= 0.0 && ra != rb)
    {
      f0 = piece.Face;
      start = piece.A + (piece.B - piece.A) * ((c - ra) / (rb - ra));
      break;
    }
  }
  if (f0 < 0)
  {
    return ShootGeodesic(Mesh, Source, Reference + theta * Turn / TwoPi, c).End;
  }
  // 2. The loop, as points (with their faces) and cumulative lengths.
  int h = -1;
  for (int k = 0; k < 3; ++k)
  {
    const int e = 3 * f0 + k;
    if (!below(Mesh.Origin(e)) && below(Mesh.Destination(e)))
    {
      h = e;
    }
  }
  if (h < 0)
  {
    return toSurface(f0, start);
  }
  std::vector<Vec3> points{ start };
  std::vector<int> faces;
  std::vector<double> cumulative{ 0.0 };
  const int maxSteps = 4 * Mesh.NumberOfFaces() + 8;
  for (int step = 0; step < maxSteps; ++step)
  {
    const Vec3 y = crossing(h);
    faces.push_back(h / 3);
    cumulative.push_back(cumulative.back() + Norm(y - points.back()));
    points.push_back(y);
    const int twin = Mesh.Twin(h);
    if (twin < 0)
    {
      break; // not a loop: walk what there is
    }
    const int g = twin / 3;
    if (g == f0)
    {
      // Back in the start face: close the loop at the start point.
      faces.push_back(f0);
      cumulative.push_back(cumulative.back() + Norm(start - points.back()));
      points.push_back(start);
      break;
    }
    const int e1 = TriangleMesh::Next(twin), e2 = TriangleMesh::Prev(twin);
    const int third = Mesh.Destination(e1);
    h = below(third) == below(Mesh.Origin(e1)) ? e2 : e1;
  }
  // 3. The point at the fraction theta / 2 pi of the loop's length.
  double a = std::fmod(theta, TwoPi);
  if (a < 0.0)
  {
    a += TwoPi;
  }
  const double target = a / TwoPi * cumulative.back();
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
  {
    if (target <= cumulative[i + 1] || i + 2 == points.size())
    {
      const double piece = cumulative[i + 1] - cumulative[i];
      const double t = piece > 0.0 ? std::min(1.0, std::max(0.0, (target - cumulative[i]) / piece)) : 0.0;
      return toSurface(faces[i], points[i] + (points[i + 1] - points[i]) * t);
    }
  }
  return toSurface(f0, start);
}

} // namespace gs
