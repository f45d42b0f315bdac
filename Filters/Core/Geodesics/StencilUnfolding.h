// Geodesic triangle unfolding over a vertex's polar stencil: the kernel of the unfolding
// refinement (SVGGeodesicSolver::Refine on a whole graph, PieceRefinement on a process's piece
// of a partitioned surface), shared so that both compute the same bits.
//
// StencilUnfolding<Stencils, Vertices> refines one vertex from its stencil and its neighbours'
// distances. `Stencils` gives the stencils as SaddleVertexGraph does (StencilBegin, StencilEnd,
// StencilTarget, StencilX, StencilY, StencilDistance, StencilWrapX, StencilWrapY); `Vertices`
// the per-vertex state of the solve: GraphDistance(x), Predecessor(x) (-1: none),
// PredecessorStencilIndex(x) (the predecessor's place in x's stencil, -1: none), Interior(x)
// (its stencil is a closed fan), Angle(u) (departure angles; NaN when not computed),
// AnglePeriod() and Floor() (the fraction of the graph distance refinement keeps, see
// SVGGeodesicSolver).
#pragma once

#include "SVGGeodesicSolver.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace gs
{
namespace unfolding
{
constexpr double Inf = std::numeric_limits<double>::infinity();
const double NaN = std::numeric_limits<double>::quiet_NaN();

// An order-preserving 32-bit key of a distance (>= 0): the bits of its nearest float. Vertices
// closer than a float's precision (6e-8 relative) may swap places in the sweep, which only uses
// the order to visit a vertex's cone neighbours first (they are a stencil edge closer).
inline std::uint32_t SortKey(double d)
{
  const float f = static_cast<float>(std::max(0.0, d));
  std::uint32_t bits;
  std::memcpy(&bits, &f, sizeof bits);
  return bits;
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

double NearestUnfolding2(const PairBatch& b);

} // namespace unfolding

template <class Stencils, class Vertices>
class StencilUnfolding
{
  using PairBatch = unfolding::PairBatch;
  using Unfolding = unfolding::Unfolding;
  static constexpr double Inf = unfolding::Inf;

public:
  StencilUnfolding(const Stencils& graph, const Vertices& vertices)
    : Graph(graph)
    , V(vertices)
  {
  }

  // (RefineVertex's steps and their state.)
private:
  // One vertex's refinement, step to step: the scan of its stencil's cone about the arrival
  // direction (ScanCone: the cone's bounds, then its pairs, each relaxed and unfolded), tried once
  // more about a better neighbour, and, for angles, the unfolded geodesic's angle or one carried
  // over from a cone neighbour (AngleThroughNeighbour).
  struct ConeScan
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
    double Unfolded = Inf, UnfoldedAngle = NaN(); // with angles: the nearest unfolded geodesic
  };

  template <class DistanceOf>
  std::int64_t ArrivalEntry(
    int x, std::int64_t begin, std::int64_t end, const DistanceOf& distanceOf) const
  {
    // The direction towards the source: the graph predecessor's place in the stencil; without
    // one, the stencil neighbour giving the best distance.
    const int stencilIndex = V.PredecessorStencilIndex(x);
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

  void ConeBounds(ConeScan& s) const
  {
    s.Ax = Graph.StencilX(s.Arrival);
    s.Ay = Graph.StencilY(s.Arrival);
    // Within the cone: dot >= cos * |a| |e|, without a square root.
    const double ax = s.Ax, ay = s.Ay;
    const double ar2 = ax * ax + ay * ay, cone2 = SVGGeodesicSolver::ConeCosine * SVGGeodesicSolver::ConeCosine;
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
  void ScanCone(ConeScan& s, const DistanceOf& distanceOf) const
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
          s.Nearest2 = std::min(s.Nearest2, unfolding::NearestUnfolding2(s.Batch));
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

  void UnfoldPairWithAngle(ConeScan& s, std::int64_t e1, std::int64_t e2,
    double c1, double c2, double p1x, double p1y, double p2x, double p2y, double d1, double d2) const
  {
    double& best = s.Best;
    double& bestAngle = s.BestAngle;
    const Unfolding u = unfolding::UnfoldAcross(p1x, p1y, p2x, p2y, d1, d2);
    for (const std::int64_t e : { e1, e2 })
    {
      const double c = e == e1 ? c1 : c2;
      if (s.Unfold && c < best)
      {
        best = c;
        bestAngle = V.Angle(Graph.StencilTarget(e));
      }
      // A neighbour whose angle is known stands in when the predecessor's is not (the
      // source itself has none).
      if (!std::isfinite(bestAngle) && std::isfinite(V.Angle(Graph.StencilTarget(e))))
      {
        bestAngle = V.Angle(Graph.StencilTarget(e));
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
      const double a1 = V.Angle(Graph.StencilTarget(e1)), a2 = V.Angle(Graph.StencilTarget(e2));
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
        d -= V.AnglePeriod() * std::round(d / V.AnglePeriod());
        s.Unfolded = candidate;
        s.UnfoldedAngle = b1 + w * d;
      }
    }
  }

  template <class DistanceOf>
  void AngleThroughNeighbour(const ConeScan& s, const DistanceOf& distanceOf) const
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
      if (std::isfinite(V.Angle(u)) && c < viaDistance)
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
    s.BestAngle = V.Angle(Graph.StencilTarget(via)) + std::atan2(bx * qy - by * qx, bx * qx + by * qy);
  }

public:
  // Vertex x's refined distance (`best`, never below the floor a discrete geodesic graph
  // guarantees) and, with `angles`, its departure angle, from its stencil neighbours' distances
  // as `distanceOf` gives them; false when x has nothing to unfold from (it keeps its graph
  // distance).
  template <class DistanceOf>
  bool RefineVertex(
    int x, bool unfold, bool angles, const DistanceOf& distanceOf, double& best, double& bestAngle) const
  {
    // The angle that goes with the current distance: the graph predecessor's.
    const int graphPred = V.Predecessor(x);
    bestAngle = angles && graphPred >= 0 ? V.Angle(graphPred) : NaN();
    const std::int64_t begin = Graph.StencilBegin(x), end = Graph.StencilEnd(x);
    if (end - begin < 1)
    {
      return false;
    }
    best = V.GraphDistance(x);
    std::int64_t arrival = ArrivalEntry(x, begin, end, distanceOf);
    // No stencil neighbour reached (x was reached through a graph link from outside its
    // stencil): nothing to unfold from.
    if (arrival < 0 || !(distanceOf(Graph.StencilTarget(arrival)) < Inf))
    {
      return false;
    }
    // Unfold only the geodesic triangles around that direction (within a wide margin of the
    // graph's angular error): the straddling pair is among them.
    ConeScan s(x, unfold, angles, begin, end - begin, V.Interior(x), best, bestAngle);
    // The predecessor's direction can be far from the source's: a graph route within the
    // accuracy may leave x up to acos(1 / (1 + accuracy)) off the geodesic, and more through a
    // near neighbour. A sparse stencil's pairs at the cone's edges still straddle the source's
    // direction, a dense one's (reached vertices) need not: its cone then holds no straddling
    // pair, and the pairs it does hold can give the mirror image of the source, too far. When
    // a stencil neighbour of the cone gives a route SVGGeodesicSolver::ArrivalMoveMargin shorter than the arrival's,
    // the cone is tried once more about that neighbour (whose direction is closer to the
    // source's). On a jittered plane with reached stencils this lowers the mean error 4-10x.
    for (int attempt = 0;; ++attempt)
    {
      s.Arrival = arrival;
      ScanCone(s, distanceOf);
      if (!angles)
      {
        s.Nearest2 = std::min(s.Nearest2, unfolding::NearestUnfolding2(s.Batch));
        s.Batch.Count = 0;
      }
      // (The arrival's route is read only when a move is possible: most vertices stop before.)
      if (attempt > 0 || s.RelaxedEntry < 0 || s.RelaxedEntry == arrival ||
        !(s.Relaxed < (distanceOf(Graph.StencilTarget(arrival)) + Graph.StencilDistance(arrival)) *
            (1.0 - SVGGeodesicSolver::ArrivalMoveMargin)))
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
    best = std::max(best, V.Floor() * V.GraphDistance(x));
    return true;
  }

private:
  static double NaN() { return unfolding::NaN; }
  const Stencils& Graph;
  const Vertices& V;
};

} // namespace gs
