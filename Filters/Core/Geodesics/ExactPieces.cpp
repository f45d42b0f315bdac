#include "ExactPieces.h"

#include "ExactGeodesic.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();

// What travels between processes, each item after a tag.
enum ItemTag : std::uint8_t
{
  WindowItem = 1,
  VertexItem = 2
};

// A vertex's fan as every process holding it sees it: the direction towards its neighbour of
// smallest global id, and the neighbour that follows it counter-clockwise (-1: none, the end of
// a boundary fan). Two processes whose meshes orient the fan alike see the same follower.
struct FanReference
{
  double Angle = 0.0;
  std::int64_t Follower = -1;
};
} // namespace

// Drives an ExactGeodesicSolver on one piece through its Route (a friend of the solver).
class ExactPieceSolve
{
public:
  ExactPieceSolve(const SurfacePiece& piece, PieceCommunicator& comm)
    : Piece(piece)
    , Mesh(piece.Mesh())
    , Comm(comm)
    , Solver(piece.Mesh(), piece.LengthScale())
  {
    const int nf = Mesh.NumberOfFaces(), nv = Mesh.NumberOfVertices();
    OtherFace.resize(static_cast<std::size_t>(nf));
    for (int f = 0; f < nf; ++f)
    {
      OtherFace[static_cast<std::size_t>(f)] = Piece.IsOwnFace(f) ? 0 : 1;
    }
    OtherVertex.resize(static_cast<std::size_t>(nv));
    for (int v = 0; v < nv; ++v)
    {
      OtherVertex[static_cast<std::size_t>(v)] = Piece.IsOwned(v) ? 0 : 1;
    }
    Route.OtherFace = &OtherFace;
    Route.OtherVertex = &OtherVertex;
    Route.Listed.assign(static_cast<std::size_t>(nv), 0);
    Solver.Route = &Route;
  }
  ~ExactPieceSolve() { Solver.Route = nullptr; }
  ExactPieceSolve(const ExactPieceSolve&) = delete;
  ExactPieceSolve& operator=(const ExactPieceSolve&) = delete;

  Status Run(const std::vector<std::int64_t>& sources, const std::vector<SurfacePoint>& points,
    double maxDistance, const ProgressCallback& progress, ExactPiecesResult& result);

private:
  using Window = ExactGeodesicSolver::Window;
  // Adds the vertex sources this process owns and its surface points; fails on every process
  // when a vertex is owned by none or there is no source.
  Status AddSources(
    const std::vector<std::int64_t>& sources, const std::vector<SurfacePoint>& points);
  // Propagates the queued windows of keys up to `threshold`, in key order.
  void ProcessUpTo(double threshold);
  // What left this process since the last exchange, into one buffer per process; returns the
  // number of items.
  std::int64_t Pack(std::vector<ByteBuffer>& out);
  void Unpack(const std::vector<ByteBuffer>& in);
  bool UnpackWindow(ByteReader& r);
  bool UnpackVertex(ByteReader& r);
  FanReference Reference(int v) const;
  // The distances of the own faces' vertices, the others' from their owners.
  void Collect(double limit, ExactPiecesResult& result);

  const SurfacePiece& Piece;
  const TriangleMesh& Mesh;
  PieceCommunicator& Comm;
  ExactGeodesicSolver Solver;
  ExactGeodesicSolver::PieceRoute Route;
  std::vector<unsigned char> OtherFace, OtherVertex;
  std::int64_t Sent = 0;
  bool Mirrored = false; // a window came from a piece whose faces turn the other way
  mutable std::vector<std::pair<std::int64_t, double>> Spokes; // Reference's scratch
};

FanReference ExactPieceSolve::Reference(int v) const
{
  // The spokes (neighbour id, fan angle) counter-clockwise; a boundary fan ends at its last
  // neighbour, at the total angle.
  Spokes.clear();
  int last = -1;
  Mesh.ForEachOutgoingHalfedge(v, [&](int h) {
    const double angle = Solver.FanAngle[static_cast<std::size_t>(h)];
    Spokes.push_back({ Piece.GlobalId(Mesh.Destination(h)), angle });
    last = h;
  });
  const bool boundary = Mesh.IsBoundaryVertex(v);
  if (boundary && last >= 0)
  {
    Spokes.push_back({ Piece.GlobalId(Mesh.Origin(TriangleMesh::Prev(last))), Mesh.TotalAngle(v) });
  }
  FanReference ref;
  if (Spokes.empty())
  {
    return ref;
  }
  std::size_t best = 0;
  for (std::size_t i = 1; i < Spokes.size(); ++i)
  {
    best = Spokes[i].first < Spokes[best].first ? i : best;
  }
  ref.Angle = Spokes[best].second;
  ref.Follower = best + 1 < Spokes.size() ? Spokes[best + 1].first
    : boundary                            ? -1
                                          : Spokes[0].first;
  return ref;
}

Status ExactPieceSolve::AddSources(
  const std::vector<std::int64_t>& sources, const std::vector<SurfacePoint>& points)
{
  std::vector<int> owned;
  if (const Status own = Piece.OwnSources(sources, points, Comm, owned); !own.Ok())
  {
    return own;
  }
  int i = 0;
  for (const int v : owned)
  {
    Solver.AddSource(i++, SurfacePoint::AtVertex(v));
  }
  for (const SurfacePoint& p : points)
  {
    Solver.AddSource(i++, p);
  }
  return Status();
}

void ExactPieceSolve::ProcessUpTo(double threshold)
{
  while (!Solver.Queue.Empty() && Solver.Queue.MinKey() <= threshold)
  {
    Solver.Handle(Solver.Dequeue());
  }
}

std::int64_t ExactPieceSolve::Pack(std::vector<ByteBuffer>& out)
{
  out.assign(static_cast<std::size_t>(Comm.Size()), ByteBuffer());
  std::int64_t items = 0;
  for (const Window& w : Route.Leaving)
  {
    const int f = w.H / 3;
    ByteWriter put(out[static_cast<std::size_t>(Piece.FaceOwner(f))]);
    put.Put(WindowItem);
    // The edge, and the face's third corner (the face across the edge has another).
    put.Put(Piece.GlobalId(Mesh.Origin(w.H)));
    put.Put(Piece.GlobalId(Mesh.Destination(w.H)));
    put.Put(Piece.GlobalId(Mesh.Opposite(w.H)));
    for (const double x : { w.Key, w.B0, w.B1, w.Ix, w.Iy, w.Sigma, w.Phi })
    {
      put.Put(x);
    }
    // A pseudo-source vertex is named by its local number: elsewhere it is just "not direct".
    put.Put(w.Src >= 0 ? w.Src : -1);
    put.Put(w.Root);
    ++items;
  }
  Sent += static_cast<std::int64_t>(Route.Leaving.size());
  Route.Leaving.clear();
  for (const int v : Route.LeavingVertices)
  {
    Route.Listed[static_cast<std::size_t>(v)] = 0;
    const int owner = Piece.Owner(v);
    if (owner < 0)
    {
      continue; // (vertices of own faces and their neighbours are complete)
    }
    // The arrival direction, from the fan's reference; NaN stays NaN.
    const FanReference ref = Reference(v);
    double in = Solver.InAngle[static_cast<std::size_t>(v)].Value() - ref.Angle;
    if (!Mesh.IsBoundaryVertex(v) && std::isfinite(in))
    {
      const double total = Mesh.TotalAngle(v);
      in -= total * std::floor(in / total);
    }
    ByteWriter put(out[static_cast<std::size_t>(owner)]);
    put.Put(VertexItem);
    put.Put(Piece.GlobalId(v));
    put.Put(Solver.Dist[static_cast<std::size_t>(v)]);
    put.Put(in);
    put.Put(Solver.Departure[static_cast<std::size_t>(v)].Value());
    put.Put(ref.Follower);
    ++items;
  }
  Route.LeavingVertices.clear();
  return items;
}

bool ExactPieceSolve::UnpackWindow(ByteReader& r)
{
  std::int64_t a = 0, b = 0, c = 0;
  Window w;
  if (!(r.Get(a) && r.Get(b) && r.Get(c) && r.Get(w.Key) && r.Get(w.B0) && r.Get(w.B1) &&
        r.Get(w.Ix) && r.Get(w.Iy) && r.Get(w.Sigma) && r.Get(w.Phi) && r.Get(w.Src) &&
        r.Get(w.Root)))
  {
    return false;
  }
  const int va = Piece.Vertex(a), vb = Piece.Vertex(b), vc = Piece.Vertex(c);
  if (va < 0 || vb < 0 || vc < 0)
  {
    return false;
  }
  // The half-edge between a and b in the face whose third corner is c.
  int h = -1;
  Mesh.ForEachOutgoingHalfedge(va, [&](int e) {
    const int back = TriangleMesh::Prev(e); // into a, in e's face
    if (Mesh.Destination(e) == vb && Mesh.Opposite(e) == vc)
    {
      h = e;
    }
    else if (Mesh.Origin(back) == vb && Mesh.Destination(e) == vc)
    {
      h = back; // the face runs b -> a here
    }
  });
  if (h < 0 || !Piece.IsOwnFace(h / 3))
  {
    return false;
  }
  w.H = h;
  if (Mesh.Origin(h) != va)
  {
    // The face is oriented the other way here: the same frame mirrored along the edge (y still
    // points into the face). (A window seen from the source itself no longer reads its
    // departure angles as Phi plus an angle; one behind a pseudo-source keeps Phi.)
    Mirrored = Mirrored || w.Src >= 0;
    const double L = Mesh.EdgeLength(h), b0 = w.B0;
    w.Ix = L - w.Ix;
    w.B0 = std::max(0.0, L - w.B1);
    w.B1 = std::min(L, L - b0);
  }
  Solver.PushWindow(w);
  return true;
}

bool ExactPieceSolve::UnpackVertex(ByteReader& r)
{
  std::int64_t id = 0, follower = 0;
  double d = 0.0, in = 0.0, departure = 0.0;
  if (!(r.Get(id) && r.Get(d) && r.Get(in) && r.Get(departure) && r.Get(follower)))
  {
    return false;
  }
  const int v = Piece.Vertex(id);
  if (v < 0 || !Piece.IsOwned(v))
  {
    return false;
  }
  ExactGeodesicSolver::LazyAngle arrival;
  if (std::isfinite(in))
  {
    const FanReference ref = Reference(v);
    double local = follower == ref.Follower ? ref.Angle + in : ref.Angle - in;
    if (!Mesh.IsBoundaryVertex(v))
    {
      const double total = Mesh.TotalAngle(v);
      local -= total * std::floor(local / total);
    }
    arrival = ExactGeodesicSolver::LazyAngle::Exactly(local);
  }
  Solver.UpdateVertex(v, d, -1, -1, 0.0, arrival, ExactGeodesicSolver::LazyAngle::Exactly(departure), 0);
  return true;
}

void ExactPieceSolve::Unpack(const std::vector<ByteBuffer>& in)
{
  // (Every item names a face or vertex of this process: the owners are the same everywhere.)
  ReadTaggedRecords(Comm, in, [this](std::uint8_t tag, ByteReader& r) {
    return tag == WindowItem ? UnpackWindow(r) : tag == VertexItem && UnpackVertex(r);
  });
}

void ExactPieceSolve::Collect(double limit, ExactPiecesResult& result)
{
  const int nv = Mesh.NumberOfVertices();
  result.Distance.assign(static_cast<std::size_t>(nv), std::numeric_limits<double>::quiet_NaN());
  result.Departure.assign(static_cast<std::size_t>(nv), std::numeric_limits<double>::quiet_NaN());
  const bool angles = Comm.Max(Mirrored ? 1.0 : 0.0) == 0.0;
  for (int v = 0; v < nv; ++v)
  {
    if (Piece.IsOwned(v))
    {
      const double d = Solver.Dist[static_cast<std::size_t>(v)];
      result.Distance[static_cast<std::size_t>(v)] = d <= limit ? d : Inf;
      if (angles && d <= limit)
      {
        result.Departure[static_cast<std::size_t>(v)] = Solver.Departure[static_cast<std::size_t>(v)].Value();
      }
    }
  }
  Piece.ValuesFromOwners(result.Distance, Comm);
}

Status ExactPieceSolve::Run(const std::vector<std::int64_t>& sources,
  const std::vector<SurfacePoint>& points, double maxDistance, const ProgressCallback& progress,
  ExactPiecesResult& result)
{
  Solver.Reset();
  Solver.Fenced.Start(nullptr, Mesh.NumberOfFaces());
  if (const Status added = AddSources(sources, points); !added.Ok())
  {
    return added;
  }
  const double limit = maxDistance > 0.0 && std::isfinite(maxDistance) ? maxDistance : Inf;
  // Each round's threshold: a step of the surface's size beyond the smallest key left anywhere
  // (dozens of rounds over a surface; each round's passes settle what crossed between pieces).
  const double step = std::max(Piece.LengthScale() / 64.0, 1e-300);
  const std::int64_t owned = Piece.NumberOfOwnedVertices();
  std::size_t counted = 0;
  std::int64_t reached = 0;
  // What the sources sent elsewhere first (a source whose windows all enter other processes'
  // faces queues nothing here).
  {
    std::vector<ByteBuffer> out, in;
    const std::int64_t items = Pack(out);
    ExchangeCounting(Comm, out, in, items);
    Unpack(in);
    ++result.Exchanges;
  }
  while (true)
  {
    const double lowest = Comm.Min(Solver.Queue.MinKey());
    if (!(lowest < Inf) || lowest > limit)
    {
      break;
    }
    const double threshold = std::min(lowest + step, limit);
    ++result.Rounds;
    std::int64_t moved = 0;
    do
    {
      ProcessUpTo(threshold);
      std::vector<ByteBuffer> out, in;
      const std::int64_t items = Pack(out);
      moved = ExchangeCounting(Comm, out, in, items);
      Unpack(in);
      ++result.Exchanges;
    } while (moved > 0);
    for (; counted < Solver.Touched.size(); ++counted)
    {
      reached += Piece.IsOwned(Solver.Touched[counted]) ? 1 : 0;
    }
    if (!EveryProcessGoesOn(
          Comm, progress, owned > 0 ? static_cast<double>(reached) / owned : 1.0))
    {
      return Status::Aborted();
    }
  }
  result.WindowsPropagated = Solver.Stats.WindowsPropagated;
  result.WindowsSent = Sent;
  Collect(limit, result);
  return Status();
}

Status ComputeExactOnPieces(SurfacePiece& piece, const std::vector<std::int64_t>& sources,
  double maxDistance, PieceCommunicator& comm, ExactPiecesResult& result,
  const ProgressCallback& progress, const std::vector<SurfacePoint>& points)
{
  result = ExactPiecesResult();
  // Two rings: the fans of the vertices of the own faces, and the faces across their outer
  // edges, where an owned vertex's windows start.
  if (const Status grown = piece.GrowTo(1, points.size(), comm); !grown.Ok())
  {
    return grown;
  }
  ExactPieceSolve solve(piece, comm);
  return solve.Run(sources, points, maxDistance, progress, result);
}

} // namespace gs
