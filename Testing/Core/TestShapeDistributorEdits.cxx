// Place-keyed candidates (CandidateOrder::PlaceKeyed) and edits that re-decide only what they
// reach: after every brush move, resize and density edit, the run that reused the previous one
// equals a fresh distributor given the same final parameters, bit for bit (placements, decals,
// outlines), for 1 and 2 threads, on a plane with a boundary (KeepInside) and on a curved mesh
// with a saddle vertex graph, each with a long class beside the star. The results are judged
// by VerifyOverlaps on the drawn outlines, and as dense as the rounds' dart throwing.
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

#include <cmath>

using namespace gs;

namespace
{
struct Scene
{
  const TriangleMesh& Mesh;
  const SaddleVertexGraph* Graph;
  std::vector<Vec3> Directions;
  ShapeDistributionOptions Options;
};

// The paper's brush f = max(density, min(1, d / radius)), d the distance in space here (the
// edits only need densities that change in a region), times a background density.
std::vector<double> Brush(const TriangleMesh& mesh, const Vec3& centre, double radius, double density,
  const std::vector<double>& background)
{
  std::vector<double> f(mesh.NumberOfVertices());
  for (int v = 0; v < mesh.NumberOfVertices(); ++v)
  {
    f[v] = std::max(density, std::min(1.0, Norm(mesh.Position(v) - centre) / radius)) *
      (background.empty() ? 1.0 : background[v]);
  }
  return f;
}

// Runs the edits one after the other on one distributor, each compared with a fresh one.
void CheckEdits(const Scene& scene, const std::vector<std::vector<double>>& edits, const char* name)
{
  const SafeDistanceTables tables = gs_test::StarAndBar();
  gs_test::RunHashes first[8] = {};
  for (const int threads : { 1, 2 })
  {
    ShapeDistributionOptions o = scene.Options;
    o.NumberOfThreads = threads;
    o.MaximumEditShare = 1.0; // (every edit re-decided incrementally, however large)
    ShapeDistributor edited(scene.Mesh, scene.Graph);
    // (Fresh runs one after the other: the shapes they share keep their decals.)
    ShapeDistributionOptions again = o;
    again.ReuseLastRun = false;
    ShapeDistributor rerun(scene.Mesh, scene.Graph);
    for (std::size_t k = 0; k < edits.size(); ++k)
    {
      const Result<ShapeDistribution> a = edited.Run(tables, scene.Directions, edits[k], o);
      ASSERT_TRUE(a.Ok()) << a.Message();
      const Result<ShapeDistribution> c = rerun.Run(tables, scene.Directions, edits[k], again);
      ASSERT_TRUE(c.Ok()) << c.Message();
      EXPECT_FALSE(c->Statistics.Incremental);
      ShapeDistributor fresh(scene.Mesh, scene.Graph);
      const Result<ShapeDistribution> b = fresh.Run(tables, scene.Directions, edits[k], o);
      ASSERT_TRUE(b.Ok()) << b.Message();
      EXPECT_EQ(a->Statistics.Incremental, k > 0) << name << " edit " << k;
      EXPECT_FALSE(b->Statistics.Incremental);
      if (k > 0)
      {
        // Only what the edit reaches is decided again.
        EXPECT_LT(a->Statistics.Redecided, b->Statistics.Redecided) << name << " edit " << k;
      }
      ASSERT_EQ(a->Shapes.size(), b->Shapes.size()) << name << " edit " << k;
      const gs_test::RunHashes h = gs_test::HashRun(edited, a->Shapes);
      EXPECT_EQ(h, gs_test::HashRun(fresh, b->Shapes)) << name << " edit " << k << ", " << threads << " thread(s)";
      EXPECT_EQ(gs_test::HashRun(rerun, c->Shapes), gs_test::HashRun(fresh, b->Shapes)) << name << " rerun " << k;
      if (threads == 1)
      {
        first[k] = h;
        int longShapes = 0;
        for (const PlacedShape& s : a->Shapes)
        {
          longShapes += s.Curve.empty() ? 0 : 1;
        }
        EXPECT_GT(longShapes, 2) << name;
        const Result<OverlapCheckResult> overlaps =
          CheckOverlaps(edited, gs_test::Outlines(edited, edited.OutlineSpacing()));
        ASSERT_TRUE(gs_test::Succeeded(overlaps));
        EXPECT_EQ(overlaps->Pairs.size(), 0u) << name << " edit " << k;
      }
      else
      {
        EXPECT_EQ(h, first[k]) << name << " edit " << k << ": the thread count changed the result";
      }
    }
  }
}
} // namespace

TEST(ShapeDistributorEdits, BrushMovesAndDensityEditsEqualFreshRunsOnAPlaneWithABoundary)
{
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(30, 30, 6.0, 6.0));
  Scene scene{ plane, nullptr, std::vector<Vec3>(plane.NumberOfFaces()), {} };
  for (int f = 0; f < plane.NumberOfFaces(); ++f)
  {
    const auto& v = plane.Face(f);
    const Vec3 x = (plane.Position(v[0]) + plane.Position(v[1]) + plane.Position(v[2])) / 3.0;
    scene.Directions[f] = Vec3{ std::cos(0.4 * x.y), std::sin(0.4 * x.y), 0.0 };
  }
  scene.Options.ShapeSize = 0.2;
  scene.Options.Seed = 4;
  scene.Options.KeepInside = true;
  scene.Options.Order = CandidateOrder::PlaceKeyed;
  std::vector<double> background(plane.NumberOfVertices(), 1.0);
  const std::vector<double> none;
  std::vector<std::vector<double>> edits;
  edits.push_back(Brush(plane, { 1.5, 1.5, 0.0 }, 1.2, 0.5, none)); // (a brush)
  edits.push_back(Brush(plane, { 2.0, 1.6, 0.0 }, 1.2, 0.5, none)); // moved
  edits.push_back(Brush(plane, { 2.0, 1.6, 0.0 }, 1.6, 0.5, none)); // resized
  for (int v = 0; v < plane.NumberOfVertices(); ++v)
  {
    const Vec3 x = plane.Position(v);
    background[v] = x.x > 4.0 && x.y > 4.0 ? 0.8 : 1.0; // a density edited in a corner
  }
  edits.push_back(Brush(plane, { 2.0, 1.6, 0.0 }, 1.6, 0.5, background));
  CheckEdits(scene, edits, "plane");
}

TEST(ShapeDistributorEdits, BrushMovesEqualFreshRunsOnACurvedMeshWithAGraph)
{
  const TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.03));
  SaddleVertexGraph graph;
  SaddleVertexGraphOptions go;
  go.K = 20;
  ASSERT_TRUE(gs_test::Succeeded(graph.Build(sphere, go, nullptr)));
  Scene scene{ sphere, &graph, std::vector<Vec3>(sphere.NumberOfFaces()), {} };
  for (int f = 0; f < sphere.NumberOfFaces(); ++f)
  {
    const auto& v = sphere.Face(f);
    const Vec3 x = (sphere.Position(v[0]) + sphere.Position(v[1]) + sphere.Position(v[2])) / 3.0;
    scene.Directions[f] = Cross(Vec3{ 0.2, 0.1, 1.0 }, x);
  }
  scene.Options.ShapeSize = 0.1;
  scene.Options.Seed = 2;
  scene.Options.Order = CandidateOrder::PlaceKeyed;
  const std::vector<double> none;
  std::vector<std::vector<double>> edits;
  edits.push_back(Brush(sphere, { 1.0, 0.0, 0.0 }, 0.5, 0.4, none));
  edits.push_back(Brush(sphere, { 0.9, 0.4, 0.0 }, 0.5, 0.4, none));
  edits.push_back(Brush(sphere, { 0.9, 0.4, 0.0 }, 0.7, 0.6, none));
  CheckEdits(scene, edits, "sphere");
}

TEST(ShapeDistributorEdits, PlaceKeyedRunsAreAsDenseAsRoundsAndRerunFreshWhenMoreThanTheDensityChanges)
{
  const SafeDistanceTables tables = gs_test::PolygonTables({ MakeStarPolygon(5, 1.0, 0.4) });
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(40, 40, 8.0, 8.0));
  const std::vector<Vec3> directions(plane.NumberOfFaces(), Vec3{ 1.0, 0.0, 0.0 });
  const std::vector<double> density = Brush(plane, { 4.0, 4.0, 0.0 }, 2.0, 0.5, {});
  ShapeDistributionOptions o;
  o.ShapeSize = 0.25;
  o.Seed = 1;
  ShapeDistributor rounds(plane, nullptr);
  const Result<ShapeDistribution> a = rounds.Run(tables, directions, density, o);
  ASSERT_TRUE(a.Ok());
  o.Order = CandidateOrder::PlaceKeyed;
  ShapeDistributor pool(plane, nullptr);
  const Result<ShapeDistribution> b = pool.Run(tables, directions, density, o);
  ASSERT_TRUE(b.Ok());
  EXPECT_TRUE(b->Statistics.Maximal);
  // Random sequential adsorption both: the same density within a few percent, and maximal
  // (random probes that would still fit: a few per thousand at most).
  EXPECT_NEAR(static_cast<double>(b->Shapes.size()) / a->Shapes.size(), 1.0, 0.05);
  EXPECT_LT(gs_test::ProbeFitFraction(pool, 2000, 7), 0.005);
  EXPECT_LT(gs_test::ProbeFitFraction(rounds, 2000, 7), 0.005);
  // Another seed, size or field: a fresh run.
  o.Seed = 2;
  const Result<ShapeDistribution> c = pool.Run(tables, directions, density, o);
  ASSERT_TRUE(c.Ok());
  EXPECT_FALSE(c->Statistics.Incremental);
  // The same parameters again: nothing to re-decide.
  const Result<ShapeDistribution> d = pool.Run(tables, directions, density, o);
  ASSERT_TRUE(d.Ok());
  EXPECT_TRUE(d->Statistics.Incremental);
  EXPECT_EQ(d->Statistics.Redecided, 0);
  EXPECT_EQ(gs_test::HashRun(pool, c->Shapes), gs_test::HashRun(pool, d->Shapes));
  // An edit of most of the surface runs fresh (in parallel), with the same result.
  const std::vector<double> wide = Brush(plane, { 4.0, 4.0, 0.0 }, 6.0, 0.5, {});
  const Result<ShapeDistribution> w = pool.Run(tables, directions, wide, o);
  ASSERT_TRUE(w.Ok());
  EXPECT_FALSE(w->Statistics.Incremental);
  EXPECT_GT(w->Statistics.EditShare, o.MaximumEditShare);
  ShapeDistributor wideFresh(plane, nullptr);
  const Result<ShapeDistribution> wf = wideFresh.Run(tables, directions, wide, o);
  ASSERT_TRUE(wf.Ok());
  EXPECT_EQ(gs_test::HashRun(pool, w->Shapes), gs_test::HashRun(wideFresh, wf->Shapes));
  // MaximumShapes ends a run at a count: always fresh.
  o.MaximumShapes = 10;
  const Result<ShapeDistribution> e = pool.Run(tables, directions, density, o);
  ASSERT_TRUE(e.Ok());
  EXPECT_FALSE(e->Statistics.Incremental);
  EXPECT_EQ(e->Shapes.size(), 10u);
  // An aborted edit leaves nothing to reuse: the next run is fresh and right.
  o.MaximumShapes = 0;
  ASSERT_TRUE(pool.Run(tables, directions, density, o).Ok());
  const std::vector<double> moved = Brush(plane, { 3.0, 4.0, 0.0 }, 2.0, 0.5, {});
  const Result<ShapeDistribution> aborted =
    pool.Run(tables, directions, moved, o, [](double) { return false; });
  EXPECT_TRUE(aborted.IsAborted());
  const Result<ShapeDistribution> after = pool.Run(tables, directions, moved, o);
  ASSERT_TRUE(after.Ok());
  EXPECT_FALSE(after->Statistics.Incremental);
  ShapeDistributor fresh(plane, nullptr);
  const Result<ShapeDistribution> expected = fresh.Run(tables, directions, moved, o);
  ASSERT_TRUE(expected.Ok());
  EXPECT_EQ(gs_test::HashRun(pool, after->Shapes), gs_test::HashRun(fresh, expected->Shapes));
}

// A fresh place-keyed run prepares its survivors in parallel (charts, outline, exact map and the
// faithfulness verdict the drawn check reads last); an edit of the density almost everywhere on
// one thread re-decides every candidate one at a time, each testing itself where the decision
// reaches the test, and on two threads with its look-ahead. On a rough sphere where
// FaithfulCheck rejects candidates, all give the same shapes, bit for bit.
TEST(ShapeDistributorEdits, ParallelPreparationDecidesAsOneCandidateAtATimeWhereFaithfulnessFails)
{
  const TriangleMesh rough = gs_test::BuildMesh(gs_test::BumpySoup(4, 5, 0.04));
  const SafeDistanceTables tables = gs_test::StarAndBar();
  std::vector<Vec3> directions(rough.NumberOfFaces());
  for (int f = 0; f < rough.NumberOfFaces(); ++f)
  {
    const auto& v = rough.Face(f);
    directions[f] = Cross(Vec3{ 0.3, 0.2, 1.0 }, rough.Position(v[0]) + rough.Position(v[1]) + rough.Position(v[2]));
  }
  ShapeDistributionOptions o;
  o.ShapeSize = 0.08;
  o.Seed = 3;
  o.Order = CandidateOrder::PlaceKeyed;
  o.MaximumEditShare = 1.0;
  o.NumberOfThreads = 2;
  // (The edit keeps a cap at the largest density, as the kept kills need, and changes the rest.)
  const std::vector<double> ones(rough.NumberOfVertices(), 1.0);
  std::vector<double> edited(rough.NumberOfVertices(), 0.999);
  for (int v = 0; v < rough.NumberOfVertices(); ++v)
  {
    edited[v] = rough.Position(v).x > 0.9 ? 1.0 : edited[v];
  }
  ShapeDistributionOptions one = o; // (one thread: no look-ahead, every test at its turn)
  one.NumberOfThreads = 1;
  ShapeDistributor serial(rough, nullptr);
  ASSERT_TRUE(serial.Run(tables, directions, ones, one).Ok());
  const Result<ShapeDistribution> a = serial.Run(tables, directions, edited, one);
  ASSERT_TRUE(a.Ok()) << a.Message();
  EXPECT_TRUE(a->Statistics.Incremental);
  ShapeDistributor fresh(rough, nullptr);
  const Result<ShapeDistribution> b = fresh.Run(tables, directions, edited, o);
  ASSERT_TRUE(b.Ok()) << b.Message();
  EXPECT_FALSE(b->Statistics.Incremental);
  EXPECT_GT(b->Statistics.RejectedByFaithfulCheck, 5);
  EXPECT_GT(b->Shapes.size(), 20u);
  EXPECT_GT(a->Statistics.Redecided, b->Statistics.Redecided / 2); // (most of the pool)
  EXPECT_EQ(gs_test::HashRun(serial, a->Shapes), gs_test::HashRun(fresh, b->Shapes));
  ShapeDistributor ahead(rough, nullptr);
  ASSERT_TRUE(ahead.Run(tables, directions, ones, o).Ok());
  const Result<ShapeDistribution> c = ahead.Run(tables, directions, edited, o);
  ASSERT_TRUE(c.Ok()) << c.Message();
  EXPECT_TRUE(c->Statistics.Incremental);
  EXPECT_EQ(c->Statistics.Redecided, a->Statistics.Redecided);
  EXPECT_EQ(c->Statistics.Charts, a->Statistics.Charts); // (charts made ahead counted as taken)
  EXPECT_EQ(gs_test::HashRun(ahead, c->Shapes), gs_test::HashRun(fresh, b->Shapes));
}
