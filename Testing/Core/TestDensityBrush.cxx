// The density brush (Wang et al. 2016, Fig. 10): f = max(Density, min(1, d / Radius)) with d
// geodesic, from the exact solver or the distributor's graph; checked against the plane's
// Euclidean distances and the exact solver on a curved mesh.
#include "DensityBrush.h"
#include "ExactGeodesic.h"
#include "MeshGenerators.h"
#include "TestMeshes.h"
#include "TestStatus.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace gs;
using gs_test::BuildMesh;
using gs_test::FailedWith;
using gs_test::Succeeded;

namespace
{
double Expected(double d, const DensityBrush& brush)
{
  return std::max(brush.Density, std::min(1.0, d / brush.Radius));
}
} // namespace

// On a plane the exact solver's distance is the Euclidean one: the factors are the formula's
// to rounding, Density at the centre (a point inside a face), 1 from Radius on.
TEST(DensityBrush, ExactSolverFollowsTheFormulaOnAPlane)
{
  const TriangleMesh m = BuildMesh(MakeIrregularPlanarGrid(24, 1.0, 0.3, true, 5));
  DensityBrush brush;
  brush.Center = SurfacePoint::InFace(m.NumberOfFaces() / 2 + 3, 0.2, 0.5, 0.3);
  brush.Radius = 0.3;
  brush.Density = 0.25;
  const Vec3 c = m.Interpolate(brush.Center.Face, brush.Center.Bary);
  const Result<std::vector<double>> f = BrushFactors(m, nullptr, brush);
  ASSERT_TRUE(Succeeded(f));
  ASSERT_EQ(static_cast<int>(f->size()), m.NumberOfVertices());
  int inside = 0, atDensity = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const double d = Norm(m.Position(v) - c);
    EXPECT_NEAR((*f)[v], Expected(d, brush), 1e-12) << "vertex " << v;
    inside += d < brush.Radius;
    atDensity += d < brush.Density * brush.Radius;
  }
  EXPECT_GT(inside, 50);   // the ramp is sampled,
  EXPECT_GT(atDensity, 3); // and the floor at the centre
}

// Through a saddle vertex graph (the distributor's engine), on a bumpy sphere: the factors follow
// the exact solver's distances within the graph's error.
TEST(DensityBrush, GraphFactorsFollowTheExactSolver)
{
  const TriangleMesh m = BuildMesh(gs_test::BumpySoup(3, 11, 0.1));
  SaddleVertexGraph graph;
  SaddleVertexGraphOptions o;
  o.K = 50;
  ASSERT_TRUE(Succeeded(graph.Build(m, o, nullptr)));
  DensityBrush brush;
  brush.Center = SurfacePoint::AtVertex(17);
  brush.Radius = 0.6;
  brush.Density = 0.4;
  ExactGeodesicSolver exact(m);
  ASSERT_TRUE(Succeeded(exact.Solve(17)));
  for (int threads : { 1, 2 })
  {
    const Result<std::vector<double>> f = BrushFactors(m, &graph, brush, threads);
    ASSERT_TRUE(Succeeded(f));
    int ramp = 0;
    for (int v = 0; v < m.NumberOfVertices(); ++v)
    {
      const double d = exact.Distance(v);
      EXPECT_NEAR((*f)[v], Expected(d, brush), 5e-3) << "vertex " << v;
      ramp += d > brush.Density * brush.Radius && d < brush.Radius;
    }
    EXPECT_GT(ramp, 30);
  }
}

TEST(DensityBrush, MultipliesTheDensity)
{
  std::vector<double> density;
  ApplyBrushFactors({ 0.5, 1.0, 0.25 }, density);
  EXPECT_EQ(density, (std::vector<double>{ 0.5, 1.0, 0.25 }));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  density = { 2.0, 0.0, nan };
  ApplyBrushFactors({ 0.5, 0.5, 0.5 }, density);
  EXPECT_EQ(density[0], 1.0);
  EXPECT_EQ(density[1], 0.0); // a mask stays a mask
  EXPECT_TRUE(std::isnan(density[2]));
}

TEST(DensityBrush, RefusesAbsurdParameters)
{
  const TriangleMesh m = BuildMesh(MakePlanarGrid(6, 6, 1.0, 1.0));
  DensityBrush brush;
  brush.Center = SurfacePoint::AtVertex(3);
  brush.Radius = 0.5;
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (double radius : { 0.0, -1.0, inf, nan })
  {
    DensityBrush b = brush;
    b.Radius = radius;
    EXPECT_TRUE(FailedWith(BrushFactors(m, nullptr, b), "radius")) << radius;
  }
  for (double density : { 0.0, -0.5, 1.5, nan })
  {
    DensityBrush b = brush;
    b.Density = density;
    EXPECT_TRUE(FailedWith(BrushFactors(m, nullptr, b), "density")) << density;
  }
  DensityBrush b = brush;
  b.Center = SurfacePoint::AtVertex(m.NumberOfVertices());
  EXPECT_TRUE(FailedWith(BrushFactors(m, nullptr, b), "centre"));
  b.Center = SurfacePoint::InFace(0, nan, 0.5, 0.5);
  EXPECT_TRUE(FailedWith(BrushFactors(m, nullptr, b), "centre"));
  b = brush;
  b.Density = 1.0; // no shrinking at all: every factor 1
  const Result<std::vector<double>> f = BrushFactors(m, nullptr, b);
  ASSERT_TRUE(Succeeded(f));
  for (double x : *f)
  {
    EXPECT_EQ(x, 1.0);
  }
}
