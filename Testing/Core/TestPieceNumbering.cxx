// Pieces without global ids (PieceNumbering.h), on threads standing for the processes: numbered
// as the gathered surface numbers them, their graph and its refined distances equal, to the bit,
// those of the serial graph of the gathered surface (every piece's points in rank order,
// coincident ones welded), and the exact distances equal its exact solver's; serial point ids
// name the same points on the pieces. Pieces with ids: serial numbers name the ids by rank.
#include "ExactGeodesic.h"
#include "ExactPieces.h"
#include "GraphPieces.h"
#include "MeshGenerators.h"
#include "PieceNumbering.h"
#include "SVGGeodesicSolver.h"
#include "SaddleVertexGraph.h"
#include "TestMeshes.h"
#include "ThreadPieces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

using namespace gs;

namespace
{
// The pieces as files without ids hold them: each its faces' points, in its own order (reversed
// here, so that the gathered order is not the whole mesh's), a point repeated within a piece on
// rank 1, and a point no triangle uses.
PieceTriangles PieceWithoutIds(const TriangleMesh& mesh, const std::vector<int>& part, int rank)
{
  PieceTriangles piece = gs_test::PieceOf(mesh, part, rank);
  const int n = static_cast<int>(piece.Points.size());
  std::reverse(piece.Points.begin(), piece.Points.end());
  for (auto& t : piece.Triangles)
  {
    for (int& k : t)
    {
      k = n - 1 - k;
    }
  }
  piece.Points.push_back(Vec3(100.0 + rank, 0.0, 0.0)); // used by no triangle
  if (rank == 1 && !piece.Triangles.empty())
  {
    // The first triangle's first corner, listed again and used by the last triangle.
    piece.Points.push_back(piece.Points[static_cast<std::size_t>(piece.Triangles[0][0])]);
    for (int& k : piece.Triangles.back())
    {
      if (k == piece.Triangles[0][0])
      {
        k = static_cast<int>(piece.Points.size()) - 1;
      }
    }
  }
  piece.PointIds.clear();
  piece.TriangleIds.clear();
  return piece;
}

// The gathered surface: the pieces' points one after another, triangles likewise.
TriangleSoup Gathered(const std::vector<PieceTriangles>& pieces)
{
  TriangleSoup soup;
  for (const PieceTriangles& p : pieces)
  {
    const long long offset = static_cast<long long>(soup.Points.size());
    soup.Points.insert(soup.Points.end(), p.Points.begin(), p.Points.end());
    for (const auto& t : p.Triangles)
    {
      soup.Triangles.push_back({ offset + t[0], offset + t[1], offset + t[2] });
    }
  }
  return soup;
}

void ExpectAsGathered(const TriangleMesh& mesh, const std::vector<int>& part, int processes,
  std::int64_t sourceIndex)
{
  std::vector<PieceTriangles> inputs;
  for (int r = 0; r < processes; ++r)
  {
    inputs.push_back(PieceWithoutIds(mesh, part, r));
  }
  const TriangleSoup soup = Gathered(inputs);
  Result<MeshBuild> built = TriangleMeshBuilder::Build(soup.Points, soup.Triangles);
  ASSERT_TRUE(built.Ok()) << built.Message();
  const TriangleMesh& whole = built->Mesh;
  const int sourceVertex =
    built->PointToVertex[static_cast<std::size_t>(sourceIndex)];
  ASSERT_GE(sourceVertex, 0);
  SaddleVertexGraphOptions options;
  options.K = 30;
  options.NumberOfThreads = 1;
  SaddleVertexGraph graph;
  ASSERT_TRUE(graph.Build(whole, options, nullptr).Ok());
  SVGGeodesicSolver refined(whole, graph);
  ASSERT_TRUE(refined.Solve({ SurfacePoint::AtVertex(sourceVertex) }, SVGSolveOptions()).Ok());
  ExactGeodesicSolver exact(whole);
  ASSERT_TRUE(exact.Solve(sourceVertex).Ok());
  std::map<std::tuple<double, double, double>, std::pair<double, double>> expected;
  for (int v = 0; v < whole.NumberOfVertices(); ++v)
  {
    const Vec3& p = whole.Position(v);
    expected[{ p.x, p.y, p.z }] = { refined.Distance(v), exact.Distance(v) };
  }

  std::mutex lock;
  std::size_t compared = 0;
  double worstExact = 0.0;
  bool ok = true;
  gs_test::ThreadHub hub(processes);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    PieceTriangles own = inputs[static_cast<std::size_t>(rank)];
    GatheredNumbering numbering;
    const Status numbered = NumberAsGathered(own.Points, own.Triangles, comm, numbering);
    const std::int64_t source =
      GatheredPointId(numbering.PointIds, numbering.FirstPoint, sourceIndex, comm);
    EXPECT_GE(source, 0);
    // The piece keeps the points its triangles use, with their ids.
    PieceTriangles withIds;
    std::vector<int> at(own.Points.size(), -1);
    for (const auto& t : own.Triangles)
    {
      std::array<int, 3> u{};
      for (int k = 0; k < 3; ++k)
      {
        int& p = at[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
        if (p < 0)
        {
          p = static_cast<int>(withIds.Points.size());
          const std::size_t q = static_cast<std::size_t>(t[static_cast<std::size_t>(k)]);
          withIds.Points.push_back(own.Points[q]);
          withIds.PointIds.push_back(numbering.PointIds[q]);
        }
        u[static_cast<std::size_t>(k)] = p;
      }
      withIds.Triangles.push_back(u);
    }
    withIds.TriangleIds = numbering.TriangleIds;
    SurfacePiece piece;
    PieceGraph pieceGraph;
    Status s = numbered.Ok() ? piece.Build(withIds, 0, comm) : numbered;
    SaddleVertexGraphOptions o = options;
    s = s.Ok() ? pieceGraph.Build(piece, o, comm) : s;
    PieceDistanceSolver distances(pieceGraph);
    s = s.Ok() ? distances.Solve({ { source, 0.0 } }, 0.0, comm, true) : s;
    ExactPiecesResult exactResult;
    s = s.Ok() ? ComputeExactOnPieces(piece, { source }, 0.0, comm, exactResult) : s;
    std::vector<int> wanted;
    for (int v = 0; s.Ok() && v < piece.Mesh().NumberOfVertices(); ++v)
    {
      if (piece.IsOwned(v))
      {
        wanted.push_back(v);
      }
    }
    const std::vector<double> graphDistances =
      s.Ok() ? distances.Fetch(piece, wanted, comm) : std::vector<double>();
    std::lock_guard<std::mutex> guard(lock);
    if (!s.Ok())
    {
      ok = false;
      ADD_FAILURE() << "rank " << rank << ": " << s.Message();
      return;
    }
    for (std::size_t i = 0; i < wanted.size(); ++i)
    {
      const Vec3& p = piece.Mesh().Position(wanted[i]);
      const auto it = expected.find({ p.x, p.y, p.z });
      ASSERT_NE(it, expected.end());
      EXPECT_EQ(graphDistances[i], it->second.first) << "vertex at " << p.x << " " << p.y;
      worstExact = std::max(worstExact,
        std::abs(exactResult.Distance[static_cast<std::size_t>(wanted[i])] - it->second.second));
      ++compared;
    }
  });
  EXPECT_TRUE(ok);
  EXPECT_EQ(compared, static_cast<std::size_t>(whole.NumberOfVertices()));
  EXPECT_LE(worstExact, 1e-12);
}
} // namespace

TEST(PieceNumbering, PiecesWithoutIdsAsTheGatheredSurface)
{
  const TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(2, 5, 0.1));
  ExpectAsGathered(sphere, gs_test::PartitionFaces(sphere, 3, Vec3(1, 0.3, 0.1)), 3, 10);
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(16, 12, 1.6, 1.2));
  ExpectAsGathered(plane, gs_test::PartitionFaces(plane, 2, Vec3(1, 1, 0), 3), 2, 150);
}

TEST(PieceNumbering, IdsFollowTheGatheredList)
{
  // Rank 0: one triangle and a point no triangle uses. Rank 1: its (0, 1, 0) and (1, 0, 0) are
  // rank 0's; it lists (2, 0, 0) twice, and its triangles use the second copy first: both copies
  // weld to that one, as TriangleMesh welds the gathered list.
  const std::vector<std::vector<Vec3>> points = {
    { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(5, 5, 5) },
    { Vec3(2, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0), Vec3(1, 0, 0), Vec3(2, 0, 0) }
  };
  const std::vector<std::vector<std::array<int, 3>>> triangles = { { { 0, 1, 2 } },
    { { 2, 3, 1 }, { 3, 4, 1 }, { 0, 1, 3 } } };
  std::vector<GatheredNumbering> got(2);
  std::vector<std::int64_t> unused(2), outside(2), shared(2), copy(2);
  gs_test::ThreadHub hub(2);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    const std::size_t r = static_cast<std::size_t>(rank);
    EXPECT_TRUE(NumberAsGathered(points[r], triangles[r], comm, got[r]).Ok());
    unused[r] = GatheredPointId(got[r].PointIds, got[r].FirstPoint, 3, comm);
    outside[r] = GatheredPointId(got[r].PointIds, got[r].FirstPoint, 9, comm);
    shared[r] = GatheredPointId(got[r].PointIds, got[r].FirstPoint, 6, comm);
    copy[r] = GatheredPointId(got[r].PointIds, got[r].FirstPoint, 4, comm);
  });
  EXPECT_EQ(got[0].PointIds, (std::vector<std::int64_t>{ 0, 1, 2, -1 }));
  EXPECT_EQ(got[1].PointIds, (std::vector<std::int64_t>{ 8, 5, 2, 1, 8 }));
  EXPECT_EQ(got[1].TriangleIds, (std::vector<std::int64_t>{ 1, 2, 3 }));
  EXPECT_EQ(got[1].FirstPoint, 4);
  EXPECT_EQ(got[0].TotalPoints, 9);
  for (int r = 0; r < 2; ++r)
  {
    EXPECT_EQ(unused[static_cast<std::size_t>(r)], -1);
    EXPECT_EQ(outside[static_cast<std::size_t>(r)], -1);
    EXPECT_EQ(shared[static_cast<std::size_t>(r)], 2);
    EXPECT_EQ(copy[static_cast<std::size_t>(r)], 8);
  }
}

TEST(PieceNumbering, SerialNumbersOfGivenIds)
{
  // Ids 10 + 3 v (not 0 to N - 1): serial number i names the id of rank i; dense ids name
  // themselves; numbers beyond the vertices name none.
  const TriangleMesh mesh = gs_test::BuildMesh(MakePlanarGrid(8, 6, 0.8, 0.6));
  const std::vector<int> part = gs_test::PartitionFaces(mesh, 3, Vec3(1, 0.3, 0), 2);
  const std::int64_t n = mesh.NumberOfVertices();
  std::vector<std::vector<std::int64_t>> sparse(3), dense(3);
  gs_test::ThreadHub hub(3);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    PieceTriangles own = gs_test::PieceOf(mesh, part, rank);
    SurfacePiece plain, spread;
    EXPECT_TRUE(plain.Build(own, 0, comm).Ok());
    for (std::int64_t& id : own.PointIds)
    {
      id = 10 + 3 * id;
    }
    EXPECT_TRUE(spread.Build(own, 0, comm).Ok());
    for (const std::int64_t i : { std::int64_t(0), std::int64_t(7), n - 1, n, std::int64_t(-1) })
    {
      sparse[static_cast<std::size_t>(rank)].push_back(spread.IdOfRank(i, comm));
      dense[static_cast<std::size_t>(rank)].push_back(plain.IdOfRank(i, comm));
    }
  });
  for (int r = 0; r < 3; ++r)
  {
    EXPECT_EQ(sparse[static_cast<std::size_t>(r)],
      (std::vector<std::int64_t>{ 10, 31, 10 + 3 * (n - 1), -1, -1 }));
    EXPECT_EQ(dense[static_cast<std::size_t>(r)],
      (std::vector<std::int64_t>{ 0, 7, n - 1, -1, -1 }));
  }
}
