// The unfolding refinement of SVGGeodesicSolver (Ying, Wang, He 2013, Section 4.2, with the
// departure angles carried along): graph distances lowered by geodesic triangle unfolding over
// each vertex's polar stencil, swept in order of distance, on one thread or several with the
// same result to the bit.
#include "SVGGeodesicSolver.h"

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

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
const double NaN = std::numeric_limits<double>::quiet_NaN();

// An order-preserving 32-bit key of a distance (>= 0): the bits of its nearest float. Vertices
// closer than a float's precision (6e-8 relative) may swap places in the sweep, which only uses
// the order to visit a vertex's cone neighbours first (they are a stencil edge closer).
std::uint32_t SortKey(double d)
{
  const float f = static_cast<float>(std::max(0.0, d));
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return bits;
}

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

// The geodesic triangle (x, p1, p2) laid out in x's tangent plane (x at the origin, p1 -> p2
// counter-clockwise), with the source unfolded across the segment p1 p2 from its distances d1,
// d2: the source S = (Sx, Sy) lies on the far side of p1 p2 from x, and the segment from S to x
// crosses p1 p2 at the parameter T = Num / Den. Valid when the directions span an angle strictly
// between 0 and pi, the distances form a triangle with p1 p2, and the crossing lies on the
// segment; computed without branches (the pairs' outcomes are unpredictable), with one division
// and one square root. Its distance to x is sqrt(S2).
struct Unfolding
{
  double Sx, Sy, S2, Num, Den;
  bool Valid;
};

inline Unfolding UnfoldAcross(double p1x, double p1y, double p2x, double p2y, double d1, double d2)
{
  // The two directions must span an angle strictly between 0 and pi; vertices in the same
  // direction form no triangle.
  const double cross = p1x * p2y - p1y * p2x;
  const bool spans = cross > 1e-12 * (std::abs(p1x) + std::abs(p1y)) * (std::abs(p2x) + std::abs(p2y));
  // Unnormalised: with the segment's length L, alongL = along * L and hL = h * L, where `along`
  // and h place the source from p1 along and across p1 -> p2.
  const double ex = p2x - p1x, ey = p2y - p1y;
  const double L2 = ex * ex + ey * ey;
  const double alongL = 0.5 * (d1 * d1 - d2 * d2 + L2);
  const double h2L2 = d1 * d1 * L2 - alongL * alongL;
  const bool triangle = h2L2 >= 0.0;
  const double hL = std::sqrt(triangle ? h2L2 : 0.0);
  // Away from x (the origin): x is to the left of p1 -> p2, so the source is to the right,
  // along (ey, -ex).
  const double inv = 1.0 / (spans ? L2 : 1.0);
  Unfolding u;
  u.Sx = p1x + (ex * alongL + ey * hL) * inv;
  u.Sy = p1y + (ey * alongL - ex * hL) * inv;
  u.S2 = u.Sx * u.Sx + u.Sy * u.Sy;
  // The segment from S to x crosses p1 p2 between its end points: T in [0, 1], tested without
  // dividing.
  const double qx = -u.Sx, qy = -u.Sy;
  u.Den = ex * qy - ey * qx;
  u.Num = (u.Sx - p1x) * qy - (u.Sy - p1y) * qx;
  const double sn = u.Den > 0.0 ? u.Num : -u.Num, sd = u.Den > 0.0 ? u.Den : -u.Den;
  // (NaN distances, from unreached vertices, fail these comparisons.)
  // (Bitwise &: with &&, the compiler branches on each outcome.)
  u.Valid = spans & triangle & (sd > 0.0) & (sn >= -1e-9 * sd) & (sn <= (1.0 + 1e-9) * sd);
  return u;
}

// The nearest valid unfolding's squared distance (infinite when none) over a batch of stencil
// pairs: UnfoldAcross's arithmetic, operation for operation (the same result to the
// bit), two pairs at a time where SSE2 is available (the pairs' arithmetic was a third of the
// sweep on small meshes).
struct PairBatch
{
  static constexpr int Capacity = 32;
  double P1x[Capacity], P1y[Capacity], P2x[Capacity], P2y[Capacity], D1[Capacity], D2[Capacity];
  int Count = 0;
};

double NearestUnfolding2(const PairBatch& b)
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
} // namespace

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
    if (!RefineVertex(x, unfold, angles, distanceOf, best, bestAngle))
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
      if (!Exact[x] && RefineVertex(x, true, false, distanceOf, best, angle) && best < graph &&
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

// One vertex's refinement, step to step: the scan of its stencil's cone about the arrival
// direction (ScanCone: the cone's bounds, then its pairs, each relaxed and unfolded), tried once
// more about a better neighbour, and, for angles, the unfolded geodesic's angle or one carried
// over from a cone neighbour (AngleThroughNeighbour).
struct SVGGeodesicSolver::ConeScan
{
  ConeScan(int x, bool unfold, bool angles, std::int64_t begin, std::int64_t n, bool closed,
    double& best, double& bestAngle)
    : X(x)
    , Unfold(unfold)
    , Angles(angles)
    , Begin(begin)
    , N(n)
    , Closed(closed)
    , Best(best)
    , BestAngle(bestAngle)
  {
  }
  // A stencil index wrapped once (by comparison: a 64-bit % per step cost more than the
  // unfolding itself).
  std::int64_t Index(std::int64_t i) const { return i < 0 ? i + N : (i >= N ? i - N : i); }

  const int X;
  const bool Unfold, Angles;
  const std::int64_t Begin, N;
  const bool Closed; // the stencil is a closed fan
  double& Best;      // the refined distance so far
  double& BestAngle; // its departure angle
  std::int64_t Arrival = -1;
  double Ax = 0.0, Ay = 0.0; // the arrival's direction
  // Offsets (relative to the arrival, in stencil order) of the cone's first and last entry.
  std::int64_t A = 0, Lo = 0, Hi = 0;
  double Relaxed = Inf, Nearest2 = Inf; // without angles: the minima over the pairs
  std::int64_t RelaxedEntry = -1;       // the stencil entry giving `Relaxed`
  PairBatch Batch;
  std::int64_t Carried = -1; // the last pair's second entry, its distance and route
  double CarriedDistance = Inf, CarriedRoute = Inf;
  double Unfolded = Inf, UnfoldedAngle = NaN; // with angles: the nearest unfolded geodesic
};

template <class DistanceOf>
std::int64_t SVGGeodesicSolver::ArrivalEntry(
  int x, std::int64_t begin, std::int64_t end, const DistanceOf& distanceOf) const
{
  // The direction towards the source: the graph predecessor's place in the stencil; without
  // one, the stencil neighbour giving the best distance.
  const int stencilIndex = StencilIndexOfPredecessor(x);
  std::int64_t arrival = stencilIndex >= 0 ? begin + stencilIndex : -1;
  if (arrival < 0)
  {
    double arrivalDistance = Inf;
    for (std::int64_t e = begin; e < end; ++e)
    {
      const double c = distanceOf(Graph.StencilTarget(e)) + Graph.StencilDistance(e);
      if (c < arrivalDistance)
      {
        arrivalDistance = c;
        arrival = e;
      }
    }
  }
  return arrival;
}

void SVGGeodesicSolver::ConeBounds(ConeScan& s) const
{
  s.Ax = Graph.StencilX(s.Arrival);
  s.Ay = Graph.StencilY(s.Arrival);
  // Within the cone: dot >= cos * |a| |e|, without a square root.
  const double ax = s.Ax, ay = s.Ay;
  const double ar2 = ax * ax + ay * ay, cone2 = ConeCosine * ConeCosine;
  auto within = [&](std::int64_t e) {
    const double ex = Graph.StencilX(e), ey = Graph.StencilY(e);
    const double dot = ax * ex + ay * ey;
    return dot >= 0.0 && dot * dot >= cone2 * ar2 * (ex * ex + ey * ey);
  };
  const std::int64_t n = s.N, a = s.Arrival - s.Begin;
  std::int64_t lo = 0, hi = 0;
  while (lo > -(n - 1) && (s.Closed || a + lo > 0) && within(s.Begin + s.Index(a + lo - 1)))
  {
    --lo;
  }
  while (hi < n - 1 && (s.Closed || a + hi < n - 1) && within(s.Begin + s.Index(a + hi + 1)))
  {
    ++hi;
  }
  s.A = a;
  s.Lo = lo;
  s.Hi = hi;
}

template <class DistanceOf>
void SVGGeodesicSolver::ScanCone(ConeScan& s, const DistanceOf& distanceOf) const
{
  ConeBounds(s);
  const std::int64_t a = s.A, n = s.N;
  // Pairs (k, k+1) for k from lo - 1 to hi: the ones straddling the cone's edges too.
  for (std::int64_t k = s.Lo - 1; k <= s.Hi; ++k)
  {
    if (!s.Closed && (a + k < 0 || a + k + 1 > n - 1))
    {
      continue;
    }
    const std::int64_t i1 = s.Index(a + k);
    const bool wraps = i1 == n - 1;
    if (wraps && !s.Closed)
    {
      continue;
    }
    const std::int64_t e1 = s.Begin + i1;
    const std::int64_t e2 = wraps ? s.Begin : e1 + 1;
    // Graph relaxation with the (refined) distances of the cone's stencil vertices. (Each
    // entry but the cone's ends is in two consecutive pairs: its distance and route carry
    // over from the pair before.)
    double d1, c1;
    if (e1 == s.Carried)
    {
      d1 = s.CarriedDistance;
      c1 = s.CarriedRoute;
    }
    else
    {
      d1 = distanceOf(Graph.StencilTarget(e1));
      c1 = d1 + Graph.StencilDistance(e1);
    }
    const double d2 = distanceOf(Graph.StencilTarget(e2));
    const double c2 = d2 + Graph.StencilDistance(e2);
    s.Carried = e2;
    s.CarriedDistance = d2;
    s.CarriedRoute = c2;
    const double p1x = Graph.StencilX(e1), p1y = Graph.StencilY(e1);
    const double p2x = wraps ? Graph.StencilWrapX(s.X) : Graph.StencilX(e2);
    const double p2y = wraps ? Graph.StencilWrapY(s.X) : Graph.StencilY(e2);
    if (c1 < s.Relaxed || c2 < s.Relaxed)
    {
      s.Relaxed = std::min(c1, c2);
      s.RelaxedEntry = c1 <= c2 ? e1 : e2;
    }
    if (!s.Angles)
    {
      // Distances only: the pairs are collected and unfolded together (NearestUnfolding2).
      if (s.Batch.Count == PairBatch::Capacity)
      {
        s.Nearest2 = std::min(s.Nearest2, NearestUnfolding2(s.Batch));
        s.Batch.Count = 0;
      }
      const int j = s.Batch.Count++;
      s.Batch.P1x[j] = p1x;
      s.Batch.P1y[j] = p1y;
      s.Batch.P2x[j] = p2x;
      s.Batch.P2y[j] = p2y;
      s.Batch.D1[j] = d1;
      s.Batch.D2[j] = d2;
      continue;
    }
    UnfoldPairWithAngle(s, e1, e2, c1, c2, p1x, p1y, p2x, p2y, d1, d2);
  }
}

void SVGGeodesicSolver::UnfoldPairWithAngle(ConeScan& s, std::int64_t e1, std::int64_t e2,
  double c1, double c2, double p1x, double p1y, double p2x, double p2y, double d1, double d2) const
{
  double& best = s.Best;
  double& bestAngle = s.BestAngle;
  const Unfolding u = UnfoldAcross(p1x, p1y, p2x, p2y, d1, d2);
  for (const std::int64_t e : { e1, e2 })
  {
    const double c = e == e1 ? c1 : c2;
    if (s.Unfold && c < best)
    {
      best = c;
      bestAngle = Angle[Graph.StencilTarget(e)];
    }
    // A neighbour whose angle is known stands in when the predecessor's is not (the
    // source itself has none).
    if (!std::isfinite(bestAngle) && std::isfinite(Angle[Graph.StencilTarget(e)]))
    {
      bestAngle = Angle[Graph.StencilTarget(e)];
    }
  }
  // Only a shorter candidate matters (its angle included).
  const double s2 = u.S2;
  if (!u.Valid || (!(s2 < best * best) && !(s2 < s.Unfolded * s.Unfolded)))
  {
    return;
  }
  const double sx = u.Sx, sy = u.Sy, qx = -sx, qy = -sy, num = u.Num, den = u.Den;
  const double t = num / den;
  const double candidate = std::sqrt(s2);
  if (s.Unfold)
  {
    best = std::min(best, candidate);
  }
  if (candidate < s.Unfolded)
  {
    // Interpolated along u1 u2 where the unfolded geodesic crosses it.
    const double a1 = Angle[Graph.StencilTarget(e1)], a2 = Angle[Graph.StencilTarget(e2)];
    if (std::isfinite(a1) && std::isfinite(a2))
    {
      // In the development, the angle at the unfolded source from u_i's direction to x's is
      // the difference of their departure angles: exact on developable surfaces. The two
      // estimates are blended by where the geodesic crosses u1 u2.
      auto turn = [&](double px, double py) {
        const double tx = px - sx, ty = py - sy;
        return std::atan2(tx * qy - ty * qx, tx * qx + ty * qy);
      };
      const double w = std::min(1.0, std::max(0.0, t));
      const double b1 = a1 + turn(p1x, p1y), b2 = a2 + turn(p2x, p2y);
      double d = b2 - b1;
      d -= AnglePeriod * std::round(d / AnglePeriod);
      s.Unfolded = candidate;
      s.UnfoldedAngle = b1 + w * d;
    }
  }
}

template <class DistanceOf>
void SVGGeodesicSolver::AngleThroughNeighbour(const ConeScan& s, const DistanceOf& distanceOf) const
{
  // The source is placed in x's tangent plane from x's distance and that of the cone neighbour
  // with a known angle and the shortest path through it (two circles; the intersection on the
  // arrival side), and the angle is carried over from that neighbour.
  const double best = s.Best;
  std::int64_t via = -1;
  double viaDistance = Inf;
  for (std::int64_t k = s.Lo - 1; k <= s.Hi + 1; ++k)
  {
    if (!s.Closed && (s.A + k < 0 || s.A + k > s.N - 1))
    {
      continue;
    }
    const std::int64_t e = s.Begin + s.Index(s.A + k);
    const int u = Graph.StencilTarget(e);
    const double c = distanceOf(u) + Graph.StencilDistance(e);
    if (std::isfinite(Angle[u]) && c < viaDistance)
    {
      viaDistance = c;
      via = e;
    }
  }
  if (via < 0)
  {
    return;
  }
  const double px = Graph.StencilX(via), py = Graph.StencilY(via);
  const double L = std::sqrt(px * px + py * py);
  const double du = distanceOf(Graph.StencilTarget(via));
  // |S| = best, |S - p| = du.
  const double along = (best * best - du * du + L * L) / (2.0 * L);
  const double h = std::sqrt(std::max(0.0, best * best - along * along));
  const double ux = px / L, uy = py / L;
  double sx = ux * along - uy * h, sy = uy * along + ux * h;
  if ((-uy) * s.Ax + ux * s.Ay < 0.0) // the arrival direction is on the other side
  {
    sx = ux * along + uy * h;
    sy = uy * along - ux * h;
  }
  const double qx = -sx, qy = -sy, bx = px - sx, by = py - sy;
  s.BestAngle = Angle[Graph.StencilTarget(via)] + std::atan2(bx * qy - by * qx, bx * qx + by * qy);
}

template <class DistanceOf>
bool SVGGeodesicSolver::RefineVertex(
  int x, bool unfold, bool angles, const DistanceOf& distanceOf, double& best, double& bestAngle) const
{
  // The angle that goes with the current distance: the graph predecessor's.
  const int graphPred = GraphSolver.Predecessor(x);
  bestAngle = angles && graphPred >= 0 ? Angle[graphPred] : NaN;
  const std::int64_t begin = Graph.StencilBegin(x), end = Graph.StencilEnd(x);
  if (end - begin < 1)
  {
    return false;
  }
  best = GraphSolver.Distance(x);
  std::int64_t arrival = ArrivalEntry(x, begin, end, distanceOf);
  // No stencil neighbour reached (x was reached through a graph link from outside its
  // stencil): nothing to unfold from.
  if (arrival < 0 || !(distanceOf(Graph.StencilTarget(arrival)) < Inf))
  {
    return false;
  }
  // Unfold only the geodesic triangles around that direction (within a wide margin of the
  // graph's angular error): the straddling pair is among them.
  ConeScan s(x, unfold, angles, begin, end - begin, Interior[x] != 0, best, bestAngle);
  // The predecessor's direction can be far from the source's: a graph route within the
  // accuracy may leave x up to acos(1 / (1 + accuracy)) off the geodesic, and more through a
  // near neighbour. A sparse stencil's pairs at the cone's edges still straddle the source's
  // direction, a dense one's (reached vertices) need not: its cone then holds no straddling
  // pair, and the pairs it does hold can give the mirror image of the source, too far. When
  // a stencil neighbour of the cone gives a route ArrivalMoveMargin shorter than the arrival's,
  // the cone is tried once more about that neighbour (whose direction is closer to the
  // source's). On a jittered plane with reached stencils this lowers the mean error 4-10x.
  for (int attempt = 0;; ++attempt)
  {
    s.Arrival = arrival;
    ScanCone(s, distanceOf);
    if (!angles)
    {
      s.Nearest2 = std::min(s.Nearest2, NearestUnfolding2(s.Batch));
      s.Batch.Count = 0;
    }
    // (The arrival's route is read only when a move is possible: most vertices stop before.)
    if (attempt > 0 || s.RelaxedEntry < 0 || s.RelaxedEntry == arrival ||
      !(s.Relaxed < (distanceOf(Graph.StencilTarget(arrival)) + Graph.StencilDistance(arrival)) *
          (1.0 - ArrivalMoveMargin)))
    {
      break;
    }
    arrival = s.RelaxedEntry;
  }
  if (unfold && !angles)
  {
    best = std::min(best, std::min(s.Relaxed, std::sqrt(s.Nearest2)));
  }
  // The unfolded geodesic's angle when it is (one of) the shortest; otherwise one carried over
  // from a cone neighbour.
  if (angles && s.Unfolded <= best * (1.0 + 1e-9))
  {
    bestAngle = s.UnfoldedAngle;
  }
  else if (angles)
  {
    AngleThroughNeighbour(s, distanceOf);
  }
  // A discrete geodesic graph's distance is within its accuracy above the geodesic distance:
  // refinement may not go lower than that bound (unfolding across a hole or a saddle could).
  best = std::max(best, RefinementFloor * GraphSolver.Distance(x));
  return true;
}

} // namespace gs
