#include "ExactInParts.h"

#include "ExactPieces.h"
#include "ThreadCommunicator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <string>

namespace gs
{

ExactSolverInParts::ExactSolverInParts(const TriangleMesh& mesh, int parts)
  : Surface(mesh)
  , Parts(std::max(parts, 1))
  , Dist(static_cast<std::size_t>(mesh.NumberOfVertices()), std::numeric_limits<double>::infinity())
{
}

ExactSolverInParts::~ExactSolverInParts() = default;

Status ExactSolverInParts::Solve(
  const std::vector<int>& sources, double maxDistance, const std::function<bool(double)>& progress)
{
  std::fill(Dist.begin(), Dist.end(), std::numeric_limits<double>::infinity());
  Windows = 0;
  NumRounds = 0;
  if (sources.empty())
  {
    return Status::Error("no source given");
  }
  std::vector<std::int64_t> ids;
  for (const int s : sources)
  {
    if (s < 0 || s >= Surface.NumberOfVertices())
    {
      return Status::Error("source vertex " + std::to_string(s) + " is not a vertex of the mesh (" +
        std::to_string(Surface.NumberOfVertices()) + " vertices)");
    }
    ids.push_back(s);
  }
  // The parts (a function of the mesh alone): cubes of an eighth of the bounding box's longest
  // side dealt out in turn, so that a front crossing the surface meets every part at once.
  std::vector<int> partOfFace;
  if (Pieces.empty())
  {
    partOfFace = BlockPartition(Surface, Parts, BlocksAlongLongestSide);
    for (int p = 0; p < Parts; ++p)
    {
      Pieces.push_back(std::make_unique<SurfacePiece>());
    }
  }
  std::vector<Status> statuses(static_cast<std::size_t>(Parts));
  std::vector<ExactPiecesResult> results(static_cast<std::size_t>(Parts));
  ThreadHub hub(Parts);
  hub.Run([&](int rank, PieceCommunicator& comm) {
    SurfacePiece& piece = *Pieces[static_cast<std::size_t>(rank)];
    Status& status = statuses[static_cast<std::size_t>(rank)];
    if (!partOfFace.empty())
    {
      status = piece.Build(PieceOfMesh(Surface, partOfFace, rank), 1, comm);
    }
    if (status.Ok())
    {
      // Rank 0 runs on the calling thread: it alone reports progress (and so may abort).
      const ProgressCallback report = rank == 0 ? progress : ProgressCallback();
      status = ComputeExactOnPieces(piece, ids, maxDistance, comm,
        results[static_cast<std::size_t>(rank)], report);
    }
    if (!status.Ok())
    {
      return;
    }
    // Each vertex from the part that owns it (the parts write disjoint entries).
    const ExactPiecesResult& result = results[static_cast<std::size_t>(rank)];
    for (int v = 0; v < piece.Mesh().NumberOfVertices(); ++v)
    {
      if (piece.IsOwned(v))
      {
        Dist[static_cast<std::size_t>(piece.GlobalId(v))] = result.Distance[static_cast<std::size_t>(v)];
      }
    }
  });
  for (const Status& status : statuses)
  {
    if (!status.Ok())
    {
      std::fill(Dist.begin(), Dist.end(), std::numeric_limits<double>::infinity());
      Pieces.clear(); // made again at the next solve: nothing of a failed run is used
      return status;
    }
  }
  for (const ExactPiecesResult& result : results)
  {
    Windows += result.WindowsPropagated;
    NumRounds = std::max(NumRounds, result.Rounds);
  }
  return Status();
}

} // namespace gs
