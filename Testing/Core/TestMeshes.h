// Meshes shared by the core unit tests.
#pragma once

#include "MeshGenerators.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <random>

namespace gs_test
{

inline gs::TriangleMesh BuildMesh(const gs::TriangleSoup& s)
{
  auto r = gs::TriangleMeshBuilder::Build(s.Points, s.Triangles);
  EXPECT_TRUE(r.Ok) << r.Error;
  return r.Mesh;
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

} // namespace gs_test
