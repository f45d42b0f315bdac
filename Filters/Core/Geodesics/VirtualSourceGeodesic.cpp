#include "VirtualSourceGeodesic.h"
#include "ExactGeodesic.h"
#include "WindowGeometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
constexpr double Nan = std::numeric_limits<double>::quiet_NaN();
using window_geometry::Hypot;
// Crossings between two progress reports.
constexpr std::int64_t ProgressStride = 1 << 16;
} // namespace

VirtualSourceSolver::VirtualSourceSolver(const TriangleMesh& mesh, double bucketWidth)
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
      const bool bend = Surface.IsPseudoSourceVertex(corners[k]);
      r.Corner[k] = static_cast<unsigned int>(corners[k]) | (bend ? BendFlag : 0u) |
        (bend && Surface.IsBoundaryVertex(corners[k]) ? EdgeFlag : 0u);
    }
    const double l = r.L[0], b = r.L[2], a = r.L[1];
    r.Cx = (l * l + b * b - a * a) / (2.0 * l);
    r.Cy = std::sqrt(std::max(b * b - r.Cx * r.Cx, 0.0));
    r.Sx = r.Sy = r.Sigma = r.Tx = r.Ty = 0.0;
    r.Key = Inf;
    r.Entry = r.Except = -1;
    r.Epoch = 0;
    r.Funneled = false;
  }
  const int nv = Surface.NumberOfVertices();
  FanStart.assign(static_cast<std::size_t>(nv) + 1, 0);
  FanHalfedges.reserve(3 * static_cast<std::size_t>(nf));
  for (int v = 0; v < nv; ++v)
  {
    Surface.ForEachOutgoingHalfedge(v, [this](int h) { FanHalfedges.push_back(h); });
    FanStart[static_cast<std::size_t>(v) + 1] = static_cast<int>(FanHalfedges.size());
  }
  Dist.assign(static_cast<std::size_t>(nv), Inf);
  BucketWidth = std::max(bucketWidth > 0.0 ? bucketWidth : Surface.MeanEdgeLength(), 1e-300);
}

inline VirtualSourceSolver::EdgeView VirtualSourceSolver::ViewOf(const FaceRecord& r, int k)
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
  // the one Lead1 ahead (whose record the first stage brought in); for a vertex item, its fan's
  // list, then its fan's records.
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
    else
    {
      __builtin_prefetch(FanHalfedges.data() + FanStart[static_cast<std::size_t>(-1 - id)]);
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
    else
    {
      const std::size_t v = static_cast<std::size_t>(-1 - id);
      for (int k = FanStart[v]; k < FanStart[v + 1]; ++k)
      {
        fetch(Faces[TriangleMesh::FaceOf(FanHalfedges[static_cast<std::size_t>(k)])]);
      }
    }
  }
}

void VirtualSourceSolver::SetSource(FaceRecord& r, double sx, double sy, double tx, double ty,
  double sigma, double key, int entry, int except, const Funnel& funnel)
{
  r.Funneled = !std::isnan(funnel.Lx) || !std::isnan(funnel.Rx);
  if (r.Funneled)
  {
    if (Funnels.empty())
    {
      Funnels.resize(static_cast<std::size_t>(Surface.NumberOfFaces())); // (the first funnel)
    }
    Funnels[static_cast<std::size_t>(&r - Faces.get())] = funnel;
  }
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

void VirtualSourceSolver::Seed(
  int f, double sx, double sy, double tx, double ty, const FaceAngle& start)
{
  // The segment's distance from a point of f's frame.
  FaceRecord& r = Faces[f];
  const double l = r.L[0], cx = r.Cx, cy = r.Cy;
  const double vx = tx - sx, vy = ty - sy, vv = vx * vx + vy * vy;
  auto distance = [&](double x, double y) {
    const double u = vv > 0.0 ? std::min(std::max(((x - sx) * vx + (y - sy) * vy) / vv, 0.0), 1.0) : 0.0;
    return Hypot(x - sx - u * vx, y - sy - u * vy);
  };
  UpdateVertex(r.Corner[0], distance(0.0, 0.0), TrackAngles, [&] { return Towards(start, sx, sy, 0.0, 0.0); });
  UpdateVertex(r.Corner[1], distance(l, 0.0), TrackAngles, [&] { return Towards(start, sx, sy, l, 0.0); });
  UpdateVertex(r.Corner[2], distance(cx, cy), TrackAngles, [&] { return Towards(start, sx, sy, cx, cy); });
  const double key = distance((l + cx) / 3.0, cy / 3.0);
  if (key < KeyOf(r))
  {
    SetSource(r, sx, sy, tx, ty, 0.0, key, -1, -1);
    if (TrackAngles)
    {
      FaceAngles[f] = start;
    }
  }
}

void VirtualSourceSolver::SeedAround(int v, double sigma, bool source)
{
  // Each face around v, with v as its source: its corners along its edges from v, its key from
  // its centroid's position in the frame of the half-edge leaving v. Departure angles: from a
  // source vertex, each half-edge's fan angle (the corner angles before it, counter-clockwise
  // from VertexHalfedge); behind a bend, v's own.
  const double behind = TrackAngles && !source ? VertexAngles[v].Value() : 0.0;
  double fan = 0.0;
  for (int i = FanStart[static_cast<std::size_t>(v)]; i < FanStart[static_cast<std::size_t>(v) + 1]; ++i)
  {
    const int h = FanHalfedges[static_cast<std::size_t>(i)];
    const int f = TriangleMesh::FaceOf(h);
    FaceRecord& r = Faces[f];
    const int k = h % 3;
    const EdgeView e = ViewOf(r, k);
    // (The corner angles are read only for angles: a bend's seeding would wait on them.)
    const double corner = TrackAngles && source ? Surface.CornerAngle(h) : 0.0;
    const double p0 = source ? fan : behind, p1 = source ? fan + corner : behind;
    fan += corner;
    UpdateVertex(r.Corner[(k + 1) % 3], sigma + e.Length, TrackAngles, [&] { return VertexAngle{ p0, 1.0, 0.0 }; });
    UpdateVertex(
      r.Corner[(k + 2) % 3], sigma + r.L[(k + 2) % 3], TrackAngles, [&] { return VertexAngle{ p1, 1.0, 0.0 }; });
    const double key = sigma + Hypot((e.Length + e.Px) / 3.0, e.Py / 3.0);
    if (key < KeyOf(r))
    {
      SetSource(r, e.Ox, e.Oy, e.Ox, e.Oy, sigma, key, -1, -1);
      if (TrackAngles)
      {
        FaceAngles[f] = source ? FaceAngle{ p0, e.Ux, e.Uy } : FaceAngle{ behind, Nan, Nan };
      }
    }
  }
}

namespace
{
// Where the path through a crossing bends: nowhere, at an end of the edge crossed (A or B), or
// at the far corner D of the face left.
enum class Bend
{
  None,
  AtA,
  AtB,
  AtD,
  AtLeft, // the funnel's bounds (CrossingSource)
  AtRight
};

// The source of the face being left, in the frame of the half-edge it crosses into (origin
// A = Origin(ht), x along ht towards B = Destination(ht), y > 0 into the next face), and the
// tests that route a path from it through the crossing.
struct CrossingSource
{
  double L;              // the edge's length
  double Sx, Sy, Tx, Ty; // the segment from (Sx, Sy) to (Tx, Ty), one point when !Segment
  bool Segment;
  // The edge the face left was entered by, A - D or D - B with D = (Dx, Dy) its far corner. A
  // line that passes through this edge but not through that one leaves the faces the source
  // was unfolded over, beyond D; where D is a saddle (or a boundary vertex a path may bend at:
  // CheckD), the line is no path at all and the path bends at D instead. (Elsewhere the line
  // stays: the error of going on straight past a vertex whose angle is near or below 2 pi is
  // smaller than a bend's.)
  double Dx, Dy;
  int Entry; // the half-edge the source is seen through in the face left
  int Hs;    // the half-edge crossed, in the face left
  bool CheckD;
  // The face left's funnel (a point source): a line from the source to the left of (Lx, Ly) or
  // to the right of (Rx, Ry), reflex boundary corners of the edges crossed since the source,
  // leaves the surface: the path bends there.
  bool HasLeft = false, HasRight = false;
  double Lx = 0.0, Ly = 0.0, Rx = 0.0, Ry = 0.0;
  // For a face that takes the point source straight on: the funnel narrowed by this edge's ends
  // that are reflex boundary corners (A on the left, B on the right), NaN x where unbounded.
  void Narrowed(bool reflexA, bool reflexB, double& lx, double& ly, double& rx, double& ry) const
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    lx = HasLeft ? Lx : nan;
    ly = Ly;
    rx = HasRight ? Rx : nan;
    ry = Ry;
    if (reflexA && (!HasLeft || (Lx - Sx) * (-Sy) - (Ly - Sy) * (-Sx) < 0.0))
    {
      lx = ly = 0.0;
    }
    if (reflexB && (!HasRight || (Rx - Sx) * (-Sy) - (Ry - Sy) * (L - Sx) > 0.0))
    {
      rx = L;
      ry = 0.0;
    }
  }
  Bend OutsideFunnel(double ex, double ey, double x, double y) const
  {
    const double ux = x - ex, uy = y - ey;
    if (HasLeft && (Lx - ex) * uy - (Ly - ey) * ux > 0.0)
    {
      return Bend::AtLeft;
    }
    if (HasRight && (Rx - ex) * uy - (Ry - ey) * ux < 0.0)
    {
      return Bend::AtRight;
    }
    return Bend::None;
  }

  // The point of the source nearest to (x, y): where the path to it starts.
  void Nearest(double x, double y, double& ex, double& ey) const
  {
    ex = Sx;
    ey = Sy;
    if (Segment)
    {
      const double vx = Tx - Sx, vy = Ty - Sy, vv = vx * vx + vy * vy;
      const double u = vv > 0.0 ? std::min(std::max(((x - Sx) * vx + (y - Sy) * vy) / vv, 0.0), 1.0) : 0.0;
      ex = Sx + u * vx;
      ey = Sy + u * vy;
    }
  }
  // Does the line from (ex, ey) to (x, y) (y > 0) miss the entry edge beyond D? (The sides of
  // that line that D and the entry edge's other end, A or B, lie on: both on one side, D the
  // nearer.)
  bool BeyondD(double ex, double ey, double x, double y) const
  {
    if (!CheckD)
    {
      return false;
    }
    const double ux = x - ex, uy = y - ey;
    const double sD = ux * (Dy - ey) - uy * (Dx - ex);
    const double sE = Entry == TriangleMesh::Next(Hs) ? ux * (-ey) - uy * (-ex)
                                                      : ux * (-ey) - uy * (L - ex);
    return sD * sE > 0.0 && std::abs(sD) < std::abs(sE);
  }
  // The path from (ex, ey) to (x, y) through this crossing: straight when the line passes
  // through the edge (a line through an end of it passes, up to rounding: on flat meshes that
  // line is the geodesic, and the bend there would tie with it) and past D as above, else bent
  // at the end it misses or at D. A source in front of the edge's line goes around the nearer
  // end.
  Bend Route(double ex, double ey, double x, double y) const
  {
    if (ey <= 0.0)
    {
      const double t = ex + (x - ex) * (-ey) / (y - ey), slack = 1e-9 * L;
      return t < -slack ? Bend::AtA
        : t > L + slack ? Bend::AtB
        : BeyondD(ex, ey, x, y) ? Bend::AtD
                                : OutsideFunnel(ex, ey, x, y);
    }
    return Hypot(ex, ey) + Hypot(x, y) <= Hypot(ex - L, ey) + Hypot(x - L, y) ? Bend::AtA
                                                                            : Bend::AtB;
  }
  // The distance through this crossing to (px, py), the opposite vertex of the next face: the
  // centroid's bend (`bend` at (kx, ky), nsigma there) when it bends, else its own path from
  // the source at sigma; (fx, fy) where that path first turns ((px, py) when straight).
  double DistanceTo(double px, double py, double sigma, Bend bend, double kx, double ky,
    double nsigma, double& fx, double& fy) const
  {
    fx = px;
    fy = py;
    if (bend != Bend::None)
    {
      fx = kx;
      fy = ky;
      return nsigma + Hypot(px - kx, py - ky);
    }
    double qx, qy;
    Nearest(px, py, qx, qy);
    const Bend b = Route(qx, qy, px, py);
    if (b != Bend::None)
    {
      BendPoint(b, fx, fy);
    }
    return sigma + Hypot(qx - fx, qy - fy) + Hypot(px - fx, py - fy);
  }
  void BendPoint(Bend b, double& bx, double& by) const
  {
    bx = b == Bend::AtA ? 0.0 : b == Bend::AtB ? L : b == Bend::AtLeft ? Lx : b == Bend::AtRight ? Rx : Dx;
    by = b == Bend::AtD ? Dy : b == Bend::AtLeft ? Ly : b == Bend::AtRight ? Ry : 0.0;
  }
};
} // namespace

template <bool Angles>
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
  // The source in the frame of ht: hs's frame turned by half a turn about the edge's midpoint.
  auto toEdge = [&](double x, double y, double& ex, double& ey) {
    const double qx = x - out.Ox, qy = y - out.Oy;
    ex = l - (qx * out.Ux + qy * out.Uy);
    ey = -(out.Ux * qy - out.Uy * qx);
  };
  CrossingSource source;
  source.L = l;
  toEdge(from.Sx, from.Sy, source.Sx, source.Sy);
  source.Segment = from.Tx != from.Sx || from.Ty != from.Sy;
  if (source.Segment)
  {
    toEdge(from.Tx, from.Ty, source.Tx, source.Ty);
  }
  else
  {
    source.Tx = source.Sx;
    source.Ty = source.Sy;
  }
  source.Dx = l - out.Px;
  source.Dy = -out.Py;
  source.Entry = from.Entry;
  source.Hs = hs;
  source.CheckD = from.Entry >= 0 && (from.Corner[(k + 2) % 3] & BendFlag);
  if (from.Funneled && !source.Segment)
  {
    const Funnel& funnel = Funnels[static_cast<std::size_t>(f)];
    source.HasLeft = !std::isnan(funnel.Lx);
    source.HasRight = !std::isnan(funnel.Rx);
    toEdge(funnel.Lx, funnel.Ly, source.Lx, source.Ly); // (NaN stays NaN, unread)
    toEdge(funnel.Rx, funnel.Ry, source.Rx, source.Ry);
  }
  const double sx = source.Sx, sy = source.Sy, tx = source.Tx, ty = source.Ty;
  const double sigma = from.Sigma;
  const double px = in.Px, py = in.Py;
  const double gx = (l + px) / 3.0, gy = py / 3.0; // the next face's centroid

  double ex, ey;
  source.Nearest(gx, gy, ex, ey);
  const Bend bend = source.Route(ex, ey, gx, gy);
  double nsx = sx, nsy = sy, ntx = tx, nty = ty, nsigma = sigma, kx = ex, ky = ey;
  if (bend != Bend::None)
  {
    source.BendPoint(bend, kx, ky);
    nsigma = sigma + Hypot(ex - kx, ey - ky);
    nsx = ntx = kx;
    nsy = nty = ky;
  }

  // The opposite vertex P through this crossing, whatever the face decides.
  double fx, fy;
  const double dP = source.DistanceTo(px, py, sigma, bend, kx, ky, nsigma, fx, fy);
  // Angles: the face left's reference direction in the crossing's frame (turned as its source).
  const FaceAngle angle = Angles ? Turned(FaceAngles[f], -out.Ux, out.Uy) : FaceAngle{ Nan, Nan, Nan };
  UpdateVertex(to.Corner[(kt + 2) % 3], dP, Angles, [&] { return Towards(angle, sx, sy, fx, fy); });

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
  const bool carried = source.Segment && bend == Bend::None;
  // The funnel goes on with a point source that goes straight on, narrowed by the ends of the
  // edge that are reflex boundary corners (A on the left, B on the right, as seen from the
  // source); a bend opens it again.
  Funnel next = Open();
  const unsigned int a = from.Corner[(k + 1) % 3], b = from.Corner[k];
  if (bend == Bend::None && !source.Segment &&
    (source.HasLeft || source.HasRight || ((a | b) & EdgeFlag)))
  {
    double lx, ly, rx, ry;
    source.Narrowed((a & EdgeFlag) != 0, (b & EdgeFlag) != 0, lx, ly, rx, ry);
    // (Into the next face's frame; NaN stays NaN.)
    next = { in.Ox + lx * in.Ux - ly * in.Uy, in.Oy + lx * in.Uy + ly * in.Ux,
      in.Ox + rx * in.Ux - ry * in.Uy, in.Oy + rx * in.Uy + ry * in.Ux };
  }
  SetSource(to, nx, ny, carried ? in.Ox + ntx * in.Ux - nty * in.Uy : nx,
    carried ? in.Oy + ntx * in.Uy + nty * in.Ux : ny, nsigma, key,
    bend == Bend::AtA || bend == Bend::AtB ? -1 : ht, // a source at A or B lies in the face
    kt, next);
  if constexpr (Angles)
  {
    // Straight on: the reference direction turned into the next face's frame; bent: the angle
    // of the path to the bend.
    FaceAngles[TriangleMesh::FaceOf(ht)] = bend == Bend::None
      ? Turned(angle, in.Ux, in.Uy)
      : FaceAngle{ Towards(angle, sx, sy, kx, ky).Value(), Nan, Nan };
  }
}

double VirtualSourceSolver::DepartureAngle(int v) const
{
  return TrackAngles && std::isfinite(Dist[v]) ? VertexAngles[v].Value() : Nan;
}

Status VirtualSourceSolver::Solve(
  const std::vector<SurfacePoint>& sources, const VirtualSourceOptions& options)
{
  return Solve(sources, std::vector<std::vector<CurvePiece>>(), options);
}

void VirtualSourceSolver::BeginSolve()
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
}

namespace
{
// Fails for a piece that lies in no face of the mesh or has a non-finite end.
Status CheckPieces(const TriangleMesh& mesh, const std::vector<CurvePiece>& pieces)
{
  for (std::size_t i = 0; i < pieces.size(); ++i)
  {
    const CurvePiece& piece = pieces[i];
    if (piece.Face < 0 || piece.Face >= mesh.NumberOfFaces() || !std::isfinite(piece.A.x) ||
      !std::isfinite(piece.A.y) || !std::isfinite(piece.A.z) || !std::isfinite(piece.B.x) ||
      !std::isfinite(piece.B.y) || !std::isfinite(piece.B.z))
    {
      return Status::Error("curve piece " + std::to_string(i) +
        " lies in no face of the mesh or has a non-finite end");
    }
  }
  return Status();
}
} // namespace

void VirtualSourceSolver::SeedPoints(const std::vector<SurfacePoint>& points)
{
  for (const SurfacePoint& point : points)
  {
    // A face point at a corner is that vertex (as the exact solver takes it): its faces all
    // around are seeded, not only the one that names it.
    const SurfacePoint source = ExactGeodesicSolver::SourcePoint(Surface, point);
    if (source.IsVertex())
    {
      const int v = source.Vertex;
      Dist[v] = 0.0;
      if (TrackAngles)
      {
        VertexAngles[v] = { Nan, 1.0, 0.0 }; // the pole
      }
      SeedAround(v, 0.0, true);
      continue;
    }
    // A face point (weights clamped and normalized by SourcePoint): in the frame of the face's
    // first half-edge, corner 0 at (0, 0), corner 1 at (L, 0), corner 2 at (Cx, Cy).
    auto seed = [this](int f, const std::array<double, 3>& b, const FaceAngle& start) {
      const FaceRecord& r = Faces[f];
      const double sx = b[1] * r.L[0] + b[2] * r.Cx, sy = b[2] * r.Cy;
      Seed(f, sx, sy, sx, sy, start);
    };
    const std::array<double, 3>& b = source.Bary;
    seed(source.Face, b, FaceAngle{ 0.0, 1.0, 0.0 });
    // A point on an edge is a source of the face across it too (as the exact solver seeds both
    // faces): crossing the edge it lies on, a rounding error would put it in front of the edge
    // or behind.
    const FaceRecord& r = Faces[source.Face];
    for (int k = 0; k < 3; ++k)
    {
      const int t = r.Twin[(k + 1) % 3]; // the edge opposite corner k
      if (b[static_cast<std::size_t>(k)] >= 1e-12 || t < 0)
      {
        continue;
      }
      // t runs from corner c = k + 2 to corner a = k + 1 of the face: from corner j to j + 1
      // across.
      const int a = (k + 1) % 3, c = (k + 2) % 3, g = TriangleMesh::FaceOf(t), j = t % 3;
      std::array<double, 3> w{};
      w[static_cast<std::size_t>(j)] = b[static_cast<std::size_t>(c)];
      w[static_cast<std::size_t>((j + 1) % 3)] = b[static_cast<std::size_t>(a)];
      // Angles start from the face's first edge, unfolded across: the edge's direction turned
      // by the rotation that takes the shared edge from this face's frame into the other's.
      const FaceRecord& q = Faces[g];
      const double fx = CornerX(r, a) - CornerX(r, c), fy = CornerY(r, a) - CornerY(r, c);
      const double gx = CornerX(q, (j + 1) % 3) - CornerX(q, j), gy = CornerY(q, (j + 1) % 3) - CornerY(q, j);
      const double norm = Hypot(fx, fy) * Hypot(gx, gy);
      seed(g, w, FaceAngle{ 0.0, (fx * gx + fy * gy) / norm, (fx * gy - fy * gx) / norm });
    }
  }
}

void VirtualSourceSolver::SeedRuns(
  const std::vector<std::vector<CurvePiece>>& runs, const std::function<bool(int)>& seeds)
{
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
      if (!seeds || seeds(piece.Face))
      {
        Seed(piece.Face, ax, ay, bx, by);
      }
    }
  }
}

template <bool Angles>
void VirtualSourceSolver::ProcessItem(QueueItem item)
{
  const int id = ItemId(item);
  if (id < 0)
  {
    const int v = -1 - id;
    if (ItemKey(item) == static_cast<float>(Dist[v]))
    {
      SeedAround(v, Dist[v], false);
    }
    return;
  }
  const FaceRecord& face = Faces[id];
  if (ItemKey(item) != static_cast<float>(face.Key))
  {
    return; // the face changed since: its newer item carries its source
  }
  for (int k = 0; k < 3; ++k)
  {
    if (k != face.Except)
    {
      Cross<Angles>(face, id, k);
    }
  }
}

// (The solve on pieces processes items without angles.)
template void VirtualSourceSolver::ProcessItem<false>(QueueItem item);

template <bool Angles>
bool VirtualSourceSolver::ProcessBuckets(const VirtualSourceOptions& options)
{
  const std::int64_t numFaces = std::max(1, Surface.NumberOfFaces());
  std::int64_t nextReport = ProgressStride;
  for (; Current < Buckets.size(); ++Current)
  {
    // Items pushed into the current bucket while it is processed are appended to it.
    for (std::size_t i = 0; i < Buckets[Current].size(); ++i)
    {
      Prefetch(Buckets[Current], i);
      ProcessItem<Angles>(Buckets[Current][i]);
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
          return false;
        }
      }
    }
    Buckets[Current].clear();
  }
  return true;
}

Status VirtualSourceSolver::Solve(const std::vector<SurfacePoint>& sources,
  const std::vector<std::vector<CurvePiece>>& runs, const VirtualSourceOptions& options)
{
  BeginSolve();
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
  if (const Status valid = CheckPieces(Surface, pieces); !valid.Ok())
  {
    return valid;
  }
  TrackAngles = options.Angles && runs.empty();
  if (TrackAngles)
  {
    FaceAngles.resize(static_cast<std::size_t>(Surface.NumberOfFaces()));
    VertexAngles.assign(Dist.size(), VertexAngle{ Nan, 1.0, 0.0 });
  }
  const bool limited = options.MaximumDistance > 0.0 && std::isfinite(options.MaximumDistance);
  Horizon = limited ? options.MaximumDistance + Surface.LongestEdgeLength() : Inf;
  Tolerance = 1e-12 * BucketWidth;

  SeedPoints(sources);
  SeedRuns(runs);
  if (!(TrackAngles ? ProcessBuckets<true>(options) : ProcessBuckets<false>(options)))
  {
    return Status::Aborted();
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
