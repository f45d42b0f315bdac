#include "ExactInParts.h"

#include "ExactGeodesic.h"
#include "ExactPieces.h"
#include "ThreadCommunicator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace gs
{

ExactSolverInParts::ExactSolverInParts(const TriangleMesh& mesh, int parts)
  : Surface(mesh)
  , Parts(std::max(parts, 1))
  , Dist(static_cast<std::size_t>(mesh.NumberOfVertices()), std::numeric_limits<double>::infinity())
  , Departure(static_cast<std::size_t>(mesh.NumberOfVertices()), std::numeric_limits<double>::quiet_NaN())
{
}

bool ExactSolverInParts::SameFrame(const SurfacePoint& p, const SurfacePiece& piece) const
{
  // A vertex source's angles start from its VertexHalfedge and turn counter-clockwise, a face
  // point's from its face's first edge. The part's mesh lists the faces in the mesh's order
  // with their corners as the mesh does (PieceOfMesh), so both are the mesh's; checked all the
  // same.
  const TriangleMesh& local = piece.Mesh();
  if (p.IsVertex())
  {
    // The first outgoing edge, and the next one counter-clockwise (the fan turns alike).
    const int s = p.Vertex, h = local.VertexHalfedge(piece.Vertex(s)), g = Surface.VertexHalfedge(s);
    const int hn = local.RotateCCW(h), gn = Surface.RotateCCW(g);
    return piece.GlobalId(local.Destination(h)) == Surface.Destination(g) && (hn < 0) == (gn < 0) &&
      (hn < 0 || piece.GlobalId(local.Destination(hn)) == Surface.Destination(gn));
  }
  const std::array<int, 3>& mine = local.Face(piece.Face(p.Face));
  const std::array<int, 3>& whole = Surface.Face(p.Face);
  for (std::size_t k = 0; k < 3; ++k)
  {
    if (piece.GlobalId(mine[k]) != whole[k])
    {
      return false;
    }
  }
  return true;
}

ExactSolverInParts::~ExactSolverInParts() = default;

Status ExactSolverInParts::Solve(
  const std::vector<int>& sources, double maxDistance, const std::function<bool(double)>& progress)
{
  std::vector<SurfacePoint> points;
  for (const int s : sources)
  {
    points.push_back(SurfacePoint::AtVertex(s));
  }
  return Solve(points, maxDistance, progress);
}

void ExactSolverInParts::RunParts(ThreadHub& hub, const std::vector<SurfacePoint>& sources,
  const std::vector<std::int64_t>& vertices, double maxDistance,
  const std::function<bool(double)>& progress, bool make, std::vector<Status>& statuses,
  std::vector<ExactPiecesResult>& results)
{
  hub.Run([&](int rank, PieceCommunicator& comm) {
    SurfacePiece& piece = *Pieces[static_cast<std::size_t>(rank)];
    Status& status = statuses[static_cast<std::size_t>(rank)];
    if (make)
    {
      // (One ring at once: face points name the piece's faces, which a growth renumbers.)
      status = piece.Build(PieceOfMesh(Surface, PartOfFace, rank), 1, comm);
    }
    if (status.Ok())
    {
      std::vector<SurfacePoint> points;
      for (const SurfacePoint& p : sources)
      {
        if (!p.IsVertex() && PartOfFace[static_cast<std::size_t>(p.Face)] == rank)
        {
          const std::array<int, 3>& c = Surface.Face(p.Face);
          points.push_back(piece.LocalPoint(p.Face, { { c[0], c[1], c[2] } }, p.Bary));
        }
      }
      // Rank 0 runs on the calling thread: it alone reports progress (and so may abort).
      const std::function<bool(double)> report = rank == 0 ? progress : nullptr;
      status = ComputeExactOnPieces(piece, vertices, maxDistance, comm,
        results[static_cast<std::size_t>(rank)], report, points);
    }
    if (!status.Ok())
    {
      return;
    }
    // Each vertex from the part that owns it (the parts write disjoint entries); the single
    // source's frame from the part that holds it (a vertex's owner, a face's holder).
    const ExactPiecesResult& result = results[static_cast<std::size_t>(rank)];
    for (int v = 0; v < piece.Mesh().NumberOfVertices(); ++v)
    {
      if (piece.IsOwned(v))
      {
        const std::size_t g = static_cast<std::size_t>(piece.GlobalId(v));
        Dist[g] = result.Distance[static_cast<std::size_t>(v)];
        Departure[g] = result.Departure[static_cast<std::size_t>(v)];
      }
    }
    if (sources.size() == 1)
    {
      const SurfacePoint& s = sources[0];
      const int local = s.IsVertex() ? piece.Vertex(s.Vertex) : -1;
      if (s.IsVertex() ? local >= 0 && piece.IsOwned(local) : PartOfFace[static_cast<std::size_t>(s.Face)] == rank)
      {
        Framed = SameFrame(s, piece);
      }
    }
  });
}

void ExactSolverInParts::KeepDepartures(const std::vector<SurfacePoint>& sources)
{
  // Angles from one source whose part measures them in the mesh's frame; otherwise none.
  Kept = sources.size() == 1 && Framed &&
    std::any_of(Departure.begin(), Departure.end(), [](double a) { return std::isfinite(a); });
  if (!Kept)
  {
    std::fill(Departure.begin(), Departure.end(), std::numeric_limits<double>::quiet_NaN());
  }
  else if (sources[0].IsVertex())
  {
    Departure[static_cast<std::size_t>(sources[0].Vertex)] = std::numeric_limits<double>::quiet_NaN();
  }
}

Status ExactSolverInParts::Solve(const std::vector<SurfacePoint>& sources, double maxDistance,
  const std::function<bool(double)>& progress)
{
  std::fill(Dist.begin(), Dist.end(), std::numeric_limits<double>::infinity());
  std::fill(Departure.begin(), Departure.end(), std::numeric_limits<double>::quiet_NaN());
  Framed = Kept = false;
  Windows = 0;
  NumRounds = 0;
  if (sources.empty())
  {
    return Status::Error("no source given");
  }
  if (const Status valid = Surface.CheckPoints(sources, "source"); !valid.Ok())
  {
    return valid;
  }
  // The parts (a function of the mesh alone): cubes of an eighth of the bounding box's longest
  // side dealt out in turn, so that a front crossing the surface meets every part at once.
  const bool make = Pieces.empty();
  if (make)
  {
    PartOfFace = BlockPartition(Surface, Parts, BlocksAlongLongestSide);
    for (int p = 0; p < Parts; ++p)
    {
      Pieces.push_back(std::make_unique<SurfacePiece>());
    }
  }
  // Vertices by global id (the mesh's own numbers) on every part; a face point on the part
  // holding its face; a face point at a corner is that vertex (as the serial solver takes it:
  // the part holding the face may not own the corner).
  // (Only the corners are taken: each part's solver normalizes its face points itself.)
  std::vector<SurfacePoint> points = sources;
  for (SurfacePoint& p : points)
  {
    if (const SurfacePoint q = ExactGeodesicSolver::SourcePoint(Surface, p); q.IsVertex())
    {
      p = q;
    }
  }
  std::vector<std::int64_t> vertices;
  for (const SurfacePoint& p : points)
  {
    if (p.IsVertex())
    {
      vertices.push_back(p.Vertex);
    }
  }
  std::vector<Status> statuses(static_cast<std::size_t>(Parts));
  std::vector<ExactPiecesResult> results(static_cast<std::size_t>(Parts));
  ThreadHub hub(Parts);
  bool thrown = false;
  try
  {
    RunParts(hub, points, vertices, maxDistance, progress, make, statuses, results);
  }
  catch (const std::exception& e)
  {
    thrown = true;
    statuses[0] = Status::Error(std::string("the exact solve in parts failed: ") + e.what());
  }
  catch (...)
  {
    thrown = true;
    statuses[0] = Status::Error("the exact solve in parts failed");
  }
  for (const Status& status : statuses)
  {
    if (!status.Ok())
    {
      std::fill(Dist.begin(), Dist.end(), std::numeric_limits<double>::infinity());
      std::fill(Departure.begin(), Departure.end(), std::numeric_limits<double>::quiet_NaN());
      if (make || thrown)
      {
        Pieces.clear(); // a piece that failed to build, or any of a run cut short, is made again
      }
      return status; // (after an abort or a refused source the pieces stay, as they were)
    }
  }
  for (const ExactPiecesResult& result : results)
  {
    Windows += result.WindowsPropagated;
    NumRounds = std::max(NumRounds, result.Rounds);
  }
  KeepDepartures(points);
  return Status();
}

} // namespace gs
