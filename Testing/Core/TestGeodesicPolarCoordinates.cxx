#include "GeodesicPolarCoordinates.h"
#include "GeodesicShooting.h"
#include "MeshGenerators.h"
#include "SaddleVertexGraph.h"
#include "TriangleMesh.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>

using namespace gs;
using gs_test::BuildMesh;

namespace
{
constexpr double Pi = 3.14159265358979323846;

double AngleDiff(double a, double b)
{
  double d = std::fmod(a - b, 2 * Pi);
  if (d < 0)
    d += 2 * Pi;
  return std::min(d, 2 * Pi - d);
}

// No face with all corners inside the radius flips in (rho cos theta, rho sin theta).
int FlippedFaces(const TriangleMesh& m, const GeodesicPolarCoordinates& pc, int source)
{
  int flipped = 0;
  for (int f = 0; f < m.NumberOfFaces(); ++f)
  {
    const auto& t = m.Face(f);
    if (t[0] == source || t[1] == source || t[2] == source)
      continue;
    Vec2 p[3];
    bool inside = true;
    for (int k = 0; k < 3; ++k)
    {
      inside = inside && std::isfinite(pc.Rho(t[k]));
      p[k] = Vec2(pc.Rho(t[k]) * std::cos(pc.Theta(t[k])), pc.Rho(t[k]) * std::sin(pc.Theta(t[k])));
    }
    if (inside && !(Cross(p[1] - p[0], p[2] - p[0]) > 0))
      ++flipped;
  }
  return flipped;
}
} // namespace

TEST(GeodesicPolarCoordinates, PlaneIsPolarCoordinates)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(20, 20, 2.0, 2.0));
  GeodesicPolarCoordinates pc(m);
  const int s = 10 * 21 + 10; // (1, 1)
  const Vec3 ps = m.Position(s);
  // Reference: +y, given as a tangent angle.
  const double ref = TangentAngle(m, SurfacePoint::AtVertex(s), Vec3(0, 1, 0));
  ASSERT_TRUE(gs_test::Succeeded(pc.Compute(SurfacePoint::AtVertex(s), 0.8, ref)));
  int inside = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const Vec3 d = m.Position(v) - ps;
    if (Norm(d) > 0.8 - 1e-9)
    {
      EXPECT_TRUE(std::isnan(pc.Rho(v)) || Norm(d) <= 0.8 + 1e-9);
      continue;
    }
    if (v == s)
      continue;
    ++inside;
    EXPECT_NEAR(pc.Rho(v), Norm(d), 1e-9 * 2);
    EXPECT_LT(AngleDiff(pc.Theta(v), std::atan2(d.y, d.x) - Pi / 2), 1e-9) << v;
    EXPECT_GE(pc.Theta(v), 0.0);
    EXPECT_LT(pc.Theta(v), 2 * Pi);
  }
  EXPECT_GT(inside, 150);
  EXPECT_EQ(FlippedFaces(m, pc, s), 0);
  // A face point source, and the coordinates of points inside faces.
  const SurfacePoint fp = SurfacePoint::InFace(300, 0.3, 0.3, 0.4);
  const Vec3 pf = m.Interpolate(fp.Face, fp.Bary);
  const Vec3 e0 = m.Position(m.Face(300)[1]) - m.Position(m.Face(300)[0]);
  ASSERT_TRUE(gs_test::Succeeded(pc.Compute(fp, 0.7)));
  for (int f : { 300, 301, 250, 340 })
  {
    const SurfacePoint q = SurfacePoint::InFace(f, 0.2, 0.5, 0.3);
    const Vec3 d = m.Interpolate(f, q.Bary) - pf;
    double rho, theta;
    ASSERT_TRUE(pc.PolarAt(q, rho, theta)) << f;
    EXPECT_NEAR(rho, Norm(d), 1e-9) << f;
    // Exact on a plane, in the source's face and through the unfolding elsewhere.
    EXPECT_LT(AngleDiff(theta, std::atan2(d.y, d.x) - std::atan2(e0.y, e0.x)), 1e-9) << f;
  }
}

TEST(GeodesicPolarCoordinates, ConeApexAnglesAreScaledToAFullTurn)
{
  const int rings = 8, sectors = 24;
  const TriangleMesh m = BuildMesh(MakeCone(0.4, 2.0, rings, sectors));
  GeodesicPolarCoordinates pc(m);
  ASSERT_TRUE(gs_test::Succeeded(pc.Compute(SurfacePoint::AtVertex(0), 10.0)));
  EXPECT_LT(pc.SourceAngleSum(), 2 * Pi);
  // Ring vertices of sector j sit at azimuth 2 pi j / sectors (up to a common offset, in the
  // direction the generator's orientation gives).
  const double offset = pc.Theta(1);
  const double sign = AngleDiff(pc.Theta(2) - offset, 2 * Pi / sectors) < 1e-6 ? 1.0 : -1.0;
  for (int v = 1; v < m.NumberOfVertices(); ++v)
  {
    const int i = (v - 1) / sectors + 1, j = (v - 1) % sectors;
    EXPECT_NEAR(pc.Rho(v), 2.0 * i / rings, 1e-9);
    EXPECT_LT(AngleDiff(pc.Theta(v) - offset, sign * 2 * Pi * j / sectors), 1e-9) << v;
  }
  EXPECT_EQ(FlippedFaces(m, pc, 0), 0);
}

TEST(GeodesicPolarCoordinates, ConeAwayFromTheApexMatchesTheDevelopment)
{
  const int rings = 10, sectors = 32;
  const double halfAngle = 0.5, slant = 2.0;
  const TriangleMesh m = BuildMesh(MakeCone(halfAngle, slant, rings, sectors));
  const double gamma = 2 * std::asin(std::sin(halfAngle) * std::sin(Pi / sectors));
  // Development: vertex (ring i, sector j) at polar (slant i / rings, -j gamma) about the apex
  // (the generator's faces turn clockwise with j: mirrored, the development keeps the mesh's
  // orientation counter-clockwise).
  auto developed = [&](int v, double around) {
    if (v == 0)
      return Vec2(0, 0);
    const int i = (v - 1) / sectors + 1, j = (v - 1) % sectors;
    double a = -j * gamma;
    // Unroll on the side nearest to `around`.
    const double full = sectors * gamma;
    while (a - around > full / 2)
      a -= full;
    while (around - a > full / 2)
      a += full;
    return Vec2(slant * i / rings * std::cos(a), slant * i / rings * std::sin(a));
  };
  const int s = 1 + 5 * sectors + 7;
  const double around = -7 * gamma;
  const Vec2 ps = developed(s, around);
  const Vec2 first = developed(m.Destination(m.VertexHalfedge(s)), around) - ps;
  GeodesicPolarCoordinates pc(m);
  ASSERT_TRUE(gs_test::Succeeded(pc.Compute(SurfacePoint::AtVertex(s), 0.9)));
  int checked = 0;
  for (int v : pc.Inside())
  {
    if (v == s)
      continue;
    const Vec2 d = developed(v, around) - ps;
    EXPECT_NEAR(pc.Rho(v), Norm(d), 1e-9);
    EXPECT_LT(AngleDiff(pc.Theta(v), std::atan2(d.y, d.x) - std::atan2(first.y, first.x)), 1e-9) << v;
    ++checked;
  }
  EXPECT_GT(checked, 50);
  EXPECT_EQ(FlippedFaces(m, pc, s), 0);
}

TEST(GeodesicPolarCoordinates, SphereCapAgainstAnalyticPolarCoordinates)
{
  const TriangleMesh m = BuildMesh(MakeIcosphere(1.0, 4));
  GeodesicPolarCoordinates pc(m);
  const int s = 0;
  ASSERT_TRUE(gs_test::Succeeded(pc.Compute(SurfacePoint::AtVertex(s), 0.7)));
  const Vec3 n = m.Position(s) / Norm(m.Position(s));
  // Analytic azimuth about the axis, from the direction of the source's first edge.
  auto tangent = [&](const Vec3& p) { return p - n * Dot(n, p); };
  const Vec3 e1 = tangent(m.Position(m.Destination(m.VertexHalfedge(s))));
  const Vec3 e1u = e1 / Norm(e1), e2u = Cross(n, e1u);
  std::vector<double> thetaErrors;
  for (int v : pc.Inside())
  {
    if (v == s)
      continue;
    const Vec3 p = m.Position(v);
    const double exactRho = std::acos(std::clamp(Dot(n, p / Norm(p)), -1.0, 1.0));
    EXPECT_NEAR(pc.Rho(v), exactRho, 0.01 * exactRho);
    const Vec3 t = tangent(p);
    thetaErrors.push_back(AngleDiff(pc.Theta(v), std::atan2(Dot(t, e2u), Dot(t, e1u))));
  }
  ASSERT_GT(thetaErrors.size(), 100u);
  std::nth_element(thetaErrors.begin(), thetaErrors.begin() + thetaErrors.size() / 2, thetaErrors.end());
  EXPECT_LT(thetaErrors[thetaErrors.size() / 2], 0.5 * Pi / 180);
  EXPECT_EQ(FlippedFaces(m, pc, s), 0);
  // Inverse map: back to each vertex.
  double worst = 0;
  for (int v : pc.Inside())
  {
    if (v == s)
      continue;
    const Result<SurfacePoint> q = pc.ToSurface(pc.Rho(v), pc.Theta(v));
    ASSERT_TRUE(gs_test::Succeeded(q));
    worst = std::max(worst, Norm(m.Interpolate(q->Face, q->Bary) - m.Position(v)));
  }
  EXPECT_LT(worst, 1e-6 * m.MeanEdgeLength());
}

TEST(GeodesicPolarCoordinates, RejectsBadArguments)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(4, 4, 1.0, 1.0));
  GeodesicPolarCoordinates pc(m);
  EXPECT_FALSE(pc.Compute(SurfacePoint::AtVertex(3), 0.0).Ok());
  EXPECT_FALSE(pc.Compute(SurfacePoint::AtVertex(3), -1.0).Ok());
  EXPECT_FALSE(pc.Compute(SurfacePoint::AtVertex(3), NAN).Ok());
  EXPECT_FALSE(pc.Compute(SurfacePoint::AtVertex(999), 1.0).Ok());
  EXPECT_FALSE(pc.Compute(SurfacePoint::AtVertex(3), 1.0, NAN).Ok());
  EXPECT_TRUE(gs_test::Succeeded(pc.Compute(SurfacePoint::AtVertex(3), INFINITY)));
  EXPECT_TRUE(std::isfinite(pc.Rho(24)));
  EXPECT_NE(pc.Compute(SurfacePoint::AtVertex(3), -1.0).Message().find("Radius must be > 0"),
    std::string::npos);
  // Curve points are checked as every solver checks its sources (TriangleMesh::CheckPoints).
  EXPECT_TRUE(gs_test::FailedWith(
    pc.ComputeCurve({ SurfacePoint::AtVertex(0), SurfacePoint::AtVertex(999) }, 1.0),
    "curve point 1 is invalid: vertex 999 does not exist"));
  EXPECT_TRUE(gs_test::FailedWith(
    pc.ComputeCurve({ SurfacePoint::AtVertex(0), SurfacePoint::InFace(2, 0.7, 0.7, 0.0) }, 1.0),
    "curve point 1 is invalid: the barycentric coordinates (0.7, 0.7, 0) in face 2 sum to 1.4"));
}

// The inverse maps and iso-curve angles fail unless the last Compute / ComputeCurve succeeded
// and was of their kind.
TEST(GeodesicPolarCoordinates, InverseMapsNeedTheirCoordinates)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(4, 4, 1.0, 1.0));
  GeodesicPolarCoordinates pc(m);
  EXPECT_TRUE(gs_test::FailedWith(pc.ToSurface(0.1, 0.0), "a successful Compute"));
  EXPECT_TRUE(gs_test::FailedWith(pc.UseIsoCurveAngles(), "a successful Compute"));
  EXPECT_TRUE(gs_test::FailedWith(pc.ToSurfaceFromCurve(0.5, 0.1), "a successful ComputeCurve"));
  ASSERT_TRUE(gs_test::Succeeded(pc.Compute(SurfacePoint::AtVertex(12), 0.5)));
  EXPECT_TRUE(gs_test::Succeeded(pc.ToSurface(0.1, 0.0)));
  EXPECT_TRUE(gs_test::FailedWith(pc.ToSurface(NAN, 0.0), "not finite"));
  EXPECT_TRUE(gs_test::FailedWith(pc.ToSurfaceFromCurve(0.5, 0.1), "a successful ComputeCurve"));
  ASSERT_TRUE(gs_test::Succeeded(
    pc.ComputeCurve({ SurfacePoint::AtVertex(6), SurfacePoint::AtVertex(8) }, 0.5)));
  EXPECT_TRUE(gs_test::Succeeded(pc.ToSurfaceFromCurve(0.5, 0.1)));
  EXPECT_TRUE(gs_test::FailedWith(pc.ToSurfaceFromCurve(0.5, INFINITY), "not finite"));
  EXPECT_TRUE(gs_test::FailedWith(pc.ToSurface(0.1, 0.0), "a successful Compute"));
  EXPECT_TRUE(gs_test::FailedWith(pc.UseIsoCurveAngles(), "a successful Compute"));
  EXPECT_FALSE(pc.Compute(SurfacePoint::AtVertex(12), -1.0).Ok()); // fails: nothing to invert
  EXPECT_TRUE(gs_test::FailedWith(pc.ToSurface(0.1, 0.0), "a successful Compute"));
}

namespace
{
SaddleVertexGraph Graph(const TriangleMesh& m)
{
  SaddleVertexGraph g;
  EXPECT_TRUE(gs_test::Succeeded(g.Build(m, SaddleVertexGraphOptions(), nullptr)));
  return g;
}
} // namespace

TEST(GeodesicPolarCoordinates, RefusesAGraphOfAnotherMesh)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(4, 4, 1.0, 1.0));
  const TriangleMesh other = BuildMesh(MakePlanarGrid(5, 5, 1.0, 1.0));
  const SaddleVertexGraph graph = Graph(other);
  GeodesicPolarCoordinates pc(m, &graph);
  const Status point = pc.Compute(SurfacePoint::AtVertex(3), 1.0);
  EXPECT_NE(point.Message().find("another mesh"), std::string::npos) << point.Message();
  EXPECT_FALSE(pc.ComputeCurve({ SurfacePoint::AtVertex(0), SurfacePoint::AtVertex(3) }, 1.0).Ok());
}

namespace
{
// Largest rho (relative) and theta errors of the graph engine (a saddle vertex graph of K = 50,
// or with accuracy > 0 a discrete geodesic graph) against the exact engine.
void CompareEngines(const TriangleMesh& m, const SurfacePoint& source, double radius,
  double rhoTolerance, double thetaToleranceDegrees, double medianThetaDegrees,
  double accuracy = 0.0)
{
  SaddleVertexGraphOptions o;
  if (accuracy > 0.0)
  {
    o.Construction = GraphConstruction::DiscreteGeodesic;
    o.Accuracy = accuracy;
  }
  SaddleVertexGraph g;
  ASSERT_TRUE(gs_test::Succeeded(g.Build(m, o, nullptr)));
  GeodesicPolarCoordinates exact(m), svg(m, &g);
  ASSERT_TRUE(gs_test::Succeeded(exact.Compute(source, radius)));
  ASSERT_TRUE(gs_test::Succeeded(svg.Compute(source, radius)));
  double worstRho = 0, worstTheta = 0;
  std::vector<double> thetas;
  for (int v : exact.Inside())
  {
    if (exact.Rho(v) < 1e-12 || exact.Rho(v) > 0.98 * radius)
      continue;
    ASSERT_TRUE(std::isfinite(svg.Rho(v))) << v;
    worstRho = std::max(worstRho, std::abs(svg.Rho(v) - exact.Rho(v)) / exact.Rho(v));
    const double d = AngleDiff(svg.Theta(v), exact.Theta(v)) * 180 / Pi;
    worstTheta = std::max(worstTheta, d);
    thetas.push_back(d);
  }
  ASSERT_GT(thetas.size(), 20u);
  std::nth_element(thetas.begin(), thetas.begin() + thetas.size() / 2, thetas.end());
  EXPECT_LT(worstRho, rhoTolerance);
  EXPECT_LT(worstTheta, thetaToleranceDegrees);
  EXPECT_LT(thetas[thetas.size() / 2], medianThetaDegrees);
}
} // namespace

TEST(GeodesicPolarCoordinates, GraphEngineOnAPlaneAndACone)
{
  // The figures: rho within 1e-3 relative, theta within 0.1 degree.
  CompareEngines(BuildMesh(MakePlanarGrid(40, 40, 4.0, 4.0)), SurfacePoint::AtVertex(20 * 41 + 20),
    1.8, 1e-3, 0.1, 0.05);
  CompareEngines(BuildMesh(MakePlanarGrid(40, 40, 4.0, 4.0)), SurfacePoint::InFace(1000, 0.2, 0.3, 0.5),
    1.5, 1e-3, 0.1, 0.05);
  CompareEngines(BuildMesh(MakeCone(0.5, 2.0, 16, 48)), SurfacePoint::AtVertex(1 + 9 * 48 + 5), 1.0,
    1e-3, 0.1, 0.05);
}

TEST(GeodesicPolarCoordinates, GraphEngineOnASphereCap)
{
  const TriangleMesh m = BuildMesh(MakeIcosphere(1.0, 4));
  CompareEngines(m, SurfacePoint::AtVertex(0), 0.8, 1e-2, 2.0, 0.5);
}

TEST(GeodesicPolarCoordinates, DiscreteGeodesicGraphEngine)
{
  // The same figures as the saddle vertex graph's on developable surfaces (the unfolding is
  // exact there); on the sphere cap rho within the graph's accuracy.
  CompareEngines(BuildMesh(MakePlanarGrid(40, 40, 4.0, 4.0)), SurfacePoint::AtVertex(20 * 41 + 20),
    1.8, 1e-3, 0.1, 0.05, 1e-2);
  CompareEngines(BuildMesh(MakePlanarGrid(40, 40, 4.0, 4.0)), SurfacePoint::InFace(1000, 0.2, 0.3, 0.5),
    1.5, 1e-3, 0.1, 0.05, 1e-2);
  CompareEngines(BuildMesh(MakeCone(0.5, 2.0, 16, 48)), SurfacePoint::AtVertex(1 + 9 * 48 + 5), 1.0,
    1e-3, 0.1, 0.05, 1e-2);
  CompareEngines(BuildMesh(MakeIcosphere(1.0, 4)), SurfacePoint::AtVertex(0), 0.8, 1e-2, 2.0, 0.5,
    1e-2);
}

TEST(GeodesicPolarCoordinates, IsoCurveAnglesOnAPlane)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(40, 40, 4.0, 4.0));
  GeodesicPolarCoordinates pc(m);
  const int s = 20 * 41 + 20;
  ASSERT_TRUE(gs_test::Succeeded(pc.Compute(SurfacePoint::AtVertex(s), 1.5)));
  std::vector<double> geodesic(m.NumberOfVertices());
  for (int v : pc.Inside())
    geodesic[v] = pc.Theta(v);
  const Result<int> kept = pc.UseIsoCurveAngles();
  ASSERT_TRUE(gs_test::Succeeded(kept));
  EXPECT_EQ(*kept, 0); // every level is a closed loop crossing the reference
  double nearWorst = 0, farWorst = 0;
  for (int v : pc.Inside())
  {
    const double d = AngleDiff(pc.Theta(v), geodesic[v]) * 180 / Pi;
    if (pc.Rho(v) >= 1.0)
      farWorst = std::max(farWorst, d);
    else if (pc.Rho(v) >= 0.3)
      nearWorst = std::max(nearWorst, d);
  }
  // On a plane the arc-length fraction of a circle is its angle (the issue: 0.1 degree).
  EXPECT_LT(nearWorst, 0.1);
  EXPECT_LT(farWorst, 0.1);
  EXPECT_EQ(FlippedFaces(m, pc, s), 0);
  std::printf("iso-curve vs angle on the plane: %.2f deg (0.3 <= rho < 1), %.2f deg (rho >= 1)\n",
    nearWorst, farWorst);
}

TEST(GeodesicPolarCoordinates, IsoCurveAnglesAreBijectivePastSaddles)
{
  // A bumpy sphere: saddles everywhere; a radius well past the first cut loci.
  const TriangleMesh m = BuildMesh(gs_test::BumpySoup(3, 4, 0.08));
  GeodesicPolarCoordinates pc(m);
  ASSERT_TRUE(gs_test::Succeeded(pc.Compute(SurfacePoint::AtVertex(7), 1.2)));
  const int geodesicFlips = FlippedFaces(m, pc, 7);
  const Result<int> kept = pc.UseIsoCurveAngles();
  ASSERT_TRUE(gs_test::Succeeded(kept));
  EXPECT_EQ(*kept, 0);
  const int isoFlips = FlippedFaces(m, pc, 7);
  std::printf("flipped faces: geodesic direction %d, iso-curve arc length %d\n", geodesicFlips, isoFlips);
  EXPECT_GT(geodesicFlips, 5); // the log map folds past the cut loci here
  EXPECT_EQ(isoFlips, 0);
  // The inverse map of iso-curve coordinates: back to every vertex.
  double worst = 0;
  for (int v : pc.Inside())
  {
    if (pc.Rho(v) <= 0.0)
      continue;
    const Result<SurfacePoint> q = pc.ToSurface(pc.Rho(v), pc.Theta(v));
    ASSERT_TRUE(gs_test::Succeeded(q));
    worst = std::max(worst, Norm(m.Interpolate(q->Face, q->Bary) - m.Position(v)));
  }
  EXPECT_LT(worst, 1e-6 * m.MeanEdgeLength());
  // The torus from its inner equator (negative curvature: saddles), well past the first
  // conjugate points.
  const TriangleMesh torus = BuildMesh(MakeTorus(2.0, 0.7, 48, 24));
  GeodesicPolarCoordinates tp(torus);
  const int inner = 12; // i = 0, j = 12: the inner equator
  ASSERT_TRUE(gs_test::Succeeded(tp.Compute(SurfacePoint::AtVertex(inner), 1.8)));
  const int torusGeodesicFlips = FlippedFaces(torus, tp, inner);
  const Result<int> torusKept = tp.UseIsoCurveAngles();
  ASSERT_TRUE(gs_test::Succeeded(torusKept));
  EXPECT_EQ(*torusKept, 0);
  std::printf("torus: flipped faces geodesic direction %d, iso-curve %d\n", torusGeodesicFlips,
    FlippedFaces(torus, tp, inner));
  EXPECT_EQ(FlippedFaces(torus, tp, inner), 0);
}

TEST(GeodesicPolarCoordinates, CurveOffsetsAndArcLengthOnAPlane)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(40, 40, 4.0, 4.0));
  auto locate = [&](const Vec3& p) {
    for (int f = 0; f < m.NumberOfFaces(); ++f)
    {
      const auto& t = m.Face(f);
      const Vec3 P0 = m.Position(t[0]), P1 = m.Position(t[1]), P2 = m.Position(t[2]);
      const double area = Cross(P1 - P0, P2 - P0).z;
      const double w0 = Cross(P1 - p, P2 - p).z / area, w1 = Cross(P2 - p, P0 - p).z / area;
      if (w0 >= -1e-12 && w1 >= -1e-12 && 1 - w0 - w1 >= -1e-12)
        return SurfacePoint::InFace(f, w0, w1, 1 - w0 - w1);
    }
    return SurfacePoint();
  };
  GeodesicPolarCoordinates pc(m);
  // A straight segment: delta is the signed distance to the line, u the projection's fraction,
  // for points beside the segment.
  const Vec3 a(1.03, 1.51, 0), b(2.97, 2.23, 0);
  ASSERT_TRUE(gs_test::Succeeded(pc.ComputeCurve({ locate(a), locate(b) }, 0.6)));
  const CurveCoordinates& segment = pc.Curve();
  EXPECT_TRUE(pc.IsCurve());
  EXPECT_NEAR(segment.Length, Norm(b - a), 1e-9);
  EXPECT_TRUE(std::isnan(pc.Rho(pc.Inside().front()))); // not polar coordinates
  const Vec3 dir = (b - a) / Norm(b - a);
  int beside = 0, queried = 0;
  for (int v : pc.Inside())
  {
    const Vec3 d = m.Position(v) - a;
    const double along = Dot(d, dir) / Norm(b - a);
    if (along < 0.02 || along > 0.98)
      continue;
    ++beside;
    const double signedDistance = Cross(dir, d).z; // > 0 on the left (normal +z)
    EXPECT_NEAR(segment.Offset[v], signedDistance, 1e-9) << v;
    EXPECT_NEAR(segment.ArcLength[v], along, 1e-9) << v;
    // Inverse map: back to the vertex.
    const Result<SurfacePoint> inverse =
      pc.ToSurfaceFromCurve(segment.ArcLength[v], segment.Offset[v]);
    ASSERT_TRUE(gs_test::Succeeded(inverse));
    const SurfacePoint& back = *inverse;
    // And the coordinates of that surface point (inside a face, all of whose corners are in the
    // band) are the vertex's.
    double offset = 0, u = 0;
    if (pc.CurveCoordinatesAt(back, offset, u))
    {
      ++queried;
      EXPECT_NEAR(offset, segment.Offset[v], 1e-6 * m.MeanEdgeLength());
      EXPECT_NEAR(u, segment.ArcLength[v], 1e-6);
    }
    EXPECT_LT(Norm(m.Interpolate(back.Face, back.Bary) - m.Position(v)), 1e-6 * m.MeanEdgeLength()) << v;
  }
  EXPECT_GT(beside, 100);
  EXPECT_GT(queried, beside / 2);
  // A circular arc about (2, 2): offsets are radius differences (inside the circle is on the left
  // of a counter-clockwise arc), u the angle fraction.
  std::vector<SurfacePoint> arc;
  const double r0 = 1.0, a0 = 0.3, a1 = 2.4;
  for (int i = 0; i <= 40; ++i)
  {
    const double t = a0 + (a1 - a0) * i / 40.0;
    arc.push_back(locate(Vec3(2 + r0 * std::cos(t), 2 + r0 * std::sin(t), 0)));
  }
  ASSERT_TRUE(gs_test::Succeeded(pc.ComputeCurve(arc, 0.4)));
  const CurveCoordinates& onArc = pc.Curve();
  int checked = 0;
  for (int v : pc.Inside())
  {
    const Vec3 d = m.Position(v) - Vec3(2, 2, 0);
    const double angle = std::atan2(d.y, d.x);
    if (angle < a0 + 0.05 || angle > a1 - 0.05)
      continue;
    ++checked;
    EXPECT_NEAR(onArc.Offset[v], r0 - Norm(d), 2e-3) << v; // the arc is a polyline of 40 chords
    EXPECT_NEAR(onArc.ArcLength[v], (angle - a0) / (a1 - a0), 1e-2) << v; // chords, not the arc
  }
  EXPECT_GT(checked, 50);
  EXPECT_FALSE(pc.ComputeCurve({}, 1.0).Ok());
  EXPECT_FALSE(pc.ComputeCurve({ locate(a), locate(a) }, 1.0).Ok()); // zero length
  // Along mesh edges and through mesh vertices (points on edges, some exactly on vertices, as
  // face points): the side is still the side.
  std::vector<SurfacePoint> grid;
  for (int k = 0; k <= 42; ++k)
    grid.push_back(locate(Vec3(1.0 + 2.0 * k / 42.0, 2.0, 0)));
  ASSERT_TRUE(gs_test::Succeeded(pc.ComputeCurve(grid, 0.5)));
  const CurveCoordinates& alongEdges = pc.Curve();
  int wrong = 0, near = 0;
  for (int v : pc.Inside())
  {
    const Vec3 p = m.Position(v);
    if (p.x < 1.05 || p.x > 2.95)
      continue;
    ++near;
    wrong += std::abs(alongEdges.Offset[v] - (p.y - 2.0)) > 1e-6;
  }
  EXPECT_GT(near, 100);
  EXPECT_EQ(wrong, 0);
}

TEST(GeodesicPolarCoordinates, CurveArcLengthAlongEachOffsetCurve)
{
  // A left turn: (1, 1) -> (2, 1) -> (2, 2). On the outer (right) side the offset curve at
  // distance d is a segment, a quarter circle of radius d and a segment (length 2 + pi d / 2);
  // on the inner side two segments of 1 - d. u runs along each of them (the paper's Fig. 3), not
  // along the curve itself.
  const TriangleMesh m = BuildMesh(MakePlanarGrid(40, 40, 4.0, 4.0));
  auto vertexAt = [&](double x, double y) {
    return SurfacePoint::AtVertex(static_cast<int>(std::lround(y * 10) * 41 + std::lround(x * 10)));
  };
  GeodesicPolarCoordinates pc(m);
  ASSERT_TRUE(gs_test::Succeeded(pc.ComputeCurve({ vertexAt(1, 1), vertexAt(2, 1), vertexAt(2, 2) }, 0.35)));
  const CurveCoordinates& turn = pc.Curve();
  EXPECT_NEAR(turn.Length, 2.0, 1e-12);
  const double d = 0.2;
  for (int i = 11; i <= 17; ++i)
  {
    const double x = 0.1 * i;
    const SurfacePoint outer = vertexAt(x, 1 - d), inner = vertexAt(x, 1 + d);
    EXPECT_NEAR(turn.Offset[outer.Vertex], -d, 1e-9);
    EXPECT_NEAR(turn.Offset[inner.Vertex], d, 1e-9);
    // (The quarter circle is traced as chords across the faces: 0.2% shorter.)
    EXPECT_NEAR(turn.ArcLength[outer.Vertex], (x - 1) / (2 + Pi * d / 2), 3e-3 * (x - 1) / 2) << x;
    EXPECT_GT(std::abs(turn.ArcLength[outer.Vertex] - (x - 1) / 2), 0.05 * (x - 1) / 2) << x;
    EXPECT_NEAR(turn.ArcLength[inner.Vertex], (x - 1) / (2 - 2 * d), 1e-6) << x;
  }
}

// A snapshot (LogMapSnapshot: the coordinates kept without the engine) reads every surface point
// as the engine does, to the bit, inside and outside the radius; from a face point and a vertex
// source on a bumpy sphere (saddles: unfolded and interpolated angles), and after a curve
// Compute, empty.
TEST(GeodesicPolarCoordinates, SnapshotReadsAsTheEngine)
{
  const TriangleMesh m = BuildMesh(gs_test::BumpySoup(3, 7, 0.05));
  GeodesicPolarCoordinates pc(m);
  std::uint64_t state = 12345;
  auto uniform = [&state]() {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<double>(state >> 11) * (1.0 / 9007199254740992.0);
  };
  for (const SurfacePoint& source : { SurfacePoint::InFace(7, 0.2, 0.3, 0.5), SurfacePoint::AtVertex(11) })
  {
    ASSERT_TRUE(gs_test::Succeeded(pc.Compute(source, 0.6, 0.4)));
    const LogMapSnapshot snapshot = pc.Snapshot();
    ASSERT_EQ(snapshot.Entries.size(), pc.Inside().size());
    int inside = 0;
    for (int i = 0; i < 4000; ++i)
    {
      const int f = static_cast<int>(uniform() * m.NumberOfFaces()) % m.NumberOfFaces();
      double a = uniform(), b = uniform();
      if (a + b > 1.0)
      {
        a = 1.0 - a;
        b = 1.0 - b;
      }
      const SurfacePoint q = i % 10 == 0 ? SurfacePoint::AtVertex(m.Face(f)[0]) : SurfacePoint::InFace(f, a, b, 1.0 - a - b);
      Vec2 p1{ 0.0, 0.0 }, p2{ 0.0, 0.0 };
      const bool r1 = pc.LogMapAt(q, p1), r2 = snapshot.LogMapAt(m, q, p2);
      ASSERT_EQ(r1, r2);
      if (r1)
      {
        ++inside;
        EXPECT_EQ(p1.x, p2.x);
        EXPECT_EQ(p1.y, p2.y);
      }
    }
    EXPECT_GT(inside, 200);
  }
  ASSERT_TRUE(gs_test::Succeeded(pc.ComputeCurve({ SurfacePoint::AtVertex(11), SurfacePoint::AtVertex(12) }, 0.5)));
  EXPECT_TRUE(pc.Snapshot().Entries.empty());
}

// ComputeCoveringDisc against a Compute out to the radius plus the mesh's longest edge: on a
// rough plane (saddles everywhere) with a spike far away (edges 20 times the mean), every point
// of the disc reads the same coordinates, bit for bit, from a map that holds far fewer vertices.
TEST(GeodesicPolarCoordinates, CoveringDiscReadsTheDiscAsTheLongestEdgeBound)
{
  TriangleSoup soup = MakePlanarGrid(40, 40, 4.0, 4.0);
  std::mt19937 noise(11);
  std::uniform_real_distribution<double> bump(-0.03, 0.03);
  for (Vec3& p : soup.Points)
    p.z = p.x + p.y < 1e-9 ? 2.0 : bump(noise); // (the spike at the corner (0, 0))
  const TriangleMesh m = BuildMesh(soup);
  ASSERT_GT(m.LongestEdgeLength(), 15.0 * m.MeanEdgeLength());
  GeodesicPolarCoordinates covering(m), bound(m);
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> face(0, m.NumberOfFaces() - 1);
  auto farFromTheSpike = [&m](int f) {
    const Vec3 c = m.Position(m.Face(f)[0]);
    return c.x > 1.5 && c.y > 1.5 && c.x < 3.5 && c.y < 3.5;
  };
  const double radius = 4.0 * m.MeanEdgeLength();
  long long smallEntries = 0, boundEntries = 0, disc = 0;
  for (int k = 0; k < 30; ++k)
  {
    int f0 = face(rng);
    while (!farFromTheSpike(f0))
      f0 = face(rng);
    const SurfacePoint source = k % 3 == 0
      ? SurfacePoint::AtVertex(m.Face(f0)[0])
      : SurfacePoint{ -1, f0, { 0.2, 0.3, 0.5 } };
    const Result<double> reached = covering.ComputeCoveringDisc(source, radius, 0.4);
    ASSERT_TRUE(gs_test::Succeeded(reached));
    ASSERT_TRUE(gs_test::Succeeded(bound.Compute(source, radius + 1.01 * m.LongestEdgeLength(), 0.4)));
    EXPECT_GE(*reached, radius * 0.999);
    const LogMapSnapshot a = covering.Snapshot(), b = bound.Snapshot();
    smallEntries += static_cast<long long>(a.Entries.size());
    boundEntries += static_cast<long long>(b.Entries.size());
    for (int v : covering.Inside())
    {
      ASSERT_EQ(covering.Rho(v), bound.Rho(v));
      ASSERT_EQ(covering.Theta(v), bound.Theta(v));
    }
    // Every lattice point of every face that the disc holds (by the bound's map) reads alike.
    for (int f = 0; f < m.NumberOfFaces(); ++f)
    {
      for (int i = 0; i <= 6; ++i)
        for (int j = 0; i + j <= 6; ++j)
        {
          const SurfacePoint q{ -1, f, { i / 6.0, j / 6.0, (6 - i - j) / 6.0 } };
          double rho = 0.0, theta = 0.0;
          if (!b.PolarAt(m, q, rho, theta) || !(rho < radius))
            continue;
          ++disc;
          Vec2 pa, pb;
          ASSERT_TRUE(a.LogMapAt(m, q, pa)) << "source " << k << ", face " << f;
          ASSERT_TRUE(b.LogMapAt(m, q, pb));
          ASSERT_EQ(pa.x, pb.x);
          ASSERT_EQ(pa.y, pb.y);
        }
    }
  }
  EXPECT_GT(disc, 1000);
  // Bad arguments: Compute's errors, nothing computed.
  EXPECT_FALSE(covering.ComputeCoveringDisc(SurfacePoint::AtVertex(-1), radius).Ok());
  EXPECT_FALSE(covering.ComputeCoveringDisc(SurfacePoint{ -1, m.NumberOfFaces(), { 1, 0, 0 } }, radius).Ok());
  EXPECT_FALSE(covering.ComputeCoveringDisc(SurfacePoint::AtVertex(0), std::nan("")).Ok());
  EXPECT_FALSE(covering.ComputeCoveringDisc(SurfacePoint::AtVertex(0), -1.0).Ok());
  EXPECT_TRUE(covering.Inside().empty());
  EXPECT_LT(10 * smallEntries, boundEntries) << smallEntries << " against " << boundEntries;
  std::cout << "covering maps: " << smallEntries << " vertices against " << boundEntries
            << " out to the longest edge; " << disc << " disc points read alike\n";
}

// A chart over the whole of a large surface (ExactInPartsMinimumFaces faces or more) is solved
// by the exact engine in parts on threads: the same rho (to 1e-12 of the largest) and theta (to
// 1e-9, modulo a turn) as the serial solve, which a piece of a partitioned surface (a length
// scale given) keeps, and the same iso-curve angles; a chart of a small radius stays serial on
// any surface.
TEST(GeodesicPolarCoordinates, WholeChartsOfLargeSurfacesAreSolvedInParts)
{
  // (Jittered: on a symmetric torus whole lines of vertices have two shortest paths, and which
  // one a solve keeps is a matter of rounding.)
  TriangleSoup soup = MakeTorus(1.0, 0.35, 400, 130);
  std::mt19937 random(5);
  std::uniform_real_distribution<double> jitter(-1e-3, 1e-3);
  for (Vec3& p : soup.Points)
  {
    p = p + Vec3(jitter(random), jitter(random), jitter(random));
  }
  const TriangleMesh torus = BuildMesh(soup);
  ASSERT_GE(torus.NumberOfFaces(), ExactInPartsMinimumFaces);
  GeodesicPolarCoordinates parts(torus), serial(torus, nullptr, torus.BoundingBoxDiagonal());
  for (const SurfacePoint& source : { SurfacePoint::AtVertex(77), SurfacePoint::InFace(5000, 0.2, 0.3, 0.5) })
  {
    ASSERT_TRUE(gs_test::Succeeded(parts.Compute(source, std::numeric_limits<double>::infinity(), 0.4)));
    ASSERT_TRUE(gs_test::Succeeded(serial.Compute(source, std::numeric_limits<double>::infinity(), 0.4)));
    ASSERT_EQ(parts.Inside().size(), serial.Inside().size());
    double largest = 0.0, worstRho = 0.0, worstTheta = 0.0;
    for (int v = 0; v < torus.NumberOfVertices(); ++v)
    {
      largest = std::max(largest, serial.Rho(v));
      worstRho = std::max(worstRho, std::abs(parts.Rho(v) - serial.Rho(v)));
      const double dt = std::abs(std::remainder(parts.Theta(v) - serial.Theta(v), 2.0 * M_PI));
      worstTheta = std::max(worstTheta, dt);
    }
    EXPECT_LE(worstRho, 1e-12 * largest);
    EXPECT_LE(worstTheta, 1e-9);
  }
  // Iso-curve angles read the distances beyond the chart from the solve in parts too.
  const SurfacePoint source = SurfacePoint::AtVertex(77);
  ASSERT_TRUE(gs_test::Succeeded(parts.Compute(source, 2.0, 0.4)));
  ASSERT_TRUE(gs_test::Succeeded(serial.Compute(source, 2.0, 0.4)));
  const Result<int> keptParts = parts.UseIsoCurveAngles(), keptSerial = serial.UseIsoCurveAngles();
  ASSERT_TRUE(keptParts.Ok() && keptSerial.Ok());
  EXPECT_EQ(*keptParts, *keptSerial);
  double worstIso = 0.0;
  for (int v = 0; v < torus.NumberOfVertices(); ++v)
  {
    if (std::isfinite(serial.Theta(v)))
    {
      worstIso = std::max(worstIso, std::abs(std::remainder(parts.Theta(v) - serial.Theta(v), 2.0 * M_PI)));
    }
  }
  EXPECT_LE(worstIso, 1e-9);
  ASSERT_TRUE(gs_test::Succeeded(parts.Compute(SurfacePoint::AtVertex(77), 0.1)));
  ASSERT_TRUE(gs_test::Succeeded(serial.Compute(SurfacePoint::AtVertex(77), 0.1)));
  EXPECT_EQ(parts.Inside(), serial.Inside()); // (the serial solver's order: the same solve)
}
