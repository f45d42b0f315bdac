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
  Faces.assign(Surface.NumberOfFaces(), FaceState{ 0.0, 0.0, 0.0, Inf, -1, 0.0, 0.0 });
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

void VirtualSourceSolver::Seed(int f, double sx, double sy, double tx, double ty)
{
  // The segment's distance from a point of f's frame (corners (0, 0), (L, 0), (Cx, Cy) of its
  // first half-edge).
  const int h = 3 * f;
  const double l = Surface.EdgeLength(h), cx = Cx[h], cy = Cy[h];
  const double vx = tx - sx, vy = ty - sy, vv = vx * vx + vy * vy;
  auto distance = [&](double x, double y) {
    const double u = vv > 0.0 ? std::min(std::max(((x - sx) * vx + (y - sy) * vy) / vv, 0.0), 1.0) : 0.0;
    return Hypot(x - sx - u * vx, y - sy - u * vy);
  };
  const std::array<int, 3>& corners = Surface.Face(f);
  UpdateVertex(corners[0], distance(0.0, 0.0));
  UpdateVertex(corners[1], distance(l, 0.0));
  UpdateVertex(corners[2], distance(cx, cy));
  const double key = distance((l + cx) / 3.0, cy / 3.0);
  FaceState& face = Faces[f];
  if (!(key < face.Key))
  {
    return;
  }
  Stats.FacesReached += face.Key == Inf;
  face = FaceState{ sx, sy, 0.0, key, -1, tx, ty };
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
    face.Tx = face.Sx;
    face.Ty = face.Sy;
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
  // The source, the segment from (sx, sy) to (tx, ty) (one point for point sources), in the frame
  // of ht (origin A = Origin(ht), x along ht towards B = Destination(ht), y > 0 into the next
  // face ft): hs's frame turned by half a turn about the edge's midpoint.
  const EdgeFrame out = FrameOf(hs);
  auto toEdge = [&](double x, double y, double& ex, double& ey) {
    const double qx = x - out.Ox, qy = y - out.Oy;
    ex = l - (qx * out.Ux + qy * out.Uy);
    ey = -(out.Ux * qy - out.Uy * qx);
  };
  double sx, sy, tx, ty;
  toEdge(from.Sx, from.Sy, sx, sy);
  const bool segment = from.Tx != from.Sx || from.Ty != from.Sy;
  if (segment)
  {
    toEdge(from.Tx, from.Ty, tx, ty);
  }
  else
  {
    tx = sx;
    ty = sy;
  }
  const double sigma = from.Sigma;
  const double px = Cx[ht], py = Cy[ht];
  const double gx = (l + px) / 3.0, gy = py / 3.0; // ft's centroid
  // The point of the source nearest to (x, y): where the path to it starts.
  auto nearest = [&](double x, double y, double& ex, double& ey) {
    ex = sx;
    ey = sy;
    if (segment)
    {
      const double vx = tx - sx, vy = ty - sy, vv = vx * vx + vy * vy;
      const double u = vv > 0.0 ? std::min(std::max(((x - sx) * vx + (y - sy) * vy) / vv, 0.0), 1.0) : 0.0;
      ex = sx + u * vx;
      ey = sy + u * vy;
    }
  };

  // The edge fs was entered by, A - D or D - B with D the far corner of fs. A line that passes
  // through this edge but not through that one leaves the faces the source was unfolded over,
  // beyond D; where D is a saddle (or a boundary vertex a path may bend at), the line is no
  // path at all and the path bends at D instead. (Elsewhere the line stays: the error of going
  // on straight past a vertex whose angle is near or below 2 pi is smaller than a bend's.)
  const double dx = l - Cx[hs], dy = -Cy[hs];
  const int entry = from.Entry;
  const bool checkD = entry >= 0 && Surface.IsPseudoSourceVertex(Surface.Opposite(hs));
  // Does the line from (ex, ey) to (x, y) (y > 0) miss the entry edge beyond D? (The sides of
  // that line that D and the entry edge's other end, A or B, lie on: both on one side, D the
  // nearer.)
  auto beyondD = [&](double ex, double ey, double x, double y) {
    if (!checkD)
    {
      return false;
    }
    const double ux = x - ex, uy = y - ey;
    const double sD = ux * (dy - ey) - uy * (dx - ex);
    const double sE = entry == TriangleMesh::Next(hs) ? ux * (-ey) - uy * (-ex)
                                                      : ux * (-ey) - uy * (l - ex);
    return sD * sE > 0.0 && std::abs(sD) < std::abs(sE);
  };
  // The path from (ex, ey) to (x, y) through this crossing: straight when the line passes
  // through the edge (a line through an end of it passes, up to rounding: on flat meshes that
  // line is the geodesic, and the bend there would tie with it) and past D as above, else bent
  // at the end it misses or at D. A source in front of the edge's line goes around the nearer
  // end.
  enum Bend
  {
    None,
    AtA,
    AtB,
    AtD
  };
  auto route = [&](double ex, double ey, double x, double y) {
    if (ey <= 0.0)
    {
      const double t = ex + (x - ex) * (-ey) / (y - ey), slack = 1e-9 * l;
      return t < -slack ? AtA : t > l + slack ? AtB : beyondD(ex, ey, x, y) ? AtD : None;
    }
    return Hypot(ex, ey) + Hypot(x, y) <= Hypot(ex - l, ey) + Hypot(x - l, y) ? AtA : AtB;
  };
  auto bendPoint = [&](Bend b, double& bx, double& by) {
    bx = b == AtA ? 0.0 : b == AtB ? l : dx;
    by = b == AtD ? dy : 0.0;
  };

  double ex, ey;
  nearest(gx, gy, ex, ey);
  const Bend bend = route(ex, ey, gx, gy);
  double nsx = sx, nsy = sy, ntx = tx, nty = ty, nsigma = sigma, kx = ex, ky = ey;
  if (bend != None)
  {
    bendPoint(bend, kx, ky);
    nsigma = sigma + Hypot(ex - kx, ey - ky);
    nsx = ntx = kx;
    nsy = nty = ky;
  }

  // The opposite vertex P through this crossing, whatever the face decides: the centroid's bend
  // when it bends, else its own path.
  double dP;
  if (bend != None)
  {
    dP = nsigma + Hypot(px - kx, py - ky);
  }
  else
  {
    double fx, fy;
    nearest(px, py, fx, fy);
    const Bend b = route(fx, fy, px, py);
    double bx = fx, by = fy;
    if (b != None)
    {
      bendPoint(b, bx, by);
    }
    dP = sigma + Hypot(fx - bx, fy - by) + Hypot(px - bx, py - by);
  }
  UpdateVertex(Surface.Opposite(ht), dP);

  const int ft = TriangleMesh::FaceOf(ht);
  const double key = nsigma + Hypot(gx - kx, gy - ky);
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
  to.Tx = segment && bend == None ? in.Ox + ntx * in.Ux - nty * in.Uy : to.Sx;
  to.Ty = segment && bend == None ? in.Oy + ntx * in.Uy + nty * in.Ux : to.Sy;
  to.Sigma = nsigma;
  to.Key = key;
  to.Entry = bend == AtA || bend == AtB ? -1 : ht; // a source at A or B lies in ft
  Push(ft, ht, key);
}

Status VirtualSourceSolver::Solve(
  const std::vector<SurfacePoint>& sources, const VirtualSourceOptions& options)
{
  return Solve(sources, std::vector<std::vector<CurvePiece>>(), options);
}

Status VirtualSourceSolver::Solve(const std::vector<SurfacePoint>& sources,
  const std::vector<std::vector<CurvePiece>>& runs, const VirtualSourceOptions& options)
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
  std::vector<CurvePiece> pieces;
  for (const std::vector<CurvePiece>& run : runs)
  {
    pieces.insert(pieces.end(), run.begin(), run.end());
  }
  if (sources.empty() && pieces.empty())
  {
    return Status::Error("no source given");
  }
  if (const Status valid = Surface.CheckPoints(sources, "source"); !sources.empty() && !valid.Ok())
  {
    return valid;
  }
  for (std::size_t i = 0; i < pieces.size(); ++i)
  {
    const CurvePiece& piece = pieces[i];
    if (piece.Face < 0 || piece.Face >= Surface.NumberOfFaces() || !std::isfinite(piece.A.x) ||
      !std::isfinite(piece.A.y) || !std::isfinite(piece.A.z) || !std::isfinite(piece.B.x) ||
      !std::isfinite(piece.B.y) || !std::isfinite(piece.B.z))
    {
      return Status::Error("curve piece " + std::to_string(i) +
        " lies in no face of the mesh or has a non-finite end");
    }
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
    Seed(source.Face, sx, sy, sx, sy);
  }
  for (const std::vector<CurvePiece>& run : runs)
  {
    double total = 0.0;
    for (const CurvePiece& piece : run)
    {
      total += Norm(piece.B - piece.A);
    }
    double before = 0.0;
    for (const CurvePiece& piece : run)
    {
      // The piece's ends in its face's frame (x along corner 0 -> corner 1, y towards corner
      // 2), then the whole run along the piece's line: the run unfolded into this face.
      const std::array<int, 3>& corners = Surface.Face(piece.Face);
      const Vec3& origin = Surface.Position(corners[0]);
      const Vec3 u = (Surface.Position(corners[1]) - origin) / Surface.EdgeLength(3 * piece.Face);
      const Vec3 v = gs::Cross(Surface.FaceNormal(piece.Face), u);
      double ax = Dot(piece.A - origin, u), ay = Dot(piece.A - origin, v);
      double bx = Dot(piece.B - origin, u), by = Dot(piece.B - origin, v);
      const double length = Norm(piece.B - piece.A);
      if (length > 0.0)
      {
        const double after = std::max(total - before - length, 0.0);
        const double dx = (bx - ax) / length, dy = (by - ay) / length;
        ax -= before * dx;
        ay -= before * dy;
        bx += after * dx;
        by += after * dy;
      }
      before += length;
      Seed(piece.Face, ax, ay, bx, by);
    }
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
