// Minimum safe distance tables and silhouettes: analytic cases (disk, square), conservativeness
// against an independent exact overlap test (ShapeOverlapOracle.h), tightness, image reading,
// polygons, long-shape splitting, multi-class tables, determinism and errors.
#include "MeshGenerators.h"
#include "SafeDistanceTable.h"
#include "ShapeOverlapOracle.h"
#include "Silhouette.h"
#include "TestStatus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace gs;

namespace
{
constexpr double Pi = 3.14159265358979323846;

std::string TempFile(const std::string& name)
{
  return ::testing::TempDir() + "/gs_msdt_" + name;
}

std::vector<Vec2> RegularPolygon(int n, double radius, double phase = 0.0)
{
  std::vector<Vec2> ring;
  for (int k = 0; k < n; ++k)
  {
    const double a = phase + 2.0 * Pi * k / n;
    ring.emplace_back(radius * std::cos(a), radius * std::sin(a));
  }
  return ring;
}

std::vector<Vec2> StarPolygon(int points, double outer, double inner, Vec2 centre = {})
{
  std::vector<Vec2> ring = MakeStarPolygon(points, outer, inner);
  for (Vec2& p : ring)
    p = p + centre;
  return ring;
}

SilhouetteMask DiskMask(int size, double radius)
{
  SilhouetteMask m;
  m.Width = m.Height = size;
  m.Inside.assign(static_cast<std::size_t>(size) * size, 0);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      m.Inside[static_cast<std::size_t>(y) * size + x] =
        std::hypot(x + 0.5 - size / 2.0, y + 0.5 - size / 2.0) <= radius;
  return m;
}

// A star rasterized at `size` pixels: the pixel shape used for conservativeness tests.
Shape2D PixelStar(int size)
{
  const Shape2D star = ShapeFromPolygons({ StarPolygon(5, 0.48 * size, 0.2 * size,
    { 0.5 * size, 0.5 * size }) });
  return ShapeFromMask(RasterizeShape(star, size, size, { 0.0, 0.0 }, 1.0));
}

// Right extent of a convex polygon at height y (-inf when the line misses it); left extent.
void Extents(const std::vector<Vec2>& poly, double y, double& left, double& right)
{
  left = 1e300;
  right = -1e300;
  for (std::size_t k = 0; k < poly.size(); ++k)
  {
    const Vec2 a = poly[k], b = poly[(k + 1) % poly.size()];
    if ((a.y - y) * (b.y - y) > 0)
      continue;
    double x0, x1;
    if (a.y == b.y)
    {
      x0 = std::min(a.x, b.x);
      x1 = std::max(a.x, b.x);
    }
    else
      x0 = x1 = a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x);
    left = std::min(left, x0);
    right = std::max(right, x1);
  }
}

std::vector<Vec2> Rotated(const std::vector<Vec2>& poly, double a)
{
  std::vector<Vec2> out;
  for (const Vec2& p : poly)
    out.emplace_back(std::cos(a) * p.x - std::sin(a) * p.y, std::sin(a) * p.x + std::cos(a) * p.y);
  return out;
}

// Exact translation distance of two convex polygons along x: the maximum of
// right_A(y) - left_B(y) is reached at a vertex height of A or B.
double ConvexSafeDistance(const std::vector<Vec2>& A, const std::vector<Vec2>& B)
{
  double D = -1e300;
  std::vector<double> ys;
  for (const Vec2& p : A)
    ys.push_back(p.y);
  for (const Vec2& p : B)
    ys.push_back(p.y);
  for (double y : ys)
  {
    double la, ra, lb, rb;
    Extents(A, y, la, ra);
    Extents(B, y, lb, rb);
    if (ra > -1e299 && lb < 1e299)
      D = std::max(D, ra - lb);
  }
  return D;
}

std::vector<std::vector<Vec2>> RingsAround(const Shape2D& shape, const Vec2& centre)
{
  std::vector<std::vector<Vec2>> rings = shape.Rings;
  for (auto& ring : rings)
    for (auto& p : ring)
      p = p - centre;
  return rings;
}

// Random probes of table (a, b): angles anywhere in their bins, d >= the table value.
long long CountOverlaps(const SafeDistanceTables& T, int a, int b, const gs_test::OverlapOracle& A,
  const gs_test::OverlapOracle& B, int probes, unsigned seed)
{
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double w = T.BinWidth();
  long long overlaps = 0;
  for (int k = 0; k < probes; ++k)
  {
    const int i = static_cast<int>(unit(random) * T.AngleBins) % T.AngleBins;
    const int j = static_cast<int>(unit(random) * T.AngleBins) % T.AngleBins;
    const double aA = (i + unit(random) - 0.5) * w, aB = (j + unit(random) - 0.5) * w;
    const double d0 = T.Value(a, b, i, j);
    const double dmax = T.Parts[a].Radius + T.Parts[b].Radius;
    const double d = k % 2 == 0 ? d0 : d0 + unit(random) * (dmax - d0);
    overlaps += A.Overlaps(aA, B, aB, d);
  }
  return overlaps;
}

double Mean(const std::vector<double>& v)
{
  double s = 0;
  for (double x : v)
    s += x;
  return s / v.size();
}
} // namespace

TEST(SafeDistanceTable, SmallestEnclosingCircleMatchesBruteForce)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial)
  {
    std::vector<Vec2> pts;
    for (int k = 0; k < 25; ++k)
      pts.emplace_back(u(random), 0.5 * u(random));
    const Circle c = SmallestEnclosingCircle(pts);
    for (const Vec2& p : pts)
      EXPECT_LE(Norm(p - c.Centre), c.Radius * (1 + 1e-12));
    // Brute force: the smallest circle through 2 or 3 points enclosing all.
    double best = 1e300;
    auto consider = [&](Vec2 centre) {
      double r = 0;
      for (const Vec2& p : pts)
        r = std::max(r, Norm(p - centre));
      best = std::min(best, r);
    };
    for (std::size_t i = 0; i < pts.size(); ++i)
      for (std::size_t j = i + 1; j < pts.size(); ++j)
      {
        consider((pts[i] + pts[j]) * 0.5);
        for (std::size_t k = j + 1; k < pts.size(); ++k)
        {
          const Vec2 a = pts[i], ab = pts[j] - a, ac = pts[k] - a;
          const double d = 2 * Cross(ab, ac);
          if (std::abs(d) < 1e-12)
            continue;
          consider({ a.x + (ac.y * Dot(ab, ab) - ab.y * Dot(ac, ac)) / d,
            a.y + (ab.x * Dot(ac, ac) - ac.x * Dot(ab, ab)) / d });
        }
      }
    EXPECT_NEAR(c.Radius, best, 1e-12);
  }
}

TEST(Silhouette, MaskContoursAreExactPixelBoundaries)
{
  std::mt19937 random(3);
  SilhouetteMask m;
  m.Width = 40;
  m.Height = 30;
  m.Inside.resize(40 * 30);
  for (auto& v : m.Inside)
    v = random() % 3 == 0; // blobs, holes, diagonal contacts
  const Shape2D shape = ShapeFromMask(m);
  EXPECT_DOUBLE_EQ(shape.Area(), static_cast<double>(m.Count()));
  for (int y = 0; y < m.Height; ++y)
    for (int x = 0; x < m.Width; ++x)
      ASSERT_EQ(shape.Contains({ x + 0.5, y + 0.5 }), m.At(x, y)) << x << "," << y;
  // Collinear pixel edges are merged: a filled rectangle has 4 corners.
  SilhouetteMask r;
  r.Width = 10;
  r.Height = 6;
  r.Inside.assign(60, 0);
  for (int y = 1; y < 5; ++y)
    for (int x = 2; x < 9; ++x)
      r.Inside[y * 10 + x] = 1;
  const Shape2D rect = ShapeFromMask(r);
  ASSERT_EQ(rect.Rings.size(), 1u);
  EXPECT_EQ(rect.Rings[0].size(), 4u);
  EXPECT_DOUBLE_EQ(rect.Area(), 28.0);
}

TEST(Silhouette, ReadsAlphaAndLuminanceImages)
{
  const SilhouetteMask disk = DiskMask(64, 20.0);
  const std::string rgba = TempFile("disk_rgba.png"), grey = TempFile("disk_grey.png");
  ASSERT_TRUE(gs_test::Succeeded(WriteSilhouetteImage(disk, rgba, true)));
  ASSERT_TRUE(gs_test::Succeeded(WriteSilhouetteImage(disk, grey, false)));
  for (const std::string& file : { rgba, grey })
  {
    const Result<SilhouetteImage> read = ReadSilhouetteImage(file);
    ASSERT_TRUE(read.Ok()) << read.Message();
    EXPECT_EQ(read->FromAlpha, file == rgba);
    EXPECT_EQ(read->Mask.Inside, disk.Inside);
  }
  // y is up: a mask with only its bottom row set reads back the same (not flipped).
  SilhouetteMask bottom;
  bottom.Width = 8;
  bottom.Height = 4;
  bottom.Inside.assign(32, 0);
  for (int x = 0; x < 8; ++x)
    bottom.Inside[x] = 1;
  ASSERT_TRUE(gs_test::Succeeded(WriteSilhouetteImage(bottom, TempFile("bottom.tif"), true)));
  const Result<SilhouetteImage> b = ReadSilhouetteImage(TempFile("bottom.tif"));
  ASSERT_TRUE(b.Ok()) << b.Message();
  EXPECT_TRUE(b->Mask.At(3, 0));
  EXPECT_FALSE(b->Mask.At(3, 3));
  // Thresholds: half-transparent pixels.
  const float pixels[] = { 0, 0, 0, 0.3f, 0, 0, 0, 0.7f };
  const Result<SilhouetteImage> half = MakeSilhouette(pixels, 2, 1, 4, 3, { 0.5, 0.5 });
  ASSERT_TRUE(half.Ok()) << half.Message();
  EXPECT_FALSE(half->Mask.At(0, 0));
  EXPECT_TRUE(half->Mask.At(1, 0));
  EXPECT_FALSE(MakeSilhouette(pixels, 2, 1, 4, 3, { 0.2, 0.5 }).Ok()); // all opaque
  const float grey2[] = { 0.2f, 0.8f };
  const Result<SilhouetteImage> l = MakeSilhouette(grey2, 2, 1, 1, -1, { 0.5, 0.5 });
  ASSERT_TRUE(l.Ok()) << l.Message();
  EXPECT_TRUE(l->Mask.At(0, 0));
  EXPECT_FALSE(l->Mask.At(1, 0));
}

TEST(Silhouette, ImageErrorsAreClear)
{
  Result<SilhouetteImage> r = ReadSilhouetteImage(TempFile("does_not_exist.png"));
  EXPECT_FALSE(r.Ok());
  EXPECT_NE(r.Message().find("cannot read"), std::string::npos) << r.Message();
  {
    std::ofstream garbage(TempFile("garbage.png"), std::ios::binary);
    garbage << "this is not an image";
  }
  r = ReadSilhouetteImage(TempFile("garbage.png"));
  EXPECT_FALSE(r.Ok());
  EXPECT_FALSE(r.Message().empty());
  SilhouetteMask none;
  none.Width = none.Height = 8;
  none.Inside.assign(64, 0);
  ASSERT_TRUE(gs_test::Succeeded(WriteSilhouetteImage(none, TempFile("transparent.png"), true)));
  r = ReadSilhouetteImage(TempFile("transparent.png"));
  EXPECT_FALSE(r.Ok());
  EXPECT_NE(r.Message().find("all transparent"), std::string::npos) << r.Message();
  SilhouetteMask all = none;
  all.Inside.assign(64, 1);
  ASSERT_TRUE(gs_test::Succeeded(WriteSilhouetteImage(all, TempFile("opaque.png"), true)));
  r = ReadSilhouetteImage(TempFile("opaque.png"));
  EXPECT_FALSE(r.Ok());
  EXPECT_NE(r.Message().find("all opaque"), std::string::npos) << r.Message();
  ASSERT_TRUE(gs_test::Succeeded(WriteSilhouetteImage(all, TempFile("dark.png"), false)));
  r = ReadSilhouetteImage(TempFile("dark.png"));
  EXPECT_FALSE(r.Ok());
  EXPECT_NE(r.Message().find("all dark"), std::string::npos) << r.Message();
  EXPECT_FALSE(MakeSilhouette(nullptr, 0, 0, 4, 3).Ok());
}

TEST(SafeDistanceTable, DiskIsConstantTwo)
{
  const Result<SafeDistanceTables> r =
    ComputeSafeDistanceTables({ { "disk", ShapeFromMask(DiskMask(100, 40.0)) } });
  ASSERT_TRUE(r.Ok()) << r.Message();
  const SafeDistanceTables& T = *r;
  ASSERT_EQ(T.NumberOfPairs(), 1);
  EXPECT_DOUBLE_EQ(T.Classes[0].Radius, 1.0);
  EXPECT_NEAR(T.Scale, 40.0, 1.0);
  const double step = T.Step(0, 0);
  EXPECT_DOUBLE_EQ(step, 2.0 / 64);
  for (double v : T.Values)
  {
    EXPECT_LE(v, 2.0);
    EXPECT_GE(v, 2.0 - step - 1e-12);
  }
}

TEST(SafeDistanceTable, SquareMatchesAnalyticDistances)
{
  // A square of side 2 (circumradius sqrt 2). Exact values over each bin: the analytic
  // distance sampled densely over the bin (the table must cover the whole bin).
  const std::vector<Vec2> square{ { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } };
  SafeDistanceOptions options;
  options.AngleBins = 32;
  options.DistanceSteps = 48;
  const Result<SafeDistanceTables> r =
    ComputeSafeDistanceTables({ { "square", ShapeFromPolygons({ square }) } }, options);
  ASSERT_TRUE(r.Ok()) << r.Message();
  const SafeDistanceTables& T = *r;
  EXPECT_NEAR(T.Scale, std::sqrt(2.0), 1e-12);
  const double s = 1.0 / std::sqrt(2.0);
  const std::vector<Vec2> unit{ { -s, -s }, { s, -s }, { s, s }, { -s, s } };
  const double step = T.Step(0, 0), w = T.BinWidth();
  int exactBins = 0;
  for (int j = 0; j < T.AngleBins; ++j)
    for (int i = 0; i < T.AngleBins; ++i)
    {
      double binMax = -1e300;
      const int n = 8;
      for (int p = 0; p <= n; ++p)
        for (int q = 0; q <= n; ++q)
          binMax = std::max(binMax,
            ConvexSafeDistance(Rotated(unit, (i - 0.5 + double(p) / n) * w),
              Rotated(unit, (j - 0.5 + double(q) / n) * w)));
      const double value = T.Value(0, 0, i, j);
      const double rounded = std::ceil(binMax / step - 1e-9) * step;
      EXPECT_GE(value, binMax - 1e-12) << i << " " << j;
      EXPECT_LE(value, rounded + step + 1e-9) << i << " " << j; // within one step
      exactBins += std::abs(value - rounded) < 1e-9;
      // The sampled-angle analytic value at the bin centre never exceeds the table.
      EXPECT_GE(value, ConvexSafeDistance(Rotated(unit, i * w), Rotated(unit, j * w)) - 1e-12);
    }
  EXPECT_GE(exactBins, T.AngleBins * T.AngleBins / 2); // most bins: no excess at all
  // Faces parallel to the joining line: d = side = 2 / sqrt 2 in normalized units.
  SafeDistanceOptions plain = options;
  plain.Conservative = false;
  const Result<SafeDistanceTables> p =
    ComputeSafeDistanceTables({ { "square", ShapeFromPolygons({ square }) } }, plain);
  ASSERT_TRUE(p.Ok());
  EXPECT_NEAR(p->Value(0, 0, 0, 0), std::sqrt(2.0), step);
  // Corner against corner (both at 45 degrees): d = 2 (the circles touch).
  EXPECT_NEAR(p->Value(0, 0, 4, 4), 2.0, step);
}

TEST(SafeDistanceTable, ConservativeAndTightOnPixelStar)
{
  const Shape2D star = PixelStar(128);
  const Result<SafeDistanceTables> r = ComputeSafeDistanceTables({ { "star", star } });
  ASSERT_TRUE(r.Ok()) << r.Message();
  const SafeDistanceTables& T = *r;
  ASSERT_EQ(T.NumberOfParts(), 1);
  const gs_test::OverlapOracle oracle(RingsAround(T.Classes[0].Outline, { 0, 0 }), T.Parts[0].Radius);
  EXPECT_EQ(CountOverlaps(T, 0, 0, oracle, oracle, 40000, 11), 0);

  SafeDistanceOptions plainOptions;
  plainOptions.Conservative = false;
  const Result<SafeDistanceTables> p = ComputeSafeDistanceTables({ { "star", star } }, plainOptions);
  ASSERT_TRUE(p.Ok());
  const double ratio = Mean(T.Values) / Mean(p->Values);
  EXPECT_GE(ratio, 1.0);
  EXPECT_LE(ratio, 1.05);
  // The oracle is not blind: well below the sampled-angle value, bin-centre copies overlap.
  int overlaps = 0, tested = 0;
  const double w = T.BinWidth();
  for (int i = 0; i < T.AngleBins; i += 4)
    for (int j = 0; j < T.AngleBins; j += 4)
    {
      const double d = p->Value(0, 0, i, j) - 1.5 * T.Step(0, 0);
      if (d > 0)
      {
        ++tested;
        overlaps += oracle.Overlaps(i * w, oracle, j * w, d);
      }
    }
  EXPECT_GE(overlaps, tested * 9 / 10);
  // Shape inside the other: the star centred on another star's centre always overlaps.
  EXPECT_TRUE(oracle.Overlaps(0.3, oracle, 1.1, 0.0));
}

TEST(SafeDistanceTable, PolygonsWithHolesAndOrientation)
{
  // Clockwise outer ring and counter-clockwise hole: re-oriented by nesting depth.
  std::vector<Vec2> outer = RegularPolygon(4, 2.0, Pi / 4);
  std::reverse(outer.begin(), outer.end());
  const std::vector<Vec2> hole = RegularPolygon(4, 1.0, Pi / 4);
  const Shape2D frame = ShapeFromPolygons({ outer, hole });
  ASSERT_EQ(frame.Rings.size(), 2u);
  EXPECT_NEAR(frame.Area(), 8.0 - 2.0, 1e-12);
  EXPECT_FALSE(frame.Contains({ 0, 0 }));
  EXPECT_TRUE(frame.Contains({ 1.2, 0 }));
  // A small square in the frame's hole still counts as overlapping: the table is beyond it.
  const Shape2D small = ShapeFromPolygons({ RegularPolygon(4, 0.3, Pi / 4) });
  const Result<SafeDistanceTables> r = ComputeSafeDistanceTables({ { "frame", frame }, { "small", small } });
  ASSERT_TRUE(r.Ok()) << r.Message();
  const SafeDistanceTables& T = *r;
  ASSERT_EQ(T.NumberOfPairs(), 4);
  EXPECT_NEAR(T.Classes[1].Radius, 0.15, 1e-12);
  // Both axis-aligned (bin 0): d >= frame half-width + small half-width (normalized by the
  // frame's radius 2), even though the small square would also fit in the hole.
  const double D = std::sqrt(2.0) / 2.0 + 0.15 / std::sqrt(2.0);
  EXPECT_GE(T.Value(0, 1, 0, 0), D - 1e-9);
  EXPECT_LE(T.Value(0, 1, 0, 0), D + 2 * T.Step(0, 1) + 1e-9);
  // Swapping the roles: table(b, a)[j + ka/2][i + ka/2] describes the same configuration.
  const int ka = T.AngleBins;
  for (int i = 0; i < ka; i += 5)
    for (int j = 0; j < ka; j += 7)
      EXPECT_NEAR(T.Value(0, 1, i, j), T.Value(1, 0, (j + ka / 2) % ka, (i + ka / 2) % ka),
        T.Step(0, 1) + 1e-9);
  // Oracles in normalized units for the probes.
  const gs_test::OverlapOracle An(RingsAround(T.Classes[0].Outline, T.Parts[0].Centre), T.Parts[0].Radius);
  const gs_test::OverlapOracle Bn(RingsAround(T.Classes[1].Outline, T.Parts[1].Centre), T.Parts[1].Radius);
  EXPECT_FALSE(An.Overlaps(0.0, Bn, 0.0, 0.0)); // in the hole: no overlap, yet d < table
  EXPECT_TRUE(An.Overlaps(0.0, Bn, 0.0, 0.53));  // inside the frame's band: contained
  EXPECT_TRUE(Bn.Overlaps(0.0, An, 0.0, -0.53));
  EXPECT_EQ(CountOverlaps(T, 0, 1, An, Bn, 20000, 5), 0);
  EXPECT_EQ(CountOverlaps(T, 1, 0, Bn, An, 20000, 6), 0);
  EXPECT_EQ(CountOverlaps(T, 1, 1, Bn, Bn, 5000, 7), 0);
}

TEST(SafeDistanceTable, PolygonsFollowTheEvenOddRule)
{
  // The filled (even-odd) area against pixel counts of the same region: random masks' exact
  // contours (no crossings: equal to the signed area).
  {
    std::mt19937 random(3);
    SilhouetteMask m;
    m.Width = 40;
    m.Height = 30;
    m.Inside.resize(40 * 30);
    for (auto& v : m.Inside)
      v = random() % 3 == 0;
    const Shape2D shape = ShapeFromMask(m);
    EXPECT_NEAR(shape.FilledArea(), static_cast<double>(m.Count()), 1e-9);
  }
  // A symmetric bow-tie (signed area 0): two triangles of area 1 each, accepted.
  const Shape2D bowTie = ShapeFromPolygons({ { { -1, -1 }, { 1, 1 }, { 1, -1 }, { -1, 1 } } });
  ASSERT_EQ(bowTie.Rings.size(), 1u);
  EXPECT_NEAR(bowTie.Area(), 0.0, 1e-12);
  EXPECT_NEAR(bowTie.FilledArea(), 2.0, 1e-12);
  EXPECT_TRUE(bowTie.Contains({ 0.8, 0.1 }));
  EXPECT_FALSE(bowTie.Contains({ 0.1, 0.8 }));
  // Two identical rings enclose nothing; two overlapping squares (area 4 each, overlapping in
  // a unit square) enclose their symmetric difference, 4 + 4 - 2.
  const std::vector<Vec2> square = { { 0, 0 }, { 2, 0 }, { 2, 2 }, { 0, 2 } };
  EXPECT_NEAR(ShapeFromPolygons({ square, square }).FilledArea(), 0.0, 1e-12);
  const std::vector<Vec2> shifted = { { 1, 1 }, { 3, 1 }, { 3, 3 }, { 1, 3 } };
  EXPECT_NEAR(ShapeFromPolygons({ square, shifted }).FilledArea(), 4.0 + 4.0 - 2.0, 1e-12);
  // The tables: the bow-tie is a shape (its table that of two triangles: zero at the pinch
  // is never reached, and the table is not that of the empty set), the repeated ring an error.
  const Result<SafeDistanceTables> tie = ComputeSafeDistanceTables({ { "bow-tie", bowTie } });
  ASSERT_TRUE(tie.Ok()) << tie.Message();
  EXPECT_GT(tie->Value(0, 0, 0, 0), 0.5);
  const Result<SafeDistanceTables> twice =
    ComputeSafeDistanceTables({ { "twice", ShapeFromPolygons({ square, square }) } });
  EXPECT_TRUE(gs_test::FailedWith(twice, "no area under the even-odd rule"));
  // An asymmetric bow-tie: one lobe 4 times the other's area; its principal axis along the
  // lobes (x), which the signed area would have mixed up (lobes of opposite signs).
  const Shape2D lopsided = ShapeFromPolygons({ { { -2, -2 }, { 1, 1 }, { 1, -1 }, { -2, 2 } } });
  EXPECT_NEAR(lopsided.FilledArea(), 4.0 + 1.0, 1e-12);
  const std::array<double, 6> i = lopsided.EvenOddIntegrals({ 0, 0 });
  // Centroid: (4 * (-4/3) + 1 * (2/3)) / 5 = -0.933...
  EXPECT_NEAR(i[1] / i[0], (4.0 * (-4.0 / 3.0) + 1.0 * (2.0 / 3.0)) / 5.0, 1e-12);
  EXPECT_NEAR(i[2] / i[0], 0.0, 1e-12);
}

TEST(SafeDistanceTable, LongShapesAreSplitAlongTheirMajorAxis)
{
  // An ellipse 5:1 whose major axis is at 30 degrees: 3 parts of aspect 5/3 <= 2.
  std::vector<Vec2> ellipse;
  const double tilt = Pi / 6;
  for (int k = 0; k < 120; ++k)
  {
    const double a = 2 * Pi * k / 120;
    const Vec2 p{ 5 * std::cos(a), std::sin(a) };
    ellipse.emplace_back(10 + std::cos(tilt) * p.x - std::sin(tilt) * p.y,
      -3 + std::sin(tilt) * p.x + std::cos(tilt) * p.y);
  }
  const Shape2D shape = ShapeFromPolygons({ ellipse });
  SafeDistanceOptions options;
  options.AngleBins = 32;
  options.DistanceSteps = 32;
  const Result<SafeDistanceTables> r = ComputeSafeDistanceTables({ { "ellipse", shape } }, options);
  ASSERT_TRUE(r.Ok()) << r.Message();
  const SafeDistanceTables& T = *r;
  const SafeDistanceClass& c = T.Classes[0];
  EXPECT_NEAR(c.AspectRatio, 5.0, 0.01);
  EXPECT_NEAR(std::abs(Dot(c.MajorAxis, { std::cos(tilt), std::sin(tilt) })), 1.0, 1e-6);
  ASSERT_EQ(T.NumberOfParts(), 3);
  ASSERT_EQ(T.NumberOfPairs(), 9);
  ASSERT_EQ(c.Parts.size(), 3u);
  for (int k = 0; k < 3; ++k)
  {
    const SafeDistancePart& part = T.Parts[k];
    EXPECT_EQ(part.ClassId, 0);
    EXPECT_EQ(part.Index, k);
    EXPECT_LT(part.Radius, 0.5);
    EXPECT_NEAR(std::abs(Dot(part.Centre, c.MajorAxis)), k == 1 ? 0.0 : 2.0 / 3.0, 0.05);
  }
  // Parts are convex: clip the ellipse to each strip (Sutherland-Hodgman) for the oracle.
  std::vector<gs_test::OverlapOracle> oracles;
  for (const SafeDistancePart& part : T.Parts)
  {
    std::vector<Vec2> ring = c.Outline.Rings[0];
    for (int side = 0; side < 2; ++side)
    {
      const double limit = side == 0 ? part.From : part.To;
      if (std::abs(limit) > 1e299)
        continue;
      auto in = [&](const Vec2& p) {
        return side == 0 ? Dot(p, part.Axis) >= limit : Dot(p, part.Axis) <= limit;
      };
      std::vector<Vec2> out;
      for (std::size_t k = 0; k < ring.size(); ++k)
      {
        const Vec2 a = ring[k], b = ring[(k + 1) % ring.size()];
        if (in(a))
          out.push_back(a);
        if (in(a) != in(b))
        {
          const double t = (limit - Dot(a, part.Axis)) / (Dot(b, part.Axis) - Dot(a, part.Axis));
          out.push_back(a + (b - a) * t);
        }
      }
      ring = out;
    }
    for (Vec2& p : ring)
      p = p - part.Centre;
    oracles.emplace_back(std::vector<std::vector<Vec2>>{ ring }, part.Radius);
  }
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      EXPECT_EQ(CountOverlaps(T, a, b, oracles[a], oracles[b], 4000, 100 + 3 * a + b), 0);
  // A large MaximumAspectRatio keeps it whole.
  options.MaximumAspectRatio = 10;
  const Result<SafeDistanceTables> whole = ComputeSafeDistanceTables({ { "ellipse", shape } }, options);
  ASSERT_TRUE(whole.Ok());
  EXPECT_EQ(whole->NumberOfParts(), 1);
}

TEST(SafeDistanceTable, NonConvexSplitPartsAreConservative)
{
  // A comb 12 x 3 with teeth (spine 12 x 1, 6 teeth 1 wide, 2 long) and a square hole: its
  // aspect (about 4) gives 2 parts; the cut crosses the spine and a tooth or gap, so each part
  // is non-convex and may have several pieces on the cut line. Parts are rebuilt by the
  // oracle's own clipping (gs_test::PartOfRegion) and probed pair by pair.
  std::vector<Vec2> comb{ { 0, 0 }, { 12, 0 }, { 12, 1 } };
  for (int t = 5; t >= 0; --t)
  {
    const double x = 2.0 * t;
    comb.insert(comb.end(), { { x + 1.5, 1 }, { x + 1.5, 3 }, { x + 0.5, 3 }, { x + 0.5, 1 } });
  }
  comb.push_back({ 0, 1 });
  const std::vector<Vec2> hole{ { 3.2, 0.3 }, { 3.6, 0.3 }, { 3.6, 0.7 }, { 3.2, 0.7 } };
  SafeDistanceOptions options;
  options.AngleBins = 24;
  options.DistanceSteps = 24;
  const Result<SafeDistanceTables> r =
    ComputeSafeDistanceTables({ { "comb", ShapeFromPolygons({ comb, hole }) } }, options);
  ASSERT_TRUE(r.Ok()) << r.Message();
  const SafeDistanceTables& T = *r;
  ASSERT_GE(T.NumberOfParts(), 2);
  SafeDistanceOptions sampledOptions = options;
  sampledOptions.Conservative = false;
  const Result<SafeDistanceTables> sampled =
    ComputeSafeDistanceTables({ { "comb", ShapeFromPolygons({ comb, hole }) } }, sampledOptions);
  ASSERT_TRUE(sampled.Ok());

  std::vector<gs_test::OverlapOracle> oracles;
  double area = 0.0;
  for (const SafeDistancePart& part : T.Parts)
  {
    gs_test::RegionBoundary region =
      gs_test::PartOfRegion(T.Classes[0].Outline.Rings, part.Axis, part.From, part.To);
    for (const auto& s : region.Segments)
      area += 0.5 * Cross(s.A, s.B); // oriented boundaries: the parts' areas add up
    for (auto& s : region.Segments)
    {
      s.A = s.A - part.Centre;
      s.B = s.B - part.Centre;
    }
    for (auto& seed : region.Seeds)
      seed = seed - part.Centre;
    oracles.emplace_back(region, part.Radius);
    EXPECT_LE(oracles.back().GetReach(), part.Radius * (1 + 1e-9));
  }
  EXPECT_NEAR(area, T.Classes[0].Outline.Area(), 1e-12);

  const int P = T.NumberOfParts();
  const double w = T.BinWidth();
  std::mt19937_64 random(99);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int overlaps = 0;
  for (int k = 0; k < 40000; ++k)
  {
    const int a = k % P, b = (k / P) % P;
    const int i = static_cast<int>(unit(random) * T.AngleBins) % T.AngleBins;
    const int j = static_cast<int>(unit(random) * T.AngleBins) % T.AngleBins;
    const double d0 = T.Value(a, b, i, j);
    const double d = k % 2 ? d0 : d0 + unit(random) * (T.Parts[a].Radius + T.Parts[b].Radius - d0);
    overlaps += oracles[a].Overlaps((i + unit(random) - 0.5) * w, oracles[b],
      (j + unit(random) - 0.5) * w, d);
  }
  EXPECT_EQ(overlaps, 0);
  // The oracle sees the parts: 1.5 steps below the sampled table they overlap.
  int below = 0, tested = 0;
  for (int a = 0; a < P; ++a)
    for (int b = 0; b < P; ++b)
      for (int i = 0; i < T.AngleBins; i += 2)
        for (int j = 0; j < T.AngleBins; j += 2)
        {
          const double d = sampled->Value(a, b, i, j) - 1.5 * T.Step(a, b);
          if (d <= 0)
            continue;
          ++tested;
          below += oracles[a].Overlaps(i * w, oracles[b], j * w, d);
        }
  EXPECT_GT(tested, 100);
  EXPECT_GE(below, tested * 95 / 100);
}

TEST(SafeDistanceTable, DeterministicAcrossThreadCounts)
{
  const Shape2D star = PixelStar(64);
  const Result<SafeDistanceTables> a = ComputeSafeDistanceTables({ { "s", star }, { "d", ShapeFromMask(DiskMask(50, 12)) } });
#ifdef _OPENMP
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
#endif
  const Result<SafeDistanceTables> b = ComputeSafeDistanceTables({ { "s", star }, { "d", ShapeFromMask(DiskMask(50, 12)) } });
#ifdef _OPENMP
  omp_set_num_threads(threads);
#endif
  ASSERT_TRUE(a.Ok() && b.Ok());
  EXPECT_EQ(a->Values, b->Values);
}

TEST(SafeDistanceTable, RejectsBadParametersAndAborts)
{
  const Shape2D star = PixelStar(32);
  SafeDistanceOptions o;
  o.AngleBins = 0;
  EXPECT_FALSE(ComputeSafeDistanceTables({ { "s", star } }, o).Ok());
  o = {};
  o.DistanceSteps = 0;
  EXPECT_FALSE(ComputeSafeDistanceTables({ { "s", star } }, o).Ok());
  o = {};
  o.MaximumAspectRatio = 0.5;
  EXPECT_FALSE(ComputeSafeDistanceTables({ { "s", star } }, o).Ok());
  EXPECT_FALSE(ComputeSafeDistanceTables({}, {}).Ok());
  EXPECT_FALSE(ComputeSafeDistanceTables({ { "empty", Shape2D{} } }, {}).Ok());
  int calls = 0;
  const Result<SafeDistanceTables> aborted = ComputeSafeDistanceTables(
    { { "s", star } }, {}, [&](double) { return ++calls < 2; });
  EXPECT_TRUE(aborted.IsAborted());
}

TEST(SafeDistanceTable, AngleBinsWrap)
{
  EXPECT_EQ(SafeDistanceTables::AngleBin(0.0, 64), 0);
  EXPECT_EQ(SafeDistanceTables::AngleBin(-0.01, 64), 0);
  EXPECT_EQ(SafeDistanceTables::AngleBin(2 * Pi - 0.01, 64), 0);
  EXPECT_EQ(SafeDistanceTables::AngleBin(-2 * Pi / 64, 64), 63);
  EXPECT_EQ(SafeDistanceTables::AngleBin(Pi, 64), 32);
  EXPECT_EQ(SafeDistanceTables::AngleBin(7 * 2 * Pi + 0.1, 64), 1);
}

TEST(SafeDistanceTable, TablesTooLargeForMemoryAreRefusedBeforeAllocation)
{
  EXPECT_TRUE(CheckSafeDistanceTableSize(100, 64).Ok()); // 328 MB
  const std::string error = CheckSafeDistanceTableSize(400, 128).Message(); // 21 GB
  EXPECT_NE(error.find("MB of tables"), std::string::npos) << error;
  // 400 classes: the parts are cheap, the values are refused with that message.
  std::vector<SafeDistanceInput> classes;
  for (int k = 0; k < 400; ++k)
  {
    classes.push_back({ "square", ShapeFromPolygons({ RegularPolygon(4, 1.0, Pi / 4) }) });
  }
  SafeDistanceOptions options;
  options.AngleBins = 128;
  const Result<SafeDistanceTables> parts = ComputeSafeDistanceParts(classes, options);
  ASSERT_TRUE(parts.Ok()) << parts.Message();
  const Result<SafeDistanceTables> values = ComputeSafeDistanceValues(*parts, options);
  EXPECT_FALSE(values.Ok());
  EXPECT_EQ(values.Message(), error);
}
