// Geodesic triangle unfolding set up once per face (FaceUnfolding, FacePolarCoordinates) against
// the plain per-point computation, bit for bit, and NormExceeds against the norm it stands for.
#include "GeodesicPolarCoordinates.h"
#include "GeodesicUnfolding.h"
#include "TestMeshes.h"
#include "TestStatus.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

using namespace gs;
using gs_test::BuildMesh;

namespace
{
bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

// GTU written plainly, one point at a time: every corner and edge candidate computed in full
// (the definition FaceUnfolding must reproduce, whatever it sets up once or skips).
UnfoldedTriangle PlainUnfolding(
  const TriangleMesh& mesh, int f, const std::array<double, 3>& bary, const std::array<double, 3>& d)
{
  const double l01 = mesh.EdgeLength(3 * f), l02 = mesh.EdgeLength(3 * f + 2);
  const double a0 = mesh.CornerAngle(3 * f);
  const Vec2 P[3] = { Vec2(0.0, 0.0), Vec2(l01, 0.0), Vec2(l02 * std::cos(a0), l02 * std::sin(a0)) };
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
    const double candidate = d[i] + Norm(q - P[i]);
    if (std::isfinite(d[i]) && candidate < best)
    {
      best = candidate;
      out.Source = P[i];
    }
  }
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
      n = n * -1.0;
    }
    const double x = (d[i] * d[i] - d[j] * d[j] + L * L) / (2.0 * L);
    const double y2 = d[i] * d[i] - x * x;
    if (y2 < 0.0)
    {
      continue;
    }
    const Vec2 s = P[i] + u * x + n * std::sqrt(y2);
    const Vec2 sq = q - s;
    const double den = Cross(sq, e);
    if (std::abs(den) < 1e-300)
    {
      continue;
    }
    const double t = Cross(P[i] - s, sq) / den;
    if (t < -1e-9 || t > 1.0 + 1e-9 || !(Norm(sq) < best))
    {
      continue;
    }
    best = Norm(sq);
    out.Source = s;
    out.FromEdge = true;
    out.Edge = i;
  }
  out.Distance = best;
  return out;
}
} // namespace

// Corner distances from a point off the surface (consistent geodesic triangles), perturbed ones
// (some violating the triangle inequality), ties and infinite corners; many points per face.
TEST(GeodesicUnfolding, FaceUnfoldingIsThePlainUnfoldingBitForBit)
{
  const TriangleMesh m = BuildMesh(gs_test::BumpySoup(2, 3, 0.1));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double inf = std::numeric_limits<double>::infinity();
  int fromEdge = 0, fromCorner = 0;
  for (int f = 0; f < m.NumberOfFaces(); ++f)
  {
    const auto& t = m.Face(f);
    const Vec3 s = Vec3(2.0 * u(rng) - 1.0, 2.0 * u(rng) - 1.0, 2.0 * u(rng) - 1.0) * 2.0;
    std::array<double, 3> d{ { Norm(m.Position(t[0]) - s), Norm(m.Position(t[1]) - s),
      Norm(m.Position(t[2]) - s) } };
    switch (f % 5)
    {
      case 1: // perturbed
        for (double& x : d)
        {
          x *= 0.9 + 0.2 * u(rng);
        }
        break;
      case 2: // a tie
        d[1] = d[0];
        break;
      case 3: // one corner beyond reach
        d[f % 3] = inf;
        break;
      case 4: // two corners beyond reach
        d[f % 3] = d[(f + 1) % 3] = inf;
        break;
      default:
        break;
    }
    const FaceUnfolding once(m, f, d);
    for (int i = 0; i < 40; ++i)
    {
      double a = u(rng), b = u(rng);
      if (a + b > 1.0)
      {
        a = 1.0 - a;
        b = 1.0 - b;
      }
      const std::array<double, 3> bary = i == 0 ? std::array<double, 3>{ { 1.0, 0.0, 0.0 } }
                                                : std::array<double, 3>{ { 1.0 - a - b, a, b } };
      const UnfoldedTriangle x = once.At(bary), y = PlainUnfolding(m, f, bary, d);
      ASSERT_TRUE(SameBits(x.Distance, y.Distance)) << "face " << f << " point " << i;
      ASSERT_EQ(x.FromEdge, y.FromEdge) << "face " << f << " point " << i;
      ASSERT_EQ(x.Edge, y.Edge) << "face " << f << " point " << i;
      ASSERT_TRUE(SameBits(x.Source.x, y.Source.x) && SameBits(x.Source.y, y.Source.y));
      (x.FromEdge ? fromEdge : fromCorner) += 1;
    }
  }
  EXPECT_GT(fromEdge, 1000);
  EXPECT_GT(fromCorner, 1000);
}

// One FacePolarCoordinates read at many points in any order (its edge offsets filled as they are
// needed) gives what PolarAt gives point by point, for the engine and its snapshot.
TEST(GeodesicUnfolding, FaceCoordinatesReadAsPolarAtEverywhere)
{
  const TriangleMesh m = BuildMesh(gs_test::BumpySoup(3, 5, 0.05));
  GeodesicPolarCoordinates pc(m);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const SurfacePoint& source : { SurfacePoint::InFace(9, 0.2, 0.3, 0.5), SurfacePoint::AtVertex(17) })
  {
    ASSERT_TRUE(gs_test::Succeeded(pc.Compute(source, 0.7, 0.3)));
    const LogMapSnapshot snapshot = pc.Snapshot();
    int inside = 0, outside = 0;
    for (int f = 0; f < m.NumberOfFaces(); ++f)
    {
      const FacePolarCoordinates byEngine = pc.OnFace(f), bySnapshot = snapshot.OnFace(m, f);
      ASSERT_EQ(byEngine.Face(), f);
      for (int i = 0; i < 12; ++i)
      {
        double a = u(rng), b = u(rng);
        if (a + b > 1.0)
        {
          a = 1.0 - a;
          b = 1.0 - b;
        }
        const std::array<double, 3> bary{ { 1.0 - a - b, a, b } };
        Vec2 p, q, r;
        const bool one = pc.LogMapAt(SurfacePoint::InFace(f, bary[0], bary[1], bary[2]), p);
        ASSERT_EQ(byEngine.LogMapAt(bary, q), one);
        ASSERT_EQ(bySnapshot.LogMapAt(bary, r), one);
        (one ? inside : outside) += 1;
        if (one)
        {
          ASSERT_TRUE(SameBits(p.x, q.x) && SameBits(p.y, q.y)) << "face " << f;
          ASSERT_TRUE(SameBits(p.x, r.x) && SameBits(p.y, r.y)) << "face " << f;
        }
      }
    }
    EXPECT_GT(inside, 1000);
    EXPECT_GT(outside, 1000);
  }
  // After a curve's coordinates, no point has polar coordinates.
  ASSERT_TRUE(gs_test::Succeeded(pc.ComputeCurve({ SurfacePoint::AtVertex(11), SurfacePoint::AtVertex(12) }, 0.5)));
  Vec2 p;
  EXPECT_FALSE(pc.OnFace(0).LogMapAt({ { 0.3, 0.3, 0.4 } }, p));
  EXPECT_FALSE(FacePolarCoordinates().LogMapAt({ { 0.3, 0.3, 0.4 } }, p));
}

// NormExceeds(a, bound, scale) is Norm(a) * scale > bound: at random, within rounding of the
// bound on either side, and at zero, subnormal, huge, infinite and NaN lengths and bounds.
TEST(GeodesicUnfolding, NormExceedsDecidesAsTheNorm)
{
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0, near = 0;
  for (int i = 0; i < 200000; ++i)
  {
    const Vec2 a(u(rng) * std::pow(10.0, 6.0 * u(rng)), u(rng) * std::pow(10.0, 6.0 * u(rng)));
    const double scale = i % 3 == 0 ? 1.0 : std::pow(10.0, 3.0 * u(rng));
    double bound = Norm(a) * scale;
    // Within a few units in the last place of the bound, or farther.
    const int ulps = static_cast<int>(8.0 * u(rng));
    for (int k = 0; k < std::abs(ulps); ++k)
    {
      bound = std::nextafter(bound, ulps > 0 ? 1e308 : 0.0);
    }
    if (i % 4 == 0)
    {
      bound *= 1.0 + 1e-6 * u(rng);
    }
    near += std::abs(ulps) <= 2 ? 1 : 0;
    ASSERT_EQ(NormExceeds(a, bound, scale), Norm(a) * scale > bound)
      << a.x << " " << a.y << " " << scale << " " << bound;
    ++checked;
  }
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  const double tiny = std::numeric_limits<double>::denorm_min();
  for (const Vec2& a : { Vec2(0.0, 0.0), Vec2(tiny, 0.0), Vec2(1e-200, 1e-200), Vec2(1e200, 1e200),
         Vec2(inf, 0.0), Vec2(nan, 1.0), Vec2(3.0, 4.0) })
  {
    for (double bound : { 0.0, tiny, 1e-200, 5.0, 1e300, inf, nan, -1.0 })
    {
      EXPECT_EQ(NormExceeds(a, bound), Norm(a) > bound) << a.x << " " << a.y << " " << bound;
    }
  }
  // Squares that overflow or fall below the normal range, alone or in the product.
  EXPECT_EQ(NormExceeds(Vec2(3e-162, 0.0), 3.05e-12, 1e150), Norm(Vec2(3e-162, 0.0)) * 1e150 > 3.05e-12);
  EXPECT_EQ(NormExceeds(Vec2(1e155, 0.0), 1e150, 1e-10), Norm(Vec2(1e155, 0.0)) * 1e-10 > 1e150);
  EXPECT_EQ(NormExceeds(Vec2(1e-150, 0.0), 1e51, 1e200), Norm(Vec2(1e-150, 0.0)) * 1e200 > 1e51);
  EXPECT_EQ(checked, 200000);
  EXPECT_GT(near, 20000);
}
