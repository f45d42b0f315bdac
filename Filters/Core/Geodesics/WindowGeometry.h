// Geometry shared by the window propagations (ExactGeodesicSolver, DGGPropagation): a window
// lies on a half-edge H in H's frame (origin Origin(H), x along H, y > 0 towards face(H)) with
// its unfolded source I below the edge; it crosses face(H), whose opposite vertex is C.
#pragma once

#include "TriangleMesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

namespace gs
{
namespace window_geometry
{

// Plain sqrt: std::hypot's overflow guards cost more than the whole window update, and the
// coordinates here are mesh-sized (checked finite when the mesh is built).
inline double Hypot(double x, double y)
{
  return std::sqrt(x * x + y * y);
}

// An angle kept as Base + atan2(Y, X), evaluated only when asked for: every update of a vertex
// would otherwise pay for trigonometry it rarely needs (the propagations' departure angles).
struct LazyAngle
{
  double Base = std::numeric_limits<double>::quiet_NaN();
  double X = 1.0, Y = 0.0;
  static LazyAngle Exactly(double a) { return { a, 1.0, 0.0 }; }
  double Value() const { return Y == 0.0 && X > 0.0 ? Base : Base + std::atan2(Y, X); }
};

// Distance from (ix, iy) to the segment [b0, b1] of the x axis.
inline double SegmentDistance(double ix, double iy, double b0, double b1)
{
  if (ix < b0)
  {
    return Hypot(b0 - ix, iy);
  }
  if (ix > b1)
  {
    return Hypot(ix - b1, iy);
  }
  return std::abs(iy);
}

// Where the ray from I' through P' crosses the new edge (y' = 0), in the new frame.
inline double RayHit(double jx, double jy, double px, double py, double fallback)
{
  const double den = py - jy;
  return den > 1e-300 ? jx + (px - jx) * (-jy) / den : fallback;
}

// The frame of the half-edge across A -> C (the left child): origin A, x along A -> C, given C
// at (cx, cy) and |AC| = b. A point of H's frame in the new one.
struct LeftFrame
{
  double Ux, Uy;
  LeftFrame(double cx, double cy, double b)
    : Ux(cx / b)
    , Uy(cy / b)
  {
  }
  double X(double px, double py) const { return px * Ux + py * Uy; }
  double Y(double px, double py) const { return Ux * py - Uy * px; }
  // The point at t along the new edge, in H's frame.
  double EdgeX(double t) const { return t * Ux; }
  double EdgeY(double t) const { return t * Uy; }
};

// The frame of the half-edge across C -> B (the right child): origin C, x along C -> B, given
// |AB| = L and |CB| = a.
struct RightFrame
{
  double Cx, Cy, Ux, Uy;
  RightFrame(double cx, double cy, double L, double a)
    : Cx(cx)
    , Cy(cy)
    , Ux((L - cx) / a)
    , Uy(-cy / a)
  {
  }
  double X(double px, double py) const { return (px - Cx) * Ux + (py - Cy) * Uy; }
  double Y(double px, double py) const { return Ux * (py - Cy) - Uy * (px - Cx); }
  double EdgeX(double t) const { return Cx + t * Ux; }
  double EdgeY(double t) const { return Cy + t * Uy; }
};

// Per half-edge h: the opposite vertex in h's frame (cx, cy), and h's direction about its origin
// (counter-clockwise from the origin's VertexHalfedge, 0 .. total angle).
inline void HalfedgeFrames(const TriangleMesh& mesh, std::vector<double>& cx,
  std::vector<double>& cy, std::vector<double>& fanAngle)
{
  const int nh = mesh.NumberOfHalfedges();
  cx.resize(nh);
  cy.resize(nh);
  for (int h = 0; h < nh; ++h)
  {
    // The opposite vertex C seen from Origin(h): |AC| at the corner angle of A.
    const double b = mesh.EdgeLength(TriangleMesh::Prev(h));
    const double a = mesh.CornerAngle(h);
    cx[h] = b * std::cos(a);
    cy[h] = b * std::sin(a);
  }
  fanAngle.assign(nh, 0.0);
  for (int v = 0; v < mesh.NumberOfVertices(); ++v)
  {
    const int start = mesh.VertexHalfedge(v);
    double angle = 0.0;
    int h = start;
    do
    {
      fanAngle[h] = angle;
      angle += mesh.CornerAngle(h);
      h = mesh.RotateCCW(h);
    } while (h >= 0 && h != start);
  }
}

// A child window: the rays of a window (source (ix, iy), interval [b0, b1]) that leave face(H)
// through the new edge of `frame` (length `length`), in that edge's frame. `wholeLow` /
// `wholeHigh`: the child reaches that end of the new edge (the parent's rays pass on both sides
// of C). Empty when B1 <= B0.
struct ChildWindow
{
  double Ix, Iy, B0, B1;
};
template <class Frame>
ChildWindow MakeChild(const Frame& frame, double length, double ix, double iy, double b0,
  double b1, bool wholeLow, bool wholeHigh)
{
  ChildWindow c;
  c.Ix = frame.X(ix, iy);
  c.Iy = std::min(frame.Y(ix, iy), -1e-12 * length);
  c.B0 = wholeLow ? 0.0 : RayHit(c.Ix, c.Iy, frame.X(b0, 0.0), frame.Y(b0, 0.0), 0.0);
  c.B1 = wholeHigh ? length : RayHit(c.Ix, c.Iy, frame.X(b1, 0.0), frame.Y(b1, 0.0), length);
  c.B0 = std::min(std::max(c.B0, 0.0), length);
  c.B1 = std::min(std::max(c.B1, 0.0), length);
  return c;
}

// Windows by increasing Key. A propagation's keys rarely decrease (a child window lies beyond
// its parent, a vertex spreads from its own distance), so the windows sit in a radix heap: a key
// no smaller than the last one taken goes to the bucket of the highest bit in which it differs
// from it, and only the first non-empty bucket is ever sorted out again. The windows are kept in
// the buckets themselves: moving them on is sequential work, cheaper than a binary heap's
// sifting and than loading each window from a pool when it is taken. Each bucket holds most of
// the queue at some time, so a bucket sorted out gives its memory back when it kept room for
// more windows than are queued (otherwise the buckets together kept about 16 times the largest
// queue). A key below the last one taken (a window from another piece of a partitioned surface,
// or a rounding step) waits in a binary heap beside the buckets. Pop takes the smallest key of
// both; among equal keys, the last pushed.
template <class Window>
class WindowQueue
{
public:
  void Push(const Window& w)
  {
    if (KeyBits(w.Key) < Last)
    {
      Early.push_back(w);
      std::push_heap(Early.begin(), Early.end(), Later());
    }
    else
    {
      Put(w);
    }
    ++Count;
  }
  Window Pop()
  {
    SortOutFirst();
    --Count;
    if (TakeEarly())
    {
      std::pop_heap(Early.begin(), Early.end(), Later());
      const Window w = Early.back();
      Early.pop_back();
      return w;
    }
    const Window w = Buckets[0].back();
    Buckets[0].pop_back();
    return w;
  }
  bool Empty() const { return Count == 0; }
  std::size_t Size() const { return Count; }
  // The smallest key queued (infinite when empty).
  double MinKey()
  {
    SortOutFirst();
    if (Count == 0)
    {
      return std::numeric_limits<double>::infinity();
    }
    return TakeEarly() ? Early.front().Key : Buckets[0].back().Key;
  }
  void Clear()
  {
    for (std::vector<Window>& b : Buckets)
    {
      b.clear();
    }
    Early.clear();
    Last = 0;
    Count = 0;
    Filled = 0;
  }

private:
  struct Later
  {
    bool operator()(const Window& a, const Window& b) const { return a.Key > b.Key; }
  };
  // Keys are distances (>= 0; -0 and anything below 0 count as 0). A non-negative double's bits,
  // read as an unsigned integer, are in the order of its value.
  static std::uint64_t KeyBits(double key)
  {
    if (!(key > 0.0))
    {
      return key == key ? 0 : std::numeric_limits<std::uint64_t>::max();
    }
    std::uint64_t bits;
    std::memcpy(&bits, &key, sizeof bits);
    return bits;
  }
  // 0 for a key equal to Last, else 1 + the highest bit in which it differs from Last.
  std::size_t BucketOf(std::uint64_t bits) const
  {
    const std::uint64_t x = bits ^ Last;
    return x == 0 ? 0 : static_cast<std::size_t>(64 - __builtin_clzll(x));
  }
  // After SortOutFirst: whether the smallest key is in Early rather than in bucket 0.
  bool TakeEarly() const
  {
    return !Early.empty() && (Buckets[0].empty() || KeyBits(Early.front().Key) < Last);
  }
  // Makes bucket 0 hold the smallest keys of the buckets (when any is not empty): the first
  // non-empty bucket's smallest key becomes Last, and its entries move to lower buckets.
  void SortOutFirst()
  {
    if (!Buckets[0].empty())
    {
      return;
    }
    if (Filled == 0)
    {
      return;
    }
    const std::size_t i = 1 + static_cast<std::size_t>(__builtin_ctzll(Filled));
    Filled &= Filled - 1;
    std::vector<Window>& from = Buckets[i];
    std::uint64_t lowest = KeyBits(from.front().Key);
    for (const Window& w : from)
    {
      lowest = std::min(lowest, KeyBits(w.Key));
    }
    Last = lowest;
    for (const Window& w : from)
    {
      Put(w);
    }
    if (from.capacity() > 4096 && from.capacity() > Count)
    {
      std::vector<Window>().swap(from);
    }
    else
    {
      from.clear();
    }
  }
  void Put(const Window& w)
  {
    const std::size_t b = BucketOf(KeyBits(w.Key));
    Buckets[b].push_back(w);
    if (b > 0)
    {
      Filled |= std::uint64_t(1) << (b - 1);
    }
  }
  std::array<std::vector<Window>, 65> Buckets;
  std::vector<Window> Early; // binary heap of keys below Last
  std::uint64_t Last = 0;   // the bits of the key last sorted out to bucket 0
  std::size_t Count = 0;
  std::uint64_t Filled = 0; // bit b - 1 set: bucket b (1 .. 64) is not empty
};

// Cuts from [b0, b1] the points p = (t, 0) reached at least as short through an end point of
// the edge (distances dA, dB, infinite when unknown: dA + t <= sigma + |I p|), and drops the
// window when the opposite vertex C (distance dC) dominates it entirely. Returns false when
// nothing is left.
inline bool TrimWindow(double L, double ix, double iy, double s, double cx, double cy, double dA,
  double dB, double dC, double tol, double& b0, double& b1)
{
  const double Inf = std::numeric_limits<double>::infinity();
  // The difference is monotone in t for A (and for B), so the useless part is an interval at
  // that end, found in closed form.
  if (dA < Inf)
  {
    const double target = dA + tol;
    auto g = [&](double t) { return s + Hypot(t - ix, iy) - t; };
    if (g(b1) >= target)
    {
      return false;
    }
    if (g(b0) >= target)
    {
      const double k = target - s;
      const double denom = 2.0 * (k + ix);
      if (denom > 0.0)
      {
        const double t = (ix * ix + iy * iy - k * k) / denom;
        b0 = std::min(std::max(t, b0), b1);
      }
    }
  }
  if (dB < Inf)
  {
    const double target = dB + tol;
    auto g = [&](double t) { return s + Hypot(t - ix, iy) - (L - t); };
    if (g(b0) >= target)
    {
      return false;
    }
    if (g(b1) >= target)
    {
      const double k = target - s;
      const double mx = L - ix;
      const double denom = 2.0 * (k + mx);
      if (denom > 0.0)
      {
        const double t = L - (mx * mx + iy * iy - k * k) / denom;
        b1 = std::max(std::min(t, b1), b0);
      }
    }
  }
  // C dominates the whole window when D(C) + |C p| <= s + |I p| for every p of the window: the
  // minimum of s + |I p| - |C p| is at an end or where p lies on the line through I and C
  // mirrored below the edge.
  if (dC < Inf)
  {
    auto f = [&](double t) { return s + Hypot(t - ix, iy) - Hypot(t - cx, cy); };
    double lowest = std::min(f(b0), f(b1));
    const double dy = -cy - iy;
    if (std::abs(dy) > 1e-300)
    {
      const double t = ix + (cx - ix) * (-iy) / dy;
      if (t > b0 && t < b1)
      {
        lowest = std::min(lowest, f(t));
      }
    }
    if (lowest >= dC + tol)
    {
      return false;
    }
  }
  return b1 - b0 > 1e-14 * L;
}

// A propagation's fence: faces it must not enter (one flag per face; a piece of a partitioned
// surface marks those with a vertex whose other faces are missing) and those it entered, each
// once or more. A fence of another face count, or none, watches nothing.
struct FenceWatch
{
  const std::vector<unsigned char>* Faces = nullptr;
  std::vector<int> Entered;

  void Start(const std::vector<unsigned char>* faces, int numberOfFaces)
  {
    Faces = faces && faces->size() == static_cast<std::size_t>(numberOfFaces) ? faces : nullptr;
    Entered.clear();
  }
  void Enter(int face)
  {
    if (Faces && (*Faces)[static_cast<std::size_t>(face)])
    {
      Entered.push_back(face);
    }
  }
};

} // namespace window_geometry
} // namespace gs
