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

DGGPropagation::DGGPropagation(const TriangleMesh& mesh, double lengthScale)
  : Mesh(mesh)
{
  window_geometry::HalfedgeFrames(Mesh, Cx, Cy, FanAngle);
  const int nv = Mesh.NumberOfVertices();
  Dist.assign(nv, Inf);
  IsCovered.assign(nv, 0);
  AnglePhi.assign(nv, 0.0);
  AngleX.assign(nv, 1.0);
  AngleY.assign(nv, 0.0);
  CrossHalfedge.assign(nv, -1);
  CrossX.assign(nv, 0.0);
  Tolerance =
    1e-11 * std::max(lengthScale > 0.0 ? lengthScale : Mesh.BoundingBoxDiagonal(), 1e-300);
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

void DGGPropagation::Reach(
  int v, double d, bool covered, double phi, double dx, double dy, int via, double crossing)
{
  if (d < Dist[v] - Tolerance)
  {
    if (Dist[v] == Inf)
    {
      Touched.push_back(v);
    }
    Dist[v] = d;
    IsCovered[v] = covered;
    AnglePhi[v] = phi;
    AngleX[v] = dx;
    AngleY[v] = dy;
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
  if (!window_geometry::TrimWindow(Mesh.EdgeLength(h), w.Ix, w.Iy, 0.0, Cx[h], Cy[h],
        Dist[Mesh.Origin(h)], Dist[Mesh.Destination(h)], Dist[Mesh.Opposite(h)], Tolerance, w.B0,
        w.B1))
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
  const int n = w.NumAnchors;
  if (n == 0)
  {
    return false;
  }
  const double ix = w.Ix, iy = w.Iy;
  const double grow = 1.0 + epsilon;
  // Anchor k covers the edge point (t, 0) when its slack
  //   s(t) = (1 + epsilon) p(t) - q(t) - D,  p = |x - I|, q = |x - a|, D = |a - I|,
  // is >= 0. Most windows are not covered: rejected by one sample, the interval's middle, where
  // the anchor with the most slack is also chosen (with the runner-up).
  const double mid = 0.5 * (w.B0 + w.B1);
  const double pMid = Hypot(mid - ix, iy);
  int best0 = 0, best1 = -1;
  double atMiddle[MaxAnchors] = {};
  for (int k = 0; k < n; ++k)
  {
    atMiddle[k] = grow * pMid - Hypot(mid - w.Anchors[k].X, w.Anchors[k].Y) - w.Anchors[k].D;
    if (atMiddle[k] > atMiddle[best0])
    {
      best0 = k;
    }
  }
  if (!(atMiddle[best0] >= 0.0))
  {
    return false;
  }
  for (int k = 0; k < n; ++k)
  {
    if (k != best0 && (best1 < 0 || atMiddle[k] > atMiddle[best1]))
    {
      best1 = k;
    }
  }
  const Anchor* use[2] = { &w.Anchors[best0], &w.Anchors[best1 >= 0 ? best1 : best0] };
  const int m = best1 >= 0 ? 2 : 1;
  // Over a piece [t0, t1]: p is convex, so it lies above its tangent at the middle; q is
  // convex, so it lies below its chord. Hence s is above the line
  //   (1 + epsilon) (p(tm) + p'(tm) (t - tm)) - chord of q - D,
  // and the piece is covered by the anchor when that line is >= 0 at both ends. Pieces neither
  // proven covered nor shown uncovered at an end are halved, up to a depth.
  struct Piece
  {
    double T0, T1, P0, P1, Q0[2], Q1[2];
    int Depth;
  };
  auto q = [&](int k, double t) { return Hypot(t - use[k]->X, use[k]->Y); };
  // Depth first, the later half first: the piece at hand is kept out of the stack, which holds
  // the earlier halves still to do (at most 22: a split is refused when the stack would pass 22
  // with both halves counted, as when both were pushed).
  Piece stack[24];
  int top = 0;
  Piece p{ w.B0, w.B1, Hypot(w.B0 - ix, iy), Hypot(w.B1 - ix, iy), {}, {}, 0 };
  for (int k = 0; k < m; ++k)
  {
    p.Q0[k] = q(k, w.B0);
    p.Q1[k] = q(k, w.B1);
  }
  for (;;)
  {
    bool end0 = false, end1 = false;
    for (int k = 0; k < m; ++k)
    {
      end0 = end0 || grow * p.P0 - p.Q0[k] - use[k]->D >= 0.0;
      end1 = end1 || grow * p.P1 - p.Q1[k] - use[k]->D >= 0.0;
    }
    if (!end0 || !end1)
    {
      return false;
    }
    const double tm = 0.5 * (p.T0 + p.T1);
    const double pm = Hypot(tm - ix, iy);
    const double slope = pm > 0.0 ? (tm - ix) / pm : 0.0;
    const double tangent0 = grow * (pm + slope * (p.T0 - tm));
    const double tangent1 = grow * (pm + slope * (p.T1 - tm));
    bool whole = false;
    for (int k = 0; k < m && !whole; ++k)
    {
      whole = tangent0 - p.Q0[k] - use[k]->D >= 0.0 && tangent1 - p.Q1[k] - use[k]->D >= 0.0;
    }
    if (whole)
    {
      if (top == 0)
      {
        break;
      }
      p = stack[--top];
      continue;
    }
    if (p.Depth >= 12 || top + 2 > 24)
    {
      return false;
    }
    // The earlier half waits on the stack; the later half is the next piece.
    Piece& a = stack[top++];
    a = p;
    a.T1 = tm;
    a.P1 = pm;
    a.Depth = p.Depth + 1;
    p.T0 = tm;
    p.P0 = pm;
    p.Depth = a.Depth;
    for (int k = 0; k < m; ++k)
    {
      a.Q1[k] = p.Q0[k] = q(k, tm);
    }
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
  const double L = Mesh.EdgeLength(w.H);
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
  const double L = Mesh.EdgeLength(h);
  const double cx = Cx[h], cy = Cy[h];
  const double ix = w.Ix, iy = w.Iy;
  const double xc = ix + (cx - ix) * (-iy) / (cy - iy);
  bool left = xc > w.B0;
  bool right = xc < w.B1;
  const double cover = 1e-10 * L;
  if (xc >= w.B0 - cover && xc <= w.B1 + cover)
  {
    const int vC = Mesh.Opposite(h);
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
      const double ux = cx - ix, uy = cy - iy;
      Reach(vC, dC, covered, w.Phi, w.Rc * ux - w.Rs * uy, w.Rs * ux + w.Rc * uy, h, xc);
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
  auto child = [&](int t, const auto& frame, double length, bool wholeLow, bool wholeHigh) {
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
    c.Phi = w.Phi;
    c.Rc = w.Rc * frame.Ux - w.Rs * frame.Uy;
    c.Rs = w.Rs * frame.Ux + w.Rc * frame.Uy;
    InheritAnchors(w, c, frame, cover);
    Push(c, epsilon);
  };
  const int leftEdge = Mesh.Twin(TriangleMesh::Prev(h)),
            rightEdge = Mesh.Twin(TriangleMesh::Next(h));
  if (left && leftEdge >= 0)
  {
    const double b = Mesh.EdgeLength(leftEdge);
    child(leftEdge, window_geometry::LeftFrame(cx, cy, b), b, false, right);
  }
  if (right && rightEdge >= 0)
  {
    const double a = Mesh.EdgeLength(rightEdge);
    child(rightEdge, window_geometry::RightFrame(cx, cy, L, a), a, left, false);
  }
}

void DGGPropagation::Run(
  int s, double epsilon, std::vector<Link>& links, std::vector<Link>* reached)
{
  Reset();
  links.clear();
  if (reached)
  {
    reached->clear();
  }
  Dist[s] = 0.0;
  Touched.push_back(s);
  Fenced.Start(Fence, Mesh.NumberOfFaces());
  const int start = Mesh.VertexHalfedge(s);
  int h = start;
  do
  {
    Fenced.Enter(h / 3);
    // Face(h) with h: s -> a, Next(h): a -> b, Prev(h): b -> s.
    const int opp = TriangleMesh::Next(h);
    const int a = Mesh.Destination(h);
    const int b = Mesh.Origin(TriangleMesh::Prev(h));
    const double p0 = FanAngle[h];
    Reach(a, Mesh.EdgeLength(h), false, p0, 1.0, 0.0, -1, 0.0);
    Reach(b, Mesh.EdgeLength(TriangleMesh::Prev(h)), false, p0 + Mesh.CornerAngle(h), 1.0, 0.0, -1,
      0.0);
    const int t = Mesh.Twin(opp);
    if (t >= 0)
    {
      // t runs b -> a; s lies below it at the mirror of its place in opp's frame.
      const double ab = Mesh.EdgeLength(t);
      Window w;
      w.H = t;
      w.B0 = 0.0;
      w.B1 = ab;
      w.Ix = ab - Cx[opp];
      w.Iy = -Cy[opp];
      w.Phi = p0 - std::atan2(Cy[opp], Cx[opp]);
      w.Rc = 1.0;
      w.Rs = 0.0;
      w.NumAnchors = 0; // (the edge's ends, added by Push)
      Push(w, epsilon);
    }
    h = Mesh.RotateCCW(h);
  } while (h >= 0 && h != start);

  while (!Queue.Empty())
  {
    Window w = Queue.Pop();
    Fenced.Enter(w.H / 3);
    // Vertex distances may have dropped since the window was queued.
    if (Trim(w))
    {
      Propagate(w, epsilon);
    }
  }
  for (int v : Touched)
  {
    if (v == s || (IsCovered[v] && !reached))
    {
      continue;
    }
    (IsCovered[v] ? *reached : links)
      .push_back({ v, Dist[v], AnglePhi[v] + std::atan2(AngleY[v], AngleX[v]) });
  }
}

} // namespace gs
