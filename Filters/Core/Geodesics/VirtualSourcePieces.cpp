#include "VirtualSourcePieces.h"

#include "VirtualSourceGeodesic.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();

// What travels between processes, each item after a tag.
enum ItemTag : std::uint8_t
{
  FaceItem = 1,
  VertexItem = 2
};

} // namespace

// Drives a VirtualSourceSolver on one piece (a friend of the solver): processes its queue and
// exchanges what leaves it.
class VirtualSourcePieceSolve
{
public:
  VirtualSourcePieceSolve(const SurfacePiece& piece, PieceCommunicator& comm, double bucketWidth)
    : Piece(piece)
    , Mesh(piece.Mesh())
    , Comm(comm)
    , Solver(piece.Mesh(), bucketWidth)
  {
    // The solver queues every face given a source and every bend vertex reached; this driver
    // processes the own ones and sends the others to their owners.
    Listed.assign(static_cast<std::size_t>(Mesh.NumberOfFaces()), 0);
    VertexListed.assign(static_cast<std::size_t>(Mesh.NumberOfVertices()), 0);
  }
  VirtualSourcePieceSolve(const VirtualSourcePieceSolve&) = delete;
  VirtualSourcePieceSolve& operator=(const VirtualSourcePieceSolve&) = delete;

  Status Run(const std::vector<std::int64_t>& sources, const std::vector<SurfacePoint>& points,
    const std::vector<std::vector<CurvePiece>>& runs, double maxDistance, double longestEdge,
    const ProgressCallback& progress, VirtualSourcePiecesResult& result);

private:
  using FaceRecord = VirtualSourceSolver::FaceRecord;
  // The first bucket holding an item (infinite when the queue is empty).
  double FirstBucket() const;
  // Processes the buckets up to `last`, in order: an item of this process's own face or vertex
  // is processed, another's current one leaves (Leave).
  void ProcessUpTo(std::size_t last);
  void Leave(VirtualSourceSolver::QueueItem item);
  // What left this process since the last exchange, into one buffer per process; returns the
  // number of items.
  std::int64_t Pack(std::vector<ByteBuffer>& out);
  void Unpack(const std::vector<ByteBuffer>& in);
  bool UnpackFace(ByteReader& r);
  bool UnpackVertex(ByteReader& r);
  // The global id of the corner of face f opposite its edge k (-1 for k = -1), and back.
  std::int64_t EdgeName(int f, int k) const;
  int EdgeOf(int f, std::int64_t name) const;
  // (x, y) of the frame of face f whose corners come in the order `corners` (global ids), in
  // the frame of f as this process's mesh orders its corners.
  void ToLocalFrame(int f, const std::array<std::int64_t, 3>& corners, double& x, double& y) const;
  // Each vertex's smallest distance over the processes, at its owner; then the distances of
  // the own faces' vertices from their owners.
  void Collect(double limit, VirtualSourcePiecesResult& result);

  const SurfacePiece& Piece;
  const TriangleMesh& Mesh;
  PieceCommunicator& Comm;
  VirtualSourceSolver Solver;
  // Faces and bend vertices of other processes to send at the next exchange, each once.
  std::vector<int> LeavingFaces, LeavingVertices;
  std::vector<unsigned char> Listed, VertexListed;
  std::int64_t Sent = 0;
};

double VirtualSourcePieceSolve::FirstBucket() const
{
  for (std::size_t b = Solver.Current; b < Solver.Buckets.size(); ++b)
  {
    if (!Solver.Buckets[b].empty())
    {
      return static_cast<double>(b);
    }
  }
  return Inf;
}

void VirtualSourcePieceSolve::ProcessUpTo(std::size_t last)
{
  for (; Solver.Current < Solver.Buckets.size() && Solver.Current <= last; ++Solver.Current)
  {
    // Items pushed into the current bucket while it is processed are appended to it.
    for (std::size_t i = 0; i < Solver.Buckets[Solver.Current].size(); ++i)
    {
      Solver.Prefetch(Solver.Buckets[Solver.Current], i);
      const VirtualSourceSolver::QueueItem item = Solver.Buckets[Solver.Current][i];
      const int id = VirtualSourceSolver::ItemId(item);
      if (id >= 0 ? !Piece.IsOwnFace(id) : !Piece.IsOwned(-1 - id))
      {
        Leave(item);
      }
      else
      {
        Solver.ProcessItem<false>(item);
      }
    }
    Solver.Buckets[Solver.Current].clear();
  }
}

void VirtualSourcePieceSolve::Leave(VirtualSourceSolver::QueueItem item)
{
  // Only the current item of a face or vertex: an older one was overtaken.
  const int id = VirtualSourceSolver::ItemId(item);
  const float key = VirtualSourceSolver::ItemKey(item);
  if (id >= 0)
  {
    const std::size_t f = static_cast<std::size_t>(id);
    if (key == static_cast<float>(Solver.Faces[id].Key) && !Listed[f])
    {
      Listed[f] = 1;
      LeavingFaces.push_back(id);
    }
    return;
  }
  const std::size_t v = static_cast<std::size_t>(-1 - id);
  if (key == static_cast<float>(Solver.Dist[v]) && !VertexListed[v])
  {
    VertexListed[v] = 1;
    LeavingVertices.push_back(-1 - id);
  }
}

std::int64_t VirtualSourcePieceSolve::EdgeName(int f, int k) const
{
  return k < 0 ? -1 : Piece.GlobalId(Mesh.Face(f)[static_cast<std::size_t>((k + 2) % 3)]);
}

int VirtualSourcePieceSolve::EdgeOf(int f, std::int64_t name) const
{
  for (int j = 0; j < 3 && name >= 0; ++j)
  {
    if (Piece.GlobalId(Mesh.Face(f)[static_cast<std::size_t>(j)]) == name)
    {
      return (j + 1) % 3;
    }
  }
  return -1;
}

void VirtualSourcePieceSolve::ToLocalFrame(
  int f, const std::array<std::int64_t, 3>& corners, double& x, double& y) const
{
  // This frame's corners: (0, 0), (L0, 0), (Cx, Cy); perm[i]: the local corner of corners[i].
  const FaceRecord& r = Solver.Faces[f];
  const double qx[3] = { 0.0, r.L[0], r.Cx }, qy[3] = { 0.0, 0.0, r.Cy };
  int perm[3] = { 0, 1, 2 };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      if (Piece.GlobalId(Mesh.Face(f)[static_cast<std::size_t>(j)]) == corners[static_cast<std::size_t>(i)])
      {
        perm[i] = j;
      }
    }
  }
  if (perm[0] == 0 && perm[1] == 1 && perm[2] == 2)
  {
    return; // the same frame
  }
  // The sender's frame: its corner 0 at the origin, corner 1 on the x axis, corner 2 above.
  const double ax = qx[perm[1]] - qx[perm[0]], ay = qy[perm[1]] - qy[perm[0]];
  const double bx = qx[perm[2]] - qx[perm[0]], by = qy[perm[2]] - qy[perm[0]];
  const double l = std::hypot(ax, ay);
  const double p2x = (ax * bx + ay * by) / l, p2y = std::abs(ax * by - ay * bx) / l;
  // Affine weights of (x, y) over the sender's corners, then the same weights here.
  const double v = y / p2y, u = (x - v * p2x) / l;
  x = qx[perm[0]] + u * ax + v * bx;
  y = qy[perm[0]] + u * ay + v * by;
}

std::int64_t VirtualSourcePieceSolve::Pack(std::vector<ByteBuffer>& out)
{
  out.assign(static_cast<std::size_t>(Comm.Size()), ByteBuffer());
  std::int64_t items = 0;
  for (const int f : LeavingFaces)
  {
    Listed[static_cast<std::size_t>(f)] = 0;
    const FaceRecord& r = Solver.Faces[f];
    ByteWriter put(out[static_cast<std::size_t>(Piece.FaceOwner(f))]);
    put.Put(FaceItem);
    put.Put(Piece.FaceId(f));
    for (const int v : Mesh.Face(f))
    {
      put.Put(Piece.GlobalId(v));
    }
    for (const double x : { r.Sx, r.Sy, r.Tx, r.Ty, r.Sigma, r.Key })
    {
      put.Put(x);
    }
    put.Put(EdgeName(f, r.Entry < 0 ? -1 : r.Entry % 3));
    put.Put(EdgeName(f, r.Except));
    // The funnel, in the same frame (NaN x: no bound).
    const VirtualSourceSolver::Funnel funnel =
      r.Funneled ? Solver.Funnels[static_cast<std::size_t>(f)] : VirtualSourceSolver::Open();
    for (const double x : { funnel.Lx, funnel.Ly, funnel.Rx, funnel.Ry })
    {
      put.Put(x);
    }
    ++items;
  }
  Sent += static_cast<std::int64_t>(LeavingFaces.size());
  LeavingFaces.clear();
  for (const int v : LeavingVertices)
  {
    VertexListed[static_cast<std::size_t>(v)] = 0;
    const int owner = Piece.Owner(v);
    assert(owner >= 0); // (a vertex of a face next to an own face: complete in two rings)
    if (owner < 0)
    {
      continue;
    }
    ByteWriter put(out[static_cast<std::size_t>(owner)]);
    put.Put(VertexItem);
    put.Put(Piece.GlobalId(v));
    put.Put(Solver.Dist[static_cast<std::size_t>(v)]);
    ++items;
  }
  LeavingVertices.clear();
  return items;
}

bool VirtualSourcePieceSolve::UnpackFace(ByteReader& r)
{
  std::int64_t id = 0, entry = 0, except = 0;
  std::array<std::int64_t, 3> corners{};
  double sx = 0, sy = 0, tx = 0, ty = 0, sigma = 0, key = 0;
  VirtualSourceSolver::Funnel funnel = VirtualSourceSolver::Open();
  if (!(r.Get(id) && r.Get(corners[0]) && r.Get(corners[1]) && r.Get(corners[2]) && r.Get(sx) &&
        r.Get(sy) && r.Get(tx) && r.Get(ty) && r.Get(sigma) && r.Get(key) && r.Get(entry) &&
        r.Get(except) && r.Get(funnel.Lx) && r.Get(funnel.Ly) && r.Get(funnel.Rx) &&
        r.Get(funnel.Ry)))
  {
    return false;
  }
  const int f = Piece.Face(id);
  if (f < 0 || !Piece.IsOwnFace(f))
  {
    return false;
  }
  ToLocalFrame(f, corners, sx, sy);
  ToLocalFrame(f, corners, tx, ty);
  ToLocalFrame(f, corners, funnel.Lx, funnel.Ly); // (a NaN x, no bound, stays NaN)
  ToLocalFrame(f, corners, funnel.Rx, funnel.Ry);
  FaceRecord& to = Solver.Faces[f];
  // The crossing's own rule (VirtualSourceSolver::Cross): a smaller key, or on a tie fewer bends.
  const double current = Solver.KeyOf(to), tol = Solver.Tolerance;
  if (!(key < current - tol || (key <= current + tol && sigma < to.Sigma - tol)))
  {
    return true;
  }
  const int entryEdge = EdgeOf(f, entry);
  Solver.SetSource(to, sx, sy, tx, ty, sigma, key, entryEdge < 0 ? -1 : 3 * f + entryEdge,
    EdgeOf(f, except), funnel);
  return true;
}

bool VirtualSourcePieceSolve::UnpackVertex(ByteReader& r)
{
  std::int64_t id = 0;
  double d = 0.0;
  if (!(r.Get(id) && r.Get(d)))
  {
    return false;
  }
  const int v = Piece.Vertex(id);
  if (v < 0 || !Piece.IsOwned(v))
  {
    return false;
  }
  if (d < Solver.Dist[static_cast<std::size_t>(v)])
  {
    Solver.Dist[static_cast<std::size_t>(v)] = d;
    Solver.PushVertex(v, d); // (only paths' bend vertices travel)
  }
  return true;
}

void VirtualSourcePieceSolve::Unpack(const std::vector<ByteBuffer>& in)
{
  // (Every item names a face or vertex of this process: the owners are the same everywhere.)
  ReadTaggedRecords(Comm, in, [this](std::uint8_t tag, ByteReader& r) {
    return tag == FaceItem ? UnpackFace(r) : tag == VertexItem && UnpackVertex(r);
  });
}

void VirtualSourcePieceSolve::Collect(double limit, VirtualSourcePiecesResult& result)
{
  const int nv = Mesh.NumberOfVertices();
  // The distances this process's crossings gave other processes' vertices, to their owners.
  std::vector<ByteBuffer> out(static_cast<std::size_t>(Comm.Size())), in;
  for (int v = 0; v < nv; ++v)
  {
    const double d = Solver.Dist[static_cast<std::size_t>(v)];
    if (!Piece.IsOwned(v) && Piece.Owner(v) >= 0 && d < Inf)
    {
      ByteWriter put(out[static_cast<std::size_t>(Piece.Owner(v))]);
      put.Put(Piece.GlobalId(v));
      put.Put(d);
    }
  }
  Comm.Exchange(out, in);
  ReadIdValuePairs(Comm, in, [this](std::int64_t id, double d) {
    const int v = Piece.Vertex(id);
    if (v >= 0 && Piece.IsOwned(v))
    {
      Solver.Dist[static_cast<std::size_t>(v)] = std::min(Solver.Dist[static_cast<std::size_t>(v)], d);
    }
  });
  result.Distance.assign(static_cast<std::size_t>(nv), std::numeric_limits<double>::quiet_NaN());
  for (int v = 0; v < nv; ++v)
  {
    if (Piece.IsOwned(v))
    {
      const double d = Solver.Dist[static_cast<std::size_t>(v)];
      result.Distance[static_cast<std::size_t>(v)] = d <= limit ? d : Inf;
    }
  }
  Piece.ValuesFromOwners(result.Distance, Comm);
}

Status VirtualSourcePieceSolve::Run(const std::vector<std::int64_t>& sources,
  const std::vector<SurfacePoint>& points, const std::vector<std::vector<CurvePiece>>& runs,
  double maxDistance, double longestEdge, const ProgressCallback& progress,
  VirtualSourcePiecesResult& result)
{
  Solver.BeginSolve();
  std::vector<int> owned;
  if (const Status own = Piece.OwnSources(sources, points, Comm, owned, runs.size()); !own.Ok())
  {
    return own;
  }
  // The serial solve's set-up (VirtualSourceSolver::Solve), for distances only.
  Solver.TrackAngles = false;
  const double limit = maxDistance > 0.0 && std::isfinite(maxDistance) ? maxDistance : Inf;
  Solver.Horizon = limit < Inf ? limit + longestEdge : Inf;
  Solver.Tolerance = 1e-12 * Solver.BucketWidth;
  std::vector<SurfacePoint> seeds;
  for (const int v : owned)
  {
    seeds.push_back(SurfacePoint::AtVertex(v));
  }
  seeds.insert(seeds.end(), points.begin(), points.end());
  Solver.SeedPoints(seeds);
  Solver.SeedRuns(runs, [this](int f) { return Piece.IsOwnFace(f); });

  // Each round's threshold: a step of the surface's size beyond the first bucket left anywhere.
  const double step =
    std::max(1.0, std::floor(Piece.LengthScale() / 64.0 / Solver.BucketWidth));
  const std::int64_t ownedCount = Piece.NumberOfOwnedVertices();
  while (true)
  {
    {
      std::vector<ByteBuffer> out, in;
      const std::int64_t items = Pack(out);
      ExchangeCounting(Comm, out, in, items);
      Unpack(in);
      ++result.Exchanges;
    }
    const double first = Comm.Min(FirstBucket());
    if (!(first < Inf))
    {
      break;
    }
    ++result.Rounds;
    ProcessUpTo(static_cast<std::size_t>(first + step));
    std::int64_t reached = 0;
    for (int v = 0; v < Mesh.NumberOfVertices(); ++v)
    {
      reached += Piece.IsOwned(v) && Solver.Dist[static_cast<std::size_t>(v)] < Inf ? 1 : 0;
    }
    if (!EveryProcessGoesOn(
          Comm, progress, ownedCount > 0 ? static_cast<double>(reached) / ownedCount : 1.0))
    {
      return Status::Aborted();
    }
  }
  result.Crossings = Solver.Stats.Crossings;
  result.FacesSent = Sent;
  Collect(limit, result);
  return Status();
}

Status ComputeVirtualSourcesOnPieces(SurfacePiece& piece, const std::vector<std::int64_t>& sources,
  double maxDistance, PieceCommunicator& comm, VirtualSourcePiecesResult& result,
  const ProgressCallback& progress, const std::vector<SurfacePoint>& points,
  const std::vector<std::vector<CurvePiece>>& runs)
{
  result = VirtualSourcePiecesResult();
  // Two rings: the faces across the own faces' edges, and the fans of their corners, whose
  // owners a crossing's distances go to.
  if (const Status grown = piece.GrowTo(1, points.size() + runs.size(), comm); !grown.Ok())
  {
    return grown;
  }
  // The whole surface's mean edge length (the serial solve's buckets and tolerance) and longest
  // edge (its horizon).
  const double mean = piece.MeanEdgeLength(comm);
  const double longest = comm.Max(piece.Mesh().LongestEdgeLength());
  VirtualSourcePieceSolve solve(piece, comm, mean);
  return solve.Run(sources, points, runs, maxDistance, longest, progress, result);
}

} // namespace gs
