#include "ExactGeodesic.h"
#include "MeshGenerators.h"
#include "TriangleMesh.h"
#include "WindowGeometry.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <set>
#include <random>

using namespace gs;
using gs_test::BuildMesh;

namespace
{
constexpr double Pi = 3.14159265358979323846;

// Largest relative error of the solver's distances against an analytic function of the vertex.
template <typename F>
double MaxRelativeError(const ExactGeodesicSolver& solver, F exact, double floor = 1e-12)
{
  double worst = 0;
  for (int v = 0; v < solver.Mesh().NumberOfVertices(); ++v)
  {
    const double e = exact(v);
    const double d = solver.Distance(v);
    worst = std::max(worst, std::abs(d - e) / std::max(e, floor));
  }
  return worst;
}

// Edge-graph Dijkstra: an upper bound of the geodesic distance.
std::vector<double> GraphDistances(const TriangleMesh& m, int source)
{
  std::vector<double> d(m.NumberOfVertices(), INFINITY);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  d[source] = 0;
  q.push({ 0, source });
  while (!q.empty())
  {
    auto [dv, v] = q.top();
    q.pop();
    if (dv > d[v])
      continue;
    for (int h : m.OutgoingHalfedges(v))
    {
      for (int e : { h, TriangleMesh::Prev(h) })
      {
        const int w = e == h ? m.Destination(h) : m.Origin(e);
        const double nd = dv + m.EdgeLength(e);
        if (nd < d[w])
        {
          d[w] = nd;
          q.push({ nd, w });
        }
      }
    }
  }
  return d;
}

TriangleMesh BumpyMesh(int level, unsigned seed)
{
  return gs_test::BuildMesh(gs_test::BumpySoup(level, seed, 0.15));
}
} // namespace

TEST(ExactGeodesic, PlanarGridFromVertexIsEuclidean)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(20, 15, 2.0, 1.5));
  ExactGeodesicSolver solver(m);
  for (int source : { 0, 7 * 21 + 9, 20 })
  {
    ASSERT_TRUE(gs_test::Succeeded(solver.Solve(source)));
    const Vec3 s = m.Position(source);
    EXPECT_LT(MaxRelativeError(solver, [&](int v) { return Norm(m.Position(v) - s); }), 1e-9);
    EXPECT_EQ(solver.FinalVertices().size(), static_cast<std::size_t>(m.NumberOfVertices()));
    // No saddles and no reflex boundary vertex: every shortest path is direct, even those that
    // graze the straight boundary or pass exactly through flat interior vertices.
    for (int v = 0; v < m.NumberOfVertices(); ++v)
    {
      EXPECT_TRUE(solver.IsDirect(v)) << "vertex " << v;
    }
  }
}

TEST(ExactGeodesic, PlanarGridFromFacePointAndEdgePoint)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(12, 12, 1.0, 1.0));
  ExactGeodesicSolver solver(m);
  for (auto sp : { SurfacePoint::InFace(37, 0.2, 0.5, 0.3), SurfacePoint::InFace(100, 0.6, 0.4, 0.0),
         SurfacePoint::InFace(3, 1.0, 0.0, 0.0) })
  {
    ASSERT_TRUE(gs_test::Succeeded(solver.Solve({ sp })));
    const Vec3 s = m.Interpolate(sp.Face, sp.Bary);
    EXPECT_LT(MaxRelativeError(solver, [&](int v) { return Norm(m.Position(v) - s); }), 1e-9);
  }
}

TEST(ExactGeodesic, LShapeBendsAroundReentrantCorner)
{
  const int n = 10;
  const TriangleMesh m = BuildMesh(MakeLShape(n));
  ExactGeodesicSolver solver(m);
  const Vec3 corner(1, 1, 0);
  // Visible when the segment does not enter the removed square (1,2] x (1,2].
  auto visible = [](const Vec3& a, const Vec3& b) {
    for (int k = 0; k <= 2000; ++k)
    {
      const Vec3 p = a + (b - a) * (k / 2000.0);
      if (p.x > 1 + 1e-12 && p.y > 1 + 1e-12)
        return false;
    }
    return true;
  };
  for (int source = 0; source < m.NumberOfVertices(); source += 37)
  {
    ASSERT_TRUE(gs_test::Succeeded(solver.Solve(source)));
    const Vec3 s = m.Position(source);
    int bent = 0;
    const double err = MaxRelativeError(solver, [&](int v) {
      const Vec3 p = m.Position(v);
      if (visible(s, p))
        return Norm(p - s);
      ++bent;
      return Norm(corner - s) + Norm(p - corner);
    });
    EXPECT_LT(err, 1e-9) << "source " << source;
    if (s.x > 1.2 && s.y < 0.8)
    {
      EXPECT_GT(bent, 0);
    }
  }
}

TEST(ExactGeodesic, DevelopableConeMatchesUnrolledSector)
{
  const int rings = 8, sectors = 24;
  const double halfAngle = 0.45, slant = 2.0;
  const TriangleMesh m = BuildMesh(MakeCone(halfAngle, slant, rings, sectors));
  // The polyhedral cone unrolls to a fan of isosceles triangles with apex angle gamma.
  const double gamma = 2 * std::asin(std::sin(halfAngle) * std::sin(Pi / sectors));
  auto polar = [&](int v) {
    // (slant distance, sector index) of a generated vertex (apex = 0).
    const int i = (v - 1) / sectors + 1, j = (v - 1) % sectors;
    return std::make_pair(slant * i / rings, j);
  };
  ExactGeodesicSolver solver(m);
  ASSERT_TRUE(gs_test::Succeeded(solver.Solve(0)));
  EXPECT_LT(MaxRelativeError(solver, [&](int v) { return v == 0 ? 0.0 : polar(v).first; }), 1e-9);
  for (int source : { 1 + 3 * sectors + 5, 1 + (rings - 1) * sectors, 1 + 5 })
  {
    ASSERT_TRUE(gs_test::Succeeded(solver.Solve(source)));
    const auto [rs, js] = polar(source);
    const double err = MaxRelativeError(solver, [&](int v) {
      if (v == 0)
        return rs;
      const auto [r, j] = polar(v);
      const int dj = std::abs(j - js);
      const double phi = std::min(dj, sectors - dj) * gamma;
      return phi >= Pi ? r + rs : std::sqrt(r * r + rs * rs - 2 * r * rs * std::cos(phi));
    });
    EXPECT_LT(err, 1e-9) << "source " << source;
  }
}

TEST(ExactGeodesic, DevelopableCylinderMatchesUnrolledStrip)
{
  const int sectors = 20, rings = 10;
  const double radius = 1.0, height = 3.0;
  const TriangleMesh m = BuildMesh(MakeCylinder(radius, height, sectors, rings));
  const double chord = 2 * radius * std::sin(Pi / sectors);
  ExactGeodesicSolver solver(m);
  for (int source : { 0, 4 * sectors + 7, rings * sectors + 3 })
  {
    ASSERT_TRUE(gs_test::Succeeded(solver.Solve(source)));
    const int is = source / sectors, js = source % sectors;
    const double err = MaxRelativeError(solver, [&](int v) {
      const int i = v / sectors, j = v % sectors;
      const int dj = std::abs(j - js);
      const double dx = std::min(dj, sectors - dj) * chord;
      const double dz = height * (i - is) / rings;
      return std::hypot(dx, dz);
    });
    EXPECT_LT(err, 1e-9) << "source " << source;
  }
}

TEST(ExactGeodesic, SphereConvergesToGreatCircleDistance)
{
  double previous = INFINITY;
  for (int level : { 3, 4 })
  {
    const TriangleMesh m = BuildMesh(MakeIcosphere(1.0, level));
    ExactGeodesicSolver solver(m);
    ASSERT_TRUE(gs_test::Succeeded(solver.Solve(0)));
    const Vec3 s = m.Position(0);
    double worst = 0;
    for (int v = 0; v < m.NumberOfVertices(); ++v)
    {
      const double exact = std::acos(std::clamp(Dot(m.Position(v), s), -1.0, 1.0));
      if (exact > 0.3)
      {
        worst = std::max(worst, std::abs(solver.Distance(v) - exact) / exact);
      }
    }
    EXPECT_LT(worst, level == 3 ? 0.01 : 0.003) << "level " << level;
    EXPECT_LT(worst, previous / 3.0) << "refinement must reduce the error";
    previous = worst;
  }
}

TEST(ExactGeodesic, NonDevelopableSurfaceIsSymmetricAndBounded)
{
  const TriangleMesh m = BumpyMesh(3, 7);
  ExactGeodesicSolver solver(m);
  const int nv = m.NumberOfVertices();
  std::vector<int> sources = { 0, 17, 151, 333, nv - 1 };
  std::vector<std::vector<double>> d;
  for (int s : sources)
  {
    ASSERT_TRUE(gs_test::Succeeded(solver.Solve(s)));
    d.push_back(solver.Distances());
    const std::vector<double> graph = GraphDistances(m, s);
    for (int v = 0; v < nv; ++v)
    {
      ASSERT_TRUE(std::isfinite(d.back()[v]));
      EXPECT_LE(d.back()[v], graph[v] * (1 + 1e-12));
      EXPECT_GE(d.back()[v], Norm(m.Position(v) - m.Position(s)) * (1 - 1e-12));
    }
    // 1-Lipschitz along edges.
    for (int h = 0; h < m.NumberOfHalfedges(); ++h)
    {
      EXPECT_LE(std::abs(d.back()[m.Origin(h)] - d.back()[m.Destination(h)]),
        m.EdgeLength(h) * (1 + 1e-9));
    }
  }
  for (std::size_t a = 0; a < sources.size(); ++a)
  {
    for (std::size_t b = 0; b < sources.size(); ++b)
    {
      EXPECT_NEAR(d[a][sources[b]], d[b][sources[a]], 1e-10 * (1 + d[a][sources[b]]));
    }
  }
}

TEST(ExactGeodesic, MultiSourceIsTheMinimum)
{
  const TriangleMesh m = BumpyMesh(2, 3);
  ExactGeodesicSolver solver(m);
  std::vector<double> expected(m.NumberOfVertices(), INFINITY);
  for (int s : { 5, 60, 121 })
  {
    EXPECT_TRUE(gs_test::Succeeded(solver.Solve(s)));
    for (int v = 0; v < m.NumberOfVertices(); ++v)
      expected[v] = std::min(expected[v], solver.Distance(v));
  }
  ASSERT_TRUE(gs_test::Succeeded(solver.Solve(
    { SurfacePoint::AtVertex(5), SurfacePoint::AtVertex(60), SurfacePoint::AtVertex(121) })));
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    EXPECT_NEAR(solver.Distance(v), expected[v], 1e-10);
  }
}

TEST(ExactGeodesic, FacePointSourceIsSymmetricWithVertexQueries)
{
  // d(point -> vertex) from a face source must equal the unfolded distance from the vertex's own
  // solve interpolated exactly: check on a flat region (cylinder) where both are analytic, and
  // that a source at a corner matches the vertex source.
  const TriangleMesh m = BumpyMesh(2, 11);
  ExactGeodesicSolver solver(m);
  EXPECT_TRUE(gs_test::Succeeded(solver.Solve(m.Face(10)[1])));
  const std::vector<double> ref = solver.Distances();
  EXPECT_TRUE(gs_test::Succeeded(solver.Solve({ SurfacePoint::InFace(10, 0.0, 1.0, 0.0) })));
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    EXPECT_NEAR(solver.Distance(v), ref[v], 1e-12);
  }
}

TEST(ExactGeodesic, MaximumDistanceStopsEarly)
{
  const TriangleMesh m = BumpyMesh(3, 5);
  ExactGeodesicSolver solver(m);
  EXPECT_TRUE(gs_test::Succeeded(solver.Solve(42)));
  const std::vector<double> full = solver.Distances();
  ExactGeodesicOptions opt;
  opt.MaximumDistance = 0.8;
  ASSERT_TRUE(gs_test::Succeeded(solver.Solve(42, opt)));
  int inside = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    if (full[v] <= 0.8)
    {
      ++inside;
      EXPECT_NEAR(solver.Distance(v), full[v], 1e-12);
    }
    else
    {
      EXPECT_EQ(solver.Distance(v), ExactGeodesicSolver::Unreachable);
    }
  }
  EXPECT_GT(inside, 10);
  EXPECT_LT(inside, m.NumberOfVertices());
}

TEST(ExactGeodesic, TruncatedToKNearestVertices)
{
  const TriangleMesh m = BumpyMesh(3, 9);
  ExactGeodesicSolver solver(m);
  for (int source : { 0, 100, 400 })
  {
    EXPECT_TRUE(gs_test::Succeeded(solver.Solve(source)));
    std::vector<double> full = solver.Distances();
    std::vector<double> sorted = full;
    std::sort(sorted.begin(), sorted.end());
    const std::int64_t fullWork = solver.Statistics().WindowsPropagated;
    ExactGeodesicOptions opt;
    opt.MaximumFinalVertices = 50;
    ASSERT_TRUE(gs_test::Succeeded(solver.Solve(source, opt)));
    ASSERT_EQ(solver.FinalVertices().size(), 50u);
    double last = 0;
    for (int v : solver.FinalVertices())
    {
      EXPECT_NEAR(solver.Distance(v), full[v], 1e-12);
      EXPECT_GE(solver.Distance(v), last);
      last = solver.Distance(v);
    }
    EXPECT_NEAR(last, sorted[49], 1e-12);
    EXPECT_LT(solver.Statistics().WindowsPropagated, fullWork / 5);
  }
}

TEST(ExactGeodesic, DisconnectedComponentStaysUnreachable)
{
  TriangleSoup a = MakePlanarGrid(4, 4, 1.0, 1.0);
  const TriangleSoup b = MakePlanarGrid(3, 3, 1.0, 1.0);
  const long long offset = static_cast<long long>(a.Points.size());
  for (Vec3 p : b.Points)
    a.Points.push_back(p + Vec3(5, 0, 0));
  for (auto t : b.Triangles)
    a.Triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  const TriangleMesh m = BuildMesh(a);
  ExactGeodesicSolver solver(m);
  ASSERT_TRUE(gs_test::Succeeded(solver.Solve(0)));
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    EXPECT_EQ(std::isfinite(solver.Distance(v)), v < offset);
  }
}

TEST(ExactGeodesic, DirectPathsAndPseudoSources)
{
  // On the L-shape, vertices hidden behind the re-entrant corner are reached through it.
  const TriangleMesh m = BuildMesh(MakeLShape(4));
  ExactGeodesicSolver solver(m);
  int source = -1, target = -1;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const Vec3 p = m.Position(v);
    if (p.x == 0.0 && p.y == 2.0)
      source = v;
    if (p.x == 2.0 && p.y == 0.5)
      target = v;
  }
  ASSERT_GE(source, 0);
  ASSERT_GE(target, 0);
  ASSERT_TRUE(gs_test::Succeeded(solver.Solve(source)));
  EXPECT_FALSE(solver.IsDirect(target));
  EXPECT_LT(solver.PathOrigin(target), 0);
  EXPECT_NEAR(solver.Distance(target), std::sqrt(2.0) + std::hypot(1.0, 0.5), 1e-12);
}

TEST(ExactGeodesic, RejectsInvalidSources)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(3, 3, 1.0, 1.0));
  ExactGeodesicSolver solver(m);
  EXPECT_TRUE(gs_test::FailedWith(solver.Solve(std::vector<SurfacePoint>{}), "no source"));
  EXPECT_TRUE(
    gs_test::FailedWith(solver.Solve(1000), "source 0 is invalid: vertex 1000 does not exist"));
  EXPECT_TRUE(gs_test::FailedWith(
    solver.Solve({ SurfacePoint::AtVertex(0), SurfacePoint::InFace(99, 1, 0, 0) }),
    "source 1 is invalid: face 99 does not exist"));
  EXPECT_TRUE(gs_test::FailedWith(
    solver.Solve({ SurfacePoint::InFace(0, 0.5, 0.5, 0.5) }), "sum to 1.5, not 1"));
  EXPECT_TRUE(
    gs_test::FailedWith(solver.Solve({ SurfacePoint::InFace(0, NAN, 0.5, 0.5) }), "not finite"));
  EXPECT_TRUE(
    gs_test::FailedWith(solver.Solve({ SurfacePoint::InFace(0, 1.5, -0.5, 0) }), "not all >= 0"));
  EXPECT_EQ(solver.Distance(0), ExactGeodesicSolver::Unreachable);
}

TEST(ExactGeodesic, DepartureAnglesAreTheLogMapAngles)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(16, 16, 2.0, 2.0));
  ExactGeodesicSolver solver(m);
  auto wrap = [](double a) {
    a = std::fmod(a, 2 * Pi);
    return a < 0 ? a + 2 * Pi : a;
  };
  auto angleDiff = [&](double a, double b) {
    const double d = wrap(a - b);
    return std::min(d, 2 * Pi - d);
  };
  // Vertex source in the interior: angles from the direction of its VertexHalfedge.
  const int s = 8 * 17 + 8;
  ASSERT_TRUE(gs_test::Succeeded(solver.Solve(s)));
  const Vec3 ps = m.Position(s);
  const Vec3 ref = m.Position(m.Destination(m.VertexHalfedge(s))) - ps;
  const double ref0 = std::atan2(ref.y, ref.x);
  int checked = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    if (v == s)
      continue;
    const Vec3 d = m.Position(v) - ps;
    ASSERT_TRUE(std::isfinite(solver.DepartureAngle(v))) << v;
    EXPECT_LT(angleDiff(solver.DepartureAngle(v), std::atan2(d.y, d.x) - ref0), 1e-9) << v;
    ++checked;
  }
  EXPECT_EQ(checked, m.NumberOfVertices() - 1);
  // Face point source: angles from the face's first edge.
  const SurfacePoint fp = SurfacePoint::InFace(200, 0.3, 0.3, 0.4);
  ASSERT_TRUE(gs_test::Succeeded(solver.Solve({ fp })));
  const Vec3 p = m.Interpolate(fp.Face, fp.Bary);
  const Vec3 e0 = m.Position(m.Face(fp.Face)[1]) - m.Position(m.Face(fp.Face)[0]);
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const Vec3 d = m.Position(v) - p;
    EXPECT_LT(angleDiff(solver.DepartureAngle(v), std::atan2(d.y, d.x) - std::atan2(e0.y, e0.x)), 1e-9) << v;
  }
  // Behind a reflex corner the path leaves towards the corner (the first pseudo-source).
  const TriangleMesh l = BuildMesh(MakeLShape(4));
  ExactGeodesicSolver ls(l);
  int top = -1;
  for (int v = 0; v < l.NumberOfVertices(); ++v)
    if (l.Position(v).x == 0.0 && l.Position(v).y == 2.0)
      top = v;
  ASSERT_GE(top, 0);
  EXPECT_TRUE(gs_test::Succeeded(ls.Solve(top)));
  int hidden = 0;
  const Vec3 corner(1, 1, 0);
  const Vec3 toCorner = corner - l.Position(top);
  for (int v = 0; v < l.NumberOfVertices(); ++v)
  {
    if (v == top)
      continue;
    ASSERT_TRUE(std::isfinite(ls.DepartureAngle(v))) << v;
    if (!ls.IsDirect(v))
    {
      // Behind the re-entrant corner the path leaves towards the corner.
      ++hidden;
      const Vec3 ref2 = l.Position(l.Destination(l.VertexHalfedge(top))) - l.Position(top);
      EXPECT_LT(angleDiff(ls.DepartureAngle(v),
                  std::atan2(toCorner.y, toCorner.x) - std::atan2(ref2.y, ref2.x)),
        1e-9)
        << v;
    }
  }
  EXPECT_GT(hidden, 0);
}

// The window propagations' queue (a radix heap with a binary heap beside it for keys below the
// last one taken) against a sort: every pop is the smallest key queued, through pushes above the
// last key taken (children), equal to it, below it (windows from other pieces), zero and a
// cleared queue reused; MinKey reads that key without taking it.
TEST(ExactGeodesic, WindowQueuePopsInKeyOrder)
{
  struct Item
  {
    double Key;
    int Id;
  };
  window_geometry::WindowQueue<Item> queue;
  std::multiset<std::pair<double, int>> reference;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int id = 0;
  auto push = [&](double key) {
    queue.Push({ key, id });
    reference.insert({ key, id });
    ++id;
  };
  auto popAndCheck = [&]() -> double {
    EXPECT_FALSE(queue.Empty());
    const double smallest = reference.begin()->first;
    EXPECT_EQ(queue.MinKey(), smallest);
    const Item taken = queue.Pop();
    EXPECT_EQ(taken.Key, smallest);
    // Remove the very item taken (equal keys may come in any order).
    const auto it = reference.find({ taken.Key, taken.Id });
    EXPECT_TRUE(it != reference.end());
    reference.erase(it == reference.end() ? reference.begin() : it);
    return taken.Key;
  };
  for (int round = 0; round < 2; ++round)
  {
    push(0.0);
    for (int i = 0; i < 20000; ++i)
    {
      push(unit(rng) * 10.0);
    }
    double last = 0.0;
    for (int step = 0; step < 60000 && !reference.empty(); ++step)
    {
      last = popAndCheck();
      const double r = unit(rng);
      if (step < 40000)
      {
        if (r < 0.6)
        {
          push(last + unit(rng) * 0.5); // a child beyond its parent
        }
        if (r < 0.1)
        {
          push(last); // an equal key
        }
        if (r > 0.95)
        {
          push(last * unit(rng)); // below the last one taken
        }
      }
      ASSERT_EQ(queue.Size(), reference.size());
    }
    while (!reference.empty())
    {
      popAndCheck();
    }
    EXPECT_TRUE(queue.Empty());
    EXPECT_EQ(queue.MinKey(), std::numeric_limits<double>::infinity());
    // A cleared queue starts again from key 0 (a new solve's keys restart low).
    push(5.0);
    push(1.0);
    queue.Clear();
    reference.clear();
    EXPECT_TRUE(queue.Empty());
  }
}
