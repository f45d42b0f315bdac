// A surface partitioned over "processes" that are threads of one test (the core's ThreadHub):
// the pieces of a whole mesh by a face partition, with the whole mesh's vertex and face numbers
// as global ids (the serial run the pieces must match).
#pragma once

#include "SurfacePiece.h"
#include "ThreadCommunicator.h"
#include "TriangleMesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <mutex>
#include <utility>
#include <vector>

namespace gs_test
{

using gs::ThreadHub;

// The faces of `mesh` whose part is `rank`, with the mesh's own vertex and face numbers as ids.
inline gs::PieceTriangles PieceOf(
  const gs::TriangleMesh& mesh, const std::vector<int>& partOfFace, int rank)
{
  return gs::PieceOfMesh(mesh, partOfFace, rank);
}

// A partition of the faces into `parts` slabs along the direction (dx, dy, dz) of their
// centroids (equal face counts), then each slab's faces dealt in runs of `run` faces of the
// face order to the next part (run 0: none), which leaves pieces with holes and islands.
inline std::vector<int> PartitionFaces(
  const gs::TriangleMesh& mesh, int parts, const gs::Vec3& direction, int run = 0)
{
  std::vector<int> part = gs::SlabPartition(mesh, parts, direction);
  if (run > 0)
  {
    for (int f = 0; f < mesh.NumberOfFaces(); ++f)
    {
      if ((f / run) % 7 == 3)
      {
        part[static_cast<std::size_t>(f)] = (part[static_cast<std::size_t>(f)] + 1) % parts;
      }
    }
  }
  return part;
}

// What the processes of a computation on the pieces saw.
struct PiecesRun
{
  // Per rank: the value of each corner of its own faces (global id, value).
  std::vector<std::vector<std::pair<std::int64_t, double>>> Seen;
  std::vector<int> Rings;             // per rank: its piece's rings at the end
  std::vector<gs::Status> Statuses;   // per rank
};

// Runs `solve(rank, piece, comm, mine, perVertex)` on `processes` threads, each holding the
// piece of its faces in `part` (the ranks of `flipped` give their triangles the other way
// round) and `mine`, the surface points of `points` (faces of the whole mesh) on its own faces
// named in its piece's mesh (the piece then has its two rings from the start); `solve` returns
// its status and fills perVertex, one value per vertex of the piece's mesh. It runs under no
// lock: what else it records is its own to guard.
template <class Solve>
PiecesRun RunOnPieces(const gs::TriangleMesh& mesh, const std::vector<int>& part, int processes,
  const std::vector<int>& flipped, const std::vector<gs::SurfacePoint>& points, Solve&& solve)
{
  PiecesRun run;
  run.Seen.resize(static_cast<std::size_t>(processes));
  run.Rings.resize(static_cast<std::size_t>(processes));
  run.Statuses.resize(static_cast<std::size_t>(processes));
  std::mutex lock;
  ThreadHub hub(processes);
  hub.Run([&](int rank, gs::PieceCommunicator& comm) {
    gs::PieceTriangles own = PieceOf(mesh, part, rank);
    if (std::find(flipped.begin(), flipped.end(), rank) != flipped.end())
    {
      for (auto& t : own.Triangles)
      {
        std::swap(t[1], t[2]);
      }
    }
    gs::SurfacePiece piece;
    gs::Status status = piece.Build(own, points.empty() ? 0 : 1, comm);
    std::vector<gs::SurfacePoint> mine;
    for (const gs::SurfacePoint& p : points)
    {
      if (part[static_cast<std::size_t>(p.Face)] != rank)
      {
        continue;
      }
      const std::array<int, 3>& c = mesh.Face(p.Face);
      mine.push_back(piece.LocalPoint(p.Face, { { c[0], c[1], c[2] } }, p.Bary));
    }
    std::vector<double> perVertex;
    if (status.Ok())
    {
      status = solve(rank, piece, comm, mine, perVertex);
    }
    std::lock_guard<std::mutex> guard(lock);
    run.Statuses[static_cast<std::size_t>(rank)] = status;
    if (!status.Ok())
    {
      return;
    }
    run.Rings[static_cast<std::size_t>(rank)] = piece.Rings();
    for (int f = 0; f < piece.Mesh().NumberOfFaces(); ++f)
    {
      if (piece.IsOwnFace(f))
      {
        for (const int v : piece.Mesh().Face(f))
        {
          run.Seen[static_cast<std::size_t>(rank)].push_back(
            { piece.GlobalId(v), perVertex[static_cast<std::size_t>(v)] });
        }
      }
    }
  });
  return run;
}

} // namespace gs_test
