// Virtual source propagation on a surface partitioned over processes (VirtualSourcePieces.h), on
// threads standing for the processes, against the serial VirtualSourceSolver and the exact
// solver: every corner of every process's own faces reached as serially; on flat meshes (where
// the method is exact) the serial distances to rounding; on curved ones, where the order of
// processing picks between sources of nearly equal key, distances as accurate against the exact
// solver as the serial solve's (mean relative error within 1.2x of it, largest error within
// 1.5x) and within 2% of the largest distance of the serial ones; the same bits run twice. Partitions: slabs, pieces with
// holes and islands, a rank whose faces are oriented against its neighbours', more processes
// than pieces; sources several, vertices and surface points, maximum distances; failures and
// aborts on every process.
#include "ExactGeodesic.h"
#include "MeshGenerators.h"
#include "TestMeshes.h"
#include "TestStatus.h"
#include "ThreadPieces.h"
#include "VirtualSourceGeodesic.h"
#include "VirtualSourcePieces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <mutex>

using namespace gs;

namespace
{
struct PiecesVersusSerial
{
  double Largest = 0.0;    // largest serial distance
  double Worst = 0.0;      // largest difference from the serial distance, over Largest
  double SerialError = 0.0, PiecesError = 0.0; // mean relative errors against the exact solver
  double SerialWorst = 0.0, PiecesWorst = 0.0; // largest errors against it, over Largest
  std::size_t Checked = 0, Differing = 0;
  gs_test::PiecesRun Run;
};

gs_test::PiecesRun RunVirtual(const TriangleMesh& mesh, const std::vector<int>& part,
  int processes, const std::vector<std::int64_t>& sources, double maxDistance = 0.0,
  const std::vector<int>& flipped = {}, const std::vector<SurfacePoint>& points = {},
  int abortingRank = -1)
{
  return gs_test::RunOnPieces(mesh, part, processes, flipped, points,
    [&](int rank, SurfacePiece& piece, PieceCommunicator& comm,
      const std::vector<SurfacePoint>& mine, std::vector<double>& perVertex) {
      VirtualSourcePiecesResult result;
      const Status status = ComputeVirtualSourcesOnPieces(piece, sources, maxDistance, comm,
        result, [&](double) { return rank != abortingRank; }, mine);
      perVertex = result.Distance;
      return status;
    });
}

PiecesVersusSerial Compare(const TriangleMesh& mesh, const std::vector<int>& part, int processes,
  const std::vector<std::int64_t>& sources, double maxDistance = 0.0,
  const std::vector<int>& flipped = {}, const std::vector<SurfacePoint>& facePoints = {})
{
  PiecesVersusSerial c;
  std::vector<SurfacePoint> points = facePoints;
  for (const std::int64_t s : sources)
  {
    points.push_back(SurfacePoint::AtVertex(static_cast<int>(s)));
  }
  VirtualSourceSolver serial(mesh);
  VirtualSourceOptions options;
  options.MaximumDistance = maxDistance;
  EXPECT_TRUE(serial.Solve(points, options).Ok());
  ExactGeodesicSolver exact(mesh);
  EXPECT_TRUE(exact.Solve(points).Ok());
  for (int v = 0; v < mesh.NumberOfVertices(); ++v)
  {
    if (std::isfinite(serial.Distance(v)))
    {
      c.Largest = std::max(c.Largest, serial.Distance(v));
    }
  }
  EXPECT_GT(c.Largest, 0.0);
  c.Run = RunVirtual(mesh, part, processes, sources, maxDistance, flipped, facePoints);
  std::size_t measured = 0, faces = 0;
  for (int rank = 0; rank < processes; ++rank)
  {
    EXPECT_TRUE(c.Run.Statuses[static_cast<std::size_t>(rank)].Ok())
      << c.Run.Statuses[static_cast<std::size_t>(rank)].Message();
    for (const auto& [id, d] : c.Run.Seen[static_cast<std::size_t>(rank)])
    {
      const double expected = serial.Distance(static_cast<int>(id));
      ++c.Checked;
      EXPECT_EQ(std::isfinite(expected), std::isfinite(d)) << "vertex " << id << " on rank " << rank;
      if (!std::isfinite(expected) || !std::isfinite(d))
      {
        continue;
      }
      c.Worst = std::max(c.Worst, std::abs(d - expected) / c.Largest);
      c.Differing += d != expected ? 1 : 0;
      const double e = exact.Distance(static_cast<int>(id));
      if (e > 0.0)
      {
        c.SerialError += std::abs(expected - e) / e;
        c.PiecesError += std::abs(d - e) / e;
        c.SerialWorst = std::max(c.SerialWorst, std::abs(expected - e) / c.Largest);
        c.PiecesWorst = std::max(c.PiecesWorst, std::abs(d - e) / c.Largest);
        ++measured;
      }
    }
  }
  for (const int p : part)
  {
    faces += p < processes ? 1 : 0;
  }
  EXPECT_EQ(c.Checked, 3 * faces); // every own face's corners, on every process
  EXPECT_GT(measured, 0u);
  c.SerialError /= static_cast<double>(std::max<std::size_t>(measured, 1));
  c.PiecesError /= static_cast<double>(std::max<std::size_t>(measured, 1));
  std::printf("P = %d: %zu of %zu corners differ from the serial solve, by %.2e of the largest "
              "distance at most; against exact: mean relative error %.3e (serial %.3e), largest %.2e "
              "(serial %.2e)\n",
    processes, c.Differing, c.Checked, c.Worst, c.PiecesError, c.SerialError, c.PiecesWorst,
    c.SerialWorst);
  return c;
}

void ExpectAsAccurateAsSerial(const PiecesVersusSerial& c)
{
  EXPECT_LE(c.PiecesError, 1.2 * c.SerialError + 1e-12);
  EXPECT_LE(c.PiecesWorst, 1.5 * c.SerialWorst + 1e-12);
  EXPECT_LE(c.Worst, 2e-2);
}
} // namespace

TEST(VirtualSourcePieces, FlatMeshesGiveTheSerialDistances)
{
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(24, 20, 2.4, 2.0));
  EXPECT_LE(Compare(plane, gs_test::PartitionFaces(plane, 3, Vec3(1, 0, 0)), 3, { 5, 400 }).Worst,
    1e-12);
  // Behind the L-shape's reflex corner (a bend), pieces with holes; a maximum distance.
  const TriangleMesh lshape = gs_test::BuildMesh(MakeLShape(12));
  EXPECT_LE(Compare(lshape, gs_test::PartitionFaces(lshape, 2, Vec3(1, 1, 0), 3), 2, { 0 }).Worst,
    1e-12);
  EXPECT_LE(
    Compare(lshape, gs_test::PartitionFaces(lshape, 3, Vec3(0, 1, 0)), 3, { 40 }, 1.2).Worst,
    1e-12);
}

TEST(VirtualSourcePieces, CurvedMeshesAsAccurateAsTheSerialSolve)
{
  const TriangleMesh bumpy = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  for (const int p : { 2, 3 })
  {
    ExpectAsAccurateAsSerial(Compare(bumpy, gs_test::PartitionFaces(bumpy, p, Vec3(1, 0.3, 0.1)), p, { 0 }));
  }
  // Pieces with holes and islands, two sources.
  const std::vector<int> holes = gs_test::PartitionFaces(bumpy, 4, Vec3(0.2, 1, 0.5), 5);
  const PiecesVersusSerial once = Compare(bumpy, holes, 4, { 17, 600 });
  ExpectAsAccurateAsSerial(once);
  // The same partition again: the same bits.
  const gs_test::PiecesRun again = RunVirtual(bumpy, holes, 4, { 17, 600 });
  EXPECT_EQ(once.Run.Seen, again.Seen);
  // Rank 1's faces oriented against rank 0's (sources cross into mirrored frames).
  const TriangleMesh torus = gs_test::BuildMesh(MakeTorus(1.0, 0.35, 80, 24));
  ExpectAsAccurateAsSerial(
    Compare(torus, gs_test::PartitionFaces(torus, 2, Vec3(1, 0, 0)), 2, { 7, 1500 }, 0.0, { 1 }));
  ExpectAsAccurateAsSerial(
    Compare(torus, gs_test::PartitionFaces(torus, 3, Vec3(0, 1, 0.3), 4), 3, { 100, 500 }, 0.9));
}

TEST(VirtualSourcePieces, SurfacePointsAndMoreProcessesThanPieces)
{
  // A point inside a face, a point on an edge and a vertex, on faces of different processes.
  const TriangleMesh bumpy = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  const std::vector<int> part = gs_test::PartitionFaces(bumpy, 3, Vec3(1, 0.3, 0.1));
  std::vector<SurfacePoint> points = { SurfacePoint::InFace(10, 0.2, 0.3, 0.5) };
  for (int f = 0; f < bumpy.NumberOfFaces(); ++f)
  {
    if (part[static_cast<std::size_t>(f)] == 2)
    {
      points.push_back(SurfacePoint::InFace(f, 0.0, 0.6, 0.4));
      break;
    }
  }
  ExpectAsAccurateAsSerial(Compare(bumpy, part, 3, { 300 }, 0.0, {}, points));
  // The fourth process holds no face.
  ExpectAsAccurateAsSerial(Compare(bumpy, part, 4, { 5 }));
  // A process holding one triangle inside a plane of the other's, the source point in it: its
  // faces' sources and corners all belong to the other process.
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(12, 12, 1.2, 1.2));
  std::vector<int> island(static_cast<std::size_t>(plane.NumberOfFaces()), 0);
  const int middle = plane.NumberOfFaces() / 2 + 12;
  island[static_cast<std::size_t>(middle)] = 1;
  EXPECT_LE(
    Compare(plane, island, 2, {}, 0.0, {}, { SurfacePoint::InFace(middle, 0.3, 0.3, 0.4) }).Worst,
    1e-12);
}

TEST(VirtualSourcePieces, FailuresAndAbortsOnEveryProcess)
{
  const TriangleMesh mesh = gs_test::BuildMesh(MakePlanarGrid(6, 6, 1.0, 1.0));
  const std::vector<int> part = gs_test::PartitionFaces(mesh, 2, Vec3(1, 0, 0));
  for (const Status& s : RunVirtual(mesh, part, 2, { 1000 }).Statuses)
  {
    EXPECT_TRUE(gs_test::FailedWith(s, "not a point"));
  }
  for (const Status& s : RunVirtual(mesh, part, 2, {}).Statuses)
  {
    EXPECT_TRUE(gs_test::FailedWith(s, "no source"));
  }
  for (const Status& s : RunVirtual(mesh, part, 2, { 0 }, 0.0, {}, {}, 1).Statuses)
  {
    EXPECT_TRUE(s.IsAborted()) << s.Message();
  }
}
