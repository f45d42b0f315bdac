// Direction fields: Poincare-Hopf on closed meshes of genus 0, 1, 3 and on a disc, smoothest
// fields on flat and developable meshes, hard stroke constraints, curvature alignment.
#include "DirectionField.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace
{
constexpr double Pi = 3.14159265358979323846;

double Sum(const std::vector<double>& v)
{
  double s = 0.0;
  for (double x : v)
  {
    s += x;
  }
  return s;
}

// A closed slab of genus `holes`: an nx x ny grid with square holes, top and bottom copies and
// walls along every boundary loop.
gs::TriangleSoup HoledSlab(int holes)
{
  const int nx = 4 * holes + 1, ny = 5;
  auto isHole = [&](int i, int j) { return j >= 2 && j < 3 && i % 4 >= 2 && i % 4 < 3 && i < nx - 1; };
  gs::TriangleSoup s;
  auto id = [&](int i, int j, int layer) { return static_cast<long long>(layer * (nx + 1) * (ny + 1) + j * (nx + 1) + i); };
  for (int layer = 0; layer < 2; ++layer)
  {
    for (int j = 0; j <= ny; ++j)
    {
      for (int i = 0; i <= nx; ++i)
      {
        s.Points.emplace_back(i * 1.0, j * 1.0, layer * 1.0);
      }
    }
  }
  std::map<std::pair<long long, long long>, int> edgeCount;
  std::vector<std::array<long long, 3>> top;
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      if (isHole(i, j))
      {
        continue;
      }
      const long long a = id(i, j, 1), b = id(i + 1, j, 1), c = id(i + 1, j + 1, 1), d = id(i, j + 1, 1);
      top.push_back({ a, b, c });
      top.push_back({ a, c, d });
    }
  }
  for (const auto& t : top)
  {
    for (int k = 0; k < 3; ++k)
    {
      edgeCount[{ t[k], t[(k + 1) % 3] }]++;
    }
  }
  const long long layer = (nx + 1) * (ny + 1);
  for (const auto& t : top)
  {
    s.Triangles.push_back(t);
    s.Triangles.push_back({ t[0] - layer, t[2] - layer, t[1] - layer });
    for (int k = 0; k < 3; ++k)
    {
      const long long a = t[k], b = t[(k + 1) % 3];
      if (edgeCount.count({ b, a }) == 0)
      {
        // boundary edge a -> b of the top (counter-clockwise seen from above): wall outward
        s.Triangles.push_back({ b, a, a - layer });
        s.Triangles.push_back({ b, a - layer, b - layer });
      }
    }
  }
  return s;
}

void ExpectIntegerIndices(const gs::DirectionFieldSolver& solver, int n, const std::vector<double>& angles)
{
  const std::vector<double> raw = solver.VertexIndices(n, angles);
  for (int v = 0; v < solver.Mesh().NumberOfVertices(); ++v)
  {
    if (!solver.Mesh().IsBoundaryVertex(v))
    {
      EXPECT_NEAR(raw[v] * n, std::round(raw[v] * n), 1e-8) << "vertex " << v;
    }
  }
}

int CountSingular(const gs::TriangleMesh& m, const std::vector<double>& index)
{
  int count = 0;
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    count += !m.IsBoundaryVertex(v) && index[v] != 0.0;
  }
  return count;
}
} // namespace

TEST(DirectionField, PoincareHopfOnClosedMeshes)
{
  const gs::TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 7u, 0.05));
  const gs::TriangleMesh torus = gs_test::BuildMesh(gs::MakeTorus(1.0, 0.35, 40, 16));
  const gs::TriangleMesh slab = gs_test::BuildMesh(HoledSlab(3));
  ASSERT_EQ(slab.Genus(), 3);
  for (const gs::TriangleMesh* m : { &sphere, &torus, &slab })
  {
    gs::DirectionFieldSolver solver(*m);
    for (int n : { 1, 2, 4 })
    {
      std::vector<double> angles;
      ASSERT_TRUE(gs_test::Succeeded(solver.SolveSmoothest(n, 0.0, {}, angles)));
      ExpectIntegerIndices(solver, n, angles);
      const std::vector<double> index = solver.RoundedVertexIndices(n, angles);
      EXPECT_NEAR(Sum(index), m->EulerCharacteristic(), 1e-9) << "N = " << n;
      EXPECT_NEAR(solver.IndexSum(n, angles), m->EulerCharacteristic(), 1e-9) << "N = " << n;
      // The smoothest field has no singularity of index beyond one quantum (generic case).
      for (int v = 0; v < m->NumberOfVertices(); ++v)
      {
        EXPECT_LE(std::abs(index[v]), 1.0 / n + 1e-9) << "N = " << n << " vertex " << v;
      }
      // (On this torus of revolution the smoothest cross field has +-1/4 pairs, as in Knoppel
      // et al. 2013; only the sum is fixed.)
      if (m == &sphere)
      {
        EXPECT_EQ(CountSingular(*m, index), 2 * n) << "N = " << n;
      }
    }
  }
}

TEST(DirectionField, FlatDiscIsConstantAndBoundaryConventionHolds)
{
  const gs::TriangleMesh disc = gs_test::BuildMesh(gs::MakePlanarGrid(12, 9, 1.2, 0.9));
  gs::DirectionFieldSolver solver(disc);
  for (int n : { 1, 2, 4 })
  {
    std::vector<double> angles;
    ASSERT_TRUE(gs_test::Succeeded(solver.SolveSmoothest(n, 0.0, {}, angles)));
    EXPECT_LT(solver.Energy(n, angles), 1e-12);
    const gs::Vec3 d0 = solver.DirectionInFace(0, angles[0]);
    for (int f = 0; f < disc.NumberOfFaces(); ++f)
    {
      const gs::Vec3 d = solver.DirectionInFace(f, angles[f]);
      const double a = std::atan2(gs::Cross(d0, d).z, gs::Dot(d0, d));
      EXPECT_NEAR(gs::DirectionFieldSolver::WrapSymmetric(a, n), 0.0, 1e-6);
    }
    const std::vector<double> index = solver.RoundedVertexIndices(n, angles);
    EXPECT_EQ(CountSingular(disc, index), 0);
    EXPECT_NEAR(Sum(index), 1.0, 1e-9); // boundary loop: the tangent turns once
    EXPECT_NEAR(solver.IndexSum(n, angles), 1.0, 1e-9);
    // Vertex directions of a constant field: that field, unit, at every vertex.
    for (const gs::Vec3& d : solver.VertexDirections(n, angles))
    {
      EXPECT_NEAR(gs::Norm(d), 1.0, 1e-9);
      const double a = std::atan2(gs::Cross(d0, d).z, gs::Dot(d0, d));
      EXPECT_NEAR(gs::DirectionFieldSolver::WrapSymmetric(a, n), 0.0, 1e-6);
    }
  }
}

TEST(DirectionField, StrokeConstraintsAreHardAndPropagate)
{
  // Plane with a diagonal stroke constraint on a band of faces: the smoothest extension is that
  // constant direction everywhere. On a bumpy sphere the constrained faces keep their direction.
  const gs::TriangleMesh plane = gs_test::BuildMesh(gs::MakePlanarGrid(10, 10, 1.0, 1.0));
  gs::DirectionFieldSolver solver(plane);
  const gs::Vec3 dir(1.0, 2.0, 0.0);
  std::vector<gs::FaceDirectionConstraint> c;
  for (int f = 0; f < plane.NumberOfFaces(); f += 7)
  {
    c.push_back({ f, dir });
  }
  for (int n : { 1, 2, 4 })
  {
    std::vector<double> angles;
    ASSERT_TRUE(gs_test::Succeeded(solver.SolveSmoothest(n, 0.0, c, angles)));
    for (int f = 0; f < plane.NumberOfFaces(); ++f)
    {
      const gs::Vec3 d = solver.DirectionInFace(f, angles[f]);
      const double a = std::atan2(gs::Cross(dir, d).z, gs::Dot(dir, d));
      EXPECT_NEAR(gs::DirectionFieldSolver::WrapSymmetric(a, n), 0.0, 1e-6) << "N " << n;
    }
  }
  const gs::TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 3u, 0.05));
  gs::DirectionFieldSolver s2(sphere);
  std::vector<gs::FaceDirectionConstraint> c2;
  for (int f = 0; f < sphere.NumberOfFaces(); f += 37)
  {
    const gs::Vec3 e = sphere.Position(sphere.Face(f)[1]) - sphere.Position(sphere.Face(f)[0]);
    c2.push_back({ f, e });
  }
  std::vector<double> a1, a2;
  ASSERT_TRUE(gs_test::Succeeded(s2.SolveSmoothest(4, 0.0, c2, a1)));
  for (const auto& k : c2)
  {
    EXPECT_NEAR(gs::DirectionFieldSolver::WrapSymmetric(a1[k.Face] - s2.AngleInFace(k.Face, k.Direction), 4), 0.0, 1e-9);
  }
  EXPECT_NEAR(Sum(s2.RoundedVertexIndices(4, a1)), 2.0, 1e-9);
  // Same faces, other directions: re-solve with the kept factorization.
  for (auto& k : c2)
  {
    k.Direction = gs::Cross(sphere.FaceNormal(k.Face), k.Direction);
  }
  ASSERT_TRUE(gs_test::Succeeded(s2.SolveSmoothest(4, 0.0, c2, a2)));
  for (const auto& k : c2)
  {
    EXPECT_NEAR(gs::DirectionFieldSolver::WrapSymmetric(a2[k.Face] - s2.AngleInFace(k.Face, k.Direction), 4), 0.0, 1e-9);
  }
  // Invalid constraints are refused with a message.
  std::vector<double> a3;
  const gs::Status outside = s2.SolveSmoothest(4, 0.0, { { sphere.NumberOfFaces(), dir } }, a3);
  EXPECT_FALSE(outside.Ok());
  EXPECT_FALSE(outside.Message().empty());
  EXPECT_FALSE(s2.SolveSmoothest(3, 0.0, {}, a3).Ok());
}

TEST(DirectionField, CurvatureAlignmentOnCylinder)
{
  // On a cylinder the principal directions are the axis and the circles: a strongly aligned
  // line or cross field follows them.
  const gs::TriangleMesh cyl = gs_test::BuildMesh(gs::MakeCylinder(1.0, 3.0, 48, 24));
  gs::DirectionFieldSolver solver(cyl);
  for (int n : { 2, 4 })
  {
    std::vector<double> angles;
    ASSERT_TRUE(gs_test::Succeeded(solver.SolveSmoothest(n, 10.0, {}, angles)));
    double worst = 0.0;
    for (int f = 0; f < cyl.NumberOfFaces(); ++f)
    {
      const gs::Vec3 d = solver.DirectionInFace(f, angles[f]);
      const double a = std::acos(std::min(1.0, std::abs(d.z)));
      const double dev = std::min(a, 0.5 * Pi - a); // along the axis or around it
      worst = std::max(worst, dev);
    }
    EXPECT_LT(worst * 180.0 / Pi, 2.0) << "N = " << n;
  }
}

namespace
{
// The vertex closest to a direction from the origin.
int ClosestVertex(const gs::TriangleMesh& m, const gs::Vec3& p)
{
  int best = 0;
  for (int v = 1; v < m.NumberOfVertices(); ++v)
  {
    if (gs::Norm(m.Position(v) - p) < gs::Norm(m.Position(best) - p))
    {
      best = v;
    }
  }
  return best;
}

void ExpectExactly(const gs::DirectionFieldSolver& solver, int n,
  const std::vector<double>& angles, const std::vector<gs::VertexSingularity>& placed)
{
  const gs::TriangleMesh& m = solver.Mesh();
  std::vector<double> expected(m.NumberOfVertices(), 0.0);
  for (const auto& s : placed)
  {
    expected[s.Vertex] += s.Index;
  }
  ExpectIntegerIndices(solver, n, angles);
  const std::vector<double> index = solver.VertexIndices(n, angles);
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    if (!m.IsBoundaryVertex(v))
    {
      EXPECT_NEAR(index[v], expected[v], 1e-8) << "N = " << n << " vertex " << v;
    }
  }
  for (const auto& loop : m.BoundaryLoops())
  {
    double measured = 0.0, wanted = 0.0;
    for (int v : loop)
    {
      measured += index[v];
      wanted += expected[v];
    }
    EXPECT_NEAR(measured, wanted, 1e-8) << "boundary loop of N = " << n;
  }
}
} // namespace

TEST(DirectionField, PrescribedSingularitiesAppearExactlyWherePlaced)
{
  const gs::TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 11u, 0.05));
  gs::DirectionFieldSolver solver(sphere);
  std::vector<double> angles;
  // Two +1 (a vector field), four +1/2 (a line field), eight +1/4 at the cube's corners.
  const std::vector<gs::VertexSingularity> two{ { ClosestVertex(sphere, { 0, 0, 1 }), 1.0 },
    { ClosestVertex(sphere, { 0, 0, -1 }), 1.0 } };
  ASSERT_TRUE(gs_test::Succeeded(solver.SolvePrescribed(1, two, {}, angles)));
  ExpectExactly(solver, 1, angles, two);
  std::vector<gs::VertexSingularity> four, eight;
  for (const gs::Vec3& p : { gs::Vec3(1, 0, 0), gs::Vec3(-1, 0, 0), gs::Vec3(0, 1, 0), gs::Vec3(0, -1, 0) })
  {
    four.push_back({ ClosestVertex(sphere, p), 0.5 });
  }
  ASSERT_TRUE(gs_test::Succeeded(solver.SolvePrescribed(2, four, {}, angles)));
  ExpectExactly(solver, 2, angles, four);
  for (int i = 0; i < 8; ++i)
  {
    const gs::Vec3 p((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    eight.push_back({ ClosestVertex(sphere, p / std::sqrt(3.0)), 0.25 });
  }
  ASSERT_TRUE(gs_test::Succeeded(solver.SolvePrescribed(4, eight, {}, angles)));
  ExpectExactly(solver, 4, angles, eight);
  // A +2 and a 0 + ... : one vertex carrying the whole characteristic.
  const std::vector<gs::VertexSingularity> one{ { 5, 2.0 } };
  ASSERT_TRUE(gs_test::Succeeded(solver.SolvePrescribed(1, one, {}, angles)));
  ExpectExactly(solver, 1, angles, one);

  // Wrong sums are refused with the sums in the message.
  const gs::Status wrongSum = solver.SolvePrescribed(1, { { 3, 1.0 } }, {}, angles);
  EXPECT_FALSE(wrongSum.Ok());
  EXPECT_NE(wrongSum.Message().find("sum to 1"), std::string::npos) << wrongSum.Message();
  EXPECT_NE(wrongSum.Message().find("Euler characteristic 2"), std::string::npos) << wrongSum.Message();
  const gs::Status notMultiple = solver.SolvePrescribed(4, { { 3, 0.3 }, { 4, 1.7 } }, {}, angles);
  EXPECT_FALSE(notMultiple.Ok());
  EXPECT_NE(notMultiple.Message().find("multiple of 1/4"), std::string::npos) << notMultiple.Message();
}

TEST(DirectionField, PrescribedOnTorusGenus3AndDisc)
{
  const gs::TriangleMesh torus = gs_test::BuildMesh(gs::MakeTorus(1.0, 0.35, 40, 16));
  gs::DirectionFieldSolver ts(torus);
  std::vector<double> angles;
  for (int n : { 1, 2, 4 })
  {
    ASSERT_TRUE(gs_test::Succeeded(ts.SolvePrescribed(n, {}, {}, angles)));
    ExpectExactly(ts, n, angles, {});
  }
  // A +1/-1 pair on the torus.
  const std::vector<gs::VertexSingularity> pair{ { 10, 1.0 }, { 300, -1.0 } };
  ASSERT_TRUE(gs_test::Succeeded(ts.SolvePrescribed(1, pair, {}, angles)));
  ExpectExactly(ts, 1, angles, pair);

  const gs::TriangleMesh slab = gs_test::BuildMesh(HoledSlab(3));
  gs::DirectionFieldSolver ss(slab);
  std::vector<gs::VertexSingularity> saddles;
  for (int i = 0; i < 4; ++i)
  {
    saddles.push_back({ ClosestVertex(slab, { 1.0 + 4.0 * i, 4.0, 1.0 }), -1.0 });
  }
  ASSERT_TRUE(gs_test::Succeeded(ss.SolvePrescribed(1, saddles, {}, angles)));
  ExpectExactly(ss, 1, angles, saddles);

  // Rectangle: a cross field turning by 1/4 at each corner is the constant grid-aligned field.
  const gs::TriangleMesh disc = gs_test::BuildMesh(gs::MakePlanarGrid(12, 9, 1.2, 0.9));
  gs::DirectionFieldSolver ds(disc);
  std::vector<gs::VertexSingularity> corners;
  for (const gs::Vec3& p : { gs::Vec3(0, 0, 0), gs::Vec3(1.2, 0, 0), gs::Vec3(1.2, 0.9, 0), gs::Vec3(0, 0.9, 0) })
  {
    corners.push_back({ ClosestVertex(disc, p), 0.25 });
  }
  ASSERT_TRUE(gs_test::Succeeded(ds.SolvePrescribed(4, corners, {}, angles)));
  for (int f = 0; f < disc.NumberOfFaces(); ++f)
  {
    const gs::Vec3 d = ds.DirectionInFace(f, angles[f]);
    EXPECT_NEAR(gs::DirectionFieldSolver::WrapSymmetric(std::atan2(d.y, d.x), 4), 0.0, 1e-9);
  }
  const std::vector<double> index = ds.VertexIndices(4, angles);
  for (int v = 0; v < disc.NumberOfVertices(); ++v)
  {
    EXPECT_NEAR(index[v], std::abs(disc.TotalAngle(v) - Pi / 2) < 1e-9 ? 0.25 : 0.0, 1e-9);
  }
  // Without the corners a boundary-aligned field needs a +1 inside.
  const gs::Status noCorners = ds.SolvePrescribed(4, {}, {}, angles);
  EXPECT_FALSE(noCorners.Ok());
  EXPECT_NE(noCorners.Message().find("Euler characteristic 1"), std::string::npos) << noCorners.Message();
  const std::vector<gs::VertexSingularity> centre{ { ClosestVertex(disc, { 0.6, 0.45, 0 }), 1.0 } };
  ASSERT_TRUE(gs_test::Succeeded(ds.SolvePrescribed(1, centre, {}, angles)));
  ExpectExactly(ds, 1, angles, centre);
}

TEST(DirectionField, PrescribedWithStrokes)
{
  const gs::TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 11u, 0.05));
  gs::DirectionFieldSolver solver(sphere);
  const std::vector<gs::VertexSingularity> two{ { ClosestVertex(sphere, { 0, 0, 1 }), 1.0 },
    { ClosestVertex(sphere, { 0, 0, -1 }), 1.0 } };
  // A stroke along the equator (faces whose centroid is nearest to z = 0), eastward.
  std::vector<gs::FaceDirectionConstraint> stroke;
  for (int k = 0; k < 24; ++k)
  {
    const double a = 2 * Pi * k / 24.0;
    const gs::Vec3 p(std::cos(a), std::sin(a), 0.0);
    int best = 0;
    double bestD = 1e9;
    for (int f = 0; f < sphere.NumberOfFaces(); ++f)
    {
      const gs::Vec3 c = sphere.Interpolate(f, { 1.0 / 3, 1.0 / 3, 1.0 / 3 });
      const double d = gs::Norm(c / gs::Norm(c) - p);
      if (d < bestD)
      {
        bestD = d;
        best = f;
      }
    }
    stroke.push_back({ best, gs::Vec3(-std::sin(a), std::cos(a), 0.0) });
  }
  std::vector<double> angles;
  for (int n : { 1, 4 })
  {
    const std::vector<gs::VertexSingularity> s = n == 1 ? two : std::vector<gs::VertexSingularity>{};
    std::vector<gs::VertexSingularity> sing = s;
    if (n == 4)
    {
      for (int i = 0; i < 8; ++i)
      {
        const gs::Vec3 p((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
        sing.push_back({ ClosestVertex(sphere, p / std::sqrt(3.0)), 0.25 });
      }
    }
    ASSERT_TRUE(gs_test::Succeeded(solver.SolvePrescribed(n, sing, stroke, angles)));
    for (const auto& c : stroke)
    {
      const double dev = gs::DirectionFieldSolver::WrapSymmetric(angles[c.Face] - solver.AngleInFace(c.Face, c.Direction), n);
      EXPECT_LT(std::abs(dev) * 180 / Pi, 1e-6) << "N = " << n << " face " << c.Face;
    }
    ExpectExactly(solver, n, angles, sing);
  }
}

TEST(DirectionField, StreamlineTracer)
{
  // Constant field on a plane: a straight segment of exactly the asked length.
  const gs::TriangleMesh plane = gs_test::BuildMesh(gs::MakePlanarGrid(20, 20, 1.0, 1.0));
  gs::DirectionFieldSolver solver(plane);
  const gs::Vec3 dir = gs::Vec3(1.0, 2.0, 0.0) / std::sqrt(5.0);
  std::vector<double> angles;
  ASSERT_TRUE(gs_test::Succeeded(solver.SolveSmoothest(4, 0.0, { { 0, dir } }, angles)));
  const int f0 = 2 * (10 * 20 + 10);
  const gs::SurfacePoint start = gs::SurfacePoint::InFace(f0, 0.2, 0.3, 0.5);
  const gs::Vec3 p0 = plane.Interpolate(f0, start.Bary);
  const double a0 = solver.AngleInFace(f0, dir);
  for (double length : { 0.01, 0.17, 0.33 })
  {
    const gs::Streamline line = solver.TraceStreamline(4, angles, start, a0 + 0.1, length);
    EXPECT_EQ(line.Reason, gs::Streamline::ReachedLength);
    EXPECT_NEAR(line.Length, length, 1e-12);
    const gs::Vec3 p1 = plane.Interpolate(line.End.Face, line.End.Bary);
    EXPECT_NEAR(gs::Norm(p1 - (p0 + dir * length)), 0.0, 1e-9);
    double sum = 0.0;
    for (const gs::CurvePiece& piece : line.Pieces)
    {
      sum += gs::Norm(piece.B - piece.A);
      EXPECT_LT(gs::Norm(gs::Cross(piece.A - p0, dir)), 1e-9);
      EXPECT_LT(gs::Norm(gs::Cross(piece.B - p0, dir)), 1e-9);
    }
    EXPECT_NEAR(sum, length, 1e-9);
    EXPECT_GT(line.Pieces.size(), length > 0.1 ? 3u : 0u);
  }
  // The other representatives of the cross: rotated by 90 degrees.
  const gs::Streamline side = solver.TraceStreamline(4, angles, start, a0 + Pi / 2 - 0.2, 0.2);
  const gs::Vec3 p2 = plane.Interpolate(side.End.Face, side.End.Bary);
  EXPECT_NEAR(gs::Norm(p2 - (p0 + gs::Vec3(-dir.y, dir.x, 0.0) * 0.2)), 0.0, 1e-9);
  // Too long: stops on the boundary, within the square.
  const gs::Streamline out = solver.TraceStreamline(4, angles, start, a0, 10.0);
  EXPECT_EQ(out.Reason, gs::Streamline::ReachedBoundary);
  const gs::Vec3 pb = plane.Interpolate(out.End.Face, out.End.Bary);
  EXPECT_NEAR(pb.y, 1.0, 1e-9); // slope 2 from (0.5, 0.5): leaves through y = 1
  EXPECT_NEAR(out.Length, (1.0 - p0.y) / dir.y, 1e-9);

  // Vector field on a sphere with sources at the poles: a streamline from the equator towards a
  // pole stops at its singularity.
  // A stroke on the equator pointing north makes the field meridional.
  const gs::TriangleMesh sphere = gs_test::BuildMesh(gs::MakeIcosphere(1.0, 3));
  gs::DirectionFieldSolver s2(sphere);
  const int north = ClosestVertex(sphere, { 0, 0, 1 }), south = ClosestVertex(sphere, { 0, 0, -1 });
  int fe = 0;
  for (int f = 0; f < sphere.NumberOfFaces(); ++f)
  {
    if (std::abs(sphere.Interpolate(f, { 1.0 / 3, 1.0 / 3, 1.0 / 3 }).z) <
      std::abs(sphere.Interpolate(fe, { 1.0 / 3, 1.0 / 3, 1.0 / 3 }).z))
    {
      fe = f;
    }
  }
  const gs::Vec3 up = gs::Vec3(0, 0, 1);
  ASSERT_TRUE(gs_test::Succeeded(s2.SolvePrescribed(1, { { north, 1.0 }, { south, 1.0 } }, { { fe, up } }, angles)));
  const std::vector<double> index = s2.RoundedVertexIndices(1, angles);
  const gs::Streamline pole = s2.TraceStreamline(1, angles, gs::SurfacePoint::InFace(fe, 1.0 / 3, 1.0 / 3, 1.0 / 3),
    s2.AngleInFace(fe, up), 5.0, &index);
  EXPECT_EQ(pole.Reason, gs::Streamline::ReachedSingularity);
  EXPECT_LT(pole.Length, 2.0);
  const gs::Vec3 pe = sphere.Interpolate(pole.End.Face, pole.End.Bary);
  EXPECT_GT(std::abs(pe.z), 0.9);
}

namespace
{
bool SameBits(const gs::Vec3& a, const gs::Vec3& b)
{
  return std::memcmp(&a, &b, sizeof(gs::Vec3)) == 0;
}

void ExpectSameLine(const gs::Streamline& a, const gs::Streamline& b, const char* what)
{
  ASSERT_EQ(a.Pieces.size(), b.Pieces.size()) << what;
  for (std::size_t i = 0; i < a.Pieces.size(); ++i)
  {
    EXPECT_EQ(a.Pieces[i].Face, b.Pieces[i].Face) << what << " piece " << i;
    EXPECT_TRUE(SameBits(a.Pieces[i].A, b.Pieces[i].A) && SameBits(a.Pieces[i].B, b.Pieces[i].B))
      << what << " piece " << i;
  }
  EXPECT_EQ(std::memcmp(&a.Length, &b.Length, sizeof(double)), 0) << what;
  EXPECT_EQ(a.Reason, b.Reason) << what;
  EXPECT_EQ(a.End.Face, b.End.Face) << what;
  EXPECT_TRUE(a.End.Bary == b.End.Bary) << what;
}
} // namespace

// A streamline traced in stages (the Shape Distributor checks a long candidate's parts behind
// its centre before tracing the rest) is the streamline traced at once, bit for bit, wherever
// the stages end: each stage stops at the first face exit at or beyond its length.
TEST(DirectionField, StagedStreamlineIsTheSameBitForBit)
{
  const gs::TriangleMesh sphere = gs_test::BuildMesh(gs::MakeIcosphere(1.0, 4));
  gs::DirectionFieldSolver solver(sphere);
  std::vector<double> angles;
  const int north = ClosestVertex(sphere, { 0, 0, 1 }), south = ClosestVertex(sphere, { 0, 0, -1 });
  ASSERT_TRUE(gs_test::Succeeded(solver.SolvePrescribed(2, { { north, 1.0 }, { south, 1.0 } }, {}, angles)));
  const std::vector<double> index = solver.RoundedVertexIndices(2, angles);
  int stopsAtLength = 0, stopsEarly = 0;
  for (int f = 0; f < sphere.NumberOfFaces(); f += 97)
  {
    const gs::SurfacePoint start = gs::SurfacePoint::InFace(f, 0.5, 0.3, 0.2);
    for (double length : { 0.05, 0.8, 4.0 })
    {
      const gs::Streamline once = solver.TraceStreamline(2, angles, start, 0.3, length, &index);
      (once.Reason == gs::Streamline::ReachedLength ? stopsAtLength : stopsEarly) += 1;
      for (double stage : { 0.0, 0.013, 0.31, 0.5 })
      {
        gs::DirectionFieldSolver::StreamlineTracer tracer(solver, 2, angles, start, 0.3, length, &index);
        double last = 0.0;
        for (double until = stage; until < length && !tracer.Finished(); until += stage > 0 ? stage : length)
        {
          tracer.Continue(until);
          EXPECT_TRUE(tracer.Finished() || tracer.Line().Length >= until);
          EXPECT_GE(tracer.Line().Length, last); // stages only add pieces
          last = tracer.Line().Length;
          // A stage holds a prefix of the whole line's pieces.
          ASSERT_LE(tracer.Line().Pieces.size(), once.Pieces.size());
          if (!tracer.Finished() && !tracer.Line().Pieces.empty())
          {
            const std::size_t k = tracer.Line().Pieces.size() - 1;
            EXPECT_TRUE(SameBits(tracer.Line().Pieces[k].B, once.Pieces[k].B)) << "face " << f;
          }
        }
        EXPECT_FALSE(tracer.Continue());
        ExpectSameLine(tracer.Line(), once, "staged");
      }
    }
  }
  EXPECT_GT(stopsAtLength, 10);
  EXPECT_GT(stopsEarly, 3); // (singularities at the poles)
}

// Issue 21 (part 4): a point direction array averaged per face N-symmetrically. Each corner of a
// face gets a smooth field's direction rotated by a random multiple of 2 pi / N (any arm of a
// cross, either sense of a line): the face directions must be those of the unrotated field modulo
// 2 pi / N (exactly, and to the wobble when the corners also wobble), and for N = 1 on a smooth
// sphere the corners' mean. Aligning corners by sign only (N = 2's rule) gets crosses wrong by up
// to 45 degrees.
namespace
{
// FaceDirectionsFromVertices, expected to succeed.
std::vector<gs::Vec3> FaceDirections(
  const gs::TriangleMesh& mesh, const std::vector<gs::Vec3>& atVertex, int symmetry)
{
  gs::Result<std::vector<gs::Vec3>> directions =
    gs::FaceDirectionsFromVertices(mesh, atVertex, symmetry);
  EXPECT_TRUE(gs_test::Succeeded(directions));
  return std::move(*directions);
}
} // namespace

TEST(DirectionField, PointDirectionsAreAveragedNSymmetrically)
{
  const double pi = 3.14159265358979323846;
  for (const double bumps : { 0.0, 0.02 })
  {
    const gs::TriangleMesh mesh = gs_test::BuildMesh(gs_test::BumpySoup(4, 5, bumps));
    const std::vector<gs::Vec3> normals = gs::AreaWeightedVertexNormals(mesh);
    const int nv = mesh.NumberOfVertices();
    std::mt19937 rng(21);
    std::uniform_int_distribution<int> arm(0, 3);
    std::uniform_real_distribution<double> wobble(-0.05, 0.05);
    // A smooth tangent field: the axis projected onto the tangent planes (poles at +-axis).
    const gs::Vec3 axis = gs::Unit(gs::Vec3{ 0.3, 0.2, 1.0 });
    std::vector<gs::Vec3> truth(nv);
    for (int v = 0; v < nv; ++v)
    {
      truth[v] = gs::Unit(axis - normals[v] * gs::Dot(axis, normals[v]));
    }
    const auto awayFromPoles = [&](int f) {
      const auto& c = mesh.Face(f);
      const gs::Vec3 centre =
        gs::Unit(mesh.Position(c[0]) + mesh.Position(c[1]) + mesh.Position(c[2]));
      return std::abs(gs::Dot(axis, centre)) < 0.9;
    };
    const auto angleBetween = [](const gs::Vec3& a, const gs::Vec3& b, const gs::Vec3& n) {
      return std::atan2(gs::Dot(gs::Cross(a, b), n), gs::Dot(a, b));
    };
    for (int symmetry : { 1, 2, 4 })
    {
      const double period = 2.0 * pi / symmetry;
      const std::vector<gs::Vec3> reference = FaceDirections(mesh, truth, symmetry);
      std::vector<gs::Vec3> arms(nv), wobbly(nv);
      for (int v = 0; v < nv; ++v)
      {
        const double turn = period * (arm(rng) % symmetry);
        arms[v] = gs::RotateTangent(truth[v], normals[v], turn) * (1.0 + 0.5 * wobble(rng));
        wobbly[v] = gs::RotateTangent(truth[v], normals[v], turn + wobble(rng));
      }
      const std::vector<gs::Vec3> fromArms = FaceDirections(mesh, arms, symmetry);
      const std::vector<gs::Vec3> fromWobbly = FaceDirections(mesh, wobbly, symmetry);
      ASSERT_EQ(static_cast<int>(fromArms.size()), mesh.NumberOfFaces());
      double worstArms = 0.0, worstWobbly = 0.0, worstMean = 0.0;
      int checked = 0;
      for (int f = 0; f < mesh.NumberOfFaces(); ++f)
      {
        if (!awayFromPoles(f))
        {
          continue;
        }
        const gs::Vec3 n = mesh.FaceNormal(f);
        ASSERT_NEAR(gs::Norm(fromArms[f]), 1.0, 1e-9);
        EXPECT_NEAR(gs::Dot(fromArms[f], n), 0.0, 1e-9);
        const auto offModulo = [&](double a) { return std::abs(a - period * std::round(a / period)); };
        // Equal weights: the arms' lengths (0.975..1.025) move the mean by far less than 0.02.
        worstArms = std::max(worstArms, offModulo(angleBetween(reference[f], fromArms[f], n)));
        worstWobbly = std::max(worstWobbly, offModulo(angleBetween(reference[f], fromWobbly[f], n)));
        if (symmetry == 1)
        {
          const auto& c = mesh.Face(f);
          gs::Vec3 mean = truth[c[0]] + truth[c[1]] + truth[c[2]];
          mean = gs::Unit(mean - n * gs::Dot(mean, n));
          worstMean = std::max(worstMean, std::abs(angleBetween(mean, reference[f], n)));
        }
        ++checked;
      }
      EXPECT_GT(checked, mesh.NumberOfFaces() / 2);
      EXPECT_LT(worstArms, 0.02) << "N = " << symmetry << ", bumps " << bumps;
      EXPECT_LT(worstWobbly, 0.05) << "N = " << symmetry << ", bumps " << bumps;
      if (symmetry == 1 && bumps == 0.0)
      {
        // On a smooth sphere, transport and projection agree to the faces' tilt squared.
        EXPECT_LT(worstMean, 0.01);
      }
    }
  }
  // On a plane: corners that cancel (a singular face) and non-finite corners give zero.
  const gs::TriangleMesh plane = gs_test::BuildMesh(gs::MakePlanarGrid(2, 2, 1.0, 1.0));
  std::vector<gs::Vec3> atVertex(plane.NumberOfVertices(), gs::Vec3{ 0, 0, 0 });
  const auto& c = plane.Face(0);
  const gs::Vec3 n = plane.FaceNormal(0);
  const gs::Vec3 t = gs::Unit(plane.Position(c[1]) - plane.Position(c[0]));
  atVertex[c[0]] = t;
  atVertex[c[1]] = t * -1.0;
  atVertex[c[2]] = gs::Vec3{ std::nan(""), 0, 0 };
  EXPECT_EQ(gs::Norm(FaceDirections(plane, atVertex, 1)[0]), 0.0);
  EXPECT_NEAR(gs::Norm(FaceDirections(plane, atVertex, 2)[0]), 1.0, 1e-12);
  atVertex[c[1]] = gs::RotateTangent(t, n, 0.5 * pi);
  EXPECT_EQ(gs::Norm(FaceDirections(plane, atVertex, 2)[0]), 0.0);
  EXPECT_NEAR(gs::Norm(FaceDirections(plane, atVertex, 4)[0]), 1.0, 1e-12);
  EXPECT_NEAR(gs::Dot(FaceDirections(plane, atVertex, 4)[0], t), 1.0, 1e-12);
  // Not one vector per vertex, or a symmetry other than 1, 2 and 4: an error.
  atVertex.pop_back();
  EXPECT_TRUE(gs_test::FailedWith(gs::FaceDirectionsFromVertices(plane, atVertex, 4),
    "one vector per vertex: 8 given for 9 vertices"));
  atVertex.emplace_back(0.0, 0.0, 0.0);
  EXPECT_TRUE(gs_test::FailedWith(
    gs::FaceDirectionsFromVertices(plane, atVertex, 3), "Symmetry must be 1 (vector field)"));
}
