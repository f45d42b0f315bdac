// The Shape Distributor's results bit for bit (issue 18: refactors must not change them): the
// placements, decals and outlines of small runs on a plane and a bumpy sphere (short star and a
// long bar split into parts, Random and Greedy, with and without a density, KeepInside on and
// off, with and without a saddle vertex graph) hashed and compared with hashes recorded before
// the distributor was split into files. A change of any bit fails; when a change of results is
// intended, the test prints the new hashes to record.
#include "DistributorProbes.h"
#include "DistributionChecks.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include "MeshGenerators.h"
#include "OverlapCheck.h"
#include "SaddleVertexGraph.h"
#include "SafeDistanceTable.h"
#include "ShapeDistributor.h"

#include <gtest/gtest.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>

using namespace gs;

namespace
{
struct Case
{
  const char* Name;
  bool Sphere;
  DistributionMode Mode;
  bool Density;
  bool KeepInside;
  bool Graph;
  gs_test::RunHashes Expected;
};

// Recorded from a run of the distributor and recorded again, deliberately, when a change was
// meant to move them (the git log of this file says which and why: e.g. decal triangles cut at
// the texture square's border moved every decals hash and kept every placements and outlines
// hash). A refactor must keep them all.
const Case Cases[] = {
  { "plane random keep-inside", false, DistributionMode::Random, false, true, false,
    { 0x0e76edd2852bb614ull, 0x42d7536aa80f2837ull, 0x8d8ba8c82131c243ull, 47, 0.014999999999999999 } },
  { "plane greedy density", false, DistributionMode::Greedy, true, false, false,
    { 0xdc4520260bdc79b6ull, 0x3ad9e65182904309ull, 0x52a65acc23e910c2ull, 67, 0.0050000000000000001 } },
  { "plane greedy density keep-inside graph", false, DistributionMode::Greedy, true, true, true,
    { 0xb834dd1f14121164ull, 0x623050022378277aull, 0xc19bd1c8fdb3c318ull, 51, 0.0050000000000000001 } },
  { "sphere random density graph", true, DistributionMode::Random, true, false, true,
    { 0xd24665812dc3b292ull, 0xe16a91f504ece201ull, 0xdefc0b952dca76e4ull, 131, 0 } },
  { "sphere greedy graph", true, DistributionMode::Greedy, false, false, true,
    { 0xb7b8b0157b9fd2e6ull, 0xc8d7230f2821bd1full, 0x01194656ca3099beull, 108, 0 } },
  { "sphere greedy density exact", true, DistributionMode::Greedy, true, false, false,
    { 0xf69d780ed52f0db5ull, 0xc0bbd6bf8530a092ull, 0xab806498b0c70ae3ull, 110, 0.014999999999999999 } },
  { "sphere circumcircles graph", true, DistributionMode::CircumcirclePoissonDisk, false, false, true,
    { 0x3c042043c3068257ull, 0x54d87c320a933777ull, 0xcad68a7795a2006eull, 96, 0.01 } },
};
} // namespace

TEST(ShapeDistributorRegression, PlacementsDecalsAndOutlinesBitForBit)
{
  const SafeDistanceTables t = gs_test::StarAndBar();
  ASSERT_GT(t.Classes[1].Parts.size(), 1u);
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(30, 30, 6.0, 6.0));
  const TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.03));
  SaddleVertexGraph planeGraph, sphereGraph;
  SaddleVertexGraphOptions go;
  go.K = 20;
  ASSERT_TRUE(gs_test::Succeeded(planeGraph.Build(plane, go, nullptr)));
  ASSERT_TRUE(gs_test::Succeeded(sphereGraph.Build(sphere, go, nullptr)));
  for (const Case& c : Cases)
  {
    const TriangleMesh& mesh = c.Sphere ? sphere : plane;
    // A swirling field (long shapes bend) and a density growing along x.
    std::vector<Vec3> directions(mesh.NumberOfFaces());
    for (int f = 0; f < mesh.NumberOfFaces(); ++f)
    {
      const auto& v = mesh.Face(f);
      const Vec3 x = (mesh.Position(v[0]) + mesh.Position(v[1]) + mesh.Position(v[2])) / 3.0;
      directions[f] = c.Sphere ? Cross(Vec3{ 0.2, 0.1, 1.0 }, x)
                               : Vec3{ std::cos(0.4 * x.y), std::sin(0.4 * x.y), 0.0 };
    }
    std::vector<double> density;
    if (c.Density)
    {
      for (int v = 0; v < mesh.NumberOfVertices(); ++v)
      {
        density.push_back(c.Sphere ? 1.0 + 0.3 * mesh.Position(v).x : 0.7 + 0.1 * mesh.Position(v).x);
      }
    }
    ShapeDistributionOptions o;
    o.ShapeSize = c.Sphere ? 0.12 : 0.3;
    o.Mode = c.Mode;
    o.Seed = 5;
    o.MaximalFailures = 300;
    o.KeepInside = c.KeepInside;
    gs_test::RunHashes first;
    for (const int threads : { 1, 2 })
    {
      o.NumberOfThreads = threads;
      ShapeDistributor d(mesh, c.Graph ? (c.Sphere ? &sphereGraph : &planeGraph) : nullptr);
      const Result<ShapeDistribution> r = d.Run(t, directions, density, o);
      ASSERT_TRUE(r.Ok()) << r.Message();
      gs_test::RunHashes h = gs_test::HashRun(d, r->Shapes);
      h.Probe = gs_test::ProbeFitFraction(d, 200, 1);
      std::printf("%s, %d thread(s): %d shapes, { 0x%016" PRIx64 "ull, 0x%016" PRIx64 "ull, 0x%016" PRIx64
                  "ull, %d, %.17g }\n",
        c.Name, threads, h.Shapes, h.Placements, h.Decals, h.Outlines, h.Shapes, h.Probe);
      if (threads == 1)
      {
        first = h;
        EXPECT_GT(h.Shapes, 10) << c.Name;
        // Whatever the hashes, no overlap as VerifyOverlaps judges the drawn outlines.
        const Result<OverlapCheckResult> overlaps =
          CheckOverlaps(d, gs_test::Outlines(d, d.OutlineSpacing()));
        ASSERT_TRUE(gs_test::Succeeded(overlaps));
        EXPECT_EQ(overlaps->Pairs.size(), 0u) << c.Name;
        int longShapes = 0;
        for (const PlacedShape& s : r->Shapes)
        {
          longShapes += s.Curve.empty() ? 0 : 1;
        }
        EXPECT_GT(longShapes, 2) << c.Name;
      }
      else
      {
        // The seed alone decides (ShapeDistributor.h).
        EXPECT_EQ(h.Placements, first.Placements) << c.Name;
        EXPECT_EQ(h.Decals, first.Decals) << c.Name;
        EXPECT_EQ(h.Outlines, first.Outlines) << c.Name;
        EXPECT_EQ(h.Probe, first.Probe) << c.Name;
      }
      EXPECT_EQ(h.Shapes, c.Expected.Shapes) << c.Name;
      EXPECT_EQ(h.Placements, c.Expected.Placements) << c.Name;
      EXPECT_EQ(h.Decals, c.Expected.Decals) << c.Name;
      EXPECT_EQ(h.Outlines, c.Expected.Outlines) << c.Name;
      EXPECT_EQ(h.Probe, c.Expected.Probe) << c.Name;
    }
  }
}

// Long candidates given up early (EarlyRejection: the parts behind the centre checked before the
// streamline ahead is traced) must leave every placement, decal and outline as building whole
// shapes leaves them: runs with many rejected long candidates (long bent bars of three parts
// and stars on a plane with a boundary and on a bumpy sphere, Random and Greedy), both ways.
TEST(ShapeDistributorRegression, EarlyRejectionChangesNothing)
{
  const SafeDistanceTables t = gs_test::PolygonTables({ MakeStarPolygon(5, 1.0, 0.4),
    { { -3.0, -0.45 }, { 3.0, -0.45 }, { 3.0, 0.45 }, { -3.0, 0.45 } } });
  ASSERT_GE(t.Classes[1].Parts.size(), 3u);
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(50, 50, 10.0, 10.0));
  const TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.03));
  for (const bool onSphere : { false, true })
  {
    const TriangleMesh& mesh = onSphere ? sphere : plane;
    std::vector<Vec3> directions(mesh.NumberOfFaces());
    for (int f = 0; f < mesh.NumberOfFaces(); ++f)
    {
      const auto& v = mesh.Face(f);
      const Vec3 x = (mesh.Position(v[0]) + mesh.Position(v[1]) + mesh.Position(v[2])) / 3.0;
      directions[f] = onSphere ? Cross(Vec3{ 0.2, 0.1, 1.0 }, x)
                               : Vec3{ std::cos(0.5 * x.y), std::sin(0.5 * x.y), 0.0 };
    }
    for (const DistributionMode mode : { DistributionMode::Random, DistributionMode::Greedy })
    {
      ShapeDistributionOptions o;
      o.ShapeSize = onSphere ? 0.1 : 0.3;
      o.Mode = mode;
      o.Seed = 7;
      o.MaximalFailures = 2000;
      gs_test::RunHashes h[2];
      for (const bool early : { false, true })
      {
        o.EarlyRejection = early;
        ShapeDistributor d(mesh);
        const Result<ShapeDistribution> r = d.Run(t, directions, {}, o);
        ASSERT_TRUE(r.Ok()) << r.Message();
        h[early] = gs_test::HashRun(d, r->Shapes);
        h[early].Probe = gs_test::ProbeFitFraction(d, 2000, 3);
        int longShapes = 0;
        for (const PlacedShape& s : r->Shapes)
          longShapes += s.Curve.empty() ? 0 : 1;
        EXPECT_GT(longShapes, 20) << onSphere << " " << static_cast<int>(mode);
      }
      EXPECT_EQ(h[1].Shapes, h[0].Shapes) << onSphere << " " << static_cast<int>(mode);
      EXPECT_EQ(h[1].Placements, h[0].Placements) << onSphere << " " << static_cast<int>(mode);
      EXPECT_EQ(h[1].Decals, h[0].Decals) << onSphere << " " << static_cast<int>(mode);
      EXPECT_EQ(h[1].Outlines, h[0].Outlines) << onSphere << " " << static_cast<int>(mode);
      EXPECT_EQ(h[1].Probe, h[0].Probe) << onSphere << " " << static_cast<int>(mode);
    }
  }
}
