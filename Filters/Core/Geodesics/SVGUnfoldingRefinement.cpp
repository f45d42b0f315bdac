// The unfolding refinement of SVGGeodesicSolver (Ying, Wang, He 2013, Section 4.2, with the
// departure angles carried along): graph distances lowered by geodesic triangle unfolding over
// each vertex's polar stencil, swept in order of distance, on one thread or several with the
// same result to the bit.
#include "SVGGeodesicSolver.h"
#include "StencilUnfolding.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <thread>

#if defined(_OPENMP)
#include <omp.h>
#endif

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace gs
{

using unfolding::Inf;
using unfolding::NaN;
using unfolding::SortKey;

// (The pairs' unfolding arithmetic of StencilUnfolding.h.)
double unfolding::NearestUnfolding2(const PairBatch& b)
{
  double nearest2 = Inf;
  int i = 0;
#if defined(__SSE2__)
  const __m128d zero = _mm_setzero_pd(), one = _mm_set1_pd(1.0), half = _mm_set1_pd(0.5);
  const __m128d signMask = _mm_set1_pd(-0.0), inf = _mm_set1_pd(Inf);
  const __m128d spanTol = _mm_set1_pd(1e-12), lowTol = _mm_set1_pd(-1e-9), highTol = _mm_set1_pd(1.0 + 1e-9);
  __m128d best = inf;
  auto abs = [&](__m128d v) { return _mm_andnot_pd(signMask, v); };
  auto select = [](__m128d mask, __m128d a, __m128d b) {
    return _mm_or_pd(_mm_and_pd(mask, a), _mm_andnot_pd(mask, b));
  };
  for (; i + 2 <= b.Count; i += 2)
  {
    const __m128d p1x = _mm_loadu_pd(b.P1x + i), p1y = _mm_loadu_pd(b.P1y + i);
    const __m128d p2x = _mm_loadu_pd(b.P2x + i), p2y = _mm_loadu_pd(b.P2y + i);
    const __m128d d1 = _mm_loadu_pd(b.D1 + i), d2 = _mm_loadu_pd(b.D2 + i);
    const __m128d cross = _mm_sub_pd(_mm_mul_pd(p1x, p2y), _mm_mul_pd(p1y, p2x));
    const __m128d spans = _mm_cmpgt_pd(cross,
      _mm_mul_pd(_mm_mul_pd(spanTol, _mm_add_pd(abs(p1x), abs(p1y))), _mm_add_pd(abs(p2x), abs(p2y))));
    const __m128d ex = _mm_sub_pd(p2x, p1x), ey = _mm_sub_pd(p2y, p1y);
    const __m128d L2 = _mm_add_pd(_mm_mul_pd(ex, ex), _mm_mul_pd(ey, ey));
    const __m128d alongL =
      _mm_mul_pd(half, _mm_add_pd(_mm_sub_pd(_mm_mul_pd(d1, d1), _mm_mul_pd(d2, d2)), L2));
    const __m128d h2L2 = _mm_sub_pd(_mm_mul_pd(_mm_mul_pd(d1, d1), L2), _mm_mul_pd(alongL, alongL));
    const __m128d triangle = _mm_cmpge_pd(h2L2, zero);
    const __m128d hL = _mm_sqrt_pd(_mm_and_pd(triangle, h2L2));
    const __m128d inv = _mm_div_pd(one, select(spans, L2, one));
    const __m128d sx =
      _mm_add_pd(p1x, _mm_mul_pd(_mm_add_pd(_mm_mul_pd(ex, alongL), _mm_mul_pd(ey, hL)), inv));
    const __m128d sy =
      _mm_add_pd(p1y, _mm_mul_pd(_mm_sub_pd(_mm_mul_pd(ey, alongL), _mm_mul_pd(ex, hL)), inv));
    const __m128d s2 = _mm_add_pd(_mm_mul_pd(sx, sx), _mm_mul_pd(sy, sy));
    const __m128d qx = _mm_xor_pd(sx, signMask), qy = _mm_xor_pd(sy, signMask);
    const __m128d den = _mm_sub_pd(_mm_mul_pd(ex, qy), _mm_mul_pd(ey, qx));
    const __m128d num =
      _mm_sub_pd(_mm_mul_pd(_mm_sub_pd(sx, p1x), qy), _mm_mul_pd(_mm_sub_pd(sy, p1y), qx));
    const __m128d positive = _mm_cmpgt_pd(den, zero);
    const __m128d sn = select(positive, num, _mm_xor_pd(num, signMask));
    const __m128d sd = select(positive, den, _mm_xor_pd(den, signMask));
    const __m128d valid = _mm_and_pd(_mm_and_pd(_mm_and_pd(spans, triangle), _mm_cmpgt_pd(sd, zero)),
      _mm_and_pd(_mm_cmpge_pd(sn, _mm_mul_pd(lowTol, sd)), _mm_cmple_pd(sn, _mm_mul_pd(highTol, sd))));
    best = _mm_min_pd(best, select(valid, s2, inf));
  }
  double lanes[2];
  _mm_storeu_pd(lanes, best);
  nearest2 = std::min(lanes[0], lanes[1]);
#endif
  for (; i < b.Count; ++i)
  {
    const Unfolding u = UnfoldAcross(b.P1x[i], b.P1y[i], b.P2x[i], b.P2y[i], b.D1[i], b.D2[i]);
    nearest2 = std::min(nearest2, u.Valid ? u.S2 : Inf);
  }
  return nearest2;
}

namespace
{

// Calls f(0), ..., f(parts - 1), on `parts` threads when there are several.
template <class F>
void ForEachPart(int parts, const F& f)
{
  if (parts <= 1)
  {
    f(0);
    return;
  }
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int t = 0; t < parts; ++t)
  {
    f(t);
  }
}

// Stable LSD radix sort by key, 11 bits per pass (3x faster than std::sort on the 26K-vertex
// sweeps; the stable order keeps ties deterministic). With `parts` > 1, on as many threads: each
// part of the input is counted, then scattered, by its own thread, at offsets that keep the
// parts in order within each digit (the same result). `count`: scratch.
void RadixSort(std::vector<std::pair<std::uint32_t, int>>& a,
  std::vector<std::pair<std::uint32_t, int>>& scratch, std::vector<std::size_t>& count, int parts)
{
  constexpr int digitBits = 11;
  constexpr std::uint32_t mask = (1u << digitBits) - 1u;
  constexpr std::size_t digits = mask + 1;
  const std::size_t n = a.size();
  const std::size_t p = static_cast<std::size_t>(parts);
  scratch.resize(n);
  count.resize(p * digits);
  for (int shift = 0; shift < 32; shift += digitBits)
  {
    ForEachPart(parts, [&](int t) {
      std::size_t* mine = count.data() + t * digits;
      std::fill(mine, mine + digits, 0);
      for (std::size_t i = n * t / p, end = n * (t + 1) / p; i < end; ++i)
      {
        ++mine[(a[i].first >> shift) & mask];
      }
    });
    std::size_t sum = 0;
    for (std::size_t d = 0; d < digits; ++d)
    {
      for (std::size_t t = 0; t < p; ++t)
      {
        const std::size_t c = count[t * digits + d];
        count[t * digits + d] = sum;
        sum += c;
      }
    }
    ForEachPart(parts, [&](int t) {
      std::size_t* mine = count.data() + t * digits;
      for (std::size_t i = n * t / p, end = n * (t + 1) / p; i < end; ++i)
      {
        scratch[mine[(a[i].first >> shift) & mask]++] = a[i];
      }
    });
    a.swap(scratch);
  }
}

} // namespace

struct SVGGeodesicSolver::SolveState
{
  const SVGGeodesicSolver& S;
  double GraphDistance(int x) const { return S.GraphSolver.Distance(x); }
  int Predecessor(int x) const { return S.GraphSolver.Predecessor(x); }
  int PredecessorStencilIndex(int x) const { return S.StencilIndexOfPredecessor(x); }
  bool Interior(int x) const { return S.Interior[x] != 0; }
  double Angle(int u) const { return S.Angle[u]; }
  double AnglePeriod() const { return S.AnglePeriod; }
  double Floor() const { return S.RefinementFloor; }
};

void SVGGeodesicSolver::Refine(
  double maxDistance, bool unfold, bool angles, int threads, std::int64_t parallelMinimum)
{
  // Geodesic triangle unfolding over each vertex's polar stencil, swept in order of distance
  // (Gauss-Seidel), so that refined values feed the vertices beyond them. For a vertex x and two
  // stencil neighbours u1, u2 adjacent in angle (less than pi apart), the geodesic triangle
  // (x, u1, u2) is laid out in x's tangent plane from the exact lengths and angles of the
  // stencil; the source is unfolded across the segment u1 u2 from the distances D(u1), D(u2),
  // and its distance to x is a candidate when the straight line to x crosses that segment.
  // Exact on developable surfaces; on curved ones it removes most of the graph's polyline
  // error (graph paths bend at every vertex they pass).
  const double limit = maxDistance > 0.0 ? maxDistance : Inf;
  const std::vector<int>& reached = GraphSolver.Reached();
#if defined(_OPENMP)
  threads = threads > 0 ? threads : omp_get_max_threads();
#else
  threads = 1;
#endif
  const bool parallel =
    unfold && !angles && threads > 1 && static_cast<std::int64_t>(reached.size()) >= parallelMinimum;
  const int parts = parallel ? threads : 1;
  const std::size_t n = reached.size();
  Order.resize(n);
  ForEachPart(parts, [&](int t) {
    for (std::size_t i = n * t / parts, end = n * (t + 1) / parts; i < end; ++i)
    {
      Order[i] = { SortKey(GraphSolver.Distance(reached[i])), reached[i] };
    }
  });
  RadixSort(Order, OrderScratch, OrderCounts, parts);
  if (parallel)
  {
    RefineInParallel(limit, threads);
    return;
  }
  const std::int64_t count = static_cast<std::int64_t>(Order.size());
  auto next = [](std::int64_t k) { return k + 1; };
  SweepPrefetch prefetch = StartPrefetch(0, count, next);
  // (In place, a sort key at a time: the vertices of smaller keys give their refined distances,
  // those of the same key or larger their graph distances; the distances of one key change
  // together once the key is done. Which of several vertices of one key comes first then does
  // not matter: it depended on the order of the graph search.)
  auto distanceOf = [this](int u) { return GraphSolver.Distance(u); };
  const SolveState state{ *this };
  const StencilUnfolding<SaddleVertexGraph, SolveState> kernel(Graph, state);
  std::vector<std::pair<int, double>>& lowered = Lowered;
  lowered.clear();
  for (std::int64_t i = 0; i < count; ++i)
  {
    Prefetch(prefetch, count, next);
    if (i > 0 && Order[i].first != Order[i - 1].first)
    {
      for (const auto& l : lowered)
      {
        GraphSolver.Lower(l.first, l.second);
      }
      lowered.clear();
    }
    const int x = Order[i].second;
    if (Exact[x])
    {
      continue;
    }
    double best = Inf, bestAngle = NaN;
    if (!kernel.RefineVertex(x, unfold, angles, distanceOf, best, bestAngle))
    {
      continue;
    }
    if (best < GraphSolver.Distance(x) && best <= limit)
    {
      lowered.push_back({ x, best });
    }
    if (angles)
    {
      Angle[x] = bestAngle;
      AngleSet.push_back(x);
    }
  }
  for (const auto& l : lowered)
  {
    GraphSolver.Lower(l.first, l.second);
  }
}

void SVGGeodesicSolver::RefineInParallel(double limit, int threads)
{
  // The sequential sweep's result to the bit, on several threads: each takes blocks of the
  // order in turn, and a vertex reads the refined distance of the stencil neighbours of smaller
  // sort keys (waiting for it when another thread has not yet reached it) and the graph distance
  // of the others, as the sweep in place does. Refined distances go to their own array (NaN: not
  // yet refined) until every thread is done, so that no thread sees a later vertex's refined
  // distance.
  const std::int64_t count = static_cast<std::int64_t>(Order.size());
  const std::size_t nodes = Graph.NumberOfVertices();
  if (!Refined || RefinedCount != nodes)
  {
    Refined.reset(new std::atomic<double>[nodes]);
    RefinedCount = nodes;
    for (std::size_t v = 0; v < nodes; ++v)
    {
      Refined[v].store(NaN, std::memory_order_relaxed);
    }
  }
  constexpr std::int64_t block = 256;
  const SolveState state{ *this };
  const StencilUnfolding<SaddleVertexGraph, SolveState> kernel(Graph, state);
#pragma omp parallel num_threads(threads)
  {
#if defined(_OPENMP)
    const std::int64_t team = omp_get_num_threads(), me = omp_get_thread_num();
#else
    const std::int64_t team = 1, me = 0;
#endif
    // This thread's positions: blocks me, me + team, ...
    auto next = [team](std::int64_t k) {
      ++k;
      return k % block == 0 ? k + (team - 1) * block : k;
    };
    std::uint32_t key = 0;
    auto distanceOf = [this, &key](int u) {
      const double graph = GraphSolver.Distance(u);
      const std::uint32_t k = SortKey(graph);
      if (k >= key) // not before x in the order, or unreached
      {
        return graph;
      }
      double d = Refined[u].load(std::memory_order_acquire);
      for (int spins = 0; std::isnan(d); ++spins)
      {
        if (spins > 64)
        {
          std::this_thread::yield();
        }
        d = Refined[u].load(std::memory_order_acquire);
      }
      return d;
    };
    SweepPrefetch prefetch = StartPrefetch(me * block, count, next);
    for (std::int64_t i = me * block; i < count; i = next(i))
    {
      Prefetch(prefetch, count, next);
      const int x = Order[i].second;
      key = Order[i].first;
      const double graph = GraphSolver.Distance(x);
      double value = graph;
      double best = Inf, angle = NaN;
      if (!Exact[x] && kernel.RefineVertex(x, true, false, distanceOf, best, angle) && best < graph &&
        best <= limit)
      {
        value = best;
      }
      Refined[x].store(value, std::memory_order_release);
    }
#pragma omp barrier
    // Every vertex is refined: the distances in place, the array back to NaN.
    for (std::int64_t k = me * block; k < count; k = next(k))
    {
      const int x = Order[k].second;
      const double value = Refined[x].load(std::memory_order_relaxed);
      if (value < GraphSolver.Distance(x))
      {
        GraphSolver.Lower(x, value);
      }
      Refined[x].store(NaN, std::memory_order_relaxed);
    }
  }
}

int SVGGeodesicSolver::StencilIndexOfPredecessor(int v) const
{
  const std::int64_t link = GraphSolver.PredecessorLink(v);
  return link >= 0 ? Graph.LinkStencilIndex(link) : -1;
}

template <class Next>
SVGGeodesicSolver::SweepPrefetch SVGGeodesicSolver::StartPrefetch(
  std::int64_t first, std::int64_t count, const Next& next) const
{
  SweepPrefetch p{ first, first, first };
  for (int k = 0; k < 3 * SweepAhead && p.Predecessor < count; ++k)
  {
    if (k < SweepAhead)
    {
      Graph.PrefetchStencil(Order[p.Predecessor].second, StencilIndexOfPredecessor(Order[p.Predecessor].second));
      p.Stencil = next(p.Stencil);
    }
    if (k < 2 * SweepAhead)
    {
      const int v = Order[p.Predecessor].second;
      Graph.PrefetchStencilOffsets(v, GraphSolver.PredecessorLink(v));
      p.Offsets = next(p.Offsets);
    }
    GraphSolver.PrefetchPredecessor(Order[p.Predecessor].second);
    p.Predecessor = next(p.Predecessor);
  }
  return p;
}

template <class Next>
void SVGGeodesicSolver::Prefetch(SweepPrefetch& p, std::int64_t count, const Next& next) const
{
  if (p.Predecessor < count)
  {
    GraphSolver.PrefetchPredecessor(Order[p.Predecessor].second);
    p.Predecessor = next(p.Predecessor);
  }
  if (p.Offsets < count)
  {
    const int v = Order[p.Offsets].second;
    Graph.PrefetchStencilOffsets(v, GraphSolver.PredecessorLink(v));
    p.Offsets = next(p.Offsets);
  }
  if (p.Stencil < count)
  {
    Graph.PrefetchStencil(Order[p.Stencil].second, StencilIndexOfPredecessor(Order[p.Stencil].second));
    p.Stencil = next(p.Stencil);
  }
}

} // namespace gs
