#include "DiscreteGeodesicGraph.h"

#include "WindowGeometry.h"

#include <algorithm>
#include <cmath>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
using window_geometry::Hypot;

// Whether the segment from anchor a to (x, y) (beyond the edge, y >= 0) crosses the edge's line
// within [b0, b1] (up to `slack`).
template <class Anchor>
bool CrossesWithin(const Anchor& a, double x, double y, double b0, double b1, double slack)
{
  const double den = y - a.Y;
  const double t = den > 1e-300 ? a.X + (x - a.X) * (-a.Y) / den : a.X;
  return t >= b0 - slack && t <= b1 + slack;
}

// A child window keeps the anchors of its parent w whose segments to both ends of its interval
// (hence to all of it) cross w's edge within w's interval: by induction the segment to any point
// of the child's interval then runs in the strip up to w's edge and in one face beyond.
template <class Window, class Frame>
void InheritAnchors(const Window& w, Window& c, const Frame& frame, double slack)
{
  c.NumAnchors = 0;
  const double x0 = frame.EdgeX(c.B0), y0 = frame.EdgeY(c.B0);
  const double x1 = frame.EdgeX(c.B1), y1 = frame.EdgeY(c.B1);
  for (int k = 0; k < w.NumAnchors; ++k)
  {
    const auto& a = w.Anchors[k];
    if (CrossesWithin(a, x0, y0, w.B0, w.B1, slack) && CrossesWithin(a, x1, y1, w.B0, w.B1, slack))
    {
      c.Anchors[c.NumAnchors++] = { frame.X(a.X, a.Y), frame.Y(a.X, a.Y), a.D };
    }
  }
}
} // namespace

DGGPropagation::DGGPropagation(const TriangleMesh& mesh)
  : M(mesh)
{
  window_geometry::HalfedgeFrames(M, Cx, Cy, FanAngle);
  const int nv = M.NumberOfVertices();
  Dist.assign(nv, Inf);
  IsCovered.assign(nv, 0);
  Angle.assign(nv, 0.0);
  CrossHalfedge.assign(nv, -1);
  CrossX.assign(nv, 0.0);
  Tolerance = 1e-11 * std::max(M.BoundingBoxDiagonal(), 1e-300);
}

void DGGPropagation::Reset()
{
  for (int v : Touched)
  {
    Dist[v] = Inf;
    IsCovered[v] = 0;
    CrossHalfedge[v] = -1;
  }
  Touched.clear();
  Queue.Clear();
  Stats = DGGStatistics();
}

void DGGPropagation::Reach(int v, double d, bool covered, double angle, int via, double crossing)
{
  if (d < Dist[v] - Tolerance)
  {
    if (Dist[v] == Inf)
    {
      Touched.push_back(v);
    }
    Dist[v] = d;
    IsCovered[v] = covered;
    Angle[v] = angle;
    CrossHalfedge[v] = via;
    CrossX[v] = crossing;
  }
  else if (d <= Dist[v] + Tolerance && covered)
  {
    IsCovered[v] = 1; // a tie: either arrival's cover serves
  }
}

bool DGGPropagation::Trim(Window& w) const
{
  const int h = w.H;
  if (!window_geometry::TrimWindow(M.EdgeLength(h), w.Ix, w.Iy, 0.0, Cx[h], Cy[h],
        Dist[M.Origin(h)], Dist[M.Destination(h)], Dist[M.Opposite(h)], Tolerance, w.B0, w.B1))
  {
    return false;
  }
  w.Key = window_geometry::SegmentDistance(w.Ix, w.Iy, w.B0, w.B1);
  return true;
}

void DGGPropagation::AddAnchor(Window& w, double x, double y)
{
  const double d = Hypot(x - w.Ix, y - w.Iy);
  for (int k = 0; k < w.NumAnchors; ++k)
  {
    if (std::abs(w.Anchors[k].X - x) + std::abs(w.Anchors[k].Y - y) <= 1e-12 * d)
    {
      return; // already there
    }
  }
  if (w.NumAnchors == MaxAnchors)
  {
    // Keep distances spread out (the best witness for a point at distance D lies near D / 2):
    // drop the anchor whose neighbours are closest in ratio, never the nearest or the farthest.
    int drop = 1;
    double tightest = std::numeric_limits<double>::infinity();
    for (int k = 1; k + 1 < MaxAnchors; ++k)
    {
      const double ratio = w.Anchors[k + 1].D / std::max(w.Anchors[k - 1].D, 1e-300);
      if (ratio < tightest)
      {
        tightest = ratio;
        drop = k;
      }
    }
    std::copy(w.Anchors + drop + 1, w.Anchors + MaxAnchors, w.Anchors + drop);
    --w.NumAnchors;
  }
  int at = w.NumAnchors;
  while (at > 0 && w.Anchors[at - 1].D > d)
  {
    w.Anchors[at] = w.Anchors[at - 1];
    --at;
  }
  w.Anchors[at] = { x, y, d };
  ++w.NumAnchors;
}

bool DGGPropagation::Covered(const Window& w, double epsilon) const
{
  int n = w.NumAnchors;
  if (n == 0)
  {
    return false;
  }
  Anchor anchors[MaxAnchors];
  std::copy(w.Anchors, w.Anchors + n, anchors);
  const double ix = w.Ix, iy = w.Iy;
  // Slack of anchor k at the edge point (t, 0); covered where some anchor's slack is >= 0.
  const double grow = 1.0 + epsilon;
  auto slack = [&](int k, double t) {
    return grow * Hypot(t - ix, iy) - Hypot(t - anchors[k].X, anchors[k].Y) - anchors[k].D;
  };
  // A piece [t0, t1] is covered by anchor k when (slack(t0) + slack(t1) - L (t1 - t0)) / 2 >= 0,
  // L a Lipschitz constant of the slack on the piece: its derivative is
  // (1 + epsilon) cos(aI) - cos(aA), aI and aA the angles of x - I and x - a to the edge, so
  // |derivative| <= epsilon + min(2, theta), theta the angle I x a. Where that angle is acute (x
  // outside the circle on [I, a]), theta <= pi/2 sin(theta) = pi/2 |(a - I) x (x - I)| / (|x - I|
  // |x - a|), bounded over the piece by its ends and its distances to I and a. Pieces neither
  // proven covered nor uncovered at an end are halved, up to a depth.
  auto lipschitz = [&](int k, double t0, double t1) {
    const Anchor& a = anchors[k];
    const double ax = a.X - ix, ay = a.Y - iy;
    const double mx = 0.5 * (a.X + ix), my = 0.5 * (a.Y + iy);
    if (!(window_geometry::SegmentDistance(mx, my, t0, t1) > 0.5 * a.D))
    {
      return epsilon + 2.0;
    }
    const double c0 = std::abs(ax * (-iy) - ay * (t0 - ix));
    const double c1 = std::abs(ax * (-iy) - ay * (t1 - ix));
    const double p = window_geometry::SegmentDistance(ix, iy, t0, t1);
    const double q = window_geometry::SegmentDistance(a.X, a.Y, t0, t1);
    const double theta = 1.5707963267948966 * std::max(c0, c1) / std::max(p * q, 1e-300);
    return epsilon + std::min(2.0, theta);
  };
  // Most windows are not covered: rejected by one sample, the interval's middle. Otherwise the
  // two anchors with the most slack there are tried.
  int best0 = 0, best1 = -1;
  {
    const double mid = 0.5 * (w.B0 + w.B1);
    double atMiddle[MaxAnchors] = {};
    for (int k = 0; k < n; ++k)
    {
      atMiddle[k] = slack(k, mid);
      if (atMiddle[k] > atMiddle[best0])
      {
        best0 = k;
      }
    }
    for (int k = 0; k < n; ++k)
    {
      if (k != best0 && (best1 < 0 || atMiddle[k] > atMiddle[best1]))
      {
        best1 = k;
      }
    }
    if (!(atMiddle[best0] >= 0.0))
    {
      return false;
    }
    const Anchor best[2] = { anchors[best0], anchors[best1 >= 0 ? best1 : best0] };
    n = std::min(n, 2);
    std::copy(best, best + n, anchors);
  }
  struct Piece
  {
    double T0, T1, S0[MaxAnchors], S1[MaxAnchors];
    int Depth;
  };
  Piece stack[24];
  int top = 0;
  Piece first{ w.B0, w.B1, {}, {}, 0 };
  for (int k = 0; k < n; ++k)
  {
    first.S0[k] = slack(k, w.B0);
    first.S1[k] = slack(k, w.B1);
  }
  stack[top++] = first;
  while (top > 0)
  {
    const Piece p = stack[--top];
    bool end0 = false, end1 = false, whole = false;
    for (int k = 0; k < n; ++k)
    {
      end0 = end0 || p.S0[k] >= 0.0;
      end1 = end1 || p.S1[k] >= 0.0;
    }
    for (int k = 0; k < n && end0 && end1 && !whole; ++k)
    {
      whole = p.S0[k] + p.S1[k] >= 0.0 && p.S0[k] + p.S1[k] >= lipschitz(k, p.T0, p.T1) * (p.T1 - p.T0);
    }
    if (!end0 || !end1)
    {
      return false;
    }
    if (whole)
    {
      continue;
    }
    if (p.Depth >= 10 || top + 2 > 24)
    {
      return false;
    }
    const double mid = 0.5 * (p.T0 + p.T1);
    Piece a = p, b = p;
    a.T1 = b.T0 = mid;
    a.Depth = b.Depth = p.Depth + 1;
    for (int k = 0; k < n; ++k)
    {
      a.S1[k] = b.S0[k] = slack(k, mid);
    }
    stack[top++] = a;
    stack[top++] = b;
  }
  return true;
}

void DGGPropagation::Push(Window& w, double epsilon)
{
  if (!Trim(w))
  {
    return;
  }
  // A window reaching an end of its edge has that vertex on its boundary ray: a new anchor.
  const double L = M.EdgeLength(w.H);
  if (w.B0 <= 1e-12 * L)
  {
    AddAnchor(w, 0.0, 0.0);
  }
  if (w.B1 >= L * (1.0 - 1e-12))
  {
    AddAnchor(w, L, 0.0);
  }
  if (Covered(w, epsilon))
  {
    ++Stats.WindowsCovered;
    return;
  }
  Queue.Push(w);
}

void DGGPropagation::Propagate(const Window& w, double epsilon)
{
  ++Stats.WindowsPropagated;
  const int h = w.H;
  const double L = M.EdgeLength(h);
  const double cx = Cx[h], cy = Cy[h];
  const double ix = w.Ix, iy = w.Iy;
  const double xc = ix + (cx - ix) * (-iy) / (cy - iy);
  bool left = xc > w.B0;
  bool right = xc < w.B1;
  const double cover = 1e-10 * L;
  if (xc >= w.B0 - cover && xc <= w.B1 + cover)
  {
    const int vC = M.Opposite(h);
    const double dC = Hypot(cx - ix, cy - iy);
    if (dC < Dist[vC] + Tolerance)
    {
      // C is covered by an anchor whose segment to C crosses the edge within the window.
      bool covered = false;
      for (int k = 0; k < w.NumAnchors && !covered; ++k)
      {
        const Anchor& a = w.Anchors[k];
        covered = a.D + Hypot(cx - a.X, cy - a.Y) <= (1.0 + epsilon) * dC &&
          CrossesWithin(a, cx, cy, w.B0, w.B1, cover);
      }
      Reach(vC, dC, covered, w.Phi + std::atan2(cy - iy, cx - ix), h, xc);
    }
    else if (dC > Dist[vC] + Tolerance && CrossHalfedge[vC] == h)
    {
      // One angle, one split (as in the exact solver).
      if (xc < CrossX[vC])
      {
        right = false;
      }
      else if (xc > CrossX[vC])
      {
        left = false;
      }
    }
  }
  // The children through A -> C (left) and C -> B (right), with the anchors they keep.
  auto child = [&](int t, const auto& frame, double length, bool wholeLow, bool wholeHigh,
                 double turn) {
    const window_geometry::ChildWindow made =
      window_geometry::MakeChild(frame, length, ix, iy, w.B0, w.B1, wholeLow, wholeHigh);
    if (!(made.B1 > made.B0))
    {
      return;
    }
    Window c;
    c.Ix = made.Ix;
    c.Iy = made.Iy;
    c.B0 = made.B0;
    c.B1 = made.B1;
    c.H = t;
    c.Phi = w.Phi + turn;
    InheritAnchors(w, c, frame, cover);
    Push(c, epsilon);
  };
  const int leftEdge = M.Twin(TriangleMesh::Prev(h)), rightEdge = M.Twin(TriangleMesh::Next(h));
  if (left && leftEdge >= 0)
  {
    const double b = M.EdgeLength(leftEdge);
    child(leftEdge, window_geometry::LeftFrame(cx, cy, b), b, false, right, std::atan2(cy, cx));
  }
  if (right && rightEdge >= 0)
  {
    const double a = M.EdgeLength(rightEdge);
    child(rightEdge, window_geometry::RightFrame(cx, cy, L, a), a, left, false,
      std::atan2(-cy, L - cx));
  }
}

bool DGGPropagation::Run(int s, double epsilon, std::vector<Link>& links, std::int64_t maxWindows)
{
  Reset();
  links.clear();
  Dist[s] = 0.0;
  Touched.push_back(s);
  const int start = M.VertexHalfedge(s);
  int h = start;
  do
  {
    // Face(h) with h: s -> a, Next(h): a -> b, Prev(h): b -> s.
    const int opp = TriangleMesh::Next(h);
    const int a = M.Destination(h);
    const int b = M.Origin(TriangleMesh::Prev(h));
    const double p0 = FanAngle[h];
    Reach(a, M.EdgeLength(h), false, p0, -1, 0.0);
    Reach(b, M.EdgeLength(TriangleMesh::Prev(h)), false, p0 + M.CornerAngle(h), -1, 0.0);
    const int t = M.Twin(opp);
    if (t >= 0)
    {
      // t runs b -> a; s lies below it at the mirror of its place in opp's frame.
      const double ab = M.EdgeLength(t);
      Window w;
      w.H = t;
      w.B0 = 0.0;
      w.B1 = ab;
      w.Ix = ab - Cx[opp];
      w.Iy = -Cy[opp];
      w.Phi = p0 - std::atan2(Cy[opp], Cx[opp]);
      w.NumAnchors = 0; // (the edge's ends, added by Push)
      Push(w, epsilon);
    }
    h = M.RotateCCW(h);
  } while (h >= 0 && h != start);

  bool complete = true;
  while (!Queue.Empty())
  {
    if (maxWindows > 0 && Stats.WindowsPropagated >= maxWindows)
    {
      complete = false;
      break;
    }
    Window w = Queue.Pop();
    // Vertex distances may have dropped since the window was queued.
    if (Trim(w))
    {
      Propagate(w, epsilon);
    }
  }
  for (int v : Touched)
  {
    if (v != s && !IsCovered[v])
    {
      links.push_back({ v, Dist[v], Angle[v] });
    }
  }
  return complete;
}

} // namespace gs
