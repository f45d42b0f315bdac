#include "ExactGeodesic.h"
#include "WindowGeometry.h"

#include <algorithm>
#include <cmath>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
using window_geometry::Hypot;
using window_geometry::SegmentDistance;
} // namespace

ExactGeodesicSolver::ExactGeodesicSolver(const TriangleMesh& mesh, double lengthScale)
  : Surface(mesh)
{
  {
    std::vector<double> cx, cy;
    window_geometry::HalfedgeFrames(Surface, cx, cy, FanAngle);
    Edges.resize(cx.size());
    for (std::size_t h = 0; h < Edges.size(); ++h)
    {
      const int e = static_cast<int>(h);
      Edges[h] = { cx[h], cy[h], Surface.EdgeLength(e), Surface.Origin(e), Surface.Twin(e) };
    }
  }
  const int nv = Surface.NumberOfVertices();
  InAngle.assign(nv, LazyAngle());
  Departure.assign(nv, LazyAngle());
  Root.assign(nv, -1);
  Dist.assign(nv, Inf);
  Origin.assign(nv, 0);
  CrossHalfedge.assign(nv, -1);
  CrossX.assign(nv, 0.0);
  Final.assign(nv, 0);
  Propagated.assign(nv, 0);
  // Distances are compared with an absolute tolerance well above rounding noise and far below
  // any meaningful length of the mesh.
  Tolerance =
    1e-11 * std::max(lengthScale > 0.0 ? lengthScale : Surface.BoundingBoxDiagonal(), 1e-300);
}

void ExactGeodesicSolver::Reset()
{
  for (int v : Touched)
  {
    Dist[v] = Inf;
    Origin[v] = 0;
    CrossHalfedge[v] = -1;
    Final[v] = 0;
    Propagated[v] = 0;
    InAngle[v] = LazyAngle();
    Departure[v] = LazyAngle();
    Root[v] = -1;
  }
  Touched.clear();
  FinalOrder.clear();
  Queue.Clear();
  VertexQueue.clear();
  Stats = ExactGeodesicStatistics();
}

std::vector<double> ExactGeodesicSolver::Distances() const
{
  std::vector<double> d(Surface.NumberOfVertices(), Unreachable);
  for (int v : FinalOrder)
  {
    d[v] = Dist[v];
  }
  return d;
}

void ExactGeodesicSolver::UpdateVertex(int v, double d, int origin, int via, double crossing,
  const LazyAngle& inAngle, const LazyAngle& departure, int root)
{
  if (Final[v] || !(d < Dist[v] + Tolerance))
  {
    return;
  }
  if (d >= Dist[v] - Tolerance)
  {
    // A tie: two paths of (nearly) equal length. Keep the direction only if they agree, so that
    // a pseudo-source spreads into the union of both shadows.
    if (!(std::abs(inAngle.Value() - InAngle[v].Value()) <= 1e-9))
    {
      InAngle[v] = LazyAngle();
    }
    if (!(d < Dist[v]))
    {
      return;
    }
  }
  else
  {
    InAngle[v] = inAngle;
  }
  if (Dist[v] == Inf)
  {
    Touched.push_back(v);
  }
  Dist[v] = d;
  Origin[v] = origin;
  Departure[v] = departure;
  Root[v] = root;
  CrossHalfedge[v] = via;
  CrossX[v] = crossing;
  if (Route)
  {
    RouteImprovement(v, d, root);
    return;
  }
  VertexQueue.push_back({ d, v });
  std::push_heap(VertexQueue.begin(), VertexQueue.end(),
    [](const VertexKey& a, const VertexKey& b) { return a.D > b.D; });
  if (Surface.IsPseudoSourceVertex(v) && !Propagated[v])
  {
    QueueVertexEvent(v, d, root);
  }
}

void ExactGeodesicSolver::QueueVertexEvent(int v, double d, int root)
{
  Window e;
  e.Key = d;
  e.B0 = e.B1 = e.Ix = e.Iy = 0.0;
  e.Phi = 0.0;
  e.Sigma = d;
  e.H = -1 - v;
  e.Src = -1 - v;
  e.Root = root;
  Enqueue(e);
}

void ExactGeodesicSolver::RouteImprovement(int v, double d, int root)
{
  if ((*Route->OtherVertex)[v])
  {
    if (!Route->Listed[v])
    {
      Route->Listed[v] = 1;
      Route->LeavingVertices.push_back(v);
    }
    return;
  }
  // Not final yet: a vertex spread from a longer path spreads again from this one.
  if (Surface.IsPseudoSourceVertex(v))
  {
    Propagated[v] = 0;
    QueueVertexEvent(v, d, root);
  }
}

bool ExactGeodesicSolver::Trim(Window& w) const
{
  const int h = w.H;
  const HalfedgeRecord& e = Edges[h];
  if (!window_geometry::TrimWindow(e.Length, w.Ix, w.Iy, w.Sigma, e.Cx, e.Cy, Dist[e.Origin],
        Dist[Destination(h)], Dist[Opposite(h)], Tolerance, w.B0, w.B1))
  {
    return false;
  }
  w.Key = w.Sigma + SegmentDistance(w.Ix, w.Iy, w.B0, w.B1);
  return true;
}

void ExactGeodesicSolver::Enqueue(const Window& w)
{
  Queue.Push(w);
}

ExactGeodesicSolver::Window ExactGeodesicSolver::Dequeue()
{
  return Queue.Pop();
}

void ExactGeodesicSolver::PushWindow(Window w)
{
  ++Stats.WindowsCreated;
  if (Route && (*Route->OtherFace)[w.H / 3])
  {
    // Trimmed before it leaves: less to send.
    if (Trim(w))
    {
      Route->Leaving.push_back(w);
    }
    return;
  }
  // Queued untrimmed: the distance to its untrimmed interval is a lower bound of what it can
  // give, which is all the queue's order needs, and Handle trims it against the vertex
  // distances of that time anyway (trimming here as well costs more than it saves: it seldom
  // empties a window).
  w.Key = w.Sigma + SegmentDistance(w.Ix, w.Iy, w.B0, w.B1);
  Enqueue(w);
  Stats.MaximumQueueSize =
    std::max<std::int64_t>(Stats.MaximumQueueSize, static_cast<std::int64_t>(Queue.Size()));
}

void ExactGeodesicSolver::PropagateFromVertex(int v, double sigma, int src)
{
  ++Stats.PseudoSourceEvents;
  const int root = src >= 0 ? src : Root[v];
  // A shortest path through a saddle or boundary vertex leaves it at an angle of at least pi
  // from where it arrived, on both sides (on the surface side for a boundary vertex): only that
  // shadow needs windows. A real source, or an unknown/ambiguous arrival, spreads everywhere.
  constexpr double Pi = 3.14159265358979323846;
  const double theta = Surface.TotalAngle(v);
  const double in = InAngle[v].Value();
  const double departureHere = Departure[v].Value();
  const double margin = 1e-9;
  double intervals[2][2];
  int numIntervals = 0;
  if (src >= 0 || std::isnan(in))
  {
    intervals[numIntervals][0] = -1.0;
    intervals[numIntervals++][1] = theta + 1.0;
  }
  else if (Surface.IsBoundaryVertex(v))
  {
    intervals[numIntervals][0] = -1.0;
    intervals[numIntervals++][1] = in - Pi + margin;
    intervals[numIntervals][0] = in + Pi - margin;
    intervals[numIntervals++][1] = theta + 1.0;
  }
  else
  {
    // [in + pi, in + theta - pi], taken modulo theta.
    double lo = in + Pi - margin, hi = in + theta - Pi + margin;
    if (lo >= theta)
    {
      lo -= theta;
      hi -= theta;
    }
    intervals[numIntervals][0] = lo;
    intervals[numIntervals++][1] = hi;
    if (hi > theta)
    {
      intervals[numIntervals][0] = lo - theta;
      intervals[numIntervals++][1] = hi - theta;
    }
  }

  const int start = Surface.VertexHalfedge(v);
  int h = start;
  do
  {
    // Face f = face(h) with h: v -> a, Next(h): a -> b, Prev(h): b -> v; its corner at v spans
    // [FanAngle[h], FanAngle[h] + beta] about v.
    Fenced.Enter(h / 3);
    const int opp = TriangleMesh::Next(h);
    const int a = Surface.Destination(h);
    const int b = Surface.Origin(TriangleMesh::Prev(h));
    const double p0 = FanAngle[h], beta = Surface.CornerAngle(h);
    for (int i = 0; i < numIntervals; ++i)
    {
      const bool fromStart = intervals[i][0] <= p0;
      const bool toEnd = intervals[i][1] >= p0 + beta;
      const double r0 = fromStart ? 0.0 : intervals[i][0] - p0;
      const double r1 = toEnd ? beta : intervals[i][1] - p0;
      if (r0 > r1)
      {
        continue;
      }
      if (fromStart)
      {
        const int back = Surface.Twin(h);
        UpdateVertex(a, sigma + Surface.EdgeLength(h), src, -1, 0.0,
          LazyAngle::Exactly(back >= 0 ? FanAngle[back] : Surface.TotalAngle(a)),
          LazyAngle::Exactly(src >= 0 ? p0 : departureHere), root);
      }
      if (toEnd)
      {
        UpdateVertex(b, sigma + Surface.EdgeLength(TriangleMesh::Prev(h)), src, -1, 0.0,
          LazyAngle::Exactly(FanAngle[TriangleMesh::Prev(h)]),
          LazyAngle::Exactly(src >= 0 ? p0 + beta : departureHere), root);
      }
      const int t = Surface.Twin(opp);
      if (t < 0)
      {
        continue;
      }
      // v is the opposite vertex of opp, at (Cx, Cy) in opp's frame; t's frame is opp's turned
      // by half a turn about the edge's midpoint. The ray from v at angle r from v->a meets the
      // opposite edge at |va| sin r / sin(r + alpha_a) from a (law of sines).
      const double ab = Surface.EdgeLength(t);
      const double va = Surface.EdgeLength(h);
      const double alphaA = Surface.CornerAngle(opp);
      auto fromA = [&](double r) { return va * std::sin(r) / std::sin(r + alphaA); };
      Window w;
      w.H = t;
      w.B0 = toEnd ? 0.0 : std::max(0.0, ab - fromA(r1));
      w.B1 = fromStart ? ab : std::min(ab, ab - fromA(r0));
      w.Ix = ab - Edges[opp].Cx;
      w.Iy = -Edges[opp].Cy;
      // In t's frame the direction from v to a is (Cx, Cy) of opp: departure angle p0.
      w.Phi = src >= 0 ? p0 - std::atan2(Edges[opp].Cy, Edges[opp].Cx) : departureHere;
      w.Sigma = sigma;
      w.Src = src;
      w.Root = root;
      if (w.B1 > w.B0)
      {
        PushWindow(w);
      }
    }
    h = Surface.RotateCCW(h);
  } while (h >= 0 && h != start);
}

void ExactGeodesicSolver::AddFaceSourceWindows(int f, const Vec3& p, int src, int sourceFace)
{
  // Departure angles are measured in the source face's plane from its first edge; a neighbour
  // face (source on an edge) is unfolded about the shared edge into that plane.
  const Vec3 n0 = Surface.FaceNormal(sourceFace);
  const Vec3 e0 = Surface.Position(Surface.Face(sourceFace)[1]) -
    Surface.Position(Surface.Face(sourceFace)[0]);
  const Vec3 x0 = e0 / Norm(e0), y0 = Cross(n0, x0);
  const Vec3 nf = Surface.FaceNormal(f);
  // Angle of a direction d lying in face f, expressed in the source face's frame.
  auto angleOf = [&](const Vec3& d) {
    Vec3 u = d;
    if (f != sourceFace)
    {
      // Rotate about the shared edge so that face f lies in the source face's plane.
      const Vec3 axis = Cross(nf, n0);
      const double s = Norm(axis);
      if (s > 1e-15)
      {
        const Vec3 k = axis / s;
        const double c = Dot(nf, n0);
        u = u * c + Cross(k, u) * s + k * (Dot(k, u) * (1.0 - c));
      }
    }
    return std::atan2(Dot(u, y0), Dot(u, x0));
  };
  for (int k = 0; k < 3; ++k)
  {
    const int e = 3 * f + k;
    const Vec3& X = Surface.Position(Surface.Origin(e));
    const Vec3& Y = Surface.Position(Surface.Destination(e));
    const Vec3 toP = p - X, toY = Y - X;
    UpdateVertex(Surface.Origin(e), Norm(toP), src, -1, 0.0,
      LazyAngle{ FanAngle[e], Dot(toY, toP), Norm(Cross(toY, toP)) },
      LazyAngle::Exactly(angleOf(X - p)), src);
    const int t = Surface.Twin(e);
    const double len = Surface.EdgeLength(e);
    // t runs Y -> X; in its frame the source lies below the edge (on f's side).
    const Vec3 u = (X - Y) / len;
    const Vec3 d = p - Y;
    const double x = Dot(d, u);
    const double y = -Norm(d - u * x);
    if (t < 0 || y > -1e-12 * len)
    {
      continue; // boundary edge, or the source lies on this edge (the neighbour face covers it)
    }
    Window w;
    w.H = t;
    w.B0 = 0.0;
    w.B1 = len;
    w.Ix = x;
    w.Iy = y;
    // The frame's x axis (Y -> X) has angle angleOf(X - Y) in the source frame.
    w.Phi = angleOf(X - Y);
    w.Sigma = 0.0;
    w.Src = src;
    w.Root = src;
    PushWindow(w);
  }
}

void ExactGeodesicSolver::Propagate(Window w)
{
  ++Stats.WindowsPropagated;
  const int h = w.H;
  const HalfedgeRecord& e = Edges[h];
  const double L = e.Length;
  const double cx = e.Cx, cy = e.Cy;
  const double ix = w.Ix, iy = w.Iy;
  // Where the ray from I through C crosses the edge.
  const double xc = ix + (cx - ix) * (-iy) / (cy - iy);
  bool left = xc > w.B0;  // some rays leave through edge A-C
  bool right = xc < w.B1; // some rays leave through edge C-B
  const double cover = 1e-10 * L;
  if (xc >= w.B0 - cover && xc <= w.B1 + cover)
  {
    const int vC = Opposite(h);
    const double dC = w.Sigma + Hypot(cx - ix, cy - iy);
    if (dC < Dist[vC] + Tolerance)
    {
      // Arrival direction at C, towards I, measured from C -> A (counter-clockwise in this
      // face's frame, as about C's fan).
      const double ax = -cx, ay = -cy, qx = ix - cx, qy = iy - cy;
      UpdateVertex(vC, dC, w.Src, h, xc,
        LazyAngle{ FanAngle[TriangleMesh::Prev(h)], ax * qx + ay * qy, ax * qy - ay * qx },
        w.Src >= 0 ? LazyAngle{ w.Phi, cx - ix, cy - iy } : LazyAngle::Exactly(w.Phi), w.Root);
    }
    else if (dC > Dist[vC] + Tolerance && CrossHalfedge[vC] == h)
    {
      // One angle, one split: a better path reaches C through this edge at CrossX; every ray of
      // this window on the far side of it crosses that path and is longer beyond the crossing.
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

  if (left)
  {
    const HalfedgeRecord& ca = Edges[TriangleMesh::Prev(h)];
    const int t = ca.Twin;
    if (t >= 0)
    {
      // New frame: origin A, x along A -> C.
      const double b = ca.Length;
      PushChild(w, t,
        window_geometry::MakeChild(
          window_geometry::LeftFrame(cx, cy, b), b, ix, iy, w.B0, w.B1, false, right),
        cy, cx);
    }
  }
  if (right)
  {
    const HalfedgeRecord& bc = Edges[TriangleMesh::Next(h)];
    const int t = bc.Twin;
    if (t >= 0)
    {
      // New frame: origin C, x along C -> B.
      const double a = bc.Length;
      PushChild(w, t,
        window_geometry::MakeChild(
          window_geometry::RightFrame(cx, cy, L, a), a, ix, iy, w.B0, w.B1, left, false),
        -cy, L - cx);
    }
  }
}

void ExactGeodesicSolver::PushChild(const Window& w, int t,
  const window_geometry::ChildWindow& child, double towardsY, double towardsX)
{
  if (!(child.B1 > child.B0))
  {
    return;
  }
  Window c;
  c.Ix = child.Ix;
  c.Iy = child.Iy;
  c.B0 = child.B0;
  c.B1 = child.B1;
  c.H = t;
  c.Sigma = w.Sigma;
  c.Src = w.Src;
  c.Root = w.Root;
  c.Phi = w.Src >= 0 ? w.Phi + std::atan2(towardsY, towardsX) : w.Phi;
  PushWindow(c);
}

void ExactGeodesicSolver::FinalizeUpTo(double key)
{
  auto order = [](const VertexKey& a, const VertexKey& b) { return a.D > b.D; };
  while (!VertexQueue.empty() && VertexQueue.front().D <= key)
  {
    const VertexKey k = VertexQueue.front();
    std::pop_heap(VertexQueue.begin(), VertexQueue.end(), order);
    VertexQueue.pop_back();
    if (Final[k.V] || k.D != Dist[k.V])
    {
      continue;
    }
    Final[k.V] = 1;
    FinalOrder.push_back(k.V);
  }
}

SurfacePoint ExactGeodesicSolver::SourcePoint(const TriangleMesh& mesh, SurfacePoint s)
{
  if (s.IsVertex())
  {
    return s;
  }
  std::array<double, 3>& b = s.Bary;
  for (double& x : b)
  {
    x = std::max(x, 0.0);
  }
  const double sum = b[0] + b[1] + b[2];
  for (double& x : b)
  {
    x /= sum;
  }
  for (std::size_t k = 0; k < 3; ++k)
  {
    if (b[k] > 1.0 - 1e-12)
    {
      return SurfacePoint::AtVertex(mesh.Face(s.Face)[k]);
    }
  }
  return s;
}

void ExactGeodesicSolver::AddSource(int i, SurfacePoint s)
{
  if (!s.IsVertex())
  {
    s = SourcePoint(Surface, s);
    if (!s.IsVertex())
    {
      const std::array<double, 3>& b = s.Bary;
      const Vec3 p = Surface.Interpolate(s.Face, b);
      AddFaceSourceWindows(s.Face, p, i, s.Face);
      for (int k = 0; k < 3; ++k)
      {
        // On an edge: the face across it holds the source too.
        const int e = 3 * s.Face + (k + 1) % 3; // edge opposite corner k
        if (b[k] < 1e-12 && Surface.Twin(e) >= 0)
        {
          AddFaceSourceWindows(Surface.Twin(e) / 3, p, i, s.Face);
        }
      }
      return;
    }
  }
  UpdateVertex(s.Vertex, 0.0, i, -1, 0.0, LazyAngle(), LazyAngle(), i);
  if (!Propagated[s.Vertex])
  {
    Propagated[s.Vertex] = 1;
    PropagateFromVertex(s.Vertex, 0.0, i);
  }
}

std::size_t ExactGeodesicSolver::MarkTargets(const ExactGeodesicOptions& options)
{
  std::size_t targets = 0;
  if (options.StopOnceFinal && !options.StopOnceFinal->empty())
  {
    Target.resize(Surface.NumberOfVertices(), 0);
    for (int v : *options.StopOnceFinal)
    {
      if (v >= 0 && v < Surface.NumberOfVertices() && !Target[v])
      {
        Target[v] = 1;
        ++targets;
      }
    }
  }
  return targets;
}

bool ExactGeodesicSolver::ProcessWindows(
  double maxDistance, std::size_t maxFinal, std::size_t targetsLeft)
{
  // StopOnceFinal: targetsLeft counts its distinct vertices not final yet (checked as FinalOrder
  // grows; `seen` of them checked so far).
  std::size_t seen = 0;
  const bool targeted = targetsLeft > 0;
  while (!Queue.Empty())
  {
    Window w = Dequeue();
    if (w.Key > maxDistance)
    {
      break;
    }
    FinalizeUpTo(w.Key);
    if (maxFinal > 0 && FinalOrder.size() >= maxFinal)
    {
      return true;
    }
    for (; targeted && seen < FinalOrder.size(); ++seen)
    {
      targetsLeft -= Target[FinalOrder[seen]];
    }
    if (targeted && targetsLeft == 0)
    {
      return true;
    }
    Handle(w);
  }
  return false;
}

void ExactGeodesicSolver::Handle(Window w)
{
  if (w.H < 0)
  {
    const int v = -1 - w.H;
    if (!Propagated[v] && Dist[v] == w.Key)
    {
      Propagated[v] = 1;
      PropagateFromVertex(v, w.Key, w.Src);
    }
    return;
  }
  Fenced.Enter(w.H / 3);
  if (Trim(w))
  {
    Propagate(w);
  }
}

Status ExactGeodesicSolver::Solve(
  const std::vector<SurfacePoint>& sources, const ExactGeodesicOptions& options)
{
  Reset();
  Fenced.Start(options.Fence, Surface.NumberOfFaces());
  if (sources.empty())
  {
    return Status::Error("no source given");
  }
  if (const Status valid = Surface.CheckPoints(sources, "source"); !valid.Ok())
  {
    return valid;
  }

  const double maxDistance =
    options.MaximumDistance > 0.0 && std::isfinite(options.MaximumDistance) ? options.MaximumDistance
                                                                             : Inf;
  const std::size_t maxFinal =
    options.MaximumFinalVertices > 0 ? static_cast<std::size_t>(options.MaximumFinalVertices) : 0;

  for (int i = 0; i < static_cast<int>(sources.size()); ++i)
  {
    AddSource(i, sources[i]);
  }

  const std::size_t targets = MarkTargets(options);
  const bool targeted = targets > 0;
  const bool truncated = ProcessWindows(maxDistance, maxFinal, targets);
  if (!truncated)
  {
    FinalizeUpTo(maxDistance);
  }
  if (maxFinal > 0 && FinalOrder.size() > maxFinal)
  {
    // Keep exactly the K nearest.
    for (std::size_t i = maxFinal; i < FinalOrder.size(); ++i)
    {
      Final[FinalOrder[i]] = 0;
    }
    FinalOrder.resize(maxFinal);
  }
  if (targeted)
  {
    for (int v : *options.StopOnceFinal)
    {
      if (v >= 0 && v < Surface.NumberOfVertices())
      {
        Target[v] = 0;
      }
    }
  }
  return Status();
}

} // namespace gs
