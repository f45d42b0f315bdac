#include "VirtualSourceGeodesic.h"
#include "WindowGeometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>

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
  // Corner 2 in the frame of edge 0 from the three edge lengths (law of cosines): no
  // trigonometry.
  const int nf = Surface.NumberOfFaces();
  Faces.reset(new FaceRecord[static_cast<std::size_t>(nf)]);
#pragma omp parallel for schedule(static) if (nf > 20000)
  for (int f = 0; f < nf; ++f)
  {
    FaceRecord& r = Faces[f];
    const std::array<int, 3>& corners = Surface.Face(f);
    for (int k = 0; k < 3; ++k)
    {
      r.L[k] = Surface.EdgeLength(3 * f + k);
      r.Twin[k] = Surface.Twin(3 * f + k);
      r.Corner[k] = static_cast<unsigned int>(corners[k]) |
        (Surface.IsPseudoSourceVertex(corners[k]) ? BendFlag : 0u);
    }
    const double l = r.L[0], b = r.L[2], a = r.L[1];
    r.Cx = (l * l + b * b - a * a) / (2.0 * l);
    r.Cy = std::sqrt(std::max(b * b - r.Cx * r.Cx, 0.0));
    r.Sx = r.Sy = r.Sigma = r.Tx = r.Ty = 0.0;
    r.Key = Inf;
    r.Entry = r.Except = -1;
    r.Epoch = 0;
  }
  Dist.assign(Surface.NumberOfVertices(), Inf);
  BucketWidth = std::max(Surface.MeanEdgeLength(), 1e-300);
}

VirtualSourceSolver::EdgeView VirtualSourceSolver::ViewOf(const FaceRecord& r, int k)
{
  switch (k)
  {
    case 0:
      return { 0.0, 0.0, 1.0, 0.0, r.L[0], r.Cx, r.Cy };
    case 1:
    {
      // The third corner is corner 0: (0, 0) - (L0, 0) in the edge's frame.
      const double ux = (r.Cx - r.L[0]) / r.L[1], uy = r.Cy / r.L[1];
      return { r.L[0], 0.0, ux, uy, r.L[1], -r.L[0] * ux, r.L[0] * uy };
    }
    default:
    {
      // The third corner is corner 1: (L0, 0) - (Cx, Cy).
      const double ux = -r.Cx / r.L[2], uy = -r.Cy / r.L[2];
      const double qx = r.L[0] - r.Cx, qy = -r.Cy;
      return { r.Cx, r.Cy, ux, uy, r.L[2], qx * ux + qy * uy, ux * qy - uy * qx };
    }
  }
}

VirtualSourceSolver::QueueItem VirtualSourceSolver::Item(int id, double key)
{
  const float k = static_cast<float>(key);
  std::uint32_t bits;
  std::memcpy(&bits, &k, sizeof(bits));
  return static_cast<std::uint64_t>(static_cast<std::uint32_t>(id)) |
    (static_cast<std::uint64_t>(bits) << 32);
}

namespace
{
int ItemId(std::uint64_t item)
{
  return static_cast<int>(static_cast<std::uint32_t>(item));
}
float ItemKey(std::uint64_t item)
{
  const std::uint32_t bits = static_cast<std::uint32_t>(item >> 32);
  float k;
  std::memcpy(&k, &bits, sizeof(k));
  return k;
}
} // namespace

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

void VirtualSourceSolver::Prefetch(const std::vector<QueueItem>& bucket, std::size_t i) const
{
  // The solve waits on memory: each crossing enters a record far from the last. Two stages
  // ahead of the item being processed: the face of the item Lead2 ahead, then the neighbours of
  // the one Lead1 ahead (whose record the first stage brought in).
  constexpr std::size_t Lead1 = 6, Lead2 = 12;
  auto fetch = [](const FaceRecord& r) {
    __builtin_prefetch(&r);
    __builtin_prefetch(reinterpret_cast<const char*>(&r) + 64);
  };
  if (i + Lead2 < bucket.size())
  {
    const int id = ItemId(bucket[i + Lead2]);
    if (id >= 0)
    {
      fetch(Faces[id]);
    }
  }
  if (i + Lead1 < bucket.size())
  {
    const int id = ItemId(bucket[i + Lead1]);
    if (id >= 0)
    {
      for (const int t : Faces[id].Twin)
      {
        if (t >= 0)
        {
          fetch(Faces[TriangleMesh::FaceOf(t)]);
        }
      }
    }
  }
}

void VirtualSourceSolver::SetSource(FaceRecord& r, double sx, double sy, double tx, double ty,
  double sigma, double key, int entry, int except)
{
  Stats.FacesReached += r.Epoch != Epoch;
  r.Sx = sx;
  r.Sy = sy;
  r.Tx = tx;
  r.Ty = ty;
  r.Sigma = sigma;
  r.Key = key;
  r.Entry = entry;
  r.Except = except;
  r.Epoch = Epoch;
  if (std::vector<QueueItem>* bucket = BucketFor(key))
  {
    bucket->push_back(Item(static_cast<int>(&r - Faces.get()), key));
  }
}

void VirtualSourceSolver::PushVertex(int v, double key)
{
  if (std::vector<QueueItem>* bucket = BucketFor(key))
  {
    bucket->push_back(Item(-1 - v, key));
  }
}

void VirtualSourceSolver::Seed(int f, double sx, double sy, double tx, double ty)
{
  // The segment's distance from a point of f's frame.
  FaceRecord& r = Faces[f];
  const double l = r.L[0], cx = r.Cx, cy = r.Cy;
  const double vx = tx - sx, vy = ty - sy, vv = vx * vx + vy * vy;
  auto distance = [&](double x, double y) {
    const double u = vv > 0.0 ? std::min(std::max(((x - sx) * vx + (y - sy) * vy) / vv, 0.0), 1.0) : 0.0;
    return Hypot(x - sx - u * vx, y - sy - u * vy);
  };
  UpdateVertex(r.Corner[0], distance(0.0, 0.0));
  UpdateVertex(r.Corner[1], distance(l, 0.0));
  UpdateVertex(r.Corner[2], distance(cx, cy));
  const double key = distance((l + cx) / 3.0, cy / 3.0);
  if (key < KeyOf(r))
  {
    SetSource(r, sx, sy, tx, ty, 0.0, key, -1, -1);
  }
}

void VirtualSourceSolver::SeedAround(int v, double sigma)
{
  // Each face around v, with v as its source: its corners along its edges from v, its key from
  // its centroid's position in the frame of the half-edge leaving v.
  Surface.ForEachOutgoingHalfedge(v, [&](int h) {
    FaceRecord& r = Faces[TriangleMesh::FaceOf(h)];
    const int k = h % 3;
    const EdgeView e = ViewOf(r, k);
    UpdateVertex(r.Corner[(k + 1) % 3], sigma + e.Length);
    UpdateVertex(r.Corner[(k + 2) % 3], sigma + r.L[(k + 2) % 3]);
    const double key = sigma + Hypot((e.Length + e.Px) / 3.0, e.Py / 3.0);
    if (key < KeyOf(r))
    {
      SetSource(r, e.Ox, e.Oy, e.Ox, e.Oy, sigma, key, -1, -1);
    }
  });
}

void VirtualSourceSolver::Cross(const FaceRecord& from, int f, int k)
{
  ++Stats.Crossings;
  const int ht = from.Twin[k];
  if (ht < 0)
  {
    return;
  }
  const int hs = 3 * f + k;
  FaceRecord& to = Faces[TriangleMesh::FaceOf(ht)];
  const int kt = ht % 3;
  const EdgeView out = ViewOf(from, k);
  const EdgeView in = ViewOf(to, kt);
  const double l = out.Length;
  // The source, the segment from (sx, sy) to (tx, ty) (one point for point sources), in the frame
  // of ht (origin A = Origin(ht), x along ht towards B = Destination(ht), y > 0 into the next
  // face): hs's frame turned by half a turn about the edge's midpoint.
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
  const double px = in.Px, py = in.Py;
  const double gx = (l + px) / 3.0, gy = py / 3.0; // the next face's centroid
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

  // The edge the face left was entered by, A - D or D - B with D its far corner. A line that
  // passes through this edge but not through that one leaves the faces the source was unfolded
  // over, beyond D; where D is a saddle (or a boundary vertex a path may bend at), the line is
  // no path at all and the path bends at D instead. (Elsewhere the line stays: the error of
  // going on straight past a vertex whose angle is near or below 2 pi is smaller than a bend's.)
  const double dx = l - out.Px, dy = -out.Py;
  const int entry = from.Entry;
  const bool checkD = entry >= 0 && (from.Corner[(k + 2) % 3] & BendFlag);
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
  UpdateVertex(to.Corner[(kt + 2) % 3], dP);

  const double key = nsigma + Hypot(gx - kx, gy - ky);
  const double current = KeyOf(to);
  // On a tie, the source with fewer bends behind it (a bend exactly on the line to the centroid
  // gives the centroid its distance, but the faces beyond a longer one).
  if (!(key < current - Tolerance ||
        (key <= current + Tolerance && nsigma < to.Sigma - Tolerance)))
  {
    return;
  }
  ++Stats.FaceUpdates;
  // The new state in the next face's frame.
  const double nx = in.Ox + nsx * in.Ux - nsy * in.Uy;
  const double ny = in.Oy + nsx * in.Uy + nsy * in.Ux;
  const bool carried = segment && bend == None;
  SetSource(to, nx, ny, carried ? in.Ox + ntx * in.Ux - nty * in.Uy : nx,
    carried ? in.Oy + ntx * in.Uy + nty * in.Ux : ny, nsigma, key,
    bend == AtA || bend == AtB ? -1 : ht, // a source at A or B lies in the face
    kt);
}

Status VirtualSourceSolver::Solve(
  const std::vector<SurfacePoint>& sources, const VirtualSourceOptions& options)
{
  return Solve(sources, std::vector<std::vector<CurvePiece>>(), options);
}

Status VirtualSourceSolver::Solve(const std::vector<SurfacePoint>& sources,
  const std::vector<std::vector<CurvePiece>>& runs, const VirtualSourceOptions& options)
{
  if (++Epoch == 0)
  {
    // The epoch wrapped: no record may look current.
    for (int f = 0; f < Surface.NumberOfFaces(); ++f)
    {
      Faces[f].Epoch = 0;
    }
    Epoch = 1;
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
    const FaceRecord& r = Faces[source.Face];
    const double sx = (b[1] * r.L[0] + b[2] * r.Cx) / sum;
    const double sy = b[2] * r.Cy / sum;
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
      Prefetch(Buckets[Current], i);
      const QueueItem item = Buckets[Current][i];
      const int id = ItemId(item);
      if (id < 0)
      {
        const int v = -1 - id;
        if (ItemKey(item) == static_cast<float>(Dist[v]))
        {
          SeedAround(v, Dist[v]);
        }
        continue;
      }
      const FaceRecord& face = Faces[id];
      if (ItemKey(item) != static_cast<float>(face.Key))
      {
        continue; // the face changed since: its newer item carries its source
      }
      for (int k = 0; k < 3; ++k)
      {
        if (k != face.Except)
        {
          Cross(face, id, k);
        }
      }
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
