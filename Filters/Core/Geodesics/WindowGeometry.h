// Geometry shared by the window propagations (ExactGeodesicSolver, DGGPropagation): a window
// lies on a half-edge H in H's frame (origin Origin(H), x along H, y > 0 towards face(H)) with
// its unfolded source I below the edge; it crosses face(H), whose opposite vertex is C.
#pragma once

#include "TriangleMesh.h"

#include <algorithm>
#include <cmath>
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

// Windows by increasing Key: a binary heap of small (key, slot) entries over a pool of windows
// with a free list (the windows themselves never move in the heap).
template <class Window>
class WindowQueue
{
public:
  void Push(const Window& w)
  {
    int slot;
    if (!FreeSlots.empty())
    {
      slot = FreeSlots.back();
      FreeSlots.pop_back();
      Pool[slot] = w;
    }
    else
    {
      slot = static_cast<int>(Pool.size());
      Pool.push_back(w);
    }
    Heap.push_back({ w.Key, slot });
    std::push_heap(Heap.begin(), Heap.end(), Order());
  }
  Window Pop()
  {
    std::pop_heap(Heap.begin(), Heap.end(), Order());
    const int slot = Heap.back().Slot;
    Heap.pop_back();
    FreeSlots.push_back(slot);
    return Pool[slot];
  }
  bool Empty() const { return Heap.empty(); }
  std::size_t Size() const { return Heap.size(); }
  // The smallest key queued (infinite when empty).
  double MinKey() const
  {
    return Heap.empty() ? std::numeric_limits<double>::infinity() : Heap.front().Key;
  }
  void Clear()
  {
    Heap.clear();
    Pool.clear();
    FreeSlots.clear();
  }

private:
  struct Entry
  {
    double Key;
    int Slot;
  };
  struct Order
  {
    bool operator()(const Entry& a, const Entry& b) const { return a.Key > b.Key; }
  };
  std::vector<Window> Pool;
  std::vector<int> FreeSlots;
  std::vector<Entry> Heap;
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
