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
#include <queue>
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
  Targets.clear();
  Weights.clear();
  RemoteIds.clear();
  RemoteOwners.clear();
  GlobalEntries = Resolved = 0;
  if (const Status valid = SaddleVertexGraph::CheckOptions(options); !valid.Ok())
  {
    return valid; // (the same options on every process: every one fails)
  }
  const int k = SaddleVertexGraph::EffectiveK(options,
    static_cast<int>(std::min<std::int64_t>(piece.GlobalNumberOfVertices(),
      std::numeric_limits<int>::max())));
  if (piece.Rings() < InitialRings(options, k))
  {
    if (const Status grown = piece.Grow(InitialRings(options, k) - piece.Rings(), comm);
        !grown.Ok())
    {
      return grown;
    }
  }
  for (int v = 0; v < piece.Mesh().NumberOfVertices(); ++v)
  {
    if (piece.IsOwned(v))
    {
      OwnedIds.push_back(piece.GlobalId(v));
    }
  }
  // OwnedIds is sorted: the piece numbers its vertices in global id order.

  std::vector<std::vector<FoundLink>> found(OwnedIds.size());
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

Status PieceGraph::SolveOwned(SurfacePiece& piece, const SaddleVertexGraphOptions& options, int k,
  PieceCommunicator& comm, const ProgressCallback& progress,
  std::vector<std::vector<FoundLink>>& found)
{
  const bool dgg = options.Construction == GraphConstruction::DiscreteGeodesic;
  const double epsilon = SaddleVertexGraph::DiscreteGeodesicEpsilon(options.Accuracy);
  const int threads = options.NumberOfThreads > 0 ? options.NumberOfThreads : omp_get_max_threads();
  std::vector<std::int64_t> pending = OwnedIds;
  const std::size_t total = std::max<std::size_t>(OwnedIds.size(), 1);
  std::size_t solved = 0;
  while (true)
  {
    const TriangleMesh& mesh = piece.Mesh();
    const std::vector<unsigned char>& fence = piece.Fence();
    std::vector<unsigned char> fenced(pending.size(), 0);
    std::atomic<bool> aborted(false);
    std::atomic<std::size_t> done(0);
#pragma omp parallel num_threads(threads)
    {
      std::unique_ptr<ExactGeodesicSolver> solver(
        dgg ? nullptr : new ExactGeodesicSolver(mesh, piece.LengthScale()));
      std::unique_ptr<DGGPropagation> propagation(
        dgg ? new DGGPropagation(mesh, piece.LengthScale()) : nullptr);
      if (propagation)
      {
        propagation->SetFence(&fence);
      }
      ExactGeodesicOptions opt;
      opt.MaximumFinalVertices = k;
      opt.Fence = &fence;
      std::vector<DGGPropagation::Link> links;
      int count = 0;
#pragma omp for schedule(dynamic, 64)
      for (std::int64_t i = 0; i < static_cast<std::int64_t>(pending.size()); ++i)
      {
        if (aborted.load(std::memory_order_relaxed))
        {
          continue;
        }
        const std::int64_t id = pending[static_cast<std::size_t>(i)];
        const int s = piece.Vertex(id);
        bool outside = false;
        links.clear();
        if (dgg)
        {
          propagation->Run(s, epsilon, links);
          outside = propagation->FenceReached();
        }
        else
        {
          static_cast<void>(solver->Solve(s, opt)); // s is a vertex of the mesh: accepted
          outside = solver->FenceReached();
          for (const int v : solver->FinalVertices())
          {
            if (v != s && solver->IsDirect(v))
            {
              links.push_back({ v, solver->Distance(v), 0.0 });
            }
          }
        }
        // (Sized exactly: these lists are most of the build's memory until they are assembled.)
        std::vector<FoundLink> mine(links.size());
        for (std::size_t j = 0; j < links.size(); ++j)
        {
          outside = outside || piece.Owner(links[j].Target) < 0;
          mine[j] = { piece.GlobalId(links[j].Target), links[j].Distance };
        }
        found[static_cast<std::size_t>(OwnedIndex(id))].swap(mine);
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
    std::vector<std::int64_t> again;
    for (std::size_t i = 0; i < pending.size(); ++i)
    {
      if (fenced[i])
      {
        again.push_back(pending[i]);
      }
    }
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
    if (const Status grown = piece.Grow(std::max(piece.Rings(), 1), comm); !grown.Ok())
    {
      return grown;
    }
  }
  return Status();
}

void PieceGraph::Assemble(const SurfacePiece& piece,
  std::vector<std::vector<FoundLink>>& found, PieceCommunicator& comm)
{
  // The reverse of each link whose target another process owns goes to that process.
  const int me = comm.Rank();
  const std::size_t n = OwnedIds.size();
  auto ownerOf = [&piece](std::int64_t id) { return piece.Owner(piece.Vertex(id)); };
  std::vector<ByteBuffer> outgoing(static_cast<std::size_t>(comm.Size())), incoming;
  for (std::size_t i = 0; i < n; ++i)
  {
    for (const FoundLink& l : found[i])
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
      for (const FoundLink& l : found[i])
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
  std::vector<std::vector<FoundLink>>().swap(found);
  incoming.clear();

  GlobalEntries = comm.Sum(Compact(piece, raw, count, sentBy));
}

std::int64_t PieceGraph::Compact(const SurfacePiece& piece, std::vector<RawEntry>& raw,
  const std::vector<std::int64_t>& count, const std::unordered_map<std::int64_t, int>& sentBy)
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
  raw.resize(static_cast<std::size_t>(kept));
  raw.shrink_to_fit();

  // Remote targets get slots (in id order); entries hold owned numbers or slots.
  for (const RawEntry& e : raw)
  {
    if (OwnedIndex(e.Target) < 0)
    {
      RemoteIds.push_back(e.Target);
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
  Targets.resize(raw.size());
  Weights.resize(raw.size());
  for (std::size_t e = 0; e < raw.size(); ++e)
  {
    const int t = OwnedIndex(raw[e].Target);
    Targets[e] = t >= 0 ? t
                        : -1 - static_cast<int>(std::lower_bound(RemoteIds.begin(), RemoteIds.end(),
                                                  raw[e].Target) - RemoteIds.begin());
    Weights[e] = raw[e].Weight;
  }
  return kept;
}

PieceDistanceSolver::PieceDistanceSolver(const PieceGraph& graph)
  : Graph(graph)
{
}

Status PieceDistanceSolver::Solve(const std::vector<std::pair<std::int64_t, double>>& seeds,
  double maxDistance, PieceCommunicator& comm)
{
  const double limit = maxDistance > 0.0 ? maxDistance : Inf;
  Dist.assign(static_cast<std::size_t>(Graph.NumberOfOwned()), Inf);
  NumRounds = 0;
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
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
  for (const auto& s : seeds)
  {
    const int i = Graph.OwnedIndex(s.first);
    if (i >= 0 && s.second <= limit && s.second < Dist[static_cast<std::size_t>(i)])
    {
      Dist[static_cast<std::size_t>(i)] = s.second;
      heap.push({ s.second, i });
    }
  }

  // The best distance sent so far to each vertex of another process.
  std::vector<double> sent(static_cast<std::size_t>(Graph.NumberOfRemote()), Inf);
  const std::size_t size = static_cast<std::size_t>(comm.Size());
  while (true)
  {
    std::vector<ByteBuffer> outgoing(size), incoming;
    std::int64_t messages = 0;
    while (!heap.empty())
    {
      const Item top = heap.top();
      heap.pop();
      if (top.first != Dist[static_cast<std::size_t>(top.second)])
      {
        continue;
      }
      for (std::int64_t e = Graph.Begin(top.second); e < Graph.End(top.second); ++e)
      {
        const double nd = top.first + Graph.Weight(e);
        if (!(nd <= limit))
        {
          continue;
        }
        const int t = Graph.Target(e);
        if (t >= 0)
        {
          if (nd < Dist[static_cast<std::size_t>(t)])
          {
            Dist[static_cast<std::size_t>(t)] = nd;
            heap.push({ nd, t });
          }
          continue;
        }
        double& best = sent[static_cast<std::size_t>(-1 - t)];
        if (nd < best)
        {
          best = nd;
          ByteWriter w(outgoing[static_cast<std::size_t>(Graph.RemoteOwner(-1 - t))]);
          w.Put(Graph.RemoteId(-1 - t));
          w.Put(nd);
          ++messages;
        }
      }
    }
    comm.Exchange(outgoing, incoming);
    ++NumRounds;
    if (comm.Sum(messages) == 0)
    {
      break;
    }
    for (std::size_t q = 0; q < size; ++q)
    {
      if (static_cast<int>(q) == comm.Rank())
      {
        continue;
      }
      ByteReader r(incoming[q]);
      std::int64_t id = 0;
      double d = 0.0;
      while (r.Get(id) && r.Get(d))
      {
        const int i = Graph.OwnedIndex(id);
        if (i >= 0 && d < Dist[static_cast<std::size_t>(i)])
        {
          Dist[static_cast<std::size_t>(i)] = d;
          heap.push({ d, i });
        }
      }
    }
  }
  return Status();
}

std::vector<double> PieceDistanceSolver::Fetch(
  const SurfacePiece& piece, const std::vector<int>& wanted, PieceCommunicator& comm) const
{
  std::vector<double> result(wanted.size(), Inf);
  const std::size_t size = static_cast<std::size_t>(comm.Size());
  std::vector<ByteBuffer> requests(size), asked;
  std::vector<std::vector<std::size_t>> places(size);
  for (std::size_t j = 0; j < wanted.size(); ++j)
  {
    const int v = wanted[j];
    const int owner = piece.Owner(v);
    if (owner == comm.Rank())
    {
      result[j] = Dist[static_cast<std::size_t>(Graph.OwnedIndex(piece.GlobalId(v)))];
    }
    else if (owner >= 0)
    {
      ByteWriter(requests[static_cast<std::size_t>(owner)]).Put(piece.GlobalId(v));
      places[static_cast<std::size_t>(owner)].push_back(j);
    }
  }
  comm.Exchange(requests, asked);
  std::vector<ByteBuffer> answers(size), answered;
  for (std::size_t q = 0; q < size; ++q)
  {
    if (static_cast<int>(q) == comm.Rank())
    {
      continue;
    }
    ByteReader r(asked[q]);
    ByteWriter w(answers[q]);
    std::int64_t id = 0;
    while (r.Get(id))
    {
      const int i = Graph.OwnedIndex(id);
      w.Put(i >= 0 ? Dist[static_cast<std::size_t>(i)] : Inf);
    }
  }
  comm.Exchange(answers, answered);
  for (std::size_t q = 0; q < size; ++q)
  {
    if (static_cast<int>(q) == comm.Rank())
    {
      continue;
    }
    ByteReader r(answered[q]);
    for (const std::size_t j : places[q])
    {
      double d = Inf;
      r.Get(d);
      result[j] = d;
    }
  }
  return result;
}

} // namespace gs
