#include "ExactGeodesic.h"
#include "GeodesicShooting.h"
#include "MeshGenerators.h"
#include "TriangleMesh.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace gs;
using gs_test::BuildMesh;

namespace
{
// Forward (exact log map: distance and departure angle) then inverse (shooting) must return to
// every vertex whose geodesic passes through no vertex.
void CheckRoundTrip(const TriangleMesh& m, const SurfacePoint& source, double radius, int minChecked)
{
  ExactGeodesicSolver exact(m);
  ExactGeodesicOptions opt;
  opt.MaximumDistance = radius;
  ASSERT_TRUE(gs_test::Succeeded(exact.Solve({ source }, opt)));
  int checked = 0;
  double worst = 0;
  for (int v : exact.FinalVertices())
  {
    if (!exact.IsDirect(v) || exact.Distance(v) < 1e-9)
      continue;
    const GeodesicShot shot = ShootGeodesic(m, source, exact.DepartureAngle(v), exact.Distance(v));
    EXPECT_FALSE(shot.ReachedBoundary && shot.Length < exact.Distance(v) * (1 - 1e-9));
    worst = std::max(worst, Norm(m.Position(shot.End) - m.Position(v)));
    ++checked;
  }
  EXPECT_GE(checked, minChecked);
  EXPECT_LT(worst, 1e-6 * m.MeanEdgeLength());
}
} // namespace

TEST(GeodesicShooting, StraightLinesOnAPlane)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(10, 10, 1.0, 1.0));
  const SurfacePoint p = SurfacePoint::InFace(88, 0.2, 0.3, 0.5); // near the centre
  const Vec3 start = m.Position(p);
  const Vec3 e0 = m.Position(m.Face(88)[1]) - m.Position(m.Face(88)[0]);
  const double a0 = std::atan2(e0.y, e0.x);
  for (double a : { 0.1, 1.0, 2.5, -2.0 })
  {
    const GeodesicShot shot = ShootGeodesic(m, p, a, 0.3);
    const Vec3 expected = start + Vec3(std::cos(a + a0), std::sin(a + a0), 0) * 0.3;
    EXPECT_NEAR(Norm(m.Position(shot.End) - expected), 0.0, 1e-12);
    EXPECT_NEAR(shot.Length, 0.3, 1e-12);
    EXPECT_GT(shot.Pieces.size(), 1u);
  }
  // Walking off the square stops at its boundary.
  const GeodesicShot out = ShootGeodesic(m, p, 0.3, 5.0);
  EXPECT_TRUE(out.ReachedBoundary);
  EXPECT_LT(out.Length, 1.5);
}

TEST(GeodesicShooting, InvertsTheExactLogMap)
{
  CheckRoundTrip(BuildMesh(MakeCylinder(1.0, 3.0, 24, 12)), SurfacePoint::AtVertex(24 * 6 + 5), 2.0, 100);
  CheckRoundTrip(BuildMesh(MakeCone(0.5, 2.0, 10, 24)), SurfacePoint::InFace(100, 0.3, 0.3, 0.4), 1.5, 50);
  TriangleSoup s = MakeIcosphere(1.0, 3);
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.95, 1.05);
  for (Vec3& p : s.Points)
    p = p * u(rng);
  const TriangleMesh bumpy = BuildMesh(s);
  CheckRoundTrip(bumpy, SurfacePoint::AtVertex(17), 0.8, 10);
  CheckRoundTrip(bumpy, SurfacePoint::InFace(400, 0.25, 0.5, 0.25), 0.8, 10);
}

TEST(GeodesicShooting, TangentAnglesMatchDepartureAngles)
{
  const TriangleMesh m = BuildMesh(MakeTorus(2.0, 0.7, 24, 12));
  ExactGeodesicSolver exact(m);
  const int source = 50;
  EXPECT_TRUE(gs_test::Succeeded(exact.Solve(source)));
  for (int h : m.OutgoingHalfedges(source))
  {
    const int v = m.Destination(h);
    if (!exact.IsDirect(v))
      continue;
    const double a = TangentAngle(m, SurfacePoint::AtVertex(source), m.Position(v) - m.Position(source));
    EXPECT_NEAR(a, exact.DepartureAngle(v), 1e-9);
  }
  // Normal directions have no tangent angle.
  const SurfacePoint fp = SurfacePoint::InFace(3, 0.3, 0.3, 0.4);
  EXPECT_TRUE(std::isnan(TangentAngle(m, fp, m.FaceNormal(3))));
  const Vec3 e0 = m.Position(m.Face(3)[1]) - m.Position(m.Face(3)[0]);
  EXPECT_NEAR(TangentAngle(m, fp, e0), 0.0, 1e-12);
}
