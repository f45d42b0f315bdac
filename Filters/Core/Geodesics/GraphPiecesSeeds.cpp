// The graph search's seeds from surface points on pieces (GraphPieces.h): the exact local solve
// SVGGeodesicSolver::SolveFromPieces runs on the whole surface, on the pieces.
#include "ExactPieces.h"
#include "GraphPieces.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

namespace
{
constexpr double Pi = 3.14159265358979323846;

// Collective. Every process's `mine` (global id, distance) pairs, on every process.
std::vector<std::pair<std::int64_t, double>> AllPairs(
  PieceCommunicator& comm, const std::vector<std::pair<std::int64_t, double>>& mine)
{
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.Size())), in;
  for (ByteBuffer& b : out)
  {
    ByteWriter put(b);
    for (const auto& [id, d] : mine)
    {
      put.Put(id);
      put.Put(d);
    }
  }
  comm.Exchange(out, in);
  std::vector<std::pair<std::int64_t, double>> all = mine;
  ReadIdValuePairs(comm, in, [&all](std::int64_t id, double d) { all.push_back({ id, d }); });
  return all;
}
} // namespace

Status GraphSeedsFromPoints(SurfacePiece& piece, const PieceGraph& graph,
  const std::vector<std::int64_t>& sources, const std::vector<SurfacePoint>& points,
  double maxDistance, PieceCommunicator& comm, std::vector<std::pair<std::int64_t, double>>& seeds,
  const std::vector<CurvePiece>& pieces, std::int64_t disks)
{
  seeds.clear();
  std::vector<std::int64_t> ids = sources;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const std::int64_t n =
    static_cast<std::int64_t>(ids.size()) + comm.Sum(static_cast<std::int64_t>(points.size()));
  const std::int64_t wanted = std::min<std::int64_t>(
    static_cast<std::int64_t>(graph.LocalDiskSize()) * std::max<std::int64_t>(disks > 0 ? disks : n, 1),
    piece.GlobalNumberOfVertices());
  const double limit =
    maxDistance > 0.0 && std::isfinite(maxDistance) ? maxDistance : std::numeric_limits<double>::infinity();

  // The solve's radius: the disk of `wanted` vertices at the surface's mean area per vertex,
  // with a margin; doubled until it holds them (or reaches the limit or the whole surface).
  const TriangleMesh& mesh = piece.Mesh();
  double area = 0.0;
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    area += piece.IsOwnFace(f) ? mesh.FaceArea(f) : 0.0;
  }
  const double perVertex =
    SumOverProcesses(comm, area) / static_cast<double>(std::max<std::int64_t>(piece.GlobalNumberOfVertices(), 1));
  double radius = std::min(1.5 * std::sqrt(static_cast<double>(wanted) * perVertex / Pi), limit);
  ExactPiecesResult result;
  std::vector<std::pair<std::int64_t, double>> reached;
  while (true)
  {
    if (const Status solved = ComputeExactOnPieces(piece, ids, radius, comm, result, nullptr, points);
        !solved.Ok())
    {
      return solved;
    }
    reached.clear();
    for (int v = 0; v < mesh.NumberOfVertices(); ++v)
    {
      const double d = result.Distance[static_cast<std::size_t>(v)];
      if (piece.IsOwned(v) && d <= radius)
      {
        reached.push_back({ piece.GlobalId(v), d });
      }
    }
    const std::int64_t count = comm.Sum(static_cast<std::int64_t>(reached.size()));
    if (count >= wanted || radius >= limit || radius > 4.0 * piece.LengthScale())
    {
      break;
    }
    radius = std::min(2.0 * radius, limit);
  }

  // The `wanted` nearest, as every process sees them.
  seeds = AllPairs(comm, reached);
  std::sort(seeds.begin(), seeds.end(), [](const auto& a, const auto& b) {
    return a.second < b.second || (a.second == b.second && a.first < b.first);
  });
  if (static_cast<std::int64_t>(seeds.size()) > wanted)
  {
    seeds.resize(static_cast<std::size_t>(wanted));
  }
  // The corners of the pieces' faces (the points' faces), at their straight distance.
  std::vector<CurvePiece> ends = pieces;
  if (pieces.empty())
  {
    for (const SurfacePoint& p : points)
    {
      if (!p.IsVertex())
      {
        ends.push_back({ p.Face, mesh.Position(p), mesh.Position(p) });
      }
    }
  }
  std::vector<std::pair<std::int64_t, double>> corners;
  for (const CurvePiece& p : ends)
  {
    for (const int c : mesh.Face(p.Face))
    {
      corners.push_back({ piece.GlobalId(c), PointSegmentDistance(mesh.Position(c), p.A, p.B) });
    }
  }
  const std::vector<std::pair<std::int64_t, double>> all = AllPairs(comm, corners);
  seeds.insert(seeds.end(), all.begin(), all.end());
  return Status();
}

} // namespace gs
