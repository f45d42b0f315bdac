// Decals draw the shape the outlines draw: the texture coordinates of a shape's decal, read at
// the points of its drawn outline, fall on the silhouette's boundary (short shapes: the log map
// of the centre; long shapes: arc length along the curve and the perpendicular geodesic, the map
// the outline and the parts use).
#include "TestMeshes.h"

#include "MeshGenerators.h"
#include "SaddleVertexGraph.h"
#include "SafeDistanceTable.h"
#include "ShapeDistributor.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

using namespace gs;

namespace
{
SafeDistanceTables Tables(const std::vector<std::vector<Vec2>>& classes)
{
  std::vector<SafeDistanceInput> in;
  for (std::size_t k = 0; k < classes.size(); ++k)
  {
    in.push_back({ "class" + std::to_string(k), ShapeFromPolygons({ classes[k] }) });
  }
  SafeDistanceOptions o;
  o.AngleBins = 32;
  o.DistanceSteps = 64;
  o.Rows = 512;
  SafeDistanceResult r = ComputeSafeDistanceTables(in, o);
  EXPECT_TRUE(r.Ok) << r.Error;
  return r.Tables;
}

double DistanceToRings(const std::vector<std::vector<Vec2>>& rings, const Vec2& p)
{
  double best = 1e300;
  for (const auto& ring : rings)
  {
    for (std::size_t k = 0; k < ring.size(); ++k)
    {
      const Vec2 a = ring[k], b = ring[(k + 1) % ring.size()];
      const Vec2 ab = b - a;
      const double l2 = Dot(ab, ab);
      const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, Dot(p - a, ab) / l2)) : 0.0;
      best = std::min(best, Norm(a + ab * t - p));
    }
  }
  return best;
}

struct Agreement
{
  double Max = 0.0, Mean = 0.0; // distance of the decal's class point to the silhouette, / radius
  long long Points = 0, Uncovered = 0;
  int Shapes = 0;
};

// Reads every outline point of the shapes (long or short, as asked) in its decal; shapes within
// `exclude` of the z axis are skipped.
Agreement Check(const ShapeDistributor& d, const TriangleMesh& mesh, const SafeDistanceTables& t, bool longShapes,
  double exclude = 0.0)
{
  Agreement a;
  double sum = 0.0;
  const std::vector<PlacedShape>& shapes = d.Shapes();
  for (int s = 0; s < static_cast<int>(shapes.size()); ++s)
  {
    if (shapes[s].Curve.empty() == longShapes)
      continue;
    const Vec3& x = shapes[s].Position;
    if (std::hypot(x.x, x.y) < exclude)
      continue;
    ++a.Shapes;
    const SafeDistanceClass& c = t.Classes[shapes[s].ClassId];
    const ShapeDecal decal = d.Decal(s);
    std::map<int, std::size_t> index;
    for (std::size_t k = 0; k < decal.Faces.size(); ++k)
      index[decal.Faces[k]] = k;
    for (const OutlinePiece& piece : d.Outline(s, 0.25 * mesh.MeanEdgeLength()))
    {
      for (const SurfacePoint& p : piece.Points)
      {
        ++a.Points;
        const auto it = index.find(p.Face);
        if (it == index.end())
        {
          ++a.Uncovered;
          continue;
        }
        Vec2 uv{ 0.0, 0.0 };
        for (int k = 0; k < 3; ++k)
          uv = uv + decal.TextureCoordinates[it->second][k] * p.Bary[k];
        const Vec2 q{ (2.0 * uv.x - 1.0) * c.Radius, (2.0 * uv.y - 1.0) * c.Radius };
        const double e = DistanceToRings(c.Outline.Rings, q) / c.Radius;
        a.Max = std::max(a.Max, e);
        sum += e;
      }
    }
  }
  const long long covered = a.Points - a.Uncovered;
  a.Mean = covered > 0 ? sum / covered : 0.0;
  return a;
}

std::vector<Vec2> Bar() // 5:1, split into parts by the tables
{
  return { { -2.5, -0.5 }, { 2.5, -0.5 }, { 2.5, 0.5 }, { -2.5, 0.5 } };
}
} // namespace

TEST(ShapeDecal, DecalsAgreeWithOutlinesOnAPlane)
{
  // A straight field (the map is affine: exact) and a turning one (long shapes bend).
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(60, 60, 12.0, 12.0));
  const SafeDistanceTables t = Tables({ MakeStarPolygon(5, 1.0, 0.4), Bar() });
  ASSERT_GT(t.Classes[1].Parts.size(), 1u);
  for (const bool turning : { false, true })
  {
    std::vector<Vec3> directions(plane.NumberOfFaces());
    for (int f = 0; f < plane.NumberOfFaces(); ++f)
    {
      const auto& c = plane.Face(f);
      const Vec3 x = (plane.Position(c[0]) + plane.Position(c[1]) + plane.Position(c[2])) / 3.0;
      directions[f] = turning ? Vec3{ std::cos(0.25 * x.x), std::sin(0.25 * x.x), 0.0 } : Vec3{ 1.0, 0.3, 0.0 };
    }
    ShapeDistributionOptions o;
    o.ShapeSize = 0.7;
    o.Seed = 3;
    o.MaximalFailures = 1000;
    o.KeepInside = true; // (an outline cut by the boundary is not the silhouette there)
    ShapeDistributor d(plane);
    const ShapeDistributionResult r = d.Run(t, directions, {}, o);
    ASSERT_TRUE(r.Ok) << r.Error;
    for (const bool longShapes : { false, true })
    {
      const Agreement a = Check(d, plane, t, longShapes);
      std::printf("plane, %s field, %s shapes: %d shapes, %lld outline points (%lld outside the decal), "
                  "class point off the silhouette: mean %.2e, max %.2e of the radius\n",
        turning ? "turning" : "straight", longShapes ? "long" : "short", a.Shapes, a.Points, a.Uncovered, a.Mean, a.Max);
      EXPECT_GT(a.Shapes, 5);
      EXPECT_EQ(a.Uncovered, 0);
      // Straight: the maps are affine, linear texture coordinates are exact. Turning: the
      // linear interpolation over triangles of 0.2 (the shape's radius: 1.8).
      EXPECT_LT(a.Max, turning && longShapes ? 0.03 : 1e-6);
    }
  }
}

TEST(ShapeDecal, DecalsAgreeWithOutlinesOnASphere)
{
  // Long shapes along the parallels bend (parallels are not geodesics).
  const TriangleMesh sphere = gs_test::BuildMesh(MakeIcosphere(1.0, 5));
  SaddleVertexGraph graph;
  SaddleVertexGraphOptions go;
  go.K = 50;
  std::string error;
  ASSERT_TRUE(graph.Build(sphere, go, nullptr, error)) << error;
  std::vector<Vec3> directions(sphere.NumberOfFaces());
  for (int f = 0; f < sphere.NumberOfFaces(); ++f)
  {
    const auto& c = sphere.Face(f);
    const Vec3 x = (sphere.Position(c[0]) + sphere.Position(c[1]) + sphere.Position(c[2])) / 3.0;
    directions[f] = Cross(Vec3{ 0, 0, 1 }, x);
  }
  const SafeDistanceTables t = Tables({ MakeStarPolygon(5, 1.0, 0.4), Bar() });
  ShapeDistributionOptions o;
  o.ShapeSize = 0.12;
  o.Seed = 1;
  o.MaximalFailures = 1000;
  ShapeDistributor d(sphere, &graph);
  const ShapeDistributionResult r = d.Run(t, directions, {}, o);
  ASSERT_TRUE(r.Ok) << r.Error;
  for (const bool longShapes : { false, true })
  {
    // (Near the poles, the field's singularities, a long shape's curve turns tighter than its
    // half width: the map folds and neither outline nor decal is the shape; skipped.)
    const Agreement a = Check(d, sphere, t, longShapes, 0.35);
    std::printf("sphere, %s shapes: %d shapes, %lld outline points (%lld outside the decal), class point "
                "off the silhouette: mean %.2e, max %.2e of the radius\n",
      longShapes ? "long" : "short", a.Shapes, a.Points, a.Uncovered, a.Mean, a.Max);
    EXPECT_GT(a.Shapes, 5);
    EXPECT_EQ(a.Uncovered, 0);
    EXPECT_LT(a.Mean, 0.01);
    EXPECT_LT(a.Max, 0.05);
  }
}
