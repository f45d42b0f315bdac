// Meshes shared by the core unit tests.
#pragma once

#include "MeshGenerators.h"
#include "SafeDistanceTable.h"
#include "Silhouette.h"
#include "TestStatus.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <utility>
#include <vector>

namespace gs_test
{

inline gs::TriangleMesh BuildMesh(const gs::TriangleSoup& s)
{
  gs::Result<gs::MeshBuild> r = gs::TriangleMeshBuilder::Build(s.Points, s.Triangles);
  EXPECT_TRUE(Succeeded(r));
  return std::move(r->Mesh);
}

// An icosphere whose vertices are pushed in and out by up to `amplitude` (relative): saddles
// everywhere, no analytic answer.
inline gs::TriangleSoup BumpySoup(int level, unsigned seed, double amplitude)
{
  gs::TriangleSoup s = gs::MakeIcosphere(1.0, level);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(1.0 - amplitude, 1.0 + amplitude);
  for (gs::Vec3& p : s.Points)
  {
    p = p * u(rng);
  }
  return s;
}

// Safe distance tables of polygon classes ("class 0", "class 1", ...): 32 angle bins, 64 distance
// steps, 512 rows, fine enough for the distributor's tests and fast.
inline gs::SafeDistanceTables PolygonTables(const std::vector<std::vector<gs::Vec2>>& classes)
{
  std::vector<gs::SafeDistanceInput> in;
  for (std::size_t k = 0; k < classes.size(); ++k)
  {
    in.push_back({ "class " + std::to_string(k), gs::ShapeFromPolygons({ classes[k] }) });
  }
  gs::SafeDistanceOptions o;
  o.AngleBins = 32;
  o.DistanceSteps = 64;
  o.Rows = 512;
  gs::Result<gs::SafeDistanceTables> r = gs::ComputeSafeDistanceTables(in, o);
  EXPECT_TRUE(r.Ok()) << r.Message();
  return *r;
}

// A star (5 points, radii 1 and 0.4) and a 5 x 1 bar: a short class and a long one, split into
// parts that bend along the field.
inline gs::SafeDistanceTables StarAndBar()
{
  return PolygonTables({ gs::MakeStarPolygon(5, 1.0, 0.4),
    { { -2.5, -0.5 }, { 2.5, -0.5 }, { 2.5, 0.5 }, { -2.5, 0.5 } } });
}

} // namespace gs_test
