// The graph of a surface partitioned over processes (GraphPieces.h), on threads standing for
// the processes: each process's adjacency and polar stencils equal the serial graph's for its
// vertices, entry for entry, and the distances, graph and refined by unfolding, equal the serial
// solvers' to the bit, for
// several process counts and partitions (slabs, pieces with holes and islands), on a closed
// curved mesh, a regular plane with a boundary (ties everywhere) and a torus, for both graphs.
#include "GeodesicPolarCoordinates.h"
#include "GeodesicShooting.h"
#include "GraphPieces.h"
#include "PolarPieces.h"
#include "MeshGenerators.h"
#include "SVGGeodesicSolver.h"
#include "SaddleVertexGraph.h"
#include "TestMeshes.h"
#include "TestStatus.h"
#include "ThreadPieces.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

using namespace gs;

namespace
{
// One partitioned run: every owned vertex's adjacency (target id, weight) and distance.
struct PartitionedRun
{
  std::map<std::int64_t, std::vector<std::pair<std::int64_t, double>>> Adjacency;
  std::map<std::int64_t, double> Distance, Refined;
  // Each owned vertex's stencil: (x, y, target id) in order, then the wrap as (x, y, -1).
  std::map<std::int64_t, std::vector<std::tuple<double, double, std::int64_t>>> Stencil;
  std::map<std::int64_t, int> Owner;
  std::vector<std::vector<double>> Fetched; // per rank, the distances of its own faces' vertices
  std::vector<std::vector<std::int64_t>> FetchedIds;
  std::int64_t Resolved = 0;
  int Rings = 0, Rounds = 0, Refinements = 0;
  bool Ok = true;
  std::string Message;
};

PartitionedRun RunPieces(const TriangleMesh& mesh, const std::vector<int>& part, int processes,
  const SaddleVertexGraphOptions& options, const std::vector<std::int64_t>& sources,
  double maxDistance)
{
  PartitionedRun run;
  run.Fetched.resize(static_cast<std::size_t>(processes));
  run.FetchedIds.resize(static_cast<std::size_t>(processes));
  std::mutex lock;
  gs_test::ThreadHub hub(processes);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    auto fail = [&](const Status& s) {
      std::lock_guard<std::mutex> guard(lock);
      run.Ok = false;
      run.Message = s.Message();
    };
    SurfacePiece piece;
    if (const Status s = piece.Build(gs_test::PieceOf(mesh, part, rank), 0, comm); !s.Ok())
    {
      return fail(s);
    }
    PieceGraph graph;
    SaddleVertexGraphOptions o = options;
    o.NumberOfThreads = 1;
    if (const Status s = graph.Build(piece, o, comm); !s.Ok())
    {
      return fail(s);
    }
    PieceDistanceSolver solver(graph);
    std::vector<std::pair<std::int64_t, double>> seeds;
    for (const std::int64_t s : sources)
    {
      seeds.push_back({ s, 0.0 });
    }
    if (const Status s = solver.Solve(seeds, maxDistance, comm); !s.Ok())
    {
      return fail(s);
    }
    std::vector<int> wanted;
    for (int f = 0; f < piece.Mesh().NumberOfFaces(); ++f)
    {
      if (piece.IsOwnFace(f))
      {
        for (const int v : piece.Mesh().Face(f))
        {
          wanted.push_back(v);
        }
      }
    }
    PieceDistanceSolver refiner(graph);
    if (const Status s = refiner.Solve(seeds, maxDistance, comm, true); !s.Ok())
    {
      return fail(s);
    }
    const std::vector<double> fetched = solver.Fetch(piece, wanted, comm);
    std::lock_guard<std::mutex> guard(lock);
    for (int i = 0; i < graph.NumberOfOwned(); ++i)
    {
      auto& list = run.Adjacency[graph.OwnedId(i)];
      for (std::int64_t e = graph.Begin(i); e < graph.End(i); ++e)
      {
        list.push_back({ graph.TargetId(e), graph.Weight(e) });
      }
      run.Distance[graph.OwnedId(i)] = solver.Distance(i);
      run.Refined[graph.OwnedId(i)] = refiner.Distance(i);
      auto& stencil = run.Stencil[graph.OwnedId(i)];
      for (std::int64_t e = graph.StencilBegin(i); e < graph.StencilEnd(i); ++e)
      {
        const int t = graph.StencilTarget(e);
        stencil.push_back({ graph.StencilX(e), graph.StencilY(e),
          t >= 0 ? graph.OwnedId(t) : graph.RemoteId(-1 - t) });
      }
      stencil.push_back({ graph.StencilWrapX(i), graph.StencilWrapY(i), -1 });
      run.Owner[graph.OwnedId(i)] = rank;
    }
    run.Fetched[static_cast<std::size_t>(rank)] = fetched;
    for (const int v : wanted)
    {
      run.FetchedIds[static_cast<std::size_t>(rank)].push_back(piece.GlobalId(v));
    }
    run.Resolved = graph.GlobalResolved();
    run.Rings = std::max(run.Rings, graph.Rings());
    run.Rounds = solver.Rounds();
    run.Refinements = refiner.Refinements();
  });
  return run;
}

// Builds the serial graph and compares a partitioned run with it.
void ExpectSameAsSerial(const TriangleMesh& mesh, const SaddleVertexGraphOptions& options,
  const std::vector<int>& part, int processes, const std::vector<std::int64_t>& sources,
  double maxDistance = 0.0)
{
  SaddleVertexGraph serial;
  ASSERT_TRUE(gs_test::Succeeded(serial.Build(mesh, options, nullptr)));
  GraphDistanceSolver solve(serial);
  std::vector<std::pair<int, double>> seeds;
  for (const std::int64_t s : sources)
  {
    seeds.push_back({ serial.Node(static_cast<int>(s)), 0.0 });
  }
  solve.Solve(seeds, GraphAlgorithm::LabelCorrecting, maxDistance);
  SVGGeodesicSolver refined(mesh, serial);
  std::vector<SurfacePoint> points;
  for (const std::int64_t s : sources)
  {
    points.push_back(SurfacePoint::AtVertex(static_cast<int>(s)));
  }
  SVGSolveOptions refineOptions;
  refineOptions.MaximumDistance = maxDistance;
  ASSERT_TRUE(gs_test::Succeeded(refined.Solve(points, refineOptions)));

  const PartitionedRun run = RunPieces(mesh, part, processes, options, sources, maxDistance);
  ASSERT_TRUE(run.Ok) << run.Message;
  ASSERT_EQ(run.Distance.size(), static_cast<std::size_t>(mesh.NumberOfVertices()))
    << "every vertex owned by exactly one process";
  std::int64_t entries = 0, differ = 0, distances = 0;
  for (int v = 0; v < mesh.NumberOfVertices(); ++v)
  {
    const int n = serial.Node(v);
    std::vector<std::pair<std::int64_t, double>> expected;
    for (std::int64_t e = serial.Begin(n); e < serial.End(n); ++e)
    {
      expected.push_back({ serial.Vertex(serial.Target(e)), serial.Weight(e) });
    }
    std::sort(expected.begin(), expected.end());
    const auto& got = run.Adjacency.at(v);
    entries += static_cast<std::int64_t>(expected.size());
    if (got != expected)
    {
      ++differ;
      if (differ <= 3)
      {
        ADD_FAILURE() << "vertex " << v << " (process " << run.Owner.at(v) << "): "
                      << got.size() << " entries, serial " << expected.size();
      }
    }
    const double d = solve.Distance(n), dp = run.Distance.at(v);
    if (!(d == dp || (std::isinf(d) && std::isinf(dp))))
    {
      ++distances;
      if (distances <= 3)
      {
        ADD_FAILURE() << "vertex " << v << ": distance " << dp << ", serial " << d;
      }
    }
  }
  // Stencils as the serial graph's, and the refined distances as the serial solver's.
  std::int64_t stencils = 0, refinedDiffer = 0;
  double worst = 0.0;
  for (int v = 0; v < mesh.NumberOfVertices(); ++v)
  {
    const int n = serial.Node(v);
    std::vector<std::tuple<double, double, std::int64_t>> expected;
    for (std::int64_t e = serial.StencilBegin(n); e < serial.StencilEnd(n); ++e)
    {
      expected.push_back(
        { serial.StencilX(e), serial.StencilY(e), serial.Vertex(serial.StencilTarget(e)) });
    }
    expected.push_back({ serial.StencilWrapX(n), serial.StencilWrapY(n), -1 });
    stencils += run.Stencil.at(v) != expected ? 1 : 0;
    const double d = refined.Distance(v), dp = run.Refined.at(v);
    if (!(d == dp || (std::isinf(d) && std::isinf(dp))))
    {
      ++refinedDiffer;
      worst = std::max(worst, std::abs(d - dp) / d);
    }
  }
  std::int64_t lowered = 0;
  for (const auto& [id, d] : run.Refined)
  {
    lowered += d < run.Distance.at(id) ? 1 : 0;
  }
  EXPECT_GT(lowered, mesh.NumberOfVertices() / 10) << "the refinement lowered few distances";
  EXPECT_EQ(stencils, 0) << "stencils differ from the serial graph's";
  EXPECT_EQ(refinedDiffer, 0) << "refined distances differ from the serial solver's, by up to "
                              << worst << " relative";
  EXPECT_EQ(differ, 0) << "of " << mesh.NumberOfVertices() << " vertices";
  EXPECT_EQ(distances, 0);
  // The copies every process fetched for its own faces' vertices are the owners' values.
  for (std::size_t r = 0; r < run.Fetched.size(); ++r)
  {
    for (std::size_t j = 0; j < run.Fetched[r].size(); ++j)
    {
      const double expected = run.Distance.at(run.FetchedIds[r][j]);
      ASSERT_TRUE(run.Fetched[r][j] == expected ||
        (std::isinf(expected) && std::isinf(run.Fetched[r][j])));
    }
  }
  std::printf("P = %d: %lld entries, band %d rings, %lld vertices solved again, %d rounds, "
              "%d refinement rounds\n",
    processes, static_cast<long long>(entries), run.Rings, static_cast<long long>(run.Resolved),
    run.Rounds, run.Refinements);
}

SaddleVertexGraphOptions Svg(int k)
{
  SaddleVertexGraphOptions o;
  o.K = k;
  return o;
}

SaddleVertexGraphOptions Dgg(double accuracy)
{
  SaddleVertexGraphOptions o;
  o.Construction = GraphConstruction::DiscreteGeodesic;
  o.Accuracy = accuracy;
  return o;
}
} // namespace

TEST(GraphPieces, SaddleVertexGraphOnCurvedClosedMesh)
{
  const TriangleMesh mesh = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  for (const int p : { 2, 3 })
  {
    ExpectSameAsSerial(mesh, Svg(50), gs_test::PartitionFaces(mesh, p, Vec3(1, 0.3, 0.1)), p,
      { 0, 400 });
  }
  ExpectSameAsSerial(
    mesh, Svg(30), gs_test::PartitionFaces(mesh, 4, Vec3(0.2, 1, 0.5), 5), 4, { 17 });
  // More processes than pieces: the fourth holds no face.
  ExpectSameAsSerial(mesh, Svg(50), gs_test::PartitionFaces(mesh, 3, Vec3(1, 0.3, 0.1)), 4, { 0 });
}

TEST(GraphPieces, SaddleVertexGraphOnRegularPlaneWithBoundary)
{
  const TriangleMesh mesh = gs_test::BuildMesh(MakePlanarGrid(24, 20, 2.4, 2.0));
  ExpectSameAsSerial(mesh, Svg(50), gs_test::PartitionFaces(mesh, 3, Vec3(1, 0, 0)), 3, { 5 });
  ExpectSameAsSerial(
    mesh, Svg(50), gs_test::PartitionFaces(mesh, 2, Vec3(1, 1, 0), 3), 2, { 260 }, 0.9);
}

TEST(GraphPieces, DiscreteGeodesicGraphOnTorus)
{
  const TriangleMesh mesh = gs_test::BuildMesh(MakeTorus(1.0, 0.35, 40, 16));
  ExpectSameAsSerial(mesh, Dgg(0.01), gs_test::PartitionFaces(mesh, 3, Vec3(1, 0.2, 0)), 3,
    { 3 });
  SaddleVertexGraphOptions reached = Dgg(0.01);
  reached.ReachedStencil = true; // (stencils hold the reached vertices too)
  ExpectSameAsSerial(mesh, reached, gs_test::PartitionFaces(mesh, 2, Vec3(0, 1, 0), 4), 2,
    { 100, 500 });
}

TEST(GraphPieces, SourceOwnedByNoProcessFailsEverywhere)
{
  const TriangleMesh mesh = gs_test::BuildMesh(MakePlanarGrid(6, 6, 1.0, 1.0));
  const PartitionedRun run =
    RunPieces(mesh, gs_test::PartitionFaces(mesh, 2, Vec3(1, 0, 0)), 2, Svg(10), { 1000 }, 0.0);
  EXPECT_FALSE(run.Ok);
  EXPECT_NE(run.Message.find("not a point"), std::string::npos) << run.Message;
}

TEST(GraphPieces, MalformedPieceFailsEverywhere)
{
  // One process's triangle uses a point of another id twice at two positions: every process
  // gets the error, none hangs.
  const TriangleMesh mesh = gs_test::BuildMesh(MakePlanarGrid(6, 6, 1.0, 1.0));
  const std::vector<int> part = gs_test::PartitionFaces(mesh, 2, Vec3(1, 0, 0));
  std::vector<std::string> messages(2);
  gs_test::ThreadHub hub(2);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    PieceTriangles own = gs_test::PieceOf(mesh, part, rank);
    if (rank == 1)
    {
      own.PointIds.pop_back(); // a point without an id
    }
    SurfacePiece piece;
    messages[static_cast<std::size_t>(rank)] = piece.Build(own, 1, comm).Message();
  });
  EXPECT_NE(messages[0].find("process 1"), std::string::npos) << messages[0];
  EXPECT_NE(messages[1].find("global id"), std::string::npos) << messages[1];
}

TEST(GraphPieces, BuildRefusedBeyondTheAvailableMemoryEverywhere)
{
  const TriangleMesh mesh = gs_test::BuildMesh(gs_test::BumpySoup(2, 3, 0.1));
  ::setenv("GS_AVAILABLE_MEMORY", "100000", 1); // 100 KB: less than any piece's graph needs
  const PartitionedRun run =
    RunPieces(mesh, gs_test::PartitionFaces(mesh, 2, Vec3(1, 0, 0)), 2, Svg(20), { 0 }, 0.0);
  ::unsetenv("GS_AVAILABLE_MEMORY");
  EXPECT_FALSE(run.Ok);
  EXPECT_NE(run.Message.find("MiB"), std::string::npos) << run.Message;
}

namespace
{
// Polar coordinates about `at` (a vertex, by its id, or a face point, passed by the process of
// its face) on pieces against GeodesicPolarCoordinates on the whole mesh (with iso-curve angles
// when `iso`): the same bits; over the whole surface (an infinite radius: the exact solve on the
// pieces) rho within 1e-12 of the largest and theta within 1e-9 modulo a turn.
void ExpectPolarAsSerial(const TriangleMesh& mesh, const std::vector<int>& part, int processes,
  const SurfacePoint& at, double radius, const Vec3& reference, bool iso = false)
{
  GeodesicPolarCoordinates serial(mesh);
  const double angle = reference.x == 0.0 && reference.y == 0.0 && reference.z == 0.0
    ? 0.0
    : TangentAngle(mesh, at, reference);
  ASSERT_TRUE(gs_test::Succeeded(serial.Compute(at, radius, angle)));
  const int kept = iso ? *serial.UseIsoCurveAngles() : 0;
  std::vector<int> keptOnPieces(static_cast<std::size_t>(processes), -1);
  std::vector<std::map<std::int64_t, std::pair<double, double>>> got(
    static_cast<std::size_t>(processes));
  std::vector<std::string> errors(static_cast<std::size_t>(processes));
  std::vector<double> sums(static_cast<std::size_t>(processes));
  std::vector<int> held(static_cast<std::size_t>(processes));
  gs_test::ThreadHub hub(processes);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    SurfacePiece piece;
    PiecePolarCoordinates polar;
    Status s = piece.Build(gs_test::PieceOf(mesh, part, rank), 0, comm);
    if (s.Ok() && at.IsVertex())
    {
      s = ComputePolarOnPieces(piece, at.Vertex, radius, reference, comm, polar, iso);
    }
    else if (s.Ok())
    {
      const std::array<int, 3>& c = mesh.Face(at.Face);
      const SurfacePoint mine = piece.LocalPoint(at.Face, { { c[0], c[1], c[2] } }, at.Bary);
      s = ComputePolarOnPieces(piece, part[static_cast<std::size_t>(at.Face)] == rank ? &mine : nullptr,
        radius, reference, comm, polar, iso);
    }
    errors[static_cast<std::size_t>(rank)] = s.Message();
    if (!s.Ok())
    {
      return;
    }
    sums[static_cast<std::size_t>(rank)] = polar.SourceAngleSum;
    keptOnPieces[static_cast<std::size_t>(rank)] = polar.IsoCurveKept;
    held[static_cast<std::size_t>(rank)] = polar.ChartFaces;
    // (A whole chart is given at the vertices of the process's own faces.)
    std::vector<unsigned char> corner(static_cast<std::size_t>(piece.Mesh().NumberOfVertices()), 0);
    for (int f = 0; f < piece.Mesh().NumberOfFaces(); ++f)
    {
      for (const int v : piece.Mesh().Face(f))
      {
        corner[static_cast<std::size_t>(v)] |= piece.IsOwnFace(f) ? 1 : 0;
      }
    }
    for (int v = 0; v < piece.Mesh().NumberOfVertices(); ++v)
    {
      if (std::isfinite(radius) || corner[static_cast<std::size_t>(v)])
      {
        got[static_cast<std::size_t>(rank)][piece.GlobalId(v)] = {
          polar.Rho[static_cast<std::size_t>(v)], polar.Theta[static_cast<std::size_t>(v)] };
      }
    }
  });
  int inside = 0;
  for (int r = 0; r < processes; ++r)
  {
    ASSERT_EQ(errors[static_cast<std::size_t>(r)], "");
    EXPECT_EQ(sums[static_cast<std::size_t>(r)], serial.SourceAngleSum());
    EXPECT_EQ(keptOnPieces[static_cast<std::size_t>(r)], kept);
    for (const auto& [id, value] : got[static_cast<std::size_t>(r)])
    {
      const double rho = serial.Rho(static_cast<int>(id)), theta = serial.Theta(static_cast<int>(id));
      const bool whole = !std::isfinite(radius);
      const bool same = whole
        ? std::isnan(rho) == std::isnan(value.first) && std::isnan(theta) == std::isnan(value.second) &&
          (std::isnan(rho) || (std::abs(rho - value.first) <= 1e-12 * 10.0 &&
                                std::abs(std::remainder(theta - value.second, 2.0 * M_PI)) <= 1e-9))
        : (value.first == rho || (std::isnan(rho) && std::isnan(value.first))) &&
          (value.second == theta || (std::isnan(theta) && std::isnan(value.second)));
      EXPECT_TRUE(same) << "vertex " << id << " on process " << r << ": (" << value.first << ", "
                        << value.second << "), serial (" << rho << ", " << theta << ")";
      inside += r == 0 && !std::isnan(rho) ? 1 : 0;
    }
  }
  EXPECT_LT(*std::max_element(held.begin(), held.end()), mesh.NumberOfFaces())
    << "the chart's process held the whole surface";
  std::printf("polar, P = %d: chart process held %d of %d faces\n", processes,
    *std::max_element(held.begin(), held.end()), mesh.NumberOfFaces());
  EXPECT_GT(static_cast<int>(serial.Inside().size()), 20);
}
} // namespace

TEST(GraphPieces, PolarCoordinatesSpanPieces)
{
  // A chart about a vertex or a point near a piece's edge reaches into the others; its process's
  // band grows there until the exact solve within the radius stays inside.
  const TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  const std::vector<int> slabs = gs_test::PartitionFaces(sphere, 3, Vec3(1, 0.3, 0.1));
  ExpectPolarAsSerial(sphere, slabs, 3, SurfacePoint::AtVertex(5), 0.6, Vec3(0, 0, 0));
  ExpectPolarAsSerial(sphere, gs_test::PartitionFaces(sphere, 2, Vec3(0.2, 1, 0.5), 5), 2,
    SurfacePoint::AtVertex(40), 0.9, Vec3(0, 0, 1));
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(24, 20, 2.4, 2.0));
  ExpectPolarAsSerial(plane, gs_test::PartitionFaces(plane, 3, Vec3(1, 0, 0)), 3,
    SurfacePoint::AtVertex(260), 0.5, Vec3(1, 1, 0));
  // About points inside faces of each process (the band grows after the point is named: it is
  // named again in the grown piece) and a point on an edge.
  for (const int f : { 7, 900, sphere.NumberOfFaces() - 40 })
  {
    ExpectPolarAsSerial(sphere, slabs, 3, SurfacePoint::InFace(f, 0.2, 0.5, 0.3), 0.6, Vec3(0, 0, 1));
  }
  ExpectPolarAsSerial(plane, gs_test::PartitionFaces(plane, 3, Vec3(1, 0, 0)), 3,
    SurfacePoint::InFace(300, 0.0, 0.4, 0.6), 0.5, Vec3(1, 0, 0));
  // Iso-curve angles: the band also holds what they read beyond the chart (the loops' distances
  // a few edges further, the reference geodesic), in the whole surface's mean edges.
  ExpectPolarAsSerial(sphere, slabs, 3, SurfacePoint::AtVertex(5), 0.6, Vec3(0, 0, 0), true);
  ExpectPolarAsSerial(sphere, slabs, 3, SurfacePoint::InFace(900, 0.2, 0.5, 0.3), 0.8, Vec3(0, 0, 1), true);
  ExpectPolarAsSerial(plane, gs_test::PartitionFaces(plane, 3, Vec3(1, 0, 0)), 3,
    SurfacePoint::AtVertex(260), 0.5, Vec3(1, 1, 0), true);
  // The whole surface: the exact distances and departure angles on the pieces.
  const double whole = std::numeric_limits<double>::infinity();
  ExpectPolarAsSerial(sphere, slabs, 3, SurfacePoint::AtVertex(5), whole, Vec3(0, 0, 0));
  ExpectPolarAsSerial(sphere, gs_test::PartitionFaces(sphere, 2, Vec3(0.2, 1, 0.5), 5), 2,
    SurfacePoint::InFace(900, 0.2, 0.5, 0.3), whole, Vec3(0, 0, 1));
  ExpectPolarAsSerial(plane, gs_test::PartitionFaces(plane, 3, Vec3(1, 0, 0)), 3,
    SurfacePoint::AtVertex(260), whole, Vec3(1, 1, 0));
}

namespace
{
// Graph distances from surface points on pieces (GraphSeedsFromPoints, then the graph search
// and refinement) against SVGGeodesicSolver's from the same points on the whole mesh.
void ExpectPointSourcesAsSerial(const TriangleMesh& mesh, const SaddleVertexGraphOptions& options,
  const std::vector<int>& part, int processes, const std::vector<SurfacePoint>& points,
  double maxDistance)
{
  SaddleVertexGraph serialGraph;
  ASSERT_TRUE(gs_test::Succeeded(serialGraph.Build(mesh, options, nullptr)));
  SVGGeodesicSolver serial(mesh, serialGraph);
  SVGSolveOptions o;
  o.MaximumDistance = maxDistance;
  std::vector<std::vector<double>> expected;
  for (const bool refine : { false, true })
  {
    o.Refine = refine;
    ASSERT_TRUE(gs_test::Succeeded(serial.Solve(points, o)));
    expected.push_back(serial.Distances());
  }
  std::vector<std::int64_t> vertexIds;
  for (const SurfacePoint& p : points)
  {
    if (p.IsVertex())
    {
      vertexIds.push_back(p.Vertex);
    }
  }
  std::mutex lock;
  std::vector<std::string> errors;
  std::int64_t compared = 0, differ = 0;
  double worst = 0.0, largest = 0.0;
  gs_test::ThreadHub hub(processes);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    SurfacePiece piece;
    PieceGraph graph;
    SaddleVertexGraphOptions single = options;
    single.NumberOfThreads = 1;
    Status s = piece.Build(gs_test::PieceOf(mesh, part, rank), 0, comm);
    s = s.Ok() ? graph.Build(piece, single, comm) : s;
    // This process's points, named in its piece's mesh once the graph has its band.
    std::vector<SurfacePoint> mine;
    for (const SurfacePoint& p : points)
    {
      if (!p.IsVertex() && part[static_cast<std::size_t>(p.Face)] == rank)
      {
        const std::array<int, 3>& c = mesh.Face(p.Face);
        mine.push_back(piece.LocalPoint(p.Face, { { c[0], c[1], c[2] } }, p.Bary));
      }
    }
    std::vector<std::pair<std::int64_t, double>> seeds;
    s = s.Ok() ? GraphSeedsFromPoints(piece, graph, vertexIds, mine, maxDistance, comm, seeds) : s;
    for (int k = 0; k < 2 && s.Ok(); ++k)
    {
      PieceDistanceSolver solver(graph);
      s = solver.Solve(seeds, maxDistance, comm, k == 1);
      std::lock_guard<std::mutex> guard(lock);
      for (int i = 0; s.Ok() && i < graph.NumberOfOwned(); ++i)
      {
        const double d = solver.Distance(i);
        const double e = expected[static_cast<std::size_t>(k)][static_cast<std::size_t>(graph.OwnedId(i))];
        ++compared;
        if (std::isfinite(e))
        {
          largest = std::max(largest, e);
        }
        if (!(d == e || (std::isinf(d) && std::isinf(e))))
        {
          ++differ;
          worst = std::max(worst, std::isfinite(d - e) ? std::abs(d - e) : 1e300);
        }
      }
    }
    std::lock_guard<std::mutex> guard(lock);
    if (!s.Ok())
    {
      errors.push_back(s.Message());
    }
  });
  ASSERT_TRUE(errors.empty()) << errors.front();
  EXPECT_EQ(compared, 2 * mesh.NumberOfVertices());
  // The exact local solves agree to rounding; their vertices seed the same graph search.
  EXPECT_LE(worst, 1e-12 * largest) << differ << " of " << compared << " distances differ";
  std::printf("points on pieces, P = %d: %lld of %lld distances differ from the serial solver's, "
              "by %.2e of the largest at most\n",
    processes, static_cast<long long>(differ), static_cast<long long>(compared), worst / largest);
}
} // namespace

TEST(GraphPieces, SurfacePointSourcesAsSerial)
{
  const TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  const std::vector<int> slabs = gs_test::PartitionFaces(sphere, 3, Vec3(1, 0.3, 0.1));
  SaddleVertexGraphOptions svg;
  svg.K = 30;
  // A point inside a face, one on an edge, and a vertex, on faces of different processes.
  ExpectPointSourcesAsSerial(sphere, svg, slabs, 3,
    { SurfacePoint::InFace(12, 0.2, 0.3, 0.5), SurfacePoint::InFace(sphere.NumberOfFaces() - 9, 0.0, 0.4, 0.6),
      SurfacePoint::AtVertex(300) },
    0.0);
  ExpectPointSourcesAsSerial(sphere, svg, slabs, 3, { SurfacePoint::InFace(700, 0.1, 0.1, 0.8) }, 0.8);
  SaddleVertexGraphOptions dgg;
  dgg.Construction = GraphConstruction::DiscreteGeodesic;
  dgg.Accuracy = 0.01;
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(24, 20, 2.4, 2.0));
  ExpectPointSourcesAsSerial(plane, dgg, gs_test::PartitionFaces(plane, 2, Vec3(1, 0, 0)), 2,
    { SurfacePoint::InFace(400, 0.3, 0.3, 0.4) }, 0.0);
}

// Curve coordinates about a curve on pieces (ComputeCurveCoordinatesOnPieces: process 0 grows
// its band around the curve and the chart) against GeodesicPolarCoordinates::ComputeCurve on the
// whole mesh: the same bits, the curve's length too.
TEST(GraphPieces, CurveCoordinatesSpanPieces)
{
  auto expectAsSerial = [](const TriangleMesh& mesh, const std::vector<int>& part, int processes,
                          const std::vector<SurfacePoint>& curve, double radius) {
    GeodesicPolarCoordinates serial(mesh);
    ASSERT_TRUE(gs_test::Succeeded(serial.ComputeCurve(curve, radius)));
    std::vector<PiecePointName> names;
    for (const SurfacePoint& p : curve)
    {
      PiecePointName n;
      if (p.IsVertex())
      {
        n.Vertex = p.Vertex;
      }
      else
      {
        n.Face = p.Face;
        n.Bary = p.Bary;
        for (std::size_t k = 0; k < 3; ++k)
        {
          n.Corners[k] = mesh.Face(p.Face)[k];
        }
      }
      names.push_back(n);
    }
    std::mutex lock;
    std::vector<std::string> errors;
    int compared = 0, differ = 0, inside = 0;
    std::vector<double> lengths;
    gs_test::ThreadHub hub(processes);
    hub.Run([&](int rank, PieceCommunicator& comm) {
      SurfacePiece piece;
      PiecePolarCoordinates chart;
      Status s = piece.Build(gs_test::PieceOf(mesh, part, rank), 0, comm);
      s = s.Ok() ? ComputeCurveCoordinatesOnPieces(piece, names, radius, comm, chart) : s;
      std::lock_guard<std::mutex> guard(lock);
      if (!s.Ok())
      {
        errors.push_back(s.Message());
        return;
      }
      lengths.push_back(chart.CurveLength);
      for (int v = 0; v < piece.Mesh().NumberOfVertices(); ++v)
      {
        const int w = static_cast<int>(piece.GlobalId(v));
        const double o = serial.Curve().Offset[static_cast<std::size_t>(w)];
        const double a = serial.Curve().ArcLength[static_cast<std::size_t>(w)];
        const double po = chart.Rho[static_cast<std::size_t>(v)];
        const double pa = chart.Theta[static_cast<std::size_t>(v)];
        const bool serialIn = !std::isnan(o) && std::abs(o) <= radius;
        const bool piecesIn = !std::isnan(po);
        ++compared;
        inside += serialIn && rank == 0 ? 1 : 0;
        if (serialIn != piecesIn || (serialIn && (o != po || !(a == pa || (std::isnan(a) && std::isnan(pa))))))
        {
          ++differ;
        }
      }
    });
    ASSERT_TRUE(errors.empty()) << errors.front();
    EXPECT_EQ(differ, 0) << "of " << compared;
    EXPECT_GT(inside, 20);
    for (const double l : lengths)
    {
      EXPECT_EQ(l, serial.Curve().Length);
    }
  };
  const TriangleMesh sphere = gs_test::BuildMesh(gs_test::BumpySoup(3, 7, 0.1));
  const std::vector<int> slabs = gs_test::PartitionFaces(sphere, 3, Vec3(1, 0.3, 0.1));
  expectAsSerial(sphere, slabs, 3,
    { SurfacePoint::AtVertex(5), SurfacePoint::AtVertex(40), SurfacePoint::InFace(900, 0.2, 0.5, 0.3) }, 0.4);
  const TriangleMesh plane = gs_test::BuildMesh(MakePlanarGrid(24, 20, 2.4, 2.0));
  expectAsSerial(plane, gs_test::PartitionFaces(plane, 3, Vec3(1, 0, 0)), 3,
    { SurfacePoint::AtVertex(30), SurfacePoint::AtVertex(260), SurfacePoint::AtVertex(480) }, 0.3);
}
