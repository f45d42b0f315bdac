#include "GeodesicPolarCoordinates.h"

#include "GeodesicShooting.h"
#include "GeodesicUnfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

namespace
{
constexpr double TwoPi = 6.28318530717958647692;
const double NaN = std::numeric_limits<double>::quiet_NaN();

double Wrap(double a)
{
  a = std::fmod(a, TwoPi);
  return a < 0.0 ? a + TwoPi : a;
}
} // namespace

GeodesicPolarCoordinates::GeodesicPolarCoordinates(const TriangleMesh& mesh, const SaddleVertexGraph* graph)
  : M(mesh)
  , Solver(mesh)
{
  if (graph && graph->NumberOfVertices() == mesh.NumberOfVertices())
  {
    Svg.reset(new SVGGeodesicSolver(mesh, *graph));
  }
  R.assign(M.NumberOfVertices(), NaN);
  T.assign(M.NumberOfVertices(), NaN);
}

double GeodesicPolarCoordinates::RawToTheta(double raw) const
{
  return Wrap((raw - Reference) * TwoPi / Turn);
}

bool GeodesicPolarCoordinates::Compute(const SurfacePoint& source, double radius, double referenceAngle)
{
  for (int v : InsideList)
  {
    R[v] = NaN;
    T[v] = NaN;
  }
  InsideList.clear();
  if (!(radius > 0.0) || !std::isfinite(referenceAngle))
  {
    return false;
  }
  const double maxDistance = std::isfinite(radius) ? radius : 0.0;
  Turn = source.IsVertex() && source.Vertex >= 0 && source.Vertex < M.NumberOfVertices()
    ? M.TotalAngle(source.Vertex)
    : TwoPi;
  Reference = referenceAngle;
  if (Svg)
  {
    SVGSolveOptions options;
    options.MaximumDistance = maxDistance;
    options.Angles = true;
    if (!Svg->Solve({ source }, options))
    {
      return false;
    }
    for (int v : Svg->Reached())
    {
      if (Svg->Distance(v) <= radius)
      {
        InsideList.push_back(v);
      }
    }
    std::sort(InsideList.begin(), InsideList.end(), [&](int a, int b) {
      return Svg->Distance(a) < Svg->Distance(b) || (Svg->Distance(a) == Svg->Distance(b) && a < b);
    });
  }
  else
  {
    ExactGeodesicOptions options;
    options.MaximumDistance = maxDistance;
    if (!Solver.Solve({ source }, options))
    {
      return false;
    }
    InsideList = Solver.FinalVertices();
  }
  Source = source;
  for (int v : InsideList)
  {
    R[v] = Svg ? Svg->Distance(v) : Solver.Distance(v);
    const double raw = Svg ? Svg->DepartureAngle(v) : Solver.DepartureAngle(v);
    // The source vertex itself is the pole: angle 0 by convention.
    T[v] = std::isfinite(raw) ? RawToTheta(raw) : 0.0;
  }
  return true;
}

bool GeodesicPolarCoordinates::PolarAt(const SurfacePoint& q, double& rho, double& theta) const
{
  rho = theta = NaN;
  if (q.IsVertex())
  {
    rho = R[q.Vertex];
    theta = T[q.Vertex];
    return std::isfinite(rho);
  }
  const auto& t = M.Face(q.Face);
  const Vec3 x = M.Interpolate(q.Face, q.Bary);
  const bool sourceFace = Source.IsVertex()
    ? (t[0] == Source.Vertex || t[1] == Source.Vertex || t[2] == Source.Vertex)
    : Source.Face == q.Face;
  if (sourceFace)
  {
    // Straight inside the face: exact.
    const Vec3 s = Source.IsVertex() ? M.Position(Source.Vertex) : M.Interpolate(Source.Face, Source.Bary);
    rho = Norm(x - s);
    if (rho == 0.0)
    {
      theta = 0.0;
      return true;
    }
    // The tangent angle at the source of the direction towards x, measured in x's face.
    const double raw = TangentAngle(M, Source, x - s);
    theta = std::isfinite(raw) ? RawToTheta(raw) : 0.0;
    return true;
  }
  if (!std::isfinite(R[t[0]]) || !std::isfinite(R[t[1]]) || !std::isfinite(R[t[2]]))
  {
    return false;
  }
  const UnfoldedTriangle u = UnfoldTriangle(M, q.Face, q.Bary, { { R[t[0]], R[t[1]], R[t[2]] } });
  rho = u.Distance;
  // Theta: in the unfolding, the direction from the unfolded source to q, turned by the offset
  // that maps the corners' unfolded directions onto their angles (the same for all corners on a
  // developable surface; averaged circularly otherwise). Without an unfolded source, the corner
  // angles are interpolated.
  double sum = 0.0;
  if (u.FromEdge)
  {
    const Vec2 toQ = u.Point - u.Source;
    double offset0 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const Vec2 c = u.Corners[k] - u.Source;
      // Angles in the unfolding are true angles at the source: scale them like the raw ones.
      const double o = T[t[k]] - std::atan2(c.y, c.x) * TwoPi / Turn;
      if (k == 0)
      {
        offset0 = o;
      }
      double d = o - offset0;
      d -= TwoPi * std::round(d / TwoPi);
      sum += q.Bary[k] * d;
    }
    theta = Wrap(offset0 + sum + std::atan2(toQ.y, toQ.x) * TwoPi / Turn);
    return true;
  }
  for (int k = 0; k < 3; ++k)
  {
    double d = T[t[k]] - T[t[0]];
    d -= TwoPi * std::round(d / TwoPi);
    sum += q.Bary[k] * d;
  }
  theta = Wrap(T[t[0]] + sum);
  return true;
}

SurfacePoint GeodesicPolarCoordinates::ToSurface(double rho, double theta) const
{
  if (rho <= 0.0)
  {
    return Source;
  }
  return ShootGeodesic(M, Source, Reference + theta * Turn / TwoPi, rho).End;
}

} // namespace gs
