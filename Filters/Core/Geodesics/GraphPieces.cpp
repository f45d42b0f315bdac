#include "GraphPieces.h"

#include "DiscreteGeodesicGraph.h"
#include "ExactGeodesic.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <unordered_map>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();

// GraphDistanceSolver's label-correcting queue over a distance array: a circular deque holding
// each vertex at most once; SLF (a vertex whose new label is below the front's goes to the
// front), LLL (a front vertex whose label exceeds the queue's mean goes to the back before
// extraction).
class LabelQueue
{
public:
  explicit LabelQueue(std::vector<double>& dist)
    : Dist(dist)
    , Ring(dist.size() + 1)
    , Queued(dist.size(), 0)
  {
  }
  bool Empty() const { return Count == 0; }
  // Queues v (at its current distance) unless it is queued.
  void Push(int v)
  {
    if (Queued[static_cast<std::size_t>(v)])
    {
      return;
    }
    const double d = Dist[static_cast<std::size_t>(v)];
    Queued[static_cast<std::size_t>(v)] = 1;
    Sum += d;
    if (Count > 0 && d < Dist[static_cast<std::size_t>(Ring[Head])])
    {
      Head = Head == 0 ? Ring.size() - 1 : Head - 1;
      Ring[Head] = v;
    }
    else
    {
      Ring[Wrap(Head + Count)] = v;
    }
    ++Count;
  }
  // v's distance becomes d (smaller), and v is queued.
  void Lower(int v, double d)
  {
    double& dv = Dist[static_cast<std::size_t>(v)];
    if (Queued[static_cast<std::size_t>(v)])
    {
      Sum += d - dv;
      dv = d;
      return;
    }
    dv = d;
    Push(v);
  }
  int Pop()
  {
    const double mean = Sum / static_cast<double>(Count);
    for (std::size_t tries = 0; tries < Count && Dist[static_cast<std::size_t>(Ring[Head])] > mean;
         ++tries)
    {
      const int v = Ring[Head];
      Head = Wrap(Head + 1);
      Ring[Wrap(Head + Count - 1)] = v;
    }
    const int u = Ring[Head];
    Head = Wrap(Head + 1);
    --Count;
    Queued[static_cast<std::size_t>(u)] = 0;
    Sum = Count == 0 ? 0.0 : Sum - Dist[static_cast<std::size_t>(u)]; // (no drift across emptyings)
    return u;
  }

private:
  std::size_t Wrap(std::size_t i) const { return i >= Ring.size() ? i - Ring.size() : i; }
  std::vector<double>& Dist;
  std::vector<int> Ring;
  std::vector<unsigned char> Queued;
  std::size_t Head = 0, Count = 0;
  double Sum = 0.0;
};

// The band a solve of `options` needs at first, in rings of faces around the own faces (the
// K-nearest disk of a regular mesh has about 3 r^2 vertices within r rings; a discrete geodesic
// graph's propagation reaches farther): too narrow only costs a second solve of the vertices
// near the piece's edge.
int InitialRings(const SaddleVertexGraphOptions& options, int k)
{
  if (options.Construction == GraphConstruction::DiscreteGeodesic)
  {
    return 8;
  }
  return static_cast<int>(std::ceil(std::sqrt(k / 3.0))) + 2;
}
} // namespace

int PieceGraph::Encode(std::int64_t globalId) const
{
  const int t = OwnedIndex(globalId);
  return t >= 0 ? t
                : -1 - static_cast<int>(std::lower_bound(RemoteIds.begin(), RemoteIds.end(), globalId) -
                    RemoteIds.begin());
}

int PieceGraph::OwnedIndex(std::int64_t globalId) const
{
  const auto it = std::lower_bound(OwnedIds.begin(), OwnedIds.end(), globalId);
  return it != OwnedIds.end() && *it == globalId ? static_cast<int>(it - OwnedIds.begin()) : -1;
}

Status PieceGraph::Build(SurfacePiece& piece, const SaddleVertexGraphOptions& options,
  PieceCommunicator& comm, const ProgressCallback& progress)
{
  const auto start = std::chrono::steady_clock::now();
  OwnedIds.clear();
  Offsets.assign(1, 0);
  StencilOffsets.assign(1, 0);
  Stencil.reset();
  WrapXY.clear();
  Interior.clear();
  Targets.clear();
  Weights.clear();
  RemoteIds.clear();
  RemoteOwners.clear();
  GlobalEntries = Resolved = 0;
  if (const Status valid = SaddleVertexGraph::CheckOptions(options); !valid.Ok())
  {
    return valid; // (the same options on every process: every one fails)
  }
  Construction = options.Construction;
  Accuracy = Construction == GraphConstruction::DiscreteGeodesic ? options.Accuracy : 0.0;
  const int k = SaddleVertexGraph::EffectiveK(options,
    static_cast<int>(std::min<std::int64_t>(piece.GlobalNumberOfVertices(),
      std::numeric_limits<int>::max())));
  DiskSize = SaddleVertexGraph::LocalDiskSizeFor(
    Construction, k, Accuracy, piece.GlobalNumberOfVertices());
  if (piece.Rings() < InitialRings(options, k))
  {
    if (const Status grown = piece.Grow(InitialRings(options, k) - piece.Rings(), comm);
        !grown.Ok())
    {
      return grown;
    }
  }
  // The build's memory, estimated as SaddleVertexGraph::Build does for the piece's vertices
  // (the band's included): refused on every process when one would exceed 80% of its memory.
  const double estimate =
    SaddleVertexGraph::EstimatedBuildBytes(piece.Mesh().NumberOfVertices(), options);
  const double available = SaddleVertexGraph::AvailableMemoryBytes();
  const bool tooLarge = available > 0 && estimate > 0.8 * available;
  if (comm.Sum(tooLarge ? 1 : 0) > 0)
  {
    return Status::Error(tooLarge
        ? "the graph of this process's piece (" + std::to_string(piece.Mesh().NumberOfVertices()) +
          " vertices with its band) needs about " +
          std::to_string(static_cast<long long>(estimate / 1048576.0)) + " MiB while building, more than the " +
          std::to_string(static_cast<long long>(available / 1048576.0)) +
          " MiB available; run on more processes, or ask for a smaller K or a coarser accuracy"
        : "another process's piece needs more memory than it has to build its graph");
  }
  for (int v = 0; v < piece.Mesh().NumberOfVertices(); ++v)
  {
    if (piece.IsOwned(v))
    {
      OwnedIds.push_back(piece.GlobalId(v));
    }
  }
  // OwnedIds is sorted: the piece numbers its vertices in global id order.

  std::vector<OwnedSolve> found(OwnedIds.size());
  if (const Status solved = SolveOwned(piece, options, k, comm, progress, found); !solved.Ok())
  {
    return solved;
  }
  BandRings = piece.Rings();
  Assemble(piece, found, comm);
  Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (progress)
  {
    static_cast<void>(progress(1.0));
  }
  return Status();
}

// One thread's solves from owned vertices on the piece (as SaddleVertexGraph's build solves):
// the links and the polar stencil of a vertex, and whether the solve reached the piece's fence.
struct PieceGraph::VertexSolver
{
  VertexSolver(const SurfacePiece& piece, const SaddleVertexGraphOptions& options, int k)
    : Piece(piece)
    , Dgg(options.Construction == GraphConstruction::DiscreteGeodesic)
    , ReachedStencil(Dgg && options.ReachedStencil)
    , Epsilon(SaddleVertexGraph::DiscreteGeodesicEpsilon(options.Accuracy))
  {
    // (Each engine allocates per-vertex state: only the one this graph uses is made.)
    if (Dgg)
    {
      Propagation.reset(new DGGPropagation(piece.Mesh(), piece.LengthScale()));
      Propagation->SetFence(&piece.Fence());
    }
    else
    {
      Solver.reset(new ExactGeodesicSolver(piece.Mesh(), piece.LengthScale()));
    }
    Options.MaximumFinalVertices = k;
    Options.Fence = &piece.Fence();
  }

  // Solves from piece vertex s into `made`; true when the solve reached the fence, and then
  // `where` gets the incomplete vertices (global ids) where it did.
  bool operator()(int s, OwnedSolve& made, std::vector<std::int64_t>& where)
  {
    const std::size_t before = where.size();
    Links.clear();
    Reached.clear();
    if (Dgg)
    {
      Propagation->Run(s, Epsilon, Links, ReachedStencil ? &Reached : nullptr);
      Piece.AppendIncompleteVertices(Propagation->FenceFacesEntered(), where);
    }
    else
    {
      static_cast<void>(Solver->Solve(s, Options)); // s is a vertex of the mesh: accepted
      Piece.AppendIncompleteVertices(Solver->FenceFacesEntered(), where);
      for (const int v : Solver->FinalVertices())
      {
        if (v != s && Solver->IsDirect(v))
        {
          Links.push_back({ v, Solver->Distance(v), Solver->DepartureAngle(v) });
        }
      }
    }
    // (Sized exactly: these lists are most of the build's memory until they are assembled.)
    made.Links.resize(Links.size());
    for (std::size_t j = 0; j < Links.size(); ++j)
    {
      made.Links[j] = { Piece.GlobalId(Links[j].Target), Links[j].Distance };
    }
    // The polar stencil, as SaddleVertexGraph lays it out.
    const std::size_t nl = Links.size();
    auto item = [&](std::size_t j) -> const DGGPropagation::Link& {
      return j < nl ? Links[j] : Reached[j - nl];
    };
    made.Stencil.resize(nl + Reached.size());
    LayOutPolarStencil(
      made.Stencil.size(), [&](std::size_t j) { return item(j).Distance; },
      [&](std::size_t j) { return item(j).Angle; }, Piece.Mesh().TotalAngle(s), Order,
      [&](std::size_t at, std::size_t j, double x, double y) {
        if (!Piece.IsComplete(item(j).Target))
        {
          where.push_back(Piece.GlobalId(item(j).Target));
        }
        made.Stencil[at] = { x, y, Piece.GlobalId(item(j).Target) };
      },
      made.WrapX, made.WrapY);
    made.Interior = !Piece.Mesh().IsBoundaryVertex(s);
    return where.size() > before;
  }

  const SurfacePiece& Piece;
  const bool Dgg, ReachedStencil;
  const double Epsilon;
  std::unique_ptr<ExactGeodesicSolver> Solver;
  std::unique_ptr<DGGPropagation> Propagation;
  ExactGeodesicOptions Options;
  std::vector<DGGPropagation::Link> Links, Reached;
  std::vector<int> Order;
};

Status PieceGraph::SolveOwned(SurfacePiece& piece, const SaddleVertexGraphOptions& options, int k,
  PieceCommunicator& comm, const ProgressCallback& progress, std::vector<OwnedSolve>& found)
{
  const int threads = options.NumberOfThreads > 0 ? options.NumberOfThreads : omp_get_max_threads();
  std::vector<std::int64_t> pending = OwnedIds;
  const std::size_t total = std::max<std::size_t>(OwnedIds.size(), 1);
  int growth = piece.Rings() / 2;
  std::size_t solved = 0;
  while (true)
  {
    std::vector<unsigned char> fenced(pending.size(), 0);
    std::vector<std::vector<std::int64_t>> where(pending.size());
    std::atomic<bool> aborted(false);
    std::atomic<std::size_t> done(0);
#pragma omp parallel num_threads(threads)
    {
      VertexSolver solve(piece, options, k);
      int count = 0;
#pragma omp for schedule(dynamic, 64)
      for (std::int64_t i = 0; i < static_cast<std::int64_t>(pending.size()); ++i)
      {
        if (aborted.load(std::memory_order_relaxed))
        {
          continue;
        }
        const std::int64_t id = pending[static_cast<std::size_t>(i)];
        OwnedSolve made;
        const bool outside = solve(piece.Vertex(id), made, where[static_cast<std::size_t>(i)]);
        found[static_cast<std::size_t>(OwnedIndex(id))] = std::move(made);
        fenced[static_cast<std::size_t>(i)] = outside ? 1 : 0;
        const std::size_t n = ++done;
#ifdef _OPENMP
        const bool master = omp_get_thread_num() == 0;
#else
        const bool master = true;
#endif
        if (master && progress && (++count % 16 == 0) &&
          !progress(0.9 * static_cast<double>(solved + n) / static_cast<double>(total)))
        {
          aborted = true;
        }
      }
    }
    std::vector<std::int64_t> again, around;
    for (std::size_t i = 0; i < pending.size(); ++i)
    {
      if (fenced[i])
      {
        again.push_back(pending[i]);
        around.insert(around.end(), where[i].begin(), where[i].end());
      }
    }
    where.clear();
    solved += pending.size() - again.size();
    if (comm.Sum(aborted ? 1 : 0) > 0)
    {
      return Status::Aborted();
    }
    const std::int64_t left = comm.Sum(static_cast<std::int64_t>(again.size()));
    if (left == 0)
    {
      break;
    }
    Resolved += left;
    pending.swap(again);
    // The band grows where the solves reached its edge, by rings that double each time.
    growth = std::max(2 * growth, 1);
    if (const Status grown = piece.GrowAround(around, growth, comm); !grown.Ok())
    {
      return grown;
    }
  }
  return Status();
}

void PieceGraph::Assemble(
  const SurfacePiece& piece, std::vector<OwnedSolve>& found, PieceCommunicator& comm)
{
  // The reverse of each link whose target another process owns goes to that process.
  const int me = comm.Rank();
  const std::size_t n = OwnedIds.size();
  auto ownerOf = [&piece](std::int64_t id) { return piece.Owner(piece.Vertex(id)); };
  std::vector<ByteBuffer> outgoing(static_cast<std::size_t>(comm.Size())), incoming;
  for (std::size_t i = 0; i < n; ++i)
  {
    for (const FoundLink& l : found[i].Links)
    {
      const int owner = ownerOf(l.Target);
      if (owner != me)
      {
        ByteWriter w(outgoing[static_cast<std::size_t>(owner)]);
        w.Put(l.Target);
        w.Put(OwnedIds[i]);
        w.Put(l.Weight);
      }
    }
  }
  comm.Exchange(outgoing, incoming);
  outgoing.clear();

  // Both directions of every link and mesh edge, bucketed by owned vertex (counted, then
  // filled: one array of raw entries), then each bucket sorted with the smallest weight kept per
  // target. Received sources' owners are their senders.
  const TriangleMesh& mesh = piece.Mesh();
  std::unordered_map<std::int64_t, int> sentBy;
  std::vector<std::int64_t> count(n + 1, 0);
  auto forEachEntry = [&](const auto& add) {
    for (std::size_t i = 0; i < n; ++i)
    {
      for (const FoundLink& l : found[i].Links)
      {
        add(i, l.Target, l.Weight);
        const int t = OwnedIndex(l.Target);
        if (t >= 0)
        {
          add(static_cast<std::size_t>(t), OwnedIds[i], l.Weight);
        }
      }
      mesh.ForEachOutgoingHalfedge(piece.Vertex(OwnedIds[i]), [&](int h) {
        add(i, piece.GlobalId(mesh.Destination(h)), mesh.EdgeLength(h));
        add(i, piece.GlobalId(mesh.Origin(TriangleMesh::Prev(h))),
          mesh.EdgeLength(TriangleMesh::Prev(h)));
      });
    }
    for (std::size_t q = 0; q < incoming.size(); ++q)
    {
      ByteReader r(incoming[q]);
      std::int64_t target = 0, source = 0;
      double weight = 0.0;
      while (static_cast<int>(q) != me && r.Get(target) && r.Get(source) && r.Get(weight))
      {
        const int i = OwnedIndex(target);
        if (i >= 0)
        {
          add(static_cast<std::size_t>(i), source, weight);
          sentBy.emplace(source, static_cast<int>(q));
        }
      }
    }
  };
  forEachEntry([&count](std::size_t i, std::int64_t, double) { ++count[i + 1]; });
  for (std::size_t i = 0; i < n; ++i)
  {
    count[i + 1] += count[i];
  }
  std::vector<RawEntry> raw(static_cast<std::size_t>(count[n]));
  {
    std::vector<std::int64_t> fill(count.begin(), count.end() - 1);
    forEachEntry([&](std::size_t i, std::int64_t target, double weight) {
      raw[static_cast<std::size_t>(fill[i]++)] = { target, weight };
    });
  }
  incoming.clear();
  for (OwnedSolve& f : found)
  {
    std::vector<FoundLink>().swap(f.Links);
  }
  ReturnFreedMemory();
  GlobalEntries = comm.Sum(Compact(piece, raw, count, sentBy, found));
}

std::int64_t PieceGraph::Compact(const SurfacePiece& piece, std::vector<RawEntry>& raw,
  const std::vector<std::int64_t>& count, const std::unordered_map<std::int64_t, int>& sentBy,
  std::vector<OwnedSolve>& found)
{
  const std::size_t n = OwnedIds.size();
  Offsets.assign(n + 1, 0);
  std::int64_t kept = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto first = raw.begin() + count[i], last = raw.begin() + count[i + 1];
    std::sort(first, last);
    for (auto it = first; it != last; ++it)
    {
      if (it == first || (it - 1)->Target != it->Target)
      {
        raw[static_cast<std::size_t>(kept++)] = *it; // (kept <= it: in place)
      }
    }
    Offsets[i + 1] = kept;
  }
  raw.resize(static_cast<std::size_t>(kept)); // (not shrunk: a copy would double it)

  // Remote targets (of links and stencils) get slots (in id order); entries hold owned numbers
  // or slots.
  for (const RawEntry& e : raw)
  {
    if (OwnedIndex(e.Target) < 0)
    {
      RemoteIds.push_back(e.Target);
    }
  }
  for (const OwnedSolve& f : found)
  {
    for (const StencilItem& item : f.Stencil)
    {
      if (OwnedIndex(item.Target) < 0)
      {
        RemoteIds.push_back(item.Target);
      }
    }
  }
  std::sort(RemoteIds.begin(), RemoteIds.end());
  RemoteIds.erase(std::unique(RemoteIds.begin(), RemoteIds.end()), RemoteIds.end());
  RemoteOwners.resize(RemoteIds.size());
  for (std::size_t r = 0; r < RemoteIds.size(); ++r)
  {
    const int v = piece.Vertex(RemoteIds[r]);
    const int owner = v >= 0 ? piece.Owner(v) : -1;
    RemoteOwners[r] = owner >= 0 ? owner : sentBy.at(RemoteIds[r]);
  }
  RemoteIds.shrink_to_fit();
  Targets.resize(raw.size());
  Weights.resize(raw.size());
  for (std::size_t e = 0; e < raw.size(); ++e)
  {
    Targets[e] = Encode(raw[e].Target);
    Weights[e] = raw[e].Weight;
  }
  std::vector<RawEntry>().swap(raw);
  // The stencils, in one array.
  StencilOffsets.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    StencilOffsets[i + 1] = StencilOffsets[i] + static_cast<std::int64_t>(found[i].Stencil.size());
  }
  // (Allocated without being written: its pages become resident as the slabs below fill it,
  // while the vertices' own lists are freed and handed back to the system after each slab, so
  // that the two are never both resident whole; as SaddleVertexGraph's build gathers.)
  Stencil.reset(new StencilEntry[static_cast<std::size_t>(StencilOffsets[n])]);
  WrapXY.resize(2 * n);
  Interior.resize(n);
  constexpr std::size_t slabs = 16;
  for (std::size_t slab = 0; slab < slabs; ++slab)
  {
    for (std::size_t i = n * slab / slabs; i < n * (slab + 1) / slabs; ++i)
    {
      for (std::size_t j = 0; j < found[i].Stencil.size(); ++j)
      {
        const StencilItem& item = found[i].Stencil[j];
        Stencil[static_cast<std::size_t>(StencilOffsets[i]) + j] = { item.X, item.Y,
          Encode(item.Target) };
      }
      WrapXY[2 * i] = found[i].WrapX;
      WrapXY[2 * i + 1] = found[i].WrapY;
      Interior[i] = found[i].Interior ? 1 : 0;
      found[i] = OwnedSolve();
    }
    ReturnFreedMemory();
  }
  return kept;
}

PieceDistanceSolver::PieceDistanceSolver(const PieceGraph& graph)
  : Graph(graph)
{
}

Status PieceDistanceSolver::Solve(const std::vector<std::pair<std::int64_t, double>>& seeds,
  double maxDistance, PieceCommunicator& comm, bool refine)
{
  const double limit = maxDistance > 0.0 ? maxDistance : Inf;
  const std::size_t n = static_cast<std::size_t>(Graph.NumberOfOwned());
  Dist.assign(n, Inf);
  Pred.assign(n, -1);
  NumRounds = RefinementRounds = 0;
  std::vector<std::int64_t> ids;
  for (const auto& s : seeds)
  {
    ids.push_back(s.first);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::int64_t mine = 0;
  for (const std::int64_t id : ids)
  {
    mine += Graph.OwnedIndex(id) >= 0 ? 1 : 0;
  }
  if (comm.Sum(mine) != static_cast<std::int64_t>(ids.size()) || ids.empty())
  {
    return Status::Error(ids.empty() ? "no source given"
                                     : "a source vertex id is not a point of the surface");
  }
  std::vector<int> owned;
  for (const auto& s : seeds)
  {
    const int i = Graph.OwnedIndex(s.first);
    if (i >= 0 && s.second <= limit && s.second < Dist[static_cast<std::size_t>(i)])
    {
      Dist[static_cast<std::size_t>(i)] = s.second;
      owned.push_back(i);
    }
  }
  SolveGraph(owned, limit, comm);
  if (refine)
  {
    Refine(owned, limit, comm);
  }
  return Status();
}

void PieceDistanceSolver::SolveGraph(
  const std::vector<int>& seeds, double limit, PieceCommunicator& comm)
{
  // (Any order of relaxation gives the same distances: the serial solver's queue.)
  LabelQueue queue(Dist);
  for (const int i : seeds)
  {
    queue.Push(i);
  }
  // v reached at d through u (global id): the smaller distance, or on a tie the predecessor of
  // smaller id (GraphDistanceSolver's rule), a seed keeping none.
  auto offer = [&](int v, double d, std::int64_t u) {
    double& dv = Dist[static_cast<std::size_t>(v)];
    std::int64_t& pv = Pred[static_cast<std::size_t>(v)];
    if (d < dv)
    {
      pv = u;
      queue.Lower(v, d);
    }
    else if (d == dv && pv >= 0 && u < pv)
    {
      pv = u;
    }
  };
  // The best distance (and its source) sent so far to each vertex of another process.
  std::vector<std::pair<double, std::int64_t>> sent(
    static_cast<std::size_t>(Graph.NumberOfRemote()), { Inf, 0 });
  const std::size_t size = static_cast<std::size_t>(comm.Size());
  while (true)
  {
    std::vector<ByteBuffer> outgoing(size), incoming;
    std::int64_t messages = 0;
    while (!queue.Empty())
    {
      const int u = queue.Pop();
      const double du = Dist[static_cast<std::size_t>(u)];
      const std::int64_t uid = Graph.OwnedId(u);
      for (std::int64_t e = Graph.Begin(u); e < Graph.End(u); ++e)
      {
        const double nd = du + Graph.Weight(e);
        if (!(nd <= limit))
        {
          continue;
        }
        const int t = Graph.Target(e);
        if (t >= 0)
        {
          offer(t, nd, uid);
          continue;
        }
        auto& best = sent[static_cast<std::size_t>(-1 - t)];
        if (nd < best.first || (nd == best.first && uid < best.second))
        {
          best = { nd, uid };
          ByteWriter w(outgoing[static_cast<std::size_t>(Graph.RemoteOwner(-1 - t))]);
          w.Put(Graph.RemoteId(-1 - t));
          w.Put(nd);
          w.Put(uid);
          ++messages;
        }
      }
    }
    ++NumRounds;
    if (ExchangeCounting(comm, outgoing, incoming, messages) == 0)
    {
      break; // (no process sent anything)
    }
    for (std::size_t q = 0; q < size; ++q)
    {
      ByteReader r(incoming[q]);
      std::int64_t id = 0, from = 0;
      double d = 0.0;
      while (static_cast<int>(q) != comm.Rank() && r.Get(id) && r.Get(d) && r.Get(from))
      {
        const int i = Graph.OwnedIndex(id);
        if (i >= 0)
        {
          offer(i, d, from);
        }
      }
    }
  }
}

std::vector<double> PieceDistanceSolver::Fetch(
  const SurfacePiece& piece, const std::vector<int>& wanted, PieceCommunicator& comm) const
{
  std::vector<double> result(wanted.size(), Inf);
  const std::size_t size = static_cast<std::size_t>(comm.Size());
  std::vector<std::vector<std::int64_t>> asks(size);
  std::vector<std::vector<std::size_t>> places(size);
  // The piece's vertices and the owned ones are both in global id order: owned numbers by
  // walking them together.
  std::vector<int> ownedOf(static_cast<std::size_t>(piece.Mesh().NumberOfVertices()), -1);
  for (int v = 0, i = 0; v < piece.Mesh().NumberOfVertices() && i < Graph.NumberOfOwned(); ++v)
  {
    if (piece.GlobalId(v) == Graph.OwnedId(i))
    {
      ownedOf[static_cast<std::size_t>(v)] = i++;
    }
  }
  for (std::size_t j = 0; j < wanted.size(); ++j)
  {
    const int v = wanted[j];
    const int owner = piece.Owner(v);
    if (owner == comm.Rank())
    {
      result[j] = Dist[static_cast<std::size_t>(ownedOf[static_cast<std::size_t>(v)])];
    }
    else if (owner >= 0)
    {
      asks[static_cast<std::size_t>(owner)].push_back(piece.GlobalId(v));
      places[static_cast<std::size_t>(owner)].push_back(j);
    }
  }
  const std::vector<std::vector<double>> answers =
    AskProcesses(comm, asks, [this](int, std::int64_t id) {
      const int i = Graph.OwnedIndex(id);
      return i >= 0 ? Dist[static_cast<std::size_t>(i)] : Inf;
    });
  for (std::size_t q = 0; q < size; ++q)
  {
    for (std::size_t k = 0; k < places[q].size() && k < answers[q].size(); ++k)
    {
      result[places[q][k]] = answers[q][k];
    }
  }
  return result;
}

} // namespace gs
