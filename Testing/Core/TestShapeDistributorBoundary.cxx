// Shapes hanging over the mesh boundary (KeepInside off, the default) must not overlap either:
// the case of issue 17 (a jittered planar square with a boundary, two concave classes, a
// turning field and a density gradient), judged by the shapes' drawn silhouettes.
#include "DistributionChecks.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include "ExactGeodesic.h"
#include "MeshGenerators.h"
#include "OverlapCheck.h"
#include "SaddleVertexGraph.h"
#include "SafeDistanceTable.h"
#include "ShapeDistributor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace gs;

namespace
{
// [-1, 1]^2 as an n x n grid of vertices, interior vertices jittered by up to `jitter` of the
// spacing, boundary vertices jittered along the boundary only (the square stays convex).
TriangleMesh JitteredSquare(int n, double jitter, unsigned seed)
{
  TriangleSoup s = MakePlanarGrid(n - 1, n - 1, 2.0, 2.0);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-jitter, jitter);
  const double h = 2.0 / (n - 1);
  double lo[2] = { 1e300, 1e300 };
  for (const Vec3& p : s.Points)
  {
    lo[0] = std::min(lo[0], p.x);
    lo[1] = std::min(lo[1], p.y);
  }
  for (Vec3& p : s.Points)
  {
    p.x += -1.0 - lo[0];
    p.y += -1.0 - lo[1];
    const bool bx = std::abs(std::abs(p.x) - 1.0) < 1e-9, by = std::abs(std::abs(p.y) - 1.0) < 1e-9;
    const double dx = u(rng) * h, dy = u(rng) * h;
    if (!bx && !by)
      p = p + Vec3{ dx, dy, 0.0 };
    else if (!bx || !by)
      p = p + (bx ? Vec3{ 0.0, dy, 0.0 } : Vec3{ dx, 0.0, 0.0 }); // along the side
  }
  return gs_test::BuildMesh(s);
}

// A regular 5-point star and an L tile whose circle centre lies in its notch (not star-shaped
// about its centre): rays from the centre to the far arms cross the notch.
SafeDistanceTables StarAndTile(int bins)
{
  std::vector<SafeDistanceInput> in;
  in.push_back({ "star", ShapeFromPolygons({ MakeStarPolygon(5, 1.0, 0.382) }) });
  const std::vector<Vec2> tile{ { -1.0, -1.0 }, { 1.0, -1.0 }, { 1.0, -0.4 }, { -0.4, -0.4 },
    { -0.4, 1.0 }, { -1.0, 1.0 } };
  in.push_back({ "tile", ShapeFromPolygons({ tile }) });
  SafeDistanceOptions o;
  o.AngleBins = bins;
  Result<SafeDistanceTables> r = ComputeSafeDistanceTables(in, o);
  EXPECT_TRUE(r.Ok()) << r.Message();
  return *r;
}

// The class outline of shape s placed rigidly in the plane (its circle centre at the shape's
// position, its +x axis along the shape's direction).
std::vector<std::vector<Vec2>> RigidOutline(const SafeDistanceTables& t, const PlacedShape& s, double shapeSize)
{
  const double unit = shapeSize * s.Scale;
  const double c = s.Direction.x, n = s.Direction.y;
  std::vector<std::vector<Vec2>> rings = t.Classes[s.ClassId].Outline.Rings;
  for (auto& ring : rings)
    for (Vec2& p : ring)
      p = Vec2{ s.Position.x + unit * (c * p.x - n * p.y), s.Position.y + unit * (n * p.x + c * p.y) };
  return rings;
}
} // namespace

// Issue 17: with KeepInside off (the default) shapes hang over the boundary. Their outlines used
// to be drawn by mapping every outline point to the end of its ray from the centre, clamped at
// the boundary: where a shape is not star-shaped about its centre (the L tile), the chords between
// clamped points cut across its notch, where the tables rightly let a neighbour in, and the drawn
// outlines overlapped (the oracle below finds such pairs in that drawing). Outlines are now cut
// along the boundary (ShapeOutline.h): each drawn region must be the rigid shape within the square
// (equal areas) and no two may share area.
// DrawRadialOutline against exact areas on a synthetic map: the plane cut by the line x = cut
// (rays stop there), for an L tile not star-shaped about its centre and a ring with a hole
// (rings given in any orientation), with the centre before the cut line or on it.
TEST(ShapeDistributorBoundary, RadialOutlineIsTheRegionWithinTheReach)
{
  const std::vector<Vec2> tile{ { -1.0, -1.0 }, { 1.0, -1.0 }, { 1.0, -0.4 }, { -0.4, -0.4 },
    { -0.4, 1.0 }, { -1.0, 1.0 } };
  std::vector<Vec2> outer, hole;
  for (int k = 0; k < 64; ++k)
  {
    const double a = 6.283185307179586 * k / 64;
    outer.push_back(Vec2{ std::cos(a), std::sin(a) });
    hole.push_back(Vec2{ 0.5 * std::cos(a), 0.5 * std::sin(a) }); // counter-clockwise too
  }
  for (const auto& rings : { std::vector<std::vector<Vec2>>{ tile }, std::vector<std::vector<Vec2>>{ outer, hole } })
  {
    for (double cut : { 0.7, 0.2, 0.0 })
    {
      const auto map = [cut](const Vec2& p) {
        MappedPoint m;
        m.Reached = p.x <= cut;
        // A ray from the origin stops at the line (the origin itself is on or before it).
        m.Reach = m.Reached ? 1.0 : std::max(0.0, cut / p.x);
        const Vec2 q = p * m.Reach;
        m.End = SurfacePoint::InFace(0, q.x, q.y, 0.0);
        return m;
      };
      const auto pieces = DrawRadialOutline(rings, 0.05, std::sqrt(2.0), map);
      std::vector<std::vector<Vec2>> drawn;
      for (const OutlinePiece& piece : pieces)
      {
        EXPECT_TRUE(piece.Closed);
        std::vector<Vec2> ring;
        for (const SurfacePoint& q : piece.Points)
          ring.push_back(Vec2{ q.Bary[0], q.Bary[1] });
        drawn.push_back(ring);
      }
      const std::vector<std::vector<Vec2>> half{ { { -5.0, -5.0 }, { cut, -5.0 }, { cut, 5.0 }, { -5.0, 5.0 } } };
      const double expected = gs_test::CommonArea(rings, half, 4000);
      EXPECT_NEAR(gs_test::CommonArea(drawn, drawn, 4000), expected, 1e-3) << "cut " << cut;
      EXPECT_GT(expected, 0.5);
    }
  }
}

TEST(ShapeDistributorBoundary, ShapesOverTheBoundaryAreDrawnCutAndDoNotOverlap)
{
  const TriangleMesh mesh = JitteredSquare(101, 0.3, 5);
  SaddleVertexGraph graph;
  ASSERT_TRUE(gs_test::Succeeded(graph.Build(mesh, SaddleVertexGraphOptions(), nullptr)));
  const SafeDistanceTables t = StarAndTile(64);
  std::vector<Vec3> directions(mesh.NumberOfFaces());
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    Vec3 d{ 0, 0, 0 };
    for (int v : mesh.Face(f))
      d = d + Vec3{ std::cos(2.5 * mesh.Position(v).x), std::sin(2.5 * mesh.Position(v).x), 0.0 };
    directions[f] = d;
  }
  std::vector<double> density(mesh.NumberOfVertices());
  for (int v = 0; v < mesh.NumberOfVertices(); ++v)
    density[v] = 0.6 + 0.2 * (mesh.Position(v).y + 1.0);
  const std::vector<std::vector<Vec2>> square{ { { -1.0, -1.0 }, { 1.0, -1.0 }, { 1.0, 1.0 }, { -1.0, 1.0 } } };
  const double spacing = 0.5 * mesh.MeanEdgeLength();
  int clampedOverlaps = 0, cutShapes = 0;
  struct Case
  {
    DistributionMode Mode;
    std::uint64_t Seed;
    bool KeepInside;
  };
  for (const Case& c : { Case{ DistributionMode::Random, 1, false }, Case{ DistributionMode::Random, 2, false },
         Case{ DistributionMode::Greedy, 2, false }, Case{ DistributionMode::Greedy, 3, false },
         Case{ DistributionMode::Random, 2, true } })
  {
    ShapeDistributionOptions o;
    o.ShapeSize = 0.06;
    o.Mode = c.Mode;
    o.Seed = c.Seed;
    o.KeepInside = c.KeepInside;
    ShapeDistributor d(mesh, &graph);
    const Result<ShapeDistribution> r = d.Run(t, directions, density, o);
    ASSERT_TRUE(r.Ok()) << r.Message();
    ASSERT_GT(r->Shapes.size(), 300u);
    const std::string name = "mode " + std::to_string(static_cast<int>(c.Mode)) + " seed " +
      std::to_string(c.Seed) + (c.KeepInside ? " KeepInside" : "");
    EXPECT_EQ(gs_test::CountPlanarOverlaps(mesh, t, r->Shapes, o.ShapeSize), 0) << name;
    const auto drawn = gs_test::DrawnPlanarOutlines(mesh, d, spacing);
    std::vector<double> radius;
    std::vector<std::vector<std::vector<Vec2>>> clamped(r->Shapes.size());
    for (std::size_t s = 0; s < r->Shapes.size(); ++s)
    {
      const PlacedShape& shape = r->Shapes[s];
      const double unit = o.ShapeSize * shape.Scale;
      radius.push_back(t.Classes[shape.ClassId].Radius * unit * (1.0 + 1e-9));
      // Drawn = the rigid shape within the square (the plane's exponential map is rigid).
      const auto rigid = RigidOutline(t, shape, o.ShapeSize);
      const double full = gs_test::CommonArea(rigid, rigid, 2000);
      const double inside = gs_test::CommonArea(rigid, square, 2000);
      const double area = gs_test::CommonArea(drawn[s], drawn[s], 2000);
      EXPECT_NEAR(area, inside, 2e-3 * full) << name << ", shape " << s;
      cutShapes += inside < 0.999 * full ? 1 : 0;
      // The former drawing: every outline point at its clamped ray end.
      for (const auto& ring : t.Classes[shape.ClassId].Outline.Rings)
      {
        std::vector<Vec2> line;
        for (std::size_t k = 0; k < ring.size(); ++k)
        {
          const Vec2 a = ring[k], b = ring[(k + 1) % ring.size()];
          const int pieces = std::max(1, static_cast<int>(std::ceil(Norm(b - a) / (spacing / unit))));
          for (int j = 0; j < pieces; ++j)
          {
            const SurfacePoint q = d.MapToSurface(static_cast<int>(s), a + (b - a) * (static_cast<double>(j) / pieces));
            const Vec3 x = mesh.Interpolate(q.Face, q.Bary);
            line.push_back(Vec2{ x.x, x.y });
          }
        }
        clamped[s].push_back(line);
      }
    }
    EXPECT_EQ(gs_test::CountDrawnOverlaps(r->Shapes, drawn, radius), 0) << name;
    clampedOverlaps += gs_test::CountDrawnOverlaps(r->Shapes, clamped, radius);
  }
  EXPECT_GT(cutShapes, 100) << "shapes hang over the boundary";
  EXPECT_GE(clampedOverlaps, 2) << "the oracle finds the former drawing's overlaps";
}

// A long bent class over the boundary: a concave banana (split into parts) and a star on a
// square with a swirling field, KeepInside off. Judged by the drawn outlines in the plane (their
// common area, independent of the tables and of the drawn check's own test): none overlap with
// the drawn check, at seeds where the tables alone let bent bananas overlap; with exact charts
// and with charts on the discrete geodesic graph of accuracy 0.1 (the filter's default).
TEST(ShapeDistributorBoundary, LongBentShapesOverTheBoundaryDoNotOverlap)
{
  const TriangleMesh mesh = gs_test::BuildMesh(MakePlanarGrid(80, 80, 12.0, 12.0));
  std::vector<Vec2> banana;
  for (int k = 0; k <= 24; ++k)
  {
    const double a = -0.6 + 1.2 * k / 24.0;
    banana.push_back(Vec2{ 3.0 * std::sin(a), 3.0 * std::cos(a) - 2.6 });
  }
  for (int k = 24; k >= 0; --k)
  {
    const double a = -0.6 + 1.2 * k / 24.0;
    banana.push_back(Vec2{ 2.5 * std::sin(a), 2.5 * std::cos(a) - 2.6 });
  }
  std::vector<SafeDistanceInput> in;
  in.push_back({ "star", ShapeFromPolygons({ MakeStarPolygon(5, 1.0, 0.382) }) });
  in.push_back({ "banana", ShapeFromPolygons({ banana }) });
  SafeDistanceOptions so;
  so.AngleBins = 64;
  Result<SafeDistanceTables> tables = ComputeSafeDistanceTables(in, so);
  ASSERT_TRUE(tables.Ok()) << tables.Message();
  ASSERT_GT(tables->Classes[1].Parts.size(), 1u);
  std::vector<Vec3> directions(mesh.NumberOfFaces());
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    const auto& c = mesh.Face(f);
    const Vec3 x = (mesh.Position(c[0]) + mesh.Position(c[1]) + mesh.Position(c[2])) / 3.0;
    directions[f] = Vec3{ std::cos(1.5 * x.x + 0.9 * x.y), std::sin(1.5 * x.x + 0.9 * x.y), 0.0 };
  }
  // Charts by exact geodesics, and on the discrete geodesic graph of accuracy 0.1 (the filter's
  // default engine).
  SaddleVertexGraph dgg;
  SaddleVertexGraphOptions go;
  go.Construction = GraphConstruction::DiscreteGeodesic;
  go.Accuracy = 0.1;
  ASSERT_TRUE(gs_test::Succeeded(dgg.Build(mesh, go, nullptr)));
  const SaddleVertexGraph* const engines[] = { nullptr, &dgg };
  for (const SaddleVertexGraph* graph : engines)
  {
    int without = 0, with = 0;
    for (std::uint64_t seed : { 1, 2, 3 })
    {
      for (const bool drawnCheck : { false, true })
      {
        ShapeDistributionOptions o;
        o.ShapeSize = 0.5;
        o.Seed = seed;
        o.MaximalFailures = 2000;
        o.DrawnCheck = drawnCheck;
        ShapeDistributor d(mesh, graph);
        const Result<ShapeDistribution> r = d.Run(*tables, directions, {}, o);
        ASSERT_TRUE(r.Ok()) << r.Message();
        std::vector<double> radius;
        for (const PlacedShape& s : r->Shapes)
          radius.push_back(tables->Classes[s.ClassId].Radius * o.ShapeSize * s.Scale);
        const auto drawn = gs_test::DrawnPlanarOutlines(mesh, d, 0.25 * mesh.MeanEdgeLength());
        (drawnCheck ? with : without) += gs_test::CountDrawnOverlaps(r->Shapes, drawn, radius, 1e-3);
      }
    }
    const char* engine = graph ? "discrete geodesic graph" : "exact charts";
    std::printf("%s, drawn overlaps over 3 seeds: tables alone %d, with the drawn check %d\n", engine,
      without, with);
    EXPECT_GT(without, 0) << engine; // (the case needs the drawn check)
    EXPECT_EQ(with, 0) << engine;
  }
}


// A thin closed sheet (a sphere squashed to a twelfth of its radius: a lentil): the polar chart
// of a shape on one side wraps around the rim to the other, where geodesics from all around the
// rim meet (the chart's cut locus). A face there has corners that the chart puts on opposite
// sides: it spans the chart, and a point interpolated in it lands near the centre though it lies
// far from it. Such points made VerifyOverlaps report pairs that were not there (up to 27% of
// the radius deep on elephant-with-holes' thin parts), CentreCovered and the drawn check read
// them in the wrong place, and a short shape's decal drew across the face. Such faces now hold
// no chart point (ShapeDistributor::Impl::ChartFaceHolds): wherever ClassPoint answers, the
// chart radius is the geodesic distance (exact solver) to within the face's size.
TEST(ShapeDistributorBoundary, ChartsDoNotInterpolateAcrossTheirCutLocus)
{
  TriangleSoup lentil = MakeIcosphere(1.0, 4);
  for (Vec3& p : lentil.Points)
    p.z *= 1.0 / 12.0;
  const TriangleMesh mesh = gs_test::BuildMesh(lentil);
  const SafeDistanceTables t = StarAndTile(32);
  std::vector<Vec3> directions(mesh.NumberOfFaces());
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
    directions[f] = Cross(mesh.FaceNormal(f), Vec3{ 0.3, 1.0, 0.2 });
  ExactGeodesicSolver exact(mesh);
  long long answered = 0, wrong = 0, pairs = 0, stars = 0;
  for (std::uint64_t seed : { 1, 2, 3 })
  {
    ShapeDistributionOptions o;
    o.ShapeSize = 0.5;
    o.Seed = seed;
    o.MaximalFailures = 300;
    ShapeDistributor d(mesh);
    const Result<ShapeDistribution> r = d.Run(t, directions, {}, o);
    ASSERT_TRUE(r.Ok()) << r.Message();
    for (int s = 0; s < static_cast<int>(r->Shapes.size()); ++s)
    {
      const PlacedShape& shape = r->Shapes[s];
      if (shape.ClassId != 0)
        continue;
      ++stars;
      ASSERT_TRUE(gs_test::Succeeded(exact.Solve({ shape.Centre })));
      const double unit = o.ShapeSize * shape.Scale;
      for (int f = 0; f < mesh.NumberOfFaces(); ++f)
      {
        Vec2 p;
        if (!d.ClassPoint(s, SurfacePoint::InFace(f, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0), p))
          continue;
        ++answered;
        double geodesic = 0.0, edge = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          geodesic += exact.Distance(mesh.Face(f)[k]) / 3.0;
          edge = std::max(edge, mesh.EdgeLength(3 * f + k));
        }
        wrong += std::abs(Norm(p) * unit - geodesic) > 2.0 * edge ? 1 : 0;
      }
    }
    const Result<OverlapCheckResult> found =
      CheckOverlaps(d, gs_test::Outlines(d, d.OutlineSpacing()));
    ASSERT_TRUE(found.Ok()) << found.Message();
    pairs += static_cast<long long>(found->Pairs.size());
  }
  std::printf("%lld stars; %lld chart points, %lld of them off the geodesic distance; %lld "
              "overlapping pairs\n", stars, answered, wrong, pairs);
  EXPECT_GT(stars, 3);
  EXPECT_GT(answered, 1000);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(pairs, 0);
}
