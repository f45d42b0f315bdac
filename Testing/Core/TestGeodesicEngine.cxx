// The engine seam (GeodesicEngine.h): every engine answers the same questions, from points and
// curves, bounded by MaximumDistance, with the same errors; on a flat mesh against the
// Euclidean distances (the exact answer there), each within its stated accuracy.
#include "ExactGeodesic.h"
#include "GeodesicEngine.h"
#include "MeshGenerators.h"
#include "SaddleVertexGraph.h"
#include "SurfaceCurve.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

using namespace gs;

namespace
{
constexpr GeodesicSolver AllSolvers[] = { GeodesicSolver::Exact, GeodesicSolver::SVGLabelCorrecting,
  GeodesicSolver::SVGDijkstra, GeodesicSolver::DGG, GeodesicSolver::VirtualSources };

/// A jittered flat square [0, 2]^2 (20 x 20 cells, random diagonals): no saddle vertex.
const TriangleMesh& Plane()
{
  static const TriangleMesh mesh =
    gs_test::BuildMesh(MakeIrregularPlanarGrid(20, 2.0, 0.3, true, 11));
  return mesh;
}

const SaddleVertexGraph* GraphFor(GeodesicSolver solver)
{
  static SaddleVertexGraph svg, dgg;
  static bool built = false;
  if (!built)
  {
    SaddleVertexGraphOptions o;
    o.K = 50;
    EXPECT_TRUE(gs_test::Succeeded(svg.Build(Plane(), o, nullptr)));
    o.Construction = GraphConstruction::DiscreteGeodesic;
    o.Accuracy = 1e-3;
    EXPECT_TRUE(gs_test::Succeeded(dgg.Build(Plane(), o, nullptr)));
    built = true;
  }
  if (!GeodesicSolverUsesGraph(solver))
  {
    return nullptr;
  }
  return solver == GeodesicSolver::DGG ? &dgg : &svg;
}

std::unique_ptr<GeodesicEngine> Engine(GeodesicSolver solver)
{
  Result<std::unique_ptr<GeodesicEngine>> made = MakeGeodesicEngine(solver, Plane(), GraphFor(solver));
  EXPECT_TRUE(gs_test::Succeeded(made)) << GeodesicSolverName(solver);
  return made.Ok() ? std::move(*made) : nullptr;
}

/// The engine's largest error on the plane's reached vertices against `exact` (per vertex).
template <typename Exact>
double LargestError(const GeodesicEngine& e, Exact exact, int& reached)
{
  double worst = 0.0;
  reached = 0;
  for (int v = 0; v < Plane().NumberOfVertices(); ++v)
  {
    const double d = e.Distance(v);
    if (std::isfinite(d))
    {
      ++reached;
      worst = std::max(worst, std::abs(d - exact(Plane().Position(v))));
    }
  }
  return worst;
}

/// Stated accuracy on a flat mesh (absolute, the square is 2 wide): exact engines to rounding,
/// graph engines within their relative error bound of the diameter.
double Tolerance(GeodesicSolver solver)
{
  return GeodesicSolverUsesGraph(solver) ? 2e-3 * 2.0 * std::sqrt(2.0) : 1e-9;
}
} // namespace

TEST(GeodesicEngine, NamesAndKinds)
{
  std::set<std::string> names;
  for (GeodesicSolver s : AllSolvers)
  {
    const std::unique_ptr<GeodesicEngine> e = Engine(s);
    ASSERT_TRUE(e);
    EXPECT_EQ(e->Solver(), s);
    EXPECT_EQ(&e->Mesh(), &Plane());
    names.insert(GeodesicSolverName(s));
  }
  EXPECT_EQ(names.size(), 5u);
  EXPECT_EQ(names.count(""), 0u);
  EXPECT_TRUE(GeodesicSolverUsesGraph(GeodesicSolver::DGG));
  EXPECT_FALSE(GeodesicSolverUsesGraph(GeodesicSolver::VirtualSources));
}

TEST(GeodesicEngine, EveryEngineMatchesTheEuclideanDistanceFromAPointOnAPlane)
{
  const SurfacePoint source = SurfacePoint::InFace(Plane().NumberOfFaces() / 2 + 7, 0.2, 0.3, 0.5);
  const Vec3 s = Plane().Position(source);
  for (GeodesicSolver solver : AllSolvers)
  {
    const std::unique_ptr<GeodesicEngine> e = Engine(solver);
    ASSERT_TRUE(e);
    GeodesicSources sources;
    sources.Points = { source };
    ASSERT_TRUE(gs_test::Succeeded(e->Solve(sources, GeodesicSolveOptions())));
    int reached = 0;
    const double worst = LargestError(*e, [&](const Vec3& x) { return Norm(x - s); }, reached);
    EXPECT_EQ(reached, Plane().NumberOfVertices()) << GeodesicSolverName(solver);
    EXPECT_LE(worst, Tolerance(solver)) << GeodesicSolverName(solver);
    const std::vector<double> all = e->Distances();
    ASSERT_EQ(all.size(), static_cast<std::size_t>(Plane().NumberOfVertices()));
    EXPECT_EQ(all[5], e->Distance(5));
  }
}

TEST(GeodesicEngine, EveryEngineMatchesTheDistanceToAStraightCurveOnAPlane)
{
  // A straight segment from (0.5, 0.9) to (1.5, 1.1) given as three collinear points.
  const Vec3 a{ 0.5, 0.9, 0.0 }, b{ 1.5, 1.1, 0.0 };
  auto at = [&](double t) {
    const Vec3 x = a + (b - a) * t;
    for (int f = 0; f < Plane().NumberOfFaces(); ++f)
    {
      const auto& c = Plane().Face(f);
      const Vec3 p0 = Plane().Position(c[0]), p1 = Plane().Position(c[1]), p2 = Plane().Position(c[2]);
      const double det = (p1.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (p1.y - p0.y);
      const double u = ((x.x - p0.x) * (p2.y - p0.y) - (p2.x - p0.x) * (x.y - p0.y)) / det;
      const double w = ((p1.x - p0.x) * (x.y - p0.y) - (x.x - p0.x) * (p1.y - p0.y)) / det;
      if (u >= 0.0 && w >= 0.0 && u + w <= 1.0)
      {
        return SurfacePoint::InFace(f, 1.0 - u - w, u, w);
      }
    }
    ADD_FAILURE() << "no face holds the curve point";
    return SurfacePoint::AtVertex(0);
  };
  auto toSegment = [&](const Vec3& x) {
    const Vec3 d = b - a;
    const double t = std::clamp(Dot(x - a, d) / Dot(d, d), 0.0, 1.0);
    return Norm(x - (a + d * t));
  };
  const double meanEdge = Plane().MeanEdgeLength();
  for (GeodesicSolver solver : AllSolvers)
  {
    const std::unique_ptr<GeodesicEngine> e = Engine(solver);
    ASSERT_TRUE(e);
    GeodesicSources sources;
    sources.Curves = { { at(0.0), at(0.4), at(1.0) } };
    ASSERT_TRUE(gs_test::Succeeded(e->Solve(sources, GeodesicSolveOptions())));
    int reached = 0;
    const double worst = LargestError(*e, toSegment, reached);
    EXPECT_EQ(reached, Plane().NumberOfVertices()) << GeodesicSolverName(solver);
    // The exact engine runs from samples 1/16 edge apart: half a spacing at worst.
    const double tolerance = solver == GeodesicSolver::Exact
      ? 0.5 * ExactCurveSampleSpacing * meanEdge
      : Tolerance(solver);
    EXPECT_LE(worst, tolerance) << GeodesicSolverName(solver);
  }
}

TEST(GeodesicEngine, MaximumDistanceBoundsEveryEngine)
{
  const SurfacePoint source = SurfacePoint::AtVertex(Plane().NumberOfVertices() / 2);
  const Vec3 s = Plane().Position(source);
  GeodesicSolveOptions options;
  options.MaximumDistance = 0.6;
  for (GeodesicSolver solver : AllSolvers)
  {
    const std::unique_ptr<GeodesicEngine> e = Engine(solver);
    ASSERT_TRUE(e);
    GeodesicSources sources;
    sources.Points = { source };
    ASSERT_TRUE(gs_test::Succeeded(e->Solve(sources, options)));
    int inside = 0, outside = 0;
    for (int v = 0; v < Plane().NumberOfVertices(); ++v)
    {
      const double euclid = Norm(Plane().Position(v) - s);
      const double d = e->Distance(v);
      if (euclid < 0.55)
      {
        EXPECT_TRUE(std::isfinite(d)) << GeodesicSolverName(solver) << " vertex " << v;
        ++inside;
      }
      if (std::isfinite(d))
      {
        EXPECT_LE(d, 0.6 + Plane().MeanEdgeLength() * 2) << GeodesicSolverName(solver);
      }
      if (euclid > 1.0)
      {
        EXPECT_FALSE(std::isfinite(d)) << GeodesicSolverName(solver) << " vertex " << v;
        ++outside;
      }
    }
    EXPECT_GT(inside, 20);
    EXPECT_GT(outside, 20);
  }
}

TEST(GeodesicEngine, BadSourcesAndMissingGraphsAreClearErrors)
{
  for (GeodesicSolver solver : { GeodesicSolver::SVGLabelCorrecting, GeodesicSolver::DGG })
  {
    EXPECT_TRUE(gs_test::FailedWith(MakeGeodesicEngine(solver, Plane(), nullptr), "needs a graph"));
  }
  const TriangleMesh other = gs_test::BuildMesh(MakePlanarGrid(3, 3, 1.0, 1.0));
  EXPECT_FALSE(MakeGeodesicEngine(GeodesicSolver::SVGDijkstra, other, GraphFor(GeodesicSolver::SVGDijkstra)).Ok());
  EXPECT_TRUE(gs_test::FailedWith(
    MakeGeodesicEngine(static_cast<GeodesicSolver>(9), Plane(), nullptr), "unknown geodesic solver"));
  for (GeodesicSolver solver : AllSolvers)
  {
    const std::unique_ptr<GeodesicEngine> e = Engine(solver);
    ASSERT_TRUE(e);
    const Status none = e->Solve(GeodesicSources(), GeodesicSolveOptions());
    EXPECT_FALSE(none.Ok()) << GeodesicSolverName(solver);
    EXPECT_FALSE(none.IsAborted());
    GeodesicSources bad;
    bad.Points = { SurfacePoint::AtVertex(Plane().NumberOfVertices() + 3) };
    EXPECT_FALSE(e->Solve(bad, GeodesicSolveOptions()).Ok()) << GeodesicSolverName(solver);
  }
}

TEST(GeodesicEngine, AProgressCallbackAbortsTheEnginesThatReportProgress)
{
  // (Large enough for the virtual sources to poll during the solve.)
  const TriangleMesh large = gs_test::BuildMesh(MakePlanarGrid(150, 150, 1.0, 1.0));
  Result<std::unique_ptr<GeodesicEngine>> e = MakeGeodesicEngine(GeodesicSolver::VirtualSources, large);
  ASSERT_TRUE(gs_test::Succeeded(e));
  GeodesicSources sources;
  sources.Points = { SurfacePoint::AtVertex(0) };
  GeodesicSolveOptions options;
  int calls = 0;
  options.Progress = [&](double) { return ++calls < 1; };
  EXPECT_TRUE((*e)->Solve(sources, options).IsAborted());
  EXPECT_EQ(calls, 1);
  for (int v = 0; v < large.NumberOfVertices(); ++v)
  {
    ASSERT_FALSE(std::isfinite((*e)->Distance(v))) << v;
  }
  options.Progress = [](double) { return true; };
  ASSERT_TRUE(gs_test::Succeeded((*e)->Solve(sources, options)));
  EXPECT_NEAR((*e)->Distance(large.NumberOfVertices() - 1), std::sqrt(2.0), 1e-9);
}

TEST(GeodesicEngine, ReachedSetsAndDepartureAnglesAgreeAcrossEngines)
{
  const int centre = Plane().NumberOfVertices() / 2;
  GeodesicSources sources;
  sources.Points = { SurfacePoint::AtVertex(centre) };
  GeodesicSolveOptions options;
  options.MaximumDistance = 0.6;
  options.Angles = true;
  const std::unique_ptr<GeodesicEngine> exact = Engine(GeodesicSolver::Exact);
  ASSERT_TRUE(exact && exact->Solve(sources, options).Ok());
  // The exact engine's reached vertices come in order of distance.
  const std::vector<int> exactReached = exact->Reached();
  for (std::size_t i = 1; i < exactReached.size(); ++i)
  {
    ASSERT_LE(exact->Distance(exactReached[i - 1]), exact->Distance(exactReached[i]));
  }
  for (GeodesicSolver solver : AllSolvers)
  {
    const std::unique_ptr<GeodesicEngine> e = Engine(solver);
    ASSERT_TRUE(e && e->Solve(sources, options).Ok());
    std::vector<int> reached = e->Reached();
    std::sort(reached.begin(), reached.end());
    int finite = 0;
    for (int v = 0; v < Plane().NumberOfVertices(); ++v)
    {
      const bool listed = std::binary_search(reached.begin(), reached.end(), v);
      EXPECT_EQ(listed, std::isfinite(e->Distance(v))) << GeodesicSolverName(solver) << " vertex " << v;
      finite += listed ? 1 : 0;
    }
    EXPECT_GT(finite, 20) << GeodesicSolverName(solver);
    // Departure angles (modulo the full turn) within a degree of the exact ones.
    double worst = 0.0;
    for (int v : exactReached)
    {
      if (v == centre || !std::isfinite(e->Distance(v)))
      {
        continue;
      }
      const double d = std::remainder(e->DepartureAngle(v) - exact->DepartureAngle(v), 2.0 * M_PI);
      ASSERT_TRUE(std::isfinite(d)) << GeodesicSolverName(solver) << " vertex " << v;
      worst = std::max(worst, std::abs(d));
    }
    EXPECT_LT(worst, M_PI / 180.0) << GeodesicSolverName(solver);
  }
}

// On a mesh of ExactInPartsMinimumFaces faces or more, the exact engine solves in parts on
// threads: Euclidean distances on a plane (to 1e-12) from a vertex and from a face point, the
// serial solver's departure angles (to 1e-9, modulo a turn), reached in order of distance,
// progress reported and an abort honoured (the serial solver has neither); a solve bounded to
// a small disc stays serial (no progress), as do angles from two sources.
TEST(GeodesicEngine, TheExactEngineSolvesLargeMeshesInParts)
{
  const TriangleMesh large = gs_test::BuildMesh(MakePlanarGrid(230, 230, 1.0, 1.0));
  ASSERT_GE(large.NumberOfFaces(), ExactInPartsMinimumFaces);
  Result<std::unique_ptr<GeodesicEngine>> made = MakeGeodesicEngine(GeodesicSolver::Exact, large);
  ASSERT_TRUE(gs_test::Succeeded(made));
  GeodesicEngine& e = **made;
  ExactGeodesicSolver serial(large);
  auto expectSerial = [&](const SurfacePoint& source) {
    ASSERT_TRUE(gs_test::Succeeded(serial.Solve({ source })));
    const double turn = source.IsVertex() ? large.TotalAngle(source.Vertex) : 2.0 * M_PI;
    const Vec3 p = large.Position(source);
    double worst = 0.0, worstAngle = 0.0;
    for (int v = 0; v < large.NumberOfVertices(); ++v)
    {
      worst = std::max(worst, std::abs(e.Distance(v) - Norm(large.Position(v) - p)));
      const double a = serial.DepartureAngle(v), b = e.DepartureAngle(v);
      ASSERT_EQ(std::isfinite(a), std::isfinite(b)) << "vertex " << v;
      if (std::isfinite(a))
      {
        worstAngle = std::max(worstAngle, std::abs(std::remainder(b - a, turn)));
      }
    }
    EXPECT_LT(worst, 1e-12);
    EXPECT_LT(worstAngle, 1e-9);
  };
  const int centre = large.NumberOfVertices() / 2 + 7;
  GeodesicSources sources;
  sources.Points = { SurfacePoint::AtVertex(centre) };
  GeodesicSolveOptions options;
  std::vector<double> reports;
  options.Progress = [&](double f) {
    reports.push_back(f);
    return true;
  };
  ASSERT_TRUE(gs_test::Succeeded(e.Solve(sources, options)));
  EXPECT_GT(reports.size(), 3u);
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end()));
  expectSerial(sources.Points[0]);
  const std::vector<int>& reached = e.Reached();
  ASSERT_EQ(reached.size(), static_cast<std::size_t>(large.NumberOfVertices()));
  for (std::size_t i = 1; i < reached.size(); ++i)
  {
    ASSERT_LE(e.Distance(reached[i - 1]), e.Distance(reached[i]));
  }

  GeodesicSources inFace;
  inFace.Points = { SurfacePoint::InFace(large.NumberOfFaces() / 3, 0.2, 0.3, 0.5) };
  options.Angles = true;
  ASSERT_TRUE(gs_test::Succeeded(e.Solve(inFace, options)));
  expectSerial(inFace.Points[0]);

  int calls = 0;
  options.Progress = [&](double) { return ++calls < 2; };
  EXPECT_TRUE(e.Solve(sources, options).IsAborted());
  EXPECT_FALSE(std::isfinite(e.Distance(centre)));
  EXPECT_TRUE(e.Reached().empty());

  // A solve bounded to a small disc stays serial (it reports no progress); a wide one goes in
  // parts; angles from two sources are the serial solver's.
  reports.clear();
  options.Progress = [&](double f) {
    reports.push_back(f);
    return true;
  };
  options.MaximumDistance = 0.05;
  ASSERT_TRUE(gs_test::Succeeded(e.Solve(sources, options)));
  EXPECT_TRUE(reports.empty());
  const int near = centre + 1;
  EXPECT_NEAR(e.Distance(near), Norm(large.Position(near) - large.Position(centre)), 1e-12);
  EXPECT_FALSE(std::isfinite(e.Distance(0)));
  options.MaximumDistance = 0.5;
  ASSERT_TRUE(gs_test::Succeeded(e.Solve(sources, options)));
  EXPECT_FALSE(reports.empty());
  reports.clear();
  options.MaximumDistance = 0.0;
  GeodesicSources two = sources;
  two.Points.push_back(SurfacePoint::AtVertex(0));
  ASSERT_TRUE(gs_test::Succeeded(e.Solve(two, options)));
  EXPECT_TRUE(reports.empty());
  EXPECT_TRUE(std::isfinite(e.DepartureAngle(near)));
  EXPECT_EQ(e.Distance(0), 0.0);
}
