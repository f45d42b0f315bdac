#include "VirtualSourceGeodesic.h"
#include "WindowGeometry.h"

#include <algorithm>
#include <cmath>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
using window_geometry::Hypot;
// Crossings between two progress reports.
constexpr std::int64_t ProgressStride = 1 << 16;
} // namespace

VirtualSourceSolver::VirtualSourceSolver(const TriangleMesh& mesh)
  : Surface(mesh)
{
  // The opposite vertex of each half-edge h in h's frame, from the three edge lengths (law of
  // cosines): no trigonometry.
  const int nh = Surface.NumberOfHalfedges();
  Cx.resize(nh);
  Cy.resize(nh);
  for (int h = 0; h < nh; ++h)
  {
    const double l = Surface.EdgeLength(h);
    const double b = Surface.EdgeLength(TriangleMesh::Prev(h));
    const double a = Surface.EdgeLength(TriangleMesh::Next(h));
    const double x = (l * l + b * b - a * a) / (2.0 * l);
    Cx[h] = x;
    Cy[h] = std::sqrt(std::max(b * b - x * x, 0.0));
  }
  Faces.assign(Surface.NumberOfFaces(), FaceState{ 0.0, 0.0, 0.0, Inf, -1 });
  Dist.assign(Surface.NumberOfVertices(), Inf);
  BucketWidth = std::max(Surface.MeanEdgeLength(), 1e-300);
}

std::vector<VirtualSourceSolver::QueueItem>* VirtualSourceSolver::BucketFor(double key)
{
  if (key > Horizon)
  {
    return nullptr;
  }
  // Never behind the bucket being processed (a key below it joins the current one).
  const double slot = key / BucketWidth;
  std::size_t b = slot < 1e15 ? static_cast<std::size_t>(slot) : Current;
  b = std::max(b, Current);
  if (b >= Buckets.size())
  {
    Buckets.resize(b + 1);
  }
  return &Buckets[b];
}

void VirtualSourceSolver::Push(int face, int except, double key)
{
  std::vector<QueueItem>* bucket = BucketFor(key);
  if (!bucket)
  {
    return;
  }
  for (int k = 0; k < 3; ++k)
  {
    const int h = 3 * face + k;
    if (h != except)
    {
      bucket->push_back({ h, static_cast<float>(key) });
    }
  }
}

VirtualSourceSolver::EdgeFrame VirtualSourceSolver::FrameOf(int h) const
{
  const int first = h - h % 3;
  switch (h % 3)
  {
    case 0:
      return { 0.0, 0.0, 1.0, 0.0 };
    case 1:
    {
      const double l0 = Surface.EdgeLength(first), l1 = Surface.EdgeLength(h);
      return { l0, 0.0, (Cx[first] - l0) / l1, Cy[first] / l1 };
    }
    default:
    {
      const double l2 = Surface.EdgeLength(h);
      return { Cx[first], Cy[first], -Cx[first] / l2, -Cy[first] / l2 };
    }
  }
}

void VirtualSourceSolver::PushVertex(int v, double key)
{
  if (std::vector<QueueItem>* bucket = BucketFor(key))
  {
    bucket->push_back({ -1 - v, static_cast<float>(key) });
  }
}

void VirtualSourceSolver::Seed(int f, double sx, double sy, double sigma)
{
  // Corners of f in its frame: (0, 0), (L, 0), (Cx, Cy) of its first half-edge.
  const int h = 3 * f;
  const double l = Surface.EdgeLength(h), cx = Cx[h], cy = Cy[h];
  const std::array<int, 3>& corners = Surface.Face(f);
  UpdateVertex(corners[0], sigma + Hypot(sx, sy));
  UpdateVertex(corners[1], sigma + Hypot(sx - l, sy));
  UpdateVertex(corners[2], sigma + Hypot(sx - cx, sy - cy));
  const double key = sigma + Hypot((l + cx) / 3.0 - sx, cy / 3.0 - sy);
  FaceState& face = Faces[f];
  if (!(key < face.Key))
  {
    return;
  }
  Stats.FacesReached += face.Key == Inf;
  face = FaceState{ sx, sy, sigma, key, -1 };
  Push(f, -1, key);
}

void VirtualSourceSolver::SeedAround(int v, double sigma)
{
  // Each face around v, with v as its source: its corners along its edges from v, its key from
  // its centroid's position in the frame of the half-edge leaving v.
  Surface.ForEachOutgoingHalfedge(v, [&](int h) {
    const double l = Surface.EdgeLength(h);
    UpdateVertex(Surface.Destination(h), sigma + l);
    UpdateVertex(Surface.Opposite(h), sigma + Surface.EdgeLength(TriangleMesh::Prev(h)));
    const int f = TriangleMesh::FaceOf(h);
    FaceState& face = Faces[f];
    const double key = sigma + Hypot((l + Cx[h]) / 3.0, Cy[h] / 3.0);
    if (!(key < face.Key))
    {
      return;
    }
    const int first = 3 * f;
    Stats.FacesReached += face.Key == Inf;
    face.Sx = h % 3 == 0 ? 0.0 : h % 3 == 1 ? Surface.EdgeLength(first) : Cx[first];
    face.Sy = h % 3 == 2 ? Cy[first] : 0.0;
    face.Sigma = sigma;
    face.Key = key;
    face.Entry = -1;
    Push(f, -1, key);
  });
}

void VirtualSourceSolver::Cross(int hs)
{
  ++Stats.Crossings;
  const int ht = Surface.Twin(hs);
  if (ht < 0)
  {
    return;
  }
  const FaceState& from = Faces[TriangleMesh::FaceOf(hs)];
  const double l = Surface.EdgeLength(ht);
  // The source in the frame of ht (origin A = Origin(ht), x along ht towards B = Destination(ht),
  // y > 0 into the next face ft): hs's frame turned by half a turn about the edge's midpoint.
  const EdgeFrame out = FrameOf(hs);
  const double qx = from.Sx - out.Ox, qy = from.Sy - out.Oy;
  const double sx = l - (qx * out.Ux + qy * out.Uy);
  const double sy = -(out.Ux * qy - out.Uy * qx);
  const double sigma = from.Sigma;
  const double px = Cx[ht], py = Cy[ht];
  const double gx = (l + px) / 3.0, gy = py / 3.0; // ft's centroid

  // Where the line from the source to (x, y) (y > 0 >= sy) crosses the edge's line.
  auto crossing = [&](double x, double y) { return sx + (x - sx) * (-sy) / (y - sy); };
  // Does the line to the centroid pass through the edge, or bend around A or B? A source in
  // front of the edge's line goes around the nearer end.
  enum Bend
  {
    None,
    AtA,
    AtB,
    AtD
  };
  Bend bend;
  if (sy <= 0.0)
  {
    // A line through an end of the edge passes, up to rounding (on flat meshes that line is the
    // geodesic, and the bend there would tie with it).
    const double t = crossing(gx, gy), slack = 1e-9 * l;
    bend = t < -slack ? AtA : t > l + slack ? AtB : None;
  }
  else
  {
    bend = Hypot(sx, sy) + Hypot(gx, gy) <= Hypot(sx - l, sy) + Hypot(gx - l, gy) ? AtA : AtB;
  }
  // The edge fs was entered by, A - D or D - B with D the far corner of fs. A line that passes
  // through this edge but not through that one leaves the faces the source was unfolded over,
  // beyond D; where D is a saddle (or a boundary vertex a path may bend at), the line is no
  // path at all and the path bends at D instead. (Elsewhere the line stays: the error of going
  // on straight past a vertex whose angle is near or below 2 pi is smaller than a bend's.)
  const double dx = l - Cx[hs], dy = -Cy[hs];
  const int entry = from.Entry;
  const bool checkD = entry >= 0 && Surface.IsPseudoSourceVertex(Surface.Opposite(hs));
  auto beyondD = [&](double x, double y) {
    if (!checkD)
    {
      return false;
    }
    // The sides of the line from the source to (x, y) that D and the entry edge's other end
    // (A or B) lie on: the line misses the entry edge beyond D when both are on one side and D
    // is nearer to the line.
    const double ux = x - sx, uy = y - sy;
    const double sD = ux * (dy - sy) - uy * (dx - sx);
    const double sE = entry == TriangleMesh::Next(hs) ? ux * (-sy) - uy * (-sx)
                                                      : ux * (-sy) - uy * (l - sx);
    return sD * sE > 0.0 && std::abs(sD) < std::abs(sE);
  };
  if (bend == None && beyondD(gx, gy))
  {
    bend = AtD;
  }
  double nsx = sx, nsy = sy, nsigma = sigma;
  if (bend == AtD)
  {
    nsx = dx;
    nsy = dy;
    nsigma = sigma + Hypot(sx - dx, sy - dy);
  }
  else if (bend != None)
  {
    nsx = bend == AtA ? 0.0 : l;
    nsy = 0.0;
    nsigma = sigma + Hypot(sx - nsx, sy);
  }

  // The opposite vertex P through this crossing, whatever the face decides: straight when the
  // line to it passes through the edge (and past D as above), else around the end it misses.
  double dP;
  if (bend != None)
  {
    dP = nsigma + Hypot(px - nsx, py - nsy);
  }
  else
  {
    const double tp = crossing(px, py);
    dP = tp < 0.0      ? sigma + Hypot(sx, sy) + Hypot(px, py)
      : tp > l         ? sigma + Hypot(sx - l, sy) + Hypot(px - l, py)
      : beyondD(px, py) ? sigma + Hypot(sx - dx, sy - dy) + Hypot(px - dx, py - dy)
                       : sigma + Hypot(px - sx, py - sy);
  }
  UpdateVertex(Surface.Opposite(ht), dP);

  const int ft = TriangleMesh::FaceOf(ht);
  const double key = nsigma + Hypot(gx - nsx, gy - nsy);
  FaceState& to = Faces[ft];
  // On a tie, the source with fewer bends behind it (a bend exactly on the line to the centroid
  // gives the centroid its distance, but the faces beyond a longer one).
  if (!(key < to.Key - Tolerance || (key <= to.Key + Tolerance && nsigma < to.Sigma - Tolerance)))
  {
    return;
  }
  ++Stats.FaceUpdates;
  Stats.FacesReached += to.Key == Inf;
  // The new state in ft's frame.
  const EdgeFrame in = FrameOf(ht);
  to.Sx = in.Ox + nsx * in.Ux - nsy * in.Uy;
  to.Sy = in.Oy + nsx * in.Uy + nsy * in.Ux;
  to.Sigma = nsigma;
  to.Key = key;
  to.Entry = bend == AtA || bend == AtB ? -1 : ht; // a source at A or B lies in ft
  Push(ft, ht, key);
}

Status VirtualSourceSolver::Solve(
  const std::vector<SurfacePoint>& sources, const VirtualSourceOptions& options)
{
  for (FaceState& face : Faces)
  {
    face.Key = Inf;
  }
  std::fill(Dist.begin(), Dist.end(), Inf);
  for (std::vector<QueueItem>& bucket : Buckets)
  {
    bucket.clear();
  }
  Current = 0;
  Stats = VirtualSourceStatistics();
  if (sources.empty())
  {
    return Status::Error("no source given");
  }
  if (const Status valid = Surface.CheckPoints(sources, "source"); !valid.Ok())
  {
    return valid;
  }
  const bool limited = options.MaximumDistance > 0.0 && std::isfinite(options.MaximumDistance);
  Horizon = limited ? options.MaximumDistance + Surface.LongestEdgeLength() : Inf;
  Tolerance = 1e-12 * BucketWidth;

  for (const SurfacePoint& source : sources)
  {
    if (source.IsVertex())
    {
      const int v = source.Vertex;
      Dist[v] = 0.0;
      SeedAround(v, 0.0);
      continue;
    }
    // A face point: in the frame of the face's first half-edge, corner 0 at (0, 0), corner 1 at
    // (L, 0), corner 2 at (Cx, Cy). Points on an edge reach the face across it by crossing.
    std::array<double, 3> b = source.Bary;
    for (double& x : b)
    {
      x = std::max(x, 0.0);
    }
    const double sum = b[0] + b[1] + b[2];
    const int h = 3 * source.Face;
    const double sx = (b[1] * Surface.EdgeLength(h) + b[2] * Cx[h]) / sum;
    const double sy = b[2] * Cy[h] / sum;
    Seed(source.Face, sx, sy, 0.0);
  }

  const std::int64_t numFaces = std::max(1, Surface.NumberOfFaces());
  std::int64_t nextReport = ProgressStride;
  for (; Current < Buckets.size(); ++Current)
  {
    // Items pushed into the current bucket while it is processed are appended to it.
    for (std::size_t i = 0; i < Buckets[Current].size(); ++i)
    {
      const QueueItem item = Buckets[Current][i];
      if (item.Halfedge < 0)
      {
        const int v = -1 - item.Halfedge;
        if (item.Key == static_cast<float>(Dist[v]))
        {
          SeedAround(v, Dist[v]);
        }
        continue;
      }
      if (item.Key != static_cast<float>(Faces[TriangleMesh::FaceOf(item.Halfedge)].Key))
      {
        continue; // the face changed since: its newer items carry its source
      }
      Cross(item.Halfedge);
      if (Stats.Crossings >= nextReport)
      {
        nextReport += ProgressStride;
        if (options.Progress &&
          !options.Progress(static_cast<double>(Stats.FacesReached) / static_cast<double>(numFaces)))
        {
          std::fill(Dist.begin(), Dist.end(), Inf);
          for (; Current < Buckets.size(); ++Current)
          {
            Buckets[Current].clear();
          }
          return Status::Aborted();
        }
      }
    }
    Buckets[Current].clear();
  }
  if (limited)
  {
    for (double& d : Dist)
    {
      if (d > options.MaximumDistance)
      {
        d = Inf;
      }
    }
  }
  if (options.Progress)
  {
    options.Progress(1.0);
  }
  return Status();
}

} // namespace gs
