// The no-precompute solver (virtual source propagation): exact on flat meshes, near the exact
// solver on curved ones, and the contract every solver keeps (sources, limits, abort).
#include "ExactGeodesic.h"
#include "MeshGenerators.h"
#include "TestMeshes.h"
#include "TestStatus.h"
#include "TriangleMesh.h"
#include "VirtualSourceGeodesic.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

using namespace gs;
using gs_test::BuildMesh;
using gs_test::FailedWith;
using gs_test::Succeeded;

namespace
{
// Mean and largest relative error against the exact solver from the same sources.
struct Errors
{
  double Mean = 0.0, Max = 0.0;
};
Errors AgainstExact(const TriangleMesh& m, const std::vector<SurfacePoint>& sources)
{
  ExactGeodesicSolver exact(m);
  VirtualSourceSolver solver(m);
  EXPECT_TRUE(Succeeded(exact.Solve(sources)));
  EXPECT_TRUE(Succeeded(solver.Solve(sources)));
  Errors e;
  int n = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const double d = exact.Distance(v);
    EXPECT_TRUE(std::isfinite(solver.Distance(v))) << "vertex " << v;
    if (d > 1e-9)
    {
      const double r = std::abs(solver.Distance(v) - d) / d;
      e.Mean += r;
      e.Max = std::max(e.Max, r);
      ++n;
    }
  }
  e.Mean /= std::max(n, 1);
  std::cout << m.NumberOfFaces() << " faces: mean relative error " << e.Mean << ", max " << e.Max
            << "\n";
  return e;
}

// visit(mesh, source) for the flat meshes' sources: a corner, an interior vertex and a point
// inside a face, on a regular and an irregular grid.
template <class Visit>
void ForEachFlatSource(Visit&& visit)
{
  for (const TriangleSoup& soup :
    { MakePlanarGrid(20, 20, 1.0, 1.0), MakeIrregularPlanarGrid(24, 1.0, 0.3, true, 7) })
  {
    const TriangleMesh m = BuildMesh(soup);
    for (const SurfacePoint& s :
      { SurfacePoint::AtVertex(0), SurfacePoint::AtVertex(m.NumberOfVertices() / 2 + 3),
        SurfacePoint::InFace(m.NumberOfFaces() / 3, 0.2, 0.3, 0.5) })
    {
      visit(m, s);
    }
    // Points on an edge (each of a face's three) and at a face's corner: sources of the faces
    // on both sides (and all around).
    for (const int f : { m.NumberOfFaces() / 2 + 1, m.NumberOfFaces() / 5 })
    {
      for (const SurfacePoint& s : { SurfacePoint::InFace(f, 0.0, 0.35, 0.65),
             SurfacePoint::InFace(f, 0.3, 0.0, 0.7), SurfacePoint::InFace(f, 0.45, 0.55, 0.0),
             SurfacePoint::InFace(f, 0.0, 1.0, 0.0) })
      {
        visit(m, s);
      }
    }
  }
}
} // namespace

// On a flat mesh every straight line is a geodesic: distances are Euclidean to rounding, from a
// corner, an interior vertex, a point inside a face, points on edges and a face's corner, on a
// regular and an irregular grid.
TEST(VirtualSourceGeodesic, ExactOnFlatMeshes)
{
  ForEachFlatSource([](const TriangleMesh& m, const SurfacePoint& s) {
    VirtualSourceSolver solver(m);
    ASSERT_TRUE(Succeeded(solver.Solve({ s })));
    const Vec3 p = m.Position(s);
    double worst = 0.0;
    for (int v = 0; v < m.NumberOfVertices(); ++v)
    {
      worst = std::max(worst, std::abs(solver.Distance(v) - Norm(m.Position(v) - p)));
    }
    EXPECT_LT(worst, 1e-12) << m.NumberOfVertices() << " vertices, source vertex " << s.Vertex;
  });
}

// Around the reflex corner of an L-shaped domain paths bend at the corner vertex (a boundary
// vertex of angle 3 pi / 2): the distance beyond it is the distance to the corner plus the
// straight line from it, exact to rounding.
TEST(VirtualSourceGeodesic, BendsAroundAReflexCorner)
{
  const TriangleMesh m = BuildMesh(MakeLShape(16));
  const Errors e = AgainstExact(m, { SurfacePoint::AtVertex(0) });
  EXPECT_LT(e.Mean, 1e-12);
  EXPECT_LT(e.Max, 1e-12);
  // From every vertex, lines across the notch, off the surface, give paths too short: the funnel
  // of reflex boundary corners since the source bends them at the corner. Measured on this
  // 8 x 8 L-shape: 25 (source, vertex) pairs short by up to 0.39% (through bends the funnel
  // does not follow), against 624 pairs and 1.15% without the funnel (lines checked against
  // the last two edges crossed only). Paths too long by up to about 1% remain where a face
  // whose centroid is behind the corner hands its bend to faces that see the source.
  const TriangleMesh small = BuildMesh(MakeLShape(8));
  ExactGeodesicSolver exact(small);
  VirtualSourceSolver solver(small);
  double shortest = 0.0;
  int shortPairs = 0;
  for (int s = 0; s < small.NumberOfVertices(); ++s)
  {
    ASSERT_TRUE(Succeeded(exact.Solve(s)));
    ASSERT_TRUE(Succeeded(solver.Solve({ SurfacePoint::AtVertex(s) })));
    for (int v = 0; v < small.NumberOfVertices(); ++v)
    {
      const double d = exact.Distance(v);
      if (d > 1e-9)
      {
        shortest = std::max(shortest, (d - solver.Distance(v)) / d);
        shortPairs += d - solver.Distance(v) > 1e-9 * d ? 1 : 0;
      }
    }
  }
  std::cout << "L-shape, every source: " << shortPairs << " distances short, by at most "
            << shortest << "\n";
  EXPECT_LT(shortest, 5e-3);
  EXPECT_LT(shortPairs, 50);
}

// Curved meshes: near the exact solver. Measured: sphere mean 1.0e-3 (max 9.7e-3), torus mean
// 1.3e-3 (max 1.9e-2), two sources on the sphere 1.0e-3; the bounds leave a margin. Without the
// check of the previous edge and the saddles' own sources the torus's mean was 4.2e-3; a
// solver that ignored bends or unfolded wrongly is off by several percent.
TEST(VirtualSourceGeodesic, NearTheExactSolverOnCurvedMeshes)
{
  const TriangleMesh sphere = BuildMesh(MakeIcosphere(1.0, 4));
  const Errors a = AgainstExact(sphere, { SurfacePoint::AtVertex(17) });
  EXPECT_LT(a.Mean, 1.5e-3);
  EXPECT_LT(a.Max, 2e-2);
  const TriangleMesh torus = BuildMesh(MakeTorus(1.0, 0.4, 48, 24));
  const Errors b = AgainstExact(torus, { SurfacePoint::AtVertex(5) });
  EXPECT_LT(b.Mean, 2e-3);
  EXPECT_LT(b.Max, 3e-2);
  // Several sources: the nearest one's distance.
  const Errors c =
    AgainstExact(sphere, { SurfacePoint::AtVertex(3), SurfacePoint::InFace(200, 0.3, 0.3, 0.4) });
  EXPECT_LT(c.Mean, 1.5e-3);
}

namespace
{
// Mean and largest difference of the departure angles (modulo a full turn) from the exact
// solver's, over the vertices both reach other than the sources.
Errors AnglesAgainstExact(const TriangleMesh& m, const SurfacePoint& point)
{
  const SurfacePoint source = ExactGeodesicSolver::SourcePoint(m, point); // (a corner: a vertex)
  ExactGeodesicSolver exact(m);
  VirtualSourceSolver solver(m);
  VirtualSourceOptions o;
  o.Angles = true;
  EXPECT_TRUE(Succeeded(exact.Solve({ source })));
  EXPECT_TRUE(Succeeded(solver.Solve({ source }, o)));
  Errors e;
  int n = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    if (source.IsVertex() && v == source.Vertex)
    {
      EXPECT_TRUE(std::isnan(solver.DepartureAngle(v)));
      continue;
    }
    const double d = std::abs(std::remainder(solver.DepartureAngle(v) - exact.DepartureAngle(v), 2.0 * M_PI));
    EXPECT_TRUE(std::isfinite(d)) << "vertex " << v;
    e.Mean += d;
    e.Max = std::max(e.Max, d);
    ++n;
  }
  e.Mean /= std::max(n, 1);
  std::cout << m.NumberOfFaces() << " faces: departure angles' mean difference " << e.Mean
            << " rad, max " << e.Max << "\n";
  return e;
}
} // namespace

// Departure angles in the exact solver's convention: on flat meshes equal to its (exact) angles
// to rounding, from a vertex (fan angles counted from VertexHalfedge) and a face point (from the
// face's first edge); behind the L-shape's reflex corner, the angle of the path to the corner.
// On curved meshes a face's source is one unfolding of the faces crossed, off to the side by
// about the square root of the distance's relative error times the distance, so the angles are
// off by a degree or two (measured: sphere mean 0.027 rad from a vertex, 0.032 from a face point;
// torus 0.044; near the cut locus by anything). A frame turned the wrong way or a bend given
// the angle of its bent part is off by radians. A solve without Angles leaves them NaN.
TEST(VirtualSourceGeodesic, DepartureAnglesNearTheExactSolver)
{
  ForEachFlatSource([](const TriangleMesh& m, const SurfacePoint& s) {
    const Errors e = AnglesAgainstExact(m, s);
    EXPECT_LT(e.Max, 1e-9) << m.NumberOfVertices() << " vertices, source vertex " << s.Vertex;
  });
  const Errors l = AnglesAgainstExact(BuildMesh(MakeLShape(16)), SurfacePoint::AtVertex(0));
  EXPECT_LT(l.Max, 1e-9);
  const TriangleMesh sphere = BuildMesh(MakeIcosphere(1.0, 4));
  const Errors a = AnglesAgainstExact(sphere, SurfacePoint::AtVertex(17));
  EXPECT_LT(a.Mean, 0.04);
  const Errors f = AnglesAgainstExact(sphere, SurfacePoint::InFace(200, 0.3, 0.3, 0.4));
  EXPECT_LT(f.Mean, 0.045);
  const Errors b = AnglesAgainstExact(BuildMesh(MakeTorus(1.0, 0.4, 48, 24)), SurfacePoint::AtVertex(5));
  EXPECT_LT(b.Mean, 0.06);
  VirtualSourceSolver solver(sphere);
  ASSERT_TRUE(Succeeded(solver.Solve({ SurfacePoint::AtVertex(17) })));
  EXPECT_TRUE(std::isnan(solver.DepartureAngle(0)));
  VirtualSourceOptions withAngles;
  withAngles.Angles = true;
  ASSERT_TRUE(Succeeded(solver.Solve({ SurfacePoint::AtVertex(17) }, withAngles)));
  EXPECT_TRUE(std::isfinite(solver.DepartureAngle(0)));
  ASSERT_TRUE(Succeeded(solver.Solve({ SurfacePoint::AtVertex(17) })));
  EXPECT_TRUE(std::isnan(solver.DepartureAngle(0)));
}

// MaximumDistance leaves farther vertices unreached; progress rises to 1; a false return aborts
// with every vertex unreached; the next solve runs whole.
TEST(VirtualSourceGeodesic, LimitsProgressAndAbort)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(200, 200, 1.0, 1.0));
  VirtualSourceSolver solver(m);
  VirtualSourceOptions o;
  o.MaximumDistance = 0.5;
  ASSERT_TRUE(Succeeded(solver.Solve({ SurfacePoint::AtVertex(0) }, o)));
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const double r = Norm(m.Position(v) - m.Position(0));
    if (r < 0.5 - 1e-9)
      EXPECT_NEAR(solver.Distance(v), r, 1e-12);
    else if (r > 0.5 + 1e-9)
      EXPECT_EQ(solver.Distance(v), VirtualSourceSolver::Unreachable);
  }
  std::vector<double> reports;
  o = VirtualSourceOptions();
  o.Progress = [&](double f) {
    reports.push_back(f);
    return true;
  };
  ASSERT_TRUE(Succeeded(solver.Solve({ SurfacePoint::AtVertex(0) }, o)));
  ASSERT_GE(reports.size(), 2u);
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end()));
  EXPECT_EQ(reports.back(), 1.0);
  int calls = 0;
  o.Progress = [&](double) { return ++calls < 2; };
  const Status aborted = solver.Solve({ SurfacePoint::AtVertex(0) }, o);
  EXPECT_TRUE(aborted.IsAborted());
  EXPECT_EQ(solver.Distance(m.NumberOfVertices() - 1), VirtualSourceSolver::Unreachable);
  ASSERT_TRUE(Succeeded(solver.Solve({ SurfacePoint::AtVertex(0) })));
  EXPECT_NEAR(solver.Distance(m.NumberOfVertices() - 1), std::sqrt(2.0), 1e-12);
}

// Bad sources are refused with the mesh's message; disconnected parts stay unreached.
TEST(VirtualSourceGeodesic, RefusesBadSourcesAndLeavesOtherPartsUnreached)
{
  TriangleSoup two = MakePlanarGrid(4, 4, 1.0, 1.0);
  const int offset = static_cast<int>(two.Points.size());
  const TriangleSoup other = MakePlanarGrid(4, 4, 1.0, 1.0);
  for (Vec3 p : other.Points)
  {
    p.z += 5.0;
    two.Points.push_back(p);
  }
  for (auto t : other.Triangles)
  {
    two.Triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  }
  const TriangleMesh m = BuildMesh(two);
  VirtualSourceSolver solver(m);
  EXPECT_TRUE(FailedWith(solver.Solve({}), "no source"));
  EXPECT_TRUE(FailedWith(solver.Solve({ SurfacePoint::AtVertex(m.NumberOfVertices()) }), "source"));
  ASSERT_TRUE(Succeeded(solver.Solve({ SurfacePoint::AtVertex(0) })));
  EXPECT_EQ(solver.Distance(0), 0.0);
  EXPECT_EQ(solver.Distance(m.NumberOfVertices() - 1), VirtualSourceSolver::Unreachable);
}

// A curve: each straight run is one segment source, carried across the mesh whole: on a plane
// the distance to a straight run is exact. Two runs meeting at an angle: a face keeps the run
// nearer its centre, and near the bisector a vertex can read the farther one (measured: up to
// 2.3e-3 on this unit square, 5.7e-3 on the regular grid).
TEST(VirtualSourceGeodesic, StraightRunsOfACurveAreExactOnAPlane)
{
  const TriangleMesh m = BuildMesh(MakeIrregularPlanarGrid(24, 1.0, 0.3, true, 3));
  VirtualSourceSolver solver(m);
  // Points of the plane: the face holding (x, y), found by barycentric coordinates.
  auto at = [&](double x, double y) {
    for (int f = 0; f < m.NumberOfFaces(); ++f)
    {
      const Vec3 a = m.Position(m.Face(f)[0]), b = m.Position(m.Face(f)[1]), c = m.Position(m.Face(f)[2]);
      const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
      const double u = ((x - a.x) * (c.y - a.y) - (c.x - a.x) * (y - a.y)) / det;
      const double v = ((b.x - a.x) * (y - a.y) - (x - a.x) * (b.y - a.y)) / det;
      if (u >= 0 && v >= 0 && u + v <= 1)
        return SurfacePoint::InFace(f, 1 - u - v, u, v);
    }
    return SurfacePoint();
  };
  auto toSegment = [](const Vec3& p, double ax, double ay, double bx, double by) {
    const double vx = bx - ax, vy = by - ay;
    const double u = std::min(std::max(((p.x - ax) * vx + (p.y - ay) * vy) / (vx * vx + vy * vy), 0.0), 1.0);
    return std::hypot(p.x - ax - u * vx, p.y - ay - u * vy);
  };
  const double x0 = 0.21, y0 = 0.33, x1 = 0.58, y1 = 0.47, x2 = 0.79, y2 = 0.81;
  const std::vector<CurvePiece> first = TraceSurfaceCurve(m, { at(x0, y0), at(x1, y1) });
  const std::vector<CurvePiece> second = TraceSurfaceCurve(m, { at(x1, y1), at(x2, y2) });
  ASSERT_GT(first.size(), 5u);
  ASSERT_TRUE(Succeeded(solver.Solve({}, { first })));
  double worst = 0.0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    worst = std::max(worst, std::abs(solver.Distance(v) - toSegment(m.Position(v), x0, y0, x1, y1)));
  }
  EXPECT_LT(worst, 1e-12);
  ASSERT_TRUE(Succeeded(solver.Solve({}, { first, second })));
  worst = 0.0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const Vec3 p = m.Position(v);
    const double d = std::min(toSegment(p, x0, y0, x1, y1), toSegment(p, x1, y1, x2, y2));
    EXPECT_GE(solver.Distance(v), d - 1e-12); // never below: each is a path on the plane
    worst = std::max(worst, solver.Distance(v) - d);
  }
  EXPECT_LT(worst, 5e-3);
  EXPECT_TRUE(FailedWith(
    solver.Solve({}, std::vector<std::vector<CurvePiece>>{ { CurvePiece{ -1, Vec3(), Vec3() } } }),
    "curve piece 0"));
}
