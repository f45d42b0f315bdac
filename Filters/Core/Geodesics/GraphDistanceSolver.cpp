// Shortest paths on a saddle vertex graph or discrete geodesic graph: label correcting (SLF
// insertion, LLL extraction) and Dijkstra.
#include "SaddleVertexGraph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
} // namespace

GraphDistanceSolver::GraphDistanceSolver(const SaddleVertexGraph& graph)
  : Graph(graph)
{
  const int nv = Graph.NumberOfVertices();
  Dist.assign(nv, Inf);
  Pred.assign(nv, { -1, -1 });
  InQueue.assign(nv, 0);
  Ring.assign(nv + 1, 0);
}

void GraphDistanceSolver::Solve(const std::vector<std::pair<int, double>>& seeds,
  GraphAlgorithm algorithm, double maxDistance)
{
  for (int v : Touched)
  {
    Dist[v] = Inf;
    Pred[v] = { -1, -1 };
    InQueue[v] = 0;
  }
  Touched.clear();
  NumRelaxations = 0;
  const double limit = maxDistance > 0.0 ? maxDistance : Inf;
  for (const auto& s : seeds)
  {
    if (s.first < 0 || s.first >= Graph.NumberOfVertices() || !(s.second <= limit))
    {
      continue;
    }
    if (Dist[s.first] == Inf)
    {
      Touched.push_back(s.first);
    }
    Dist[s.first] = std::min(Dist[s.first], s.second);
  }
  if (algorithm == GraphAlgorithm::Dijkstra)
  {
    SolveDijkstra(limit);
  }
  else
  {
    SolveLabelCorrecting(limit);
  }
}

void GraphDistanceSolver::PrefetchQueued(std::size_t head, std::size_t size) const
{
  // The queue says which vertices come next: their adjacency (a random place in memory, most of
  // the solve's time otherwise) is fetched while the front is scanned, the offsets a little
  // earlier. (LLL may still move them back; measured 1.5x faster on 26K-vertex meshes.)
  const std::size_t cap = Ring.size();
  auto wrap = [cap](std::size_t i) { return i >= cap ? i - cap : i; };
  if (size > 5)
  {
    Graph.PrefetchOffsets(Ring[wrap(head + 5)]);
  }
  if (size > 1)
  {
    Graph.PrefetchAdjacency(Ring[wrap(head + 1)]);
  }
}

void GraphDistanceSolver::SolveLabelCorrecting(double limit)
{
  // A circular deque holding each vertex at most once. SLF (small label first): a vertex whose
  // new label is below the front's goes to the front. LLL (large label last): a front vertex
  // whose label exceeds the queue's mean is moved to the back before extraction.
  //
  // The arrays are reached through local pointers: through the members, the stores of a
  // relaxation made the compiler reload every array's address for every link scanned (the scan
  // is most of the solve: about 55 links per popped vertex).
  double* const dist = Dist.data();
  unsigned char* const inQueue = InQueue.data();
  PredLink* const pred = Pred.data();
  int* const ring = Ring.data();
  const std::int64_t* const offsets = Graph.Offsets.data();
  const int* const targets = Graph.Targets.data();
  const double* const weights = Graph.Weights.data();
  std::int64_t relaxations = 0;
  const std::size_t cap = Ring.size();
  std::size_t head = 0, size = 0;
  double sum = 0.0;
  // (Index arithmetic by comparison, not %: a division per queue operation cost ~10% of the
  // solve.)
  auto wrap = [cap](std::size_t i) { return i >= cap ? i - cap : i; };
  for (int v : Touched)
  {
    inQueue[v] = 1;
    ring[wrap(head + size)] = v;
    ++size;
    sum += dist[v];
  }
  while (size > 0)
  {
    const double mean = sum / static_cast<double>(size);
    for (std::size_t tries = 0; tries < size && dist[ring[head]] > mean; ++tries)
    {
      const int v = ring[head];
      head = wrap(head + 1);
      ring[wrap(head + size - 1)] = v;
    }
    const int u = ring[head];
    head = wrap(head + 1);
    --size;
    PrefetchQueued(head, size);
    inQueue[u] = 0;
    sum -= dist[u];
    if (size == 0)
    {
      sum = 0.0; // no drift accumulates across emptyings
    }
    const double du = dist[u];
    const std::int64_t first = offsets[u], end = offsets[u + 1];
    // Most links relax nothing: with SSE2, two links are tested at once and only those that
    // improve go through the (scalar) update below.
    auto relax = [&](std::int64_t e) {
      const int v = targets[e];
      const double nd = du + weights[e];
      if (!(nd <= dist[v]) || !(nd <= limit))
      {
        return;
      }
      if (nd == dist[v])
      {
        KeepSmallerPredecessor(v, e, u);
        return;
      }
      ++relaxations;
      if (dist[v] == Inf)
      {
        Touched.push_back(v);
      }
      pred[v] = { e, u };
      if (inQueue[v])
      {
        sum += nd - dist[v];
        dist[v] = nd;
        return;
      }
      dist[v] = nd;
      inQueue[v] = 1;
      sum += nd;
      if (size > 0 && nd < dist[ring[head]])
      {
        head = head == 0 ? cap - 1 : head - 1;
        ring[head] = v;
      }
      else
      {
        ring[wrap(head + size)] = v;
      }
      ++size;
    };
    std::int64_t e = first;
#if defined(__SSE2__)
    const __m128d du2 = _mm_set1_pd(du);
    for (; e + 2 <= end; e += 2)
    {
      const __m128d nd = _mm_add_pd(du2, _mm_loadu_pd(weights + e));
      const __m128d old = _mm_set_pd(dist[targets[e + 1]], dist[targets[e]]);
      // (<=: a tie may change the predecessor, see KeepSmallerPredecessor.)
      const int better = _mm_movemask_pd(_mm_cmple_pd(nd, old));
      if (better & 1)
      {
        relax(e);
      }
      if (better & 2)
      {
        relax(e + 1);
      }
    }
#endif
    for (; e < end; ++e)
    {
      relax(e);
    }
  }
  NumRelaxations += relaxations;
}

void GraphDistanceSolver::SolveDijkstra(double limit)
{
  struct Item
  {
    double D;
    int V;
    bool operator<(const Item& o) const { return D > o.D; }
  };
  std::vector<Item> heap;
  heap.reserve(Touched.size() * 4 + 16);
  for (int v : Touched)
  {
    heap.push_back({ Dist[v], v });
  }
  std::make_heap(heap.begin(), heap.end());
  while (!heap.empty())
  {
    std::pop_heap(heap.begin(), heap.end());
    const Item it = heap.back();
    heap.pop_back();
    if (it.D > Dist[it.V])
    {
      continue;
    }
    for (std::int64_t e = Graph.Begin(it.V), end = Graph.End(it.V); e < end; ++e)
    {
      const int v = Graph.Target(e);
      const double nd = it.D + Graph.Weight(e);
      if (nd == Dist[v] && nd <= limit)
      {
        KeepSmallerPredecessor(v, e, it.V);
      }
      else if (nd < Dist[v] && nd <= limit)
      {
        ++NumRelaxations;
        if (Dist[v] == Inf)
        {
          Touched.push_back(v);
        }
        Dist[v] = nd;
        Pred[v] = { e, it.V };
        heap.push_back({ nd, v });
        std::push_heap(heap.begin(), heap.end());
      }
    }
  }
}

} // namespace gs
