#include "MeshGenerators.h"
#include "TestStatus.h"
#include "TriangleMesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace gs;

namespace
{
constexpr double Pi = 3.14159265358979323846;

Result<MeshBuild> Build(const TriangleSoup& s)
{
  return TriangleMeshBuilder::Build(s.Points, s.Triangles);
}
} // namespace

TEST(TriangleMesh, PlanarGridCounts)
{
  const int nx = 6, ny = 4;
  auto r = Build(MakePlanarGrid(nx, ny, 3.0, 2.0));
  ASSERT_TRUE(gs_test::Succeeded(r));
  EXPECT_TRUE(r->Warnings.empty());
  const TriangleMesh& m = r->Mesh;
  EXPECT_EQ(m.NumberOfVertices(), (nx + 1) * (ny + 1));
  EXPECT_EQ(m.NumberOfFaces(), 2 * nx * ny);
  EXPECT_EQ(m.NumberOfEdges(), nx * (ny + 1) + ny * (nx + 1) + nx * ny);
  EXPECT_EQ(m.EulerCharacteristic(), 1);
  EXPECT_EQ(m.Genus(), 0);
  EXPECT_EQ(m.NumberOfComponents(), 1);
  ASSERT_EQ(m.BoundaryLoops().size(), 1u);
  EXPECT_EQ(m.BoundaryLoops()[0].size(), static_cast<std::size_t>(2 * (nx + ny)));
  int boundary = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    EXPECT_FALSE(m.IsSaddleVertex(v));
    boundary += m.IsBoundaryVertex(v);
    if (!m.IsBoundaryVertex(v))
    {
      EXPECT_NEAR(m.TotalAngle(v), 2 * Pi, 1e-12);
      EXPECT_EQ(m.OutgoingHalfedges(v).size(), m.OutgoingHalfedges(v).size());
    }
  }
  EXPECT_EQ(boundary, 2 * (nx + ny));
  // Corner vertex (0,0) has a right angle; an edge midpoint vertex a straight one.
  EXPECT_NEAR(m.TotalAngle(0), Pi / 2, 1e-12);
  EXPECT_NEAR(m.TotalAngle(1), Pi, 1e-12);
}

TEST(TriangleMesh, HalfedgeNavigation)
{
  auto r = Build(MakeIcosphere(1.0, 1));
  ASSERT_TRUE(gs_test::Succeeded(r));
  const TriangleMesh& m = r->Mesh;
  for (int h = 0; h < m.NumberOfHalfedges(); ++h)
  {
    const int t = m.Twin(h);
    ASSERT_GE(t, 0);
    EXPECT_EQ(m.Twin(t), h);
    EXPECT_EQ(m.Origin(t), m.Destination(h));
    EXPECT_EQ(m.Destination(t), m.Origin(h));
    EXPECT_NEAR(m.EdgeLength(h), m.EdgeLength(t), 1e-15);
    EXPECT_EQ(m.Origin(m.RotateCCW(h)), m.Origin(h));
    EXPECT_EQ(m.RotateCW(m.RotateCCW(h)), h);
  }
  double angleSum = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const auto out = m.OutgoingHalfedges(v);
    EXPECT_TRUE(out.size() == 5 || out.size() == 6);
    angleSum += 2 * Pi - m.TotalAngle(v);
  }
  // Gauss-Bonnet: total angle defect = 2 pi chi.
  EXPECT_NEAR(angleSum, 2 * Pi * m.EulerCharacteristic(), 1e-9);
  // Consistent outward orientation.
  for (int f = 0; f < m.NumberOfFaces(); ++f)
  {
    const Vec3 c = m.Interpolate(f, { { 1.0 / 3, 1.0 / 3, 1.0 / 3 } });
    EXPECT_GT(Dot(m.FaceNormal(f), c), 0.0);
  }
}

TEST(TriangleMesh, TopologyOfGeneratedSurfaces)
{
  {
    auto r = Build(MakeTorus(2.0, 0.7, 24, 12));
    ASSERT_TRUE(gs_test::Succeeded(r));
    EXPECT_TRUE(r->Warnings.empty());
    EXPECT_EQ(r->Mesh.EulerCharacteristic(), 0);
    EXPECT_EQ(r->Mesh.Genus(), 1);
    EXPECT_TRUE(r->Mesh.BoundaryLoops().empty());
    int saddles = 0;
    for (int v = 0; v < r->Mesh.NumberOfVertices(); ++v)
    {
      saddles += r->Mesh.IsSaddleVertex(v);
    }
    // The inner half of a torus has negative curvature.
    EXPECT_GT(saddles, 0);
  }
  {
    auto r = Build(MakeIcosphere(2.0, 2));
    ASSERT_TRUE(gs_test::Succeeded(r));
    EXPECT_EQ(r->Mesh.EulerCharacteristic(), 2);
    EXPECT_EQ(r->Mesh.Genus(), 0);
    EXPECT_EQ(r->Mesh.NumberOfFaces(), 320);
  }
  {
    auto r = Build(MakeCylinder(1.0, 2.0, 16, 5));
    ASSERT_TRUE(gs_test::Succeeded(r));
    EXPECT_TRUE(r->Warnings.empty());
    EXPECT_EQ(r->Mesh.EulerCharacteristic(), 0);
    EXPECT_EQ(r->Mesh.Genus(), 0);
    EXPECT_EQ(r->Mesh.BoundaryLoops().size(), 2u);
  }
  {
    auto r = Build(MakeCone(0.5, 2.0, 6, 20));
    ASSERT_TRUE(gs_test::Succeeded(r));
    EXPECT_TRUE(r->Warnings.empty());
    EXPECT_EQ(r->Mesh.EulerCharacteristic(), 1);
    EXPECT_EQ(r->Mesh.BoundaryLoops().size(), 1u);
    EXPECT_LT(r->Mesh.TotalAngle(0), 2 * Pi); // apex: positive curvature
    EXPECT_FALSE(r->Mesh.IsSaddleVertex(0));
  }
  {
    auto r = Build(MakeLShape(4));
    ASSERT_TRUE(gs_test::Succeeded(r));
    EXPECT_EQ(r->Mesh.EulerCharacteristic(), 1);
    ASSERT_EQ(r->Mesh.BoundaryLoops().size(), 1u);
    EXPECT_EQ(r->Mesh.BoundaryLoops()[0].size(), 32u);
    int reentrant = 0;
    for (int v = 0; v < r->Mesh.NumberOfVertices(); ++v)
    {
      if (std::abs(r->Mesh.TotalAngle(v) - 1.5 * Pi) < 1e-12)
      {
        ++reentrant;
        EXPECT_TRUE(r->Mesh.IsPseudoSourceVertex(v));
        EXPECT_TRUE(r->Mesh.IsBoundaryVertex(v));
        EXPECT_NEAR(r->Mesh.Position(v).x, 1.0, 1e-15);
        EXPECT_NEAR(r->Mesh.Position(v).y, 1.0, 1e-15);
      }
    }
    EXPECT_EQ(reentrant, 1);
  }
}

TEST(TriangleMesh, SaddleVertex)
{
  // A hexagonal fan whose rim goes up and down: the centre has more than 2 pi of angle.
  TriangleSoup s;
  s.Points.emplace_back(0, 0, 0);
  for (int k = 0; k < 6; ++k)
  {
    const double a = 2 * Pi * k / 6;
    s.Points.emplace_back(std::cos(a), std::sin(a), (k % 2 ? 0.6 : -0.6));
  }
  for (int k = 0; k < 6; ++k)
  {
    s.Triangles.push_back({ 0, 1 + k, 1 + (k + 1) % 6 });
  }
  auto r = Build(s);
  ASSERT_TRUE(gs_test::Succeeded(r));
  EXPECT_TRUE(r->Mesh.IsSaddleVertex(0));
  EXPECT_GT(r->Mesh.TotalAngle(0), 2 * Pi);
  EXPECT_TRUE(r->Mesh.IsPseudoSourceVertex(0));
  EXPECT_FALSE(r->Mesh.IsSaddleVertex(1));
  EXPECT_FALSE(r->Mesh.IsPseudoSourceVertex(1)); // boundary, but convex
}

TEST(TriangleMesh, WeldsSplitVerticesAndKeepsUnreferencedPoints)
{
  const TriangleSoup grid = MakePlanarGrid(3, 3, 1.0, 1.0);
  TriangleSoup split;
  split.Points.emplace_back(9, 9, 9); // unreferenced
  for (const auto& t : grid.Triangles)
  {
    std::array<long long, 3> nt;
    for (int k = 0; k < 3; ++k)
    {
      nt[k] = static_cast<long long>(split.Points.size());
      split.Points.push_back(grid.Points[t[k]]);
    }
    split.Triangles.push_back(nt);
  }
  split.Points.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0, 0); // unreferenced NaN
  auto r = Build(split);
  ASSERT_TRUE(gs_test::Succeeded(r));
  EXPECT_EQ(r->Mesh.NumberOfVertices(), 16);
  EXPECT_EQ(r->Mesh.NumberOfComponents(), 1);
  EXPECT_EQ(r->PointToVertex.front(), -1);
  EXPECT_EQ(r->PointToVertex.back(), -1);
  EXPECT_EQ(r->NumberOfWeldedPoints, static_cast<int>(split.Points.size()) - 2 - 16);
  for (std::size_t p = 1; p + 1 < split.Points.size(); ++p)
  {
    const Vec3 q = r->Mesh.Position(r->PointToVertex[p]);
    EXPECT_EQ(q.x, split.Points[p].x);
    EXPECT_EQ(q.y, split.Points[p].y);
  }
}

TEST(TriangleMesh, ReorientsInconsistentFaces)
{
  TriangleSoup s = MakePlanarGrid(4, 4, 1.0, 1.0);
  std::swap(s.Triangles[5][0], s.Triangles[5][1]);
  std::swap(s.Triangles[9][1], s.Triangles[9][2]);
  auto r = Build(s);
  ASSERT_TRUE(gs_test::Succeeded(r));
  ASSERT_EQ(r->Warnings.size(), 1u);
  for (int f = 0; f < r->Mesh.NumberOfFaces(); ++f)
  {
    EXPECT_GT(r->Mesh.FaceNormal(f).z, 0.5);
  }
}

TEST(TriangleMesh, ComponentsAndGenusAreSummed)
{
  TriangleSoup a = MakeTorus(2.0, 0.5, 16, 8);
  const TriangleSoup b = MakeIcosphere(1.0, 1);
  const long long offset = static_cast<long long>(a.Points.size());
  for (Vec3 p : b.Points)
  {
    a.Points.push_back(p + Vec3(10, 0, 0));
  }
  for (auto t : b.Triangles)
  {
    a.Triangles.push_back({ t[0] + offset, t[1] + offset, t[2] + offset });
  }
  auto r = Build(a);
  ASSERT_TRUE(gs_test::Succeeded(r));
  EXPECT_EQ(r->Mesh.NumberOfComponents(), 2);
  EXPECT_EQ(r->Mesh.EulerCharacteristic(), 2);
  EXPECT_EQ(r->Mesh.Genus(), 1);
}

TEST(TriangleMesh, RejectsBadInput)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Vec3> pts = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 1, 0 } };
  auto fails = [](const std::vector<Vec3>& p, const std::vector<std::array<long long, 3>>& t,
                 const std::string& needle) {
    EXPECT_TRUE(gs_test::FailedWith(TriangleMeshBuilder::Build(p, t), needle));
  };
  fails(pts, {}, "no triangles");
  fails(pts, { { 0, 1, 7 } }, "does not exist");
  fails(pts, { { 0, 1, -1 } }, "does not exist");
  fails(pts, { { 0, 1, 1 } }, "degenerate");
  fails({ { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 } }, { { 0, 1, 2 } }, "degenerate");
  fails({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 0 } }, { { 0, 1, 2 } }, "degenerate");
  fails({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, nan, 0 } }, { { 0, 1, 2 } }, "NaN");
  fails({ { 0, 0, 0 }, { 1e120, 0, 0 }, { 0, 1, 0 } }, { { 0, 1, 2 } }, "rescale");
  fails(pts, { { 0, 1, 2 }, { 2, 1, 0 } }, "duplicates");
  fails(pts, { { 0, 1, 2 }, { 1, 0, 3 }, { 0, 1, 4 } }, "non-manifold edge");
  // Bow tie: two triangles sharing only vertex 0.
  fails({ { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { -1, 0, 0 }, { -1, -1, 0 } },
    { { 0, 1, 2 }, { 0, 3, 4 } }, "non-manifold vertex");
}

TEST(TriangleMesh, KeepsApartCoincidentPointsThatWouldPinch)
{
  // Two triangles touching at one location through two distinct (coincident) points: welding
  // would make a bow tie, so the two copies stay separate vertices.
  auto r = TriangleMeshBuilder::Build(
    { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { -1, 0, 0 }, { -1, -1, 0 }, { 0, 0, 0 } },
    { { 0, 1, 2 }, { 5, 3, 4 } });
  ASSERT_TRUE(gs_test::Succeeded(r));
  EXPECT_EQ(r->Mesh.NumberOfVertices(), 6);
  EXPECT_EQ(r->Mesh.NumberOfComponents(), 2);
  EXPECT_NE(r->PointToVertex[0], r->PointToVertex[5]);
  ASSERT_EQ(r->Warnings.size(), 1u);
  EXPECT_EQ(r->Mesh.Face(0)[0], r->PointToVertex[0]);
  EXPECT_EQ(r->Mesh.Face(1)[0], r->PointToVertex[5]);
  for (int v = 0; v < 6; ++v)
  {
    EXPECT_EQ(r->PointToVertex[r->VertexToPoint[v]], v);
    EXPECT_TRUE(r->Mesh.IsBoundaryVertex(v));
  }
}

TEST(TriangleMesh, RejectsMoebiusStrip)
{
  TriangleSoup s;
  const int n = 12;
  for (int i = 0; i < n; ++i)
  {
    const double u = 2 * Pi * i / n;
    for (int j = 0; j < 2; ++j)
    {
      const double w = j == 0 ? -0.3 : 0.3;
      s.Points.emplace_back((1 + w * std::cos(u / 2)) * std::cos(u),
        (1 + w * std::cos(u / 2)) * std::sin(u), w * std::sin(u / 2));
    }
  }
  for (int i = 0; i < n; ++i)
  {
    long long a = 2 * i, b = 2 * i + 1;
    long long c = 2 * ((i + 1) % n), d = 2 * ((i + 1) % n) + 1;
    if (i == n - 1)
    {
      std::swap(c, d); // the half twist
    }
    s.Triangles.push_back({ a, c, d });
    s.Triangles.push_back({ a, d, b });
  }
  EXPECT_TRUE(gs_test::FailedWith(Build(s), "not orientable"));
}
