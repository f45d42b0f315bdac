#include "ExactGeodesic.h"
#include "Hash.h"
#include "GeodesicUnfolding.h"
#include "MeshGenerators.h"
#include "SVGGeodesicSolver.h"
#include "SaddleVertexGraph.h"
#include "TriangleMesh.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>

using namespace gs;
using gs_test::BuildMesh;

namespace
{
TriangleMesh Bumpy(int level, unsigned seed)
{
  return gs_test::BuildMesh(gs_test::BumpySoup(level, seed, 0.1));
}

SaddleVertexGraph BuildGraph(const TriangleMesh& m, int k, int threads = 0)
{
  SaddleVertexGraph g;
  SaddleVertexGraphOptions o;
  o.K = k;
  o.NumberOfThreads = threads;
  EXPECT_TRUE(gs_test::Succeeded(g.Build(m, o, nullptr)));
  return g;
}

struct ErrorStats
{
  double Mean = 0, Max = 0;
};
ErrorStats Compare(const std::vector<double>& approx, const std::vector<double>& exact)
{
  ErrorStats s;
  int n = 0;
  for (std::size_t v = 0; v < exact.size(); ++v)
  {
    if (!(exact[v] > 1e-12) || !std::isfinite(exact[v]))
      continue;
    const double e = std::abs(approx[v] - exact[v]) / exact[v];
    s.Mean += e;
    s.Max = std::max(s.Max, e);
    ++n;
  }
  s.Mean /= std::max(n, 1);
  return s;
}

std::string TempPath(const char* name)
{
  return std::string(::testing::TempDir()) + name;
}
// Every stencil entry (u in x's stencil) is found through the link u -> x, and no other link
// claims a stencil place.
void ExpectLinksIndexStencils(const SaddleVertexGraph& g)
{
  std::int64_t indexed = 0, entries = 0;
  for (int u = 0; u < g.NumberOfVertices(); ++u)
  {
    for (std::int64_t e = g.Begin(u); e < g.End(u); ++e)
    {
      const int i = g.LinkStencilIndex(e);
      if (i >= 0)
      {
        ++indexed;
        const int x = g.Target(e);
        ASSERT_LT(g.StencilBegin(x) + i, g.StencilEnd(x));
        EXPECT_EQ(g.StencilTarget(g.StencilBegin(x) + i), u);
      }
    }
    entries += g.StencilEnd(u) - g.StencilBegin(u);
  }
  EXPECT_EQ(indexed, entries);
  EXPECT_GT(entries, 0);
}
} // namespace

TEST(SaddleVertexGraph, SymmetricSortedAndDeterministic)
{
  const TriangleMesh m = Bumpy(3, 1);
  const SaddleVertexGraph g = BuildGraph(m, 50);
  ASSERT_EQ(g.NumberOfVertices(), m.NumberOfVertices());
  EXPECT_GT(g.MeanDegree(), 6.0);
  EXPECT_LE(g.MeanDegree(), 2.0 * 50 + 6);
  for (int v = 0; v < g.NumberOfVertices(); ++v)
  {
    for (std::int64_t e = g.Begin(v); e < g.End(v); ++e)
    {
      const int w = g.Target(e);
      ASSERT_NE(w, v);
      if (e > g.Begin(v))
        EXPECT_LT(g.Target(e - 1), w);
      bool found = false;
      for (std::int64_t f = g.Begin(w); f < g.End(w); ++f)
      {
        if (g.Target(f) == v)
        {
          found = true;
          EXPECT_EQ(g.Weight(f), g.Weight(e));
        }
      }
      EXPECT_TRUE(found);
      // A link is never shorter than the straight 3D chord.
      EXPECT_GE(g.Weight(e), Norm(m.Position(g.Vertex(v)) - m.Position(g.Vertex(w))) * (1 - 1e-12));
    }
  }
  EXPECT_TRUE(BuildGraph(m, 50, 1) == BuildGraph(m, 50, 2));
  ExpectLinksIndexStencils(g);
}

// The links are gathered into per-node buckets by several threads, each filling its own range of
// nodes: the graph must come out the same for any thread count and on every run (a race there,
// a lost count, misaligns buckets: links then lose their twin or their weight).
TEST(SaddleVertexGraph, IdenticalForAnyThreadCountOnEveryRun)
{
  const TriangleMesh m = Bumpy(3, 1);
  SaddleVertexGraphOptions o;
  o.Construction = GraphConstruction::DiscreteGeodesic;
  o.Accuracy = 0.1;
  o.NumberOfThreads = 1;
  SaddleVertexGraph reference;
  ASSERT_TRUE(gs_test::Succeeded(reference.Build(m, o, nullptr)));
  for (int threads : { 2, 3, 4, 7 })
  {
    for (int run = 0; run < 4; ++run)
    {
      o.NumberOfThreads = threads;
      SaddleVertexGraph g;
      ASSERT_TRUE(gs_test::Succeeded(g.Build(m, o, nullptr)));
      EXPECT_TRUE(g == reference) << threads << " threads, run " << run;
    }
  }
}

TEST(SaddleVertexGraph, RejectsBadK)
{
  const TriangleMesh m = Bumpy(1, 1);
  SaddleVertexGraph g;
  SaddleVertexGraphOptions o;
  o.K = 0;
  EXPECT_TRUE(gs_test::FailedWith(g.Build(m, o, nullptr), "K must be"));
  o.K = 1000000; // clamped to the vertex count
  EXPECT_TRUE(gs_test::Succeeded(g.Build(m, o, nullptr)));
  EXPECT_EQ(g.GetK(), m.NumberOfVertices());
  EXPECT_EQ(SaddleVertexGraph::EffectiveK(o, m.NumberOfVertices()), g.GetK());
}

TEST(SaddleVertexGraph, CheckOptions)
{
  SaddleVertexGraphOptions o;
  EXPECT_TRUE(gs_test::Succeeded(SaddleVertexGraph::CheckOptions(o)));
  o.K = 0;
  EXPECT_TRUE(gs_test::FailedWith(SaddleVertexGraph::CheckOptions(o), "K must be at least 1"));
  o.Construction = GraphConstruction::DiscreteGeodesic; // K does not matter then
  for (double accuracy : { 1e-5, 0.01, 0.1 })
  {
    o.Accuracy = accuracy;
    EXPECT_TRUE(gs_test::Succeeded(SaddleVertexGraph::CheckOptions(o))) << accuracy;
    EXPECT_EQ(SaddleVertexGraph::EffectiveK(o, 100), 0);
  }
  for (double accuracy : { 0.0, 0.2, std::nan("") })
  {
    o.Accuracy = accuracy;
    EXPECT_TRUE(gs_test::FailedWith(SaddleVertexGraph::CheckOptions(o), "within 1e-5 .. 0.1"))
      << accuracy;
  }
}

TEST(SaddleVertexGraph, RefusesWhatMemoryCannotHold)
{
  // The estimate grows linearly with K and the vertex count, and covers what the build keeps.
  EXPECT_NEAR(SaddleVertexGraph::EstimatedBuildBytes(1000, 100),
    2.0 * SaddleVertexGraph::EstimatedBuildBytes(500, 100), 1e-6);
  EXPECT_GT(SaddleVertexGraph::EstimatedBuildBytes(1000, 200),
    1.8 * SaddleVertexGraph::EstimatedBuildBytes(1000, 100));
  EXPECT_EQ(SaddleVertexGraph::EstimatedBuildBytes(10, 1000000),
    SaddleVertexGraph::EstimatedBuildBytes(10, 10)); // K is clamped as Build clamps it
  const TriangleMesh m = Bumpy(2, 1);
  SaddleVertexGraph g;
  SaddleVertexGraphOptions o;
  o.K = 50;
  ASSERT_TRUE(gs_test::Succeeded(g.Build(m, o, nullptr)));
  EXPECT_LT(static_cast<double>(g.MemoryBytes()),
    SaddleVertexGraph::EstimatedBuildBytes(m.NumberOfVertices(), 50));
  EXPECT_GT(SaddleVertexGraph::AvailableMemoryBytes(), 0.0); // Linux: /proc/meminfo

  // A machine with 1 MiB to spare: refused before allocating, with the figures and the remedy.
  const double needed = SaddleVertexGraph::EstimatedBuildBytes(m.NumberOfVertices(), 50);
  ASSERT_GT(needed, 0.8 * 1048576.0);
  setenv("GS_AVAILABLE_MEMORY", "1048576", 1);
  const Status refused = g.Build(m, o, nullptr);
  unsetenv("GS_AVAILABLE_MEMORY");
  EXPECT_TRUE(g.Empty());
  EXPECT_TRUE(gs_test::FailedWith(refused, "MiB available; lower K"));
  EXPECT_TRUE(gs_test::Succeeded(g.Build(m, o, nullptr)));
}

TEST(SaddleVertexGraph, ProgressCanAbort)
{
  const TriangleMesh m = Bumpy(4, 1);
  SaddleVertexGraph g;
  int calls = 0;
  const auto abortSecond = [&](double) { return ++calls < 2; };
  EXPECT_TRUE(g.Build(m, SaddleVertexGraphOptions(), abortSecond).IsAborted());
  EXPECT_TRUE(g.Empty());
}

TEST(SaddleVertexGraph, SolverSaysWhichSourceIsInvalid)
{
  const TriangleMesh m = Bumpy(1, 1);
  const SaddleVertexGraph g = BuildGraph(m, 20);
  SVGGeodesicSolver svg(m, g);
  const SurfacePoint vertex = SurfacePoint::AtVertex(0);
  EXPECT_TRUE(gs_test::FailedWith(svg.Solve({}), "no source"));
  const SurfacePoint beyond = SurfacePoint::AtVertex(m.NumberOfVertices());
  EXPECT_TRUE(gs_test::FailedWith(svg.Solve({ vertex, beyond }),
    "source 1 is invalid: vertex " + std::to_string(m.NumberOfVertices()) + " does not exist"));
  EXPECT_TRUE(std::isinf(svg.Distance(0))); // a rejected solve leaves every vertex unreached
  EXPECT_TRUE(gs_test::FailedWith(svg.SolveCurves({}), "no curve"));
  EXPECT_TRUE(gs_test::FailedWith(svg.SolveCurves({ { vertex }, {} }), "curve 1 has no point"));
  const SurfacePoint overweight = SurfacePoint::InFace(0, 0.5, 0.5, 0.5);
  EXPECT_TRUE(gs_test::FailedWith(svg.SolveCurve({ vertex, overweight }),
    "curve 0, point 1 is invalid: the barycentric coordinates (0.5, 0.5, 0.5) in face 0 sum to"));
}

TEST(SaddleVertexGraph, LabelCorrectingEqualsDijkstra)
{
  const TriangleMesh m = Bumpy(3, 2);
  const SaddleVertexGraph g = BuildGraph(m, 30);
  GraphDistanceSolver a(g), b(g);
  for (int s : { 0, 99, 500 })
  {
    a.Solve({ { s, 0.0 } }, GraphAlgorithm::LabelCorrecting);
    b.Solve({ { s, 0.0 } }, GraphAlgorithm::Dijkstra);
    for (int v = 0; v < m.NumberOfVertices(); ++v)
    {
      EXPECT_NEAR(a.Distance(v), b.Distance(v), 1e-12);
      // The predecessor link ends at v, starts at the predecessor and gives v its distance.
      for (const GraphDistanceSolver* solver : { &a, &b })
      {
        const std::int64_t link = solver->PredecessorLink(v);
        if (v == s)
        {
          EXPECT_EQ(link, -1);
          continue;
        }
        ASSERT_GE(link, 0);
        const int p = solver->Predecessor(v);
        EXPECT_GE(link, g.Begin(p));
        EXPECT_LT(link, g.End(p));
        EXPECT_EQ(g.Target(link), v);
        EXPECT_NEAR(solver->Distance(p) + g.Weight(link), solver->Distance(v), 1e-12);
      }
    }
  }
  // Multi-source with offsets, and a maximum distance.
  a.Solve({ { 3, 0.2 }, { 400, 0.0 } }, GraphAlgorithm::LabelCorrecting, 0.7);
  b.Solve({ { 3, 0.2 }, { 400, 0.0 } }, GraphAlgorithm::Dijkstra, 0.7);
  int reached = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    EXPECT_EQ(std::isfinite(a.Distance(v)), std::isfinite(b.Distance(v)));
    if (std::isfinite(a.Distance(v)))
    {
      ++reached;
      EXPECT_LE(a.Distance(v), 0.7);
      EXPECT_NEAR(a.Distance(v), b.Distance(v), 1e-12);
    }
  }
  EXPECT_GT(reached, 10);
  EXPECT_LT(reached, m.NumberOfVertices());
}

TEST(SaddleVertexGraph, AccuracyAgainstExactSolver)
{
  for (unsigned seed : { 3u, 4u })
  {
    const TriangleMesh m = Bumpy(4, seed);
    ExactGeodesicSolver exact(m);
    double previous = INFINITY;
    for (int k : { 50, 100 })
    {
      const SaddleVertexGraph g = BuildGraph(m, k);
      SVGGeodesicSolver svg(m, g);
      ErrorStats total;
      for (int s : { 7, 1234, 2000 })
      {
        EXPECT_TRUE(gs_test::Succeeded(exact.Solve(s)));
        ASSERT_TRUE(gs_test::Succeeded(svg.Solve({ SurfacePoint::AtVertex(s) })));
        const ErrorStats e = Compare(svg.Distances(), exact.Distances());
        total.Mean += e.Mean / 3;
        total.Max = std::max(total.Max, e.Max);
      }
      EXPECT_LT(total.Mean, 1e-3) << "K = " << k;
      EXPECT_LT(total.Max, 2e-2) << "K = " << k;
      EXPECT_LE(total.Mean, previous) << "a larger K must not be less accurate";
      previous = total.Mean;
    }
  }
}

TEST(SaddleVertexGraph, FacePointSourceExactInsideItsDiskOnAPlane)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(30, 30, 3.0, 3.0));
  const SaddleVertexGraph g = BuildGraph(m, 50);
  SVGGeodesicSolver svg(m, g);
  const SurfacePoint src = SurfacePoint::InFace(901, 0.2, 0.3, 0.5);
  ASSERT_TRUE(gs_test::Succeeded(svg.Solve({ src })));
  const Vec3 s = m.Interpolate(src.Face, src.Bary);
  // The source's own K-disk: the exact solver's K nearest vertices.
  ExactGeodesicSolver exact(m);
  ExactGeodesicOptions opt;
  opt.MaximumFinalVertices = 50;
  EXPECT_TRUE(gs_test::Succeeded(exact.Solve({ src }, opt)));
  const double radius = exact.Distance(exact.FinalVertices().back());
  for (int v : exact.FinalVertices())
    EXPECT_NEAR(svg.Distance(v), Norm(m.Position(v) - s), 1e-9 * (1 + radius));
  // Arbitrary points of faces whose corners are all inside the disk.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int checked = 0;
  for (int f = 0; f < m.NumberOfFaces(); ++f)
  {
    const auto& t = m.Face(f);
    if (std::max({ Norm(m.Position(t[0]) - s), Norm(m.Position(t[1]) - s),
          Norm(m.Position(t[2]) - s) }) > 0.95 * radius)
      continue;
    double a = u(rng), b = u(rng);
    if (a + b > 1)
    {
      a = 1 - a;
      b = 1 - b;
    }
    const SurfacePoint q = SurfacePoint::InFace(f, a, b, 1 - a - b);
    EXPECT_NEAR(svg.DistanceAt(q), Norm(m.Interpolate(f, q.Bary) - s), 1e-9) << "face " << f;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(SaddleVertexGraph, ArbitraryPointsAgainstExactSolver)
{
  TriangleSoup soup = MakeIcosphere(1.0, 4);
  {
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> u(0.9, 1.1);
    for (Vec3& p : soup.Points)
      p = p * u(rng);
  }
  const TriangleMesh m = BuildMesh(soup);
  const SaddleVertexGraph g = BuildGraph(m, 50);
  SVGGeodesicSolver svg(m, g);
  ExactGeodesicSolver exact(m);
  std::mt19937 rng(8);
  std::uniform_int_distribution<int> face(0, m.NumberOfFaces() - 1);
  std::uniform_real_distribution<double> u(0.05, 0.9);
  double mean = 0, pointMean = 0;
  int n = 0;
  for (int trial = 0; trial < 4; ++trial)
  {
    const double a = u(rng), b = (1 - a) * u(rng);
    const SurfacePoint src = SurfacePoint::InFace(face(rng), a, b, 1 - a - b);
    ASSERT_TRUE(gs_test::Succeeded(svg.Solve({ src })));
    EXPECT_TRUE(gs_test::Succeeded(exact.Solve({ src })));
    const ErrorStats e = Compare(svg.Distances(), exact.Distances());
    mean += e.Mean;
    ++n;
    // Point to point: the exact reference inserts the target point as a vertex of its face
    // (splitting it in three: the same surface) and solves from the source point.
    SurfacePoint q = SurfacePoint::InFace(face(rng), 0.3, 0.25, 0.45);
    if (q.Face == src.Face)
      q.Face = (q.Face + 1) % m.NumberOfFaces();
    TriangleSoup split = soup;
    const long long qv = static_cast<long long>(split.Points.size());
    split.Points.push_back(m.Interpolate(q.Face, q.Bary));
    const auto t = m.Face(q.Face);
    split.Triangles[q.Face] = { t[0], t[1], qv };
    split.Triangles.push_back({ t[1], t[2], qv });
    split.Triangles.push_back({ t[2], t[0], qv });
    const TriangleMesh ms = BuildMesh(split);
    ExactGeodesicSolver reference(ms);
    EXPECT_TRUE(gs_test::Succeeded(reference.Solve({ src })));
    const double ref = reference.Distance(static_cast<int>(qv));
    const double got = svg.DistanceAt(q);
    // Unfolding assumes the geodesic triangle is flat: on this deliberately rough surface a point
    // query is within a couple of percent (on developable surfaces it is exact, tested above).
    EXPECT_NEAR(got, ref, 2e-2 * ref);
    pointMean += std::abs(got - ref) / ref;
    EXPECT_NEAR(svg.Distance(src, q), got, 1e-12);
    EXPECT_NEAR(svg.DistancesTo(src, { q, src })[0], got, 1e-12);
  }
  EXPECT_LT(mean / n, 1e-3);
  EXPECT_LT(pointMean / n, 1e-2);
}

TEST(SaddleVertexGraph, UnfoldingIsExactOnAPlane)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(4, 4, 1.0, 1.0));
  const Vec3 s(-0.7, 0.35, 0.0); // outside the mesh, as an unfolded source would be
  for (int f = 0; f < m.NumberOfFaces(); ++f)
  {
    const auto& t = m.Face(f);
    const std::array<double, 3> d = { { Norm(m.Position(t[0]) - s), Norm(m.Position(t[1]) - s),
      Norm(m.Position(t[2]) - s) } };
    const std::array<double, 3> b = { { 0.25, 0.6, 0.15 } };
    EXPECT_NEAR(UnfoldedDistance(m, f, b, d), Norm(m.Interpolate(f, b) - s), 1e-12);
  }
}

TEST(SaddleVertexGraph, CurveSourceOnAPlane)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(40, 40, 4.0, 4.0));
  const SaddleVertexGraph g = BuildGraph(m, 50);
  SVGGeodesicSolver svg(m, g);
  // A straight curve from (1.03, 1.51) to (2.97, 2.23), as surface points a fraction of an edge
  // apart (each in the face containing it).
  const Vec3 a(1.03, 1.51, 0), b(2.97, 2.23, 0);
  auto locate = [&](const Vec3& p) {
    for (int f = 0; f < m.NumberOfFaces(); ++f)
    {
      const auto& t = m.Face(f);
      const Vec3 P0 = m.Position(t[0]), P1 = m.Position(t[1]), P2 = m.Position(t[2]);
      const double area = Cross(P1 - P0, P2 - P0).z;
      const double w0 = Cross(P1 - p, P2 - p).z / area, w1 = Cross(P2 - p, P0 - p).z / area;
      const double w2 = 1 - w0 - w1;
      if (w0 >= -1e-12 && w1 >= -1e-12 && w2 >= -1e-12)
        return SurfacePoint::InFace(f, w0, w1, w2);
    }
    return SurfacePoint();
  };
  std::vector<SurfacePoint> curve;
  for (int i = 0; i <= 60; ++i)
    curve.push_back(locate(a + (b - a) * (i / 60.0)));
  ASSERT_TRUE(gs_test::Succeeded(svg.SolveCurve(curve)));
  EXPECT_GT(svg.NumberOfCurvePieces(), 60);
  double mean = 0, worst = 0;
  int n = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const Vec3 p = m.Position(v);
    const Vec3 ab = b - a;
    const double t = std::min(1.0, std::max(0.0, Dot(p - a, ab) / Dot(ab, ab)));
    const double exact = Norm(p - (a + ab * t));
    if (exact < 1e-9)
      continue;
    const double e = std::abs(svg.Distance(v) - exact) / exact;
    mean += e;
    worst = std::max(worst, e);
    ++n;
  }
  EXPECT_LT(mean / n, 1e-3);
  EXPECT_LT(worst, 2e-2);
  // A point of a face the curve crosses: the exact in-face distance to the curve.
  const SurfacePoint q = locate(Vec3(2.0, 1.9, 0));
  const Vec3 qp = m.Interpolate(q.Face, q.Bary);
  const double t = Dot(qp - a, b - a) / Dot(b - a, b - a);
  EXPECT_NEAR(svg.DistanceAt(q), Norm(qp - (a + (b - a) * t)), 1e-9);
}

TEST(SaddleVertexGraph, CacheRoundTripAndRejections)
{
  const TriangleMesh m = Bumpy(2, 9);
  const SaddleVertexGraph g = BuildGraph(m, 20);
  const std::uint64_t hash = SaddleVertexGraph::HashMesh(m);
  const std::string path = TempPath("gs_cache_test.svgg");
  ASSERT_TRUE(gs_test::Succeeded(g.Save(path, hash)));
  SaddleVertexGraph loaded;
  ASSERT_TRUE(gs_test::Succeeded(loaded.Load(path, hash, 20)));
  EXPECT_TRUE(loaded == g);
  ExpectLinksIndexStencils(loaded);
  EXPECT_EQ(loaded.BuildSeconds(), g.BuildSeconds());
  EXPECT_TRUE(gs_test::FailedWith(loaded.Load(path, hash + 1, 20), "another mesh"));
  EXPECT_TRUE(loaded.Empty());
  EXPECT_TRUE(gs_test::FailedWith(loaded.Load(path, hash, 21), "K ="));
  EXPECT_FALSE(loaded.Load(TempPath("does_not_exist.svgg"), hash, 20).Ok());

  // A stale file: the mesh moved a little.
  TriangleSoup s = MakeIcosphere(1.0, 2);
  const TriangleMesh other = BuildMesh(s);
  EXPECT_NE(SaddleVertexGraph::HashMesh(other), hash);

  // Corruption: one flipped byte in the payload, a truncated file, garbage.
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  auto writeFile = [&](const std::string& content) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << content;
  };
  std::string flipped = bytes;
  flipped[bytes.size() / 2] ^= 0x10;
  writeFile(flipped);
  EXPECT_TRUE(gs_test::FailedWith(loaded.Load(path, hash, 20), "corrupt"));
  writeFile(bytes.substr(0, bytes.size() - 100));
  EXPECT_FALSE(loaded.Load(path, hash, 20).Ok());
  // A file of the previous format (no node order) is recognised as such.
  std::string previous = bytes;
  previous[7] = '3';
  writeFile(previous);
  EXPECT_TRUE(gs_test::FailedWith(loaded.Load(path, hash, 20), "another format version"));
  writeFile("not a graph at all");
  EXPECT_FALSE(loaded.Load(path, hash, 20).Ok());
  writeFile("");
  EXPECT_FALSE(loaded.Load(path, hash, 20).Ok());
  // A forged file with a valid checksum whose node order is not a permutation (the last node
  // repeats the first's vertex): rejected by the structural checks, not read out of range.
  {
    std::string forged = bytes;
    const std::size_t nodeOrder = forged.size() - 8 - 4 * m.NumberOfVertices();
    std::memcpy(&forged[forged.size() - 12], &forged[nodeOrder], 4);
    gs::Hasher sum;
    sum.Add(forged.data() + 8, forged.size() - 16);
    std::memcpy(&forged[forged.size() - 8], &sum.H, 8);
    writeFile(forged);
    EXPECT_TRUE(gs_test::FailedWith(loaded.Load(path, hash, 20), "node order"));
    EXPECT_TRUE(loaded.Empty());
  }
  writeFile(bytes);
  EXPECT_TRUE(gs_test::Succeeded(loaded.Load(path, hash, 20)));
  std::remove(path.c_str());
}

TEST(SaddleVertexGraph, NodesAreTheVerticesInSpatialOrder)
{
  // Node and Vertex are inverse permutations; every mesh edge is a link between its end
  // points' nodes with the edge's length; and the order is local: a mesh edge joins nodes much
  // closer in index than the vertices of a shuffled mesh (whose order is random).
  TriangleSoup soup = MakeIcosphere(1.0, 4);
  std::vector<int> shuffle(soup.Points.size());
  for (std::size_t i = 0; i < shuffle.size(); ++i)
  {
    shuffle[i] = static_cast<int>(i);
  }
  std::shuffle(shuffle.begin(), shuffle.end(), std::mt19937(5));
  TriangleSoup shuffled = soup;
  for (std::size_t i = 0; i < shuffle.size(); ++i)
  {
    shuffled.Points[shuffle[i]] = soup.Points[i];
  }
  for (auto& t : shuffled.Triangles)
  {
    for (auto& v : t)
    {
      v = shuffle[v];
    }
  }
  const TriangleMesh m = BuildMesh(shuffled);
  const SaddleVertexGraph g = BuildGraph(m, 20);
  const int nv = m.NumberOfVertices();
  std::vector<int> seen(nv, 0);
  for (int v = 0; v < nv; ++v)
  {
    ASSERT_GE(g.Node(v), 0);
    ASSERT_LT(g.Node(v), nv);
    EXPECT_EQ(g.Vertex(g.Node(v)), v);
    ++seen[g.Node(v)];
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), nv);
  double vertexGap = 0.0, nodeGap = 0.0;
  for (int h = 0; h < m.NumberOfHalfedges(); ++h)
  {
    const int a = m.Origin(h), b = m.Destination(h);
    const int na = g.Node(a), nb = g.Node(b);
    bool found = false;
    for (std::int64_t e = g.Begin(na); e < g.End(na); ++e)
    {
      if (g.Target(e) == nb)
      {
        found = true;
        EXPECT_NEAR(g.Weight(e), m.EdgeLength(h), 1e-12);
      }
    }
    EXPECT_TRUE(found) << a << " " << b;
    vertexGap += std::abs(a - b);
    nodeGap += std::abs(na - nb);
  }
  EXPECT_LT(nodeGap, 0.25 * vertexGap);
  // Solves speak mesh vertices whatever the order: the shuffled sphere gives the unshuffled
  // one's distances.
  const TriangleMesh plain = BuildMesh(soup);
  const SaddleVertexGraph gp = BuildGraph(plain, 20);
  SVGGeodesicSolver a(plain, gp), b(m, g);
  ASSERT_TRUE(gs_test::Succeeded(a.Solve({ SurfacePoint::AtVertex(7) })));
  ASSERT_TRUE(gs_test::Succeeded(b.Solve({ SurfacePoint::AtVertex(shuffle[7]) })));
  const std::vector<double> da = a.Distances(), db = b.Distances();
  for (int v = 0; v < nv; ++v)
  {
    EXPECT_NEAR(da[v], db[shuffle[v]], 1e-9 * (1.0 + da[v]));
    EXPECT_EQ(b.Distance(shuffle[v]), db[shuffle[v]]);
  }
  EXPECT_EQ(b.Reached().size(), static_cast<std::size_t>(nv));
}

TEST(SaddleVertexGraph, UnfoldingRefinementOnDevelopableSurfaces)
{
  // Without saddles, graph paths are polylines; unfolding the geodesic triangles of the polar
  // stencils makes the distances exact on developable surfaces (plane, cylinder).
  for (const TriangleSoup& soup : { MakePlanarGrid(30, 20, 3.0, 2.0), MakeCylinder(1.0, 3.0, 32, 12) })
  {
    const TriangleMesh m = BuildMesh(soup);
    const SaddleVertexGraph g = BuildGraph(m, 50);
    SVGGeodesicSolver svg(m, g);
    ExactGeodesicSolver exact(m);
    for (int s : { 0, 77, 301 })
    {
      EXPECT_TRUE(gs_test::Succeeded(exact.Solve(s)));
      SVGSolveOptions plain, refined;
      plain.Refine = false;
      refined.Refine = true;
      EXPECT_TRUE(gs_test::Succeeded(svg.Solve({ SurfacePoint::AtVertex(s) }, plain)));
      const ErrorStats before = Compare(svg.Distances(), exact.Distances());
      EXPECT_TRUE(gs_test::Succeeded(svg.Solve({ SurfacePoint::AtVertex(s) }, refined)));
      const ErrorStats after = Compare(svg.Distances(), exact.Distances());
      EXPECT_GT(before.Mean, 5e-4);
      // Exact up to rounding: every geodesic triangle of a developable surface unfolds.
      EXPECT_LT(after.Mean, 1e-12);
      EXPECT_LT(after.Max, 1e-10);
    }
  }
}

TEST(SaddleVertexGraph, AnglesWithoutRefinementKeepGraphDistances)
{
  // Departure angles are interpolated across the unfolded geodesic triangles; with refinement
  // off, that unfolding must not lower the distances (on a plane it would: graph paths are
  // polylines there, the unfolding is exact). The angles themselves still come out.
  const TriangleMesh m = BuildMesh(MakePlanarGrid(30, 20, 3.0, 2.0));
  const SaddleVertexGraph g = BuildGraph(m, 50);
  SVGGeodesicSolver svg(m, g);
  for (const SurfacePoint& s : { SurfacePoint::AtVertex(77), SurfacePoint::InFace(400, 0.2, 0.3, 0.5) })
  {
    SVGSolveOptions plain, withAngles;
    plain.Refine = false;
    withAngles.Refine = false;
    withAngles.Angles = true;
    ASSERT_TRUE(gs_test::Succeeded(svg.Solve({ s }, plain)));
    const std::vector<double> expected = svg.Distances();
    ASSERT_TRUE(gs_test::Succeeded(svg.Solve({ s }, withAngles)));
    int angles = 0;
    for (int v = 0; v < m.NumberOfVertices(); ++v)
    {
      EXPECT_EQ(svg.Distance(v), expected[v]) << v;
      angles += std::isfinite(svg.DepartureAngle(v)) ? 1 : 0;
    }
    EXPECT_GT(angles, m.NumberOfVertices() - 2);
  }
}

// The refinement on several threads (SVGSolveOptions::NumberOfThreads, forced below its size
// threshold) gives the one-thread distances to the bit: vertex, face-point, multi-vertex and
// curve sources, with and without a distance limit, on both graphs, on a curved mesh and on a
// regular grid (whose symmetric distances tie in the sweep's order), every run.
TEST(SaddleVertexGraph, ParallelRefinementGivesTheSameDistances)
{
  const TriangleMesh bumpy = Bumpy(4, 3);
  const TriangleMesh grid = BuildMesh(MakePlanarGrid(60, 60, 1.0, 1.0));
  int meshIndex = 0;
  for (const TriangleMesh* m : { &bumpy, &grid })
  {
    ++meshIndex;
    SaddleVertexGraphOptions dgg;
    dgg.Construction = GraphConstruction::DiscreteGeodesic;
    dgg.Accuracy = 0.1;
    SaddleVertexGraph graphs[2];
    graphs[0] = BuildGraph(*m, 20);
    ASSERT_TRUE(gs_test::Succeeded(graphs[1].Build(*m, dgg, nullptr)));
    const int nv = m->NumberOfVertices();
    const std::vector<std::vector<SurfacePoint>> sources = { { SurfacePoint::AtVertex(nv / 2) },
      { SurfacePoint::InFace(m->NumberOfFaces() / 3, 0.2, 0.3, 0.5) },
      { SurfacePoint::AtVertex(1), SurfacePoint::AtVertex(nv - 2) } };
    for (const SaddleVertexGraph& g : graphs)
    {
      SVGGeodesicSolver solver(*m, g);
      for (double limit : { 0.0, 0.4 })
      {
        for (std::size_t s = 0; s <= sources.size(); ++s)
        {
          SVGSolveOptions one;
          one.MaximumDistance = limit;
          auto solve = [&](const SVGSolveOptions& o) {
            if (s < sources.size())
              return solver.Solve(sources[s], o);
            return solver.SolveCurve({ SurfacePoint::AtVertex(nv / 4), SurfacePoint::AtVertex(nv / 4 + 7) }, o);
          };
          ASSERT_TRUE(gs_test::Succeeded(solve(one)));
          std::vector<double> reference(nv);
          int reached = 0;
          for (int v = 0; v < nv; ++v)
          {
            reference[v] = solver.Distance(v);
            reached += std::isfinite(reference[v]) ? 1 : 0;
          }
          EXPECT_GT(reached, limit > 0.0 ? 10 : nv - 1);
          for (int threads : { 2, 3, 4 })
          {
            for (int run = 0; run < 3; ++run)
            {
              SVGSolveOptions parallel = one;
              parallel.NumberOfThreads = threads;
              parallel.ParallelRefinementMinimum = 0;
              ASSERT_TRUE(gs_test::Succeeded(solve(parallel)));
              int different = 0;
              for (int v = 0; v < nv; ++v)
              {
                const double d = solver.Distance(v);
                different += std::memcmp(&d, &reference[v], sizeof d) != 0 ? 1 : 0;
              }
              EXPECT_EQ(different, 0) << "mesh " << meshIndex << ", " << (&g == &graphs[0] ? "SVG" : "DGG")
                                      << ", source " << s << ", limit " << limit << ", " << threads
                                      << " threads, run " << run;
            }
          }
        }
      }
    }
  }
}
