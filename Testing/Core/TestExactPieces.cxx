// Exact geodesic distance on a surface partitioned over processes (ExactPieces.h), on threads
// standing for the processes: every vertex of every process's own faces gets the serial exact
// solver's distance (within 1e-9 of the largest distance: the order of the windows differs, so
// ties round differently), for several process counts and partitions (slabs, pieces with holes
// and islands, pieces whose faces are oriented against their neighbours'), on a closed curved
// mesh (saddles everywhere), a plane with a boundary, an L-shape (a reflex boundary corner) and a
// torus; sources several and far apart, vertices and surface points (inside a face, on an edge
// between two processes' faces), maximum distances; failures and aborts on every process.
#include "ExactGeodesic.h"
#include "ExactInParts.h"
#include "ExactPieces.h"
#include "MeshGenerators.h"
#include "TestMeshes.h"
#include "ThreadPieces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>

using namespace gs;

namespace
{
struct ExactRun : gs_test::PiecesRun
{
  std::int64_t Windows = 0, Sent = 0;
  int Rounds = 0;
};

// `flipped`: ranks whose own triangles are given the other way round; `points`: face points of
// the whole mesh, each added by the process whose face holds it.
ExactRun RunExact(const TriangleMesh& mesh, const std::vector<int>& part, int processes,
  const std::vector<std::int64_t>& sources, double maxDistance,
  const std::vector<int>& flipped = {}, int abortingRank = -1,
  const std::vector<SurfacePoint>& points = {})
{
  ExactRun run;
  std::mutex lock;
  static_cast<gs_test::PiecesRun&>(run) = gs_test::RunOnPieces(mesh, part, processes, flipped,
    points,
    [&](int rank, SurfacePiece& piece, PieceCommunicator& comm,
      const std::vector<SurfacePoint>& mine, std::vector<double>& perVertex) {
      ExactPiecesResult result;
      const Status status = ComputeExactOnPieces(piece, sources, maxDistance, comm, result,
        [&](double) { return rank != abortingRank; }, mine);
      perVertex = result.Distance;
      std::lock_guard<std::mutex> guard(lock);
      run.Windows += result.WindowsPropagated;
      run.Sent += result.WindowsSent;
      run.Rounds = result.Rounds;
      return status;
    });
  return run;
}

void ExpectExactAsSerial(const TriangleMesh& mesh, const std::vector<int>& part, int processes,
  const std::vector<std::int64_t>& sources, double maxDistance = 0.0,
  const std::vector<int>& flipped = {}, const std::vector<SurfacePoint>& facePoints = {})
{
  ExactGeodesicSolver serial(mesh);
  std::vector<SurfacePoint> points = facePoints;
  for (const std::int64_t s : sources)
  {
    points.push_back(SurfacePoint::AtVertex(static_cast<int>(s)));
  }
  ExactGeodesicOptions options;
  options.MaximumDistance = maxDistance;
  ASSERT_TRUE(serial.Solve(points, options).Ok());
  double largest = 0.0;
  for (int v = 0; v < mesh.NumberOfVertices(); ++v)
  {
    if (std::isfinite(serial.Distance(v)))
    {
      largest = std::max(largest, serial.Distance(v));
    }
  }
  ASSERT_GT(largest, 0.0);

  const ExactRun run =
    RunExact(mesh, part, processes, sources, maxDistance, flipped, -1, facePoints);
  double worst = 0.0;
  std::size_t checked = 0, reached = 0;
  for (int rank = 0; rank < processes; ++rank)
  {
    ASSERT_TRUE(run.Statuses[static_cast<std::size_t>(rank)].Ok())
      << run.Statuses[static_cast<std::size_t>(rank)].Message();
    for (const auto& [id, d] : run.Seen[static_cast<std::size_t>(rank)])
    {
      const double expected = serial.Distance(static_cast<int>(id));
      ++checked;
      if (!std::isfinite(expected))
      {
        EXPECT_FALSE(std::isfinite(d)) << "vertex " << id << " on rank " << rank;
        continue;
      }
      ++reached;
      ASSERT_TRUE(std::isfinite(d)) << "vertex " << id << " on rank " << rank;
      worst = std::max(worst, std::abs(d - expected) / largest);
    }
  }
  EXPECT_LE(worst, 1e-9);
  EXPECT_GT(reached, 0u);
  std::size_t faces = 0;
  for (const int p : part)
  {
    faces += p < processes ? 1 : 0;
  }
  EXPECT_EQ(checked, 3 * faces); // every own face's corners, on every process
  std::printf("P = %d: largest difference %.2e of the largest distance; %lld windows propagated "
              "(serial %lld), %lld sent, %d rounds\n",
    processes, worst, static_cast<long long>(run.Windows),
    static_cast<long long>(serial.Statistics().WindowsPropagated),
    static_cast<long long>(run.Sent), run.Rounds);
}
} // namespace

TEST(ExactPieces, CurvedClosedMesh)
{
  const TriangleMesh mesh = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  for (const int p : { 2, 3 })
  {
    ExpectExactAsSerial(mesh, gs_test::PartitionFaces(mesh, p, Vec3(1, 0.3, 0.1)), p, { 0 });
  }
  // Pieces with holes and islands, two sources.
  ExpectExactAsSerial(
    mesh, gs_test::PartitionFaces(mesh, 4, Vec3(0.2, 1, 0.5), 5), 4, { 17, 600 });
  // More processes than pieces: the fourth holds no face.
  ExpectExactAsSerial(mesh, gs_test::PartitionFaces(mesh, 3, Vec3(1, 0.3, 0.1)), 4, { 5 });
}

TEST(ExactPieces, PlaneAndReflexCornerWithBoundaries)
{
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(24, 20, 2.4, 2.0));
  ExpectExactAsSerial(plane, gs_test::PartitionFaces(plane, 3, Vec3(1, 0, 0)), 3, { 5 });
  const TriangleMesh lshape = gs_test::BuildMesh(MakeLShape(12));
  ExpectExactAsSerial(lshape, gs_test::PartitionFaces(lshape, 2, Vec3(1, 1, 0), 3), 2, { 0 });
  ExpectExactAsSerial(lshape, gs_test::PartitionFaces(lshape, 3, Vec3(0, 1, 0)), 3, { 40 }, 1.2);
}

TEST(ExactPieces, TorusWithPiecesOrientedAgainstTheirNeighbours)
{
  const TriangleMesh mesh = gs_test::BuildMesh(MakeTorus(1.0, 0.35, 40, 16));
  ExpectExactAsSerial(mesh, gs_test::PartitionFaces(mesh, 3, Vec3(1, 0.2, 0)), 3, { 3 });
  ExpectExactAsSerial(
    mesh, gs_test::PartitionFaces(mesh, 3, Vec3(0, 1, 0.3), 4), 3, { 100, 500 });
  // Rank 1 gives its triangles the other way round: its own faces outnumber its band, so its
  // piece's mesh keeps their orientation, against rank 0's (windows and arrival directions
  // cross mirrored).
  const TriangleMesh fine = gs_test::BuildMesh(MakeTorus(1.0, 0.35, 80, 24));
  ExpectExactAsSerial(
    fine, gs_test::PartitionFaces(fine, 2, Vec3(1, 0, 0)), 2, { 7, 1500 }, 0.0, { 1 });
}

TEST(ExactPieces, SurfacePointSources)
{
  // A point inside a face, a point on an edge (the face across holds it too) and a vertex, on
  // faces of different processes.
  const TriangleMesh mesh = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  const std::vector<int> part = gs_test::PartitionFaces(mesh, 3, Vec3(1, 0.3, 0.1));
  std::vector<SurfacePoint> points = { SurfacePoint::InFace(10, 0.2, 0.3, 0.5) };
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    if (part[static_cast<std::size_t>(f)] == 2)
    {
      points.push_back(SurfacePoint::InFace(f, 0.0, 0.6, 0.4));
      break;
    }
  }
  ExpectExactAsSerial(mesh, part, 3, { 300 }, 0.0, {}, points);
  ExpectExactAsSerial(mesh, part, 3, {}, 0.0, {}, points);

  // A process holding one triangle inside a plane of the other's, the source point in it: its
  // windows and corners all belong to the other process, which has nothing queued yet.
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(12, 12, 1.2, 1.2));
  std::vector<int> island(static_cast<std::size_t>(plane.NumberOfFaces()), 0);
  const int middle = plane.NumberOfFaces() / 2 + 12;
  island[static_cast<std::size_t>(middle)] = 1;
  ExpectExactAsSerial(
    plane, island, 2, {}, 0.0, {}, { SurfacePoint::InFace(middle, 0.3, 0.3, 0.4) });
}

TEST(ExactPieces, FailuresAndAbortsOnEveryProcess)
{
  const TriangleMesh mesh = gs_test::BuildMesh(MakePlanarGrid(6, 6, 1.0, 1.0));
  const std::vector<int> part = gs_test::PartitionFaces(mesh, 2, Vec3(1, 0, 0));
  for (const Status& s : RunExact(mesh, part, 2, { 1000 }, 0.0).Statuses)
  {
    EXPECT_FALSE(s.Ok());
    EXPECT_NE(s.Message().find("not a point"), std::string::npos) << s.Message();
  }
  for (const Status& s : RunExact(mesh, part, 2, {}, 0.0).Statuses)
  {
    EXPECT_NE(s.Message().find("no source"), std::string::npos) << s.Message();
  }
  // A point on a face of another process.
  std::vector<Status> statuses(2);
  gs_test::ThreadHub hub(2);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    SurfacePiece piece;
    Status s = piece.Build(gs_test::PieceOf(mesh, part, rank), 1, comm);
    int other = 0;
    while (other < piece.Mesh().NumberOfFaces() && piece.IsOwnFace(other))
    {
      ++other;
    }
    ExactPiecesResult result;
    statuses[static_cast<std::size_t>(rank)] = s.Ok()
      ? ComputeExactOnPieces(piece, {}, 0.0, comm, result, nullptr,
          { SurfacePoint::InFace(other, 0.2, 0.3, 0.5) })
      : s;
  });
  for (const Status& s : statuses)
  {
    EXPECT_NE(s.Message().find("another process"), std::string::npos) << s.Message();
  }
  for (const Status& s : RunExact(mesh, part, 2, { 0 }, 0.0, {}, 1).Statuses)
  {
    EXPECT_TRUE(s.IsAborted()) << s.Message();
  }
}

// The exact solver on threads (ExactSolverInParts): the same distances as the serial solver
// within 1e-12 of the largest (and from a single source the same departure angles within 1e-9,
// modulo a full turn), from vertices and from face points on several parts, on a closed
// curved mesh, on a plane with a boundary and behind the L-shape's reflex corner (paths bent
// across the cuts between the parts), with a maximum distance; the same to the bit solved twice
// (the pieces made once, reused); errors and an abort leave every vertex unreached and the next
// solve whole.
TEST(ExactPieces, SolverInPartsEqualsTheSerialSolver)
{
  auto compare = [](const TriangleMesh& mesh, int parts, const std::vector<SurfacePoint>& points,
                   double maxDistance) {
    ExactGeodesicSolver serial(mesh);
    ExactGeodesicOptions options;
    options.MaximumDistance = maxDistance;
    ASSERT_TRUE(serial.Solve(points, options).Ok());
    ExactSolverInParts split(mesh, parts);
    ASSERT_TRUE(split.Solve(points, maxDistance).Ok());
    const std::vector<double> first = split.Distances();
    ASSERT_TRUE(split.Solve(points, maxDistance).Ok());
    EXPECT_EQ(first, split.Distances()); // the same pieces again, the same bits
    double largest = 0.0, worst = 0.0;
    int reached = 0;
    for (int v = 0; v < mesh.NumberOfVertices(); ++v)
    {
      const double d = serial.Distance(v);
      ASSERT_EQ(std::isfinite(d), std::isfinite(split.Distance(v))) << "vertex " << v;
      if (std::isfinite(d))
      {
        largest = std::max(largest, d);
        worst = std::max(worst, std::abs(split.Distance(v) - d));
        ++reached;
      }
    }
    EXPECT_LE(worst, 1e-12 * largest) << parts << " parts";
    // From a single source, the departure angles too (modulo a full turn about the source).
    if (points.size() == 1)
    {
      const double turn =
        points[0].IsVertex() && !mesh.IsBoundaryVertex(points[0].Vertex) ? mesh.TotalAngle(points[0].Vertex) : 2.0 * M_PI;
      double worstAngle = 0.0;
      int angles = 0;
      for (int v = 0; v < mesh.NumberOfVertices(); ++v)
      {
        const double a = serial.DepartureAngle(v), b = split.DepartureAngle(v);
        ASSERT_EQ(std::isfinite(a), std::isfinite(b)) << "vertex " << v;
        if (std::isfinite(a))
        {
          const double d = std::abs(std::remainder(b - a, turn));
          worstAngle = std::max(worstAngle, d);
          ++angles;
        }
      }
      EXPECT_LE(worstAngle, 1e-9) << parts << " parts";
      EXPECT_GT(angles, 0);
    }
    else
    {
      EXPECT_TRUE(std::isnan(split.DepartureAngle(0)));
    }
    EXPECT_GE(reached, maxDistance > 0.0 ? mesh.NumberOfVertices() / 20 : mesh.NumberOfVertices());
    EXPECT_GT(split.Rounds(), 1);
  };
  using P = SurfacePoint;
  const TriangleMesh bumpy = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  compare(bumpy, 2, { P::AtVertex(0) }, 0.0);
  compare(bumpy, 3, { P::AtVertex(17), P::AtVertex(600) }, 0.0);
  compare(bumpy, 4, { P::AtVertex(0) }, 0.0);
  // Face points on several parts (a point inside a face, one on an edge), with a vertex.
  std::vector<SurfacePoint> points = { P::InFace(10, 0.2, 0.3, 0.5), P::InFace(900, 0.5, 0.5, 0.0),
    P::InFace(bumpy.NumberOfFaces() - 3, 0.6, 0.1, 0.3), P::AtVertex(300) };
  compare(bumpy, 4, points, 0.0);
  compare(bumpy, 4, { points[0] }, 0.0);
  compare(bumpy, 3, { points[2] }, 0.0);
  compare(bumpy, 4, { P::InFace(700, 0.0, 1.0, 0.0) }, 0.0); // a face point at a corner
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(24, 20, 2.4, 2.0));
  compare(plane, 2, { P::AtVertex(5) }, 0.0);
  compare(plane, 4, { P::AtVertex(25 * 10 + 12) }, 0.0);
  const TriangleMesh lshape = gs_test::BuildMesh(MakeLShape(12));
  compare(lshape, 2, { P::AtVertex(0) }, 0.0);
  compare(lshape, 2, { P::AtVertex(40), P::InFace(70, 0.3, 0.3, 0.4) }, 1.2);

  ExactSolverInParts split(bumpy, 2);
  EXPECT_TRUE(gs_test::FailedWith(split.Solve(std::vector<int>()), "no source"));
  EXPECT_TRUE(gs_test::FailedWith(split.Solve(std::vector<int>{ bumpy.NumberOfVertices() }), "source"));
  EXPECT_TRUE(gs_test::FailedWith(
    split.Solve({ SurfacePoint::InFace(bumpy.NumberOfFaces(), 1.0, 0.0, 0.0) }), "source"));
  int calls = 0;
  EXPECT_TRUE(
    split.Solve(std::vector<int>{ 0 }, 0.0, [&](double) { return ++calls < 3; }).IsAborted());
  for (int v = 0; v < bumpy.NumberOfVertices(); ++v)
  {
    ASSERT_FALSE(std::isfinite(split.Distance(v)));
  }
  ASSERT_TRUE(split.Solve(std::vector<int>{ 0 }).Ok());
  EXPECT_EQ(split.Distance(0), 0.0);
  EXPECT_TRUE(std::isfinite(split.Distance(bumpy.NumberOfVertices() - 1)));
}

// SurfacePiece::LocalPoint names the same point of the surface in the piece's mesh, whose faces
// may list their corners in another order than the whole mesh's (here each rotated by one).
TEST(ExactPieces, LocalPointIsTheSamePointOfThePiece)
{
  const TriangleMesh mesh = gs_test::BuildMesh(gs_test::BumpySoup(2, 5, 0.1));
  const std::vector<int> part = gs_test::PartitionFaces(mesh, 2, Vec3(1, 0.3, 0.1));
  gs_test::ThreadHub hub(2);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    PieceTriangles own = gs_test::PieceOf(mesh, part, rank);
    for (auto& t : own.Triangles)
    {
      t = { { t[1], t[2], t[0] } };
    }
    SurfacePiece piece;
    ASSERT_TRUE(piece.Build(own, 1, comm).Ok());
    int checked = 0;
    for (int f = 0; f < mesh.NumberOfFaces(); f += 7)
    {
      if (part[static_cast<std::size_t>(f)] != rank)
      {
        continue;
      }
      const SurfacePoint p = SurfacePoint::InFace(f, 0.1, 0.3, 0.6);
      const std::array<int, 3>& c = mesh.Face(f);
      const SurfacePoint q = piece.LocalPoint(f, { { c[0], c[1], c[2] } }, p.Bary);
      ASSERT_GE(q.Face, 0);
      EXPECT_LT(Norm(piece.Mesh().Position(q) - mesh.Position(p)), 1e-12) << "face " << f;
      ++checked;
    }
    EXPECT_GT(checked, 10);
    EXPECT_LT(piece.LocalPoint(-5, { { 0, 1, 2 } }, { { 1.0, 0.0, 0.0 } }).Face, 0);
  });
}

// The in-process communicator: reductions combine every rank's value, exchanges deliver each
// rank's buffers; a rank that throws (out of memory) ends the run with its exception instead of
// leaving the others waiting in a collective, and the hub's other ranks stop at their next one.
TEST(ExactPieces, ThreadHubCollectivesAndAFailingRank)
{
  gs_test::ThreadHub hub(3);
  std::vector<double> sums(3), mins(3);
  std::vector<std::string> got(3);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    sums[static_cast<std::size_t>(rank)] = static_cast<double>(comm.Sum(rank + 1));
    mins[static_cast<std::size_t>(rank)] = comm.Min(10.0 - rank);
    std::vector<ByteBuffer> out(3), in;
    for (int q = 0; q < 3; ++q)
    {
      ByteWriter(out[static_cast<std::size_t>(q)]).Put(static_cast<char>('a' + 3 * rank + q));
    }
    comm.Exchange(out, in);
    for (int q = 0; q < 3; ++q)
    {
      got[static_cast<std::size_t>(rank)] += static_cast<char>(in[static_cast<std::size_t>(q)][0]);
    }
  });
  EXPECT_EQ(sums, std::vector<double>(3, 6.0));
  EXPECT_EQ(mins, std::vector<double>(3, 8.0));
  EXPECT_EQ(got[0], "adg");
  EXPECT_EQ(got[2], "cfi");
  std::vector<int> rounds(3, 0);
  EXPECT_THROW(hub.Run([&](int rank, PieceCommunicator& comm) {
    for (int r = 0; r < 100; ++r)
    {
      if (rank == 1 && r == 3)
      {
        throw std::bad_alloc();
      }
      comm.Max(static_cast<double>(r));
      ++rounds[static_cast<std::size_t>(rank)];
    }
  }),
    std::bad_alloc);
  EXPECT_LE(rounds[0], 4);
  EXPECT_EQ(rounds[1], 3);
  // The hub runs again whole after a failed run.
  std::vector<double> again(3);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    again[static_cast<std::size_t>(rank)] = comm.Max(static_cast<double>(rank));
  });
  EXPECT_EQ(again, std::vector<double>(3, 2.0));
}
