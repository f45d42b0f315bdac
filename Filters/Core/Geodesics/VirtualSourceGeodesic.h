// Approximate geodesic distance with no precomputation, by virtual source propagation (after
// Trettner, Bommes, Kobbelt, "Geodesic distance computation via virtual source propagation",
// SGP 2021).
//
// Each face holds one virtual source: a point of the plane into which the faces crossed so far
// are unfolded, at geodesic distance Sigma from the real source, kept in the face's own frame.
// Crossing an edge into the next face keeps the source when the straight line
// from it to the next face's centroid passes through the edge; otherwise the path bends around
// the nearer end of the edge, which becomes the new virtual source (Sigma grows by its distance).
// The line is also checked against the edge the front entered the previous face by: where it
// misses that edge beyond the previous face's far corner and that corner is a saddle (or a
// boundary vertex a path may bend at), the path bends at that corner instead. Such a vertex is
// also a source of its own: when the front reaches its distance, the faces around it take it
// as their source where that is shorter (the shadow behind a saddle or a reflex boundary
// corner, which no single unfolded line reaches). A point source also carries its funnel: the
// reflex boundary corners at the ends of the edges crossed since the source that bound, left
// and right, the lines through all those edges; a line beyond one leaves the surface (it
// would cut across a notch or a hole), and the path bends at that corner instead.
// A face takes the crossing that gives its centroid the smallest distance, and on a tie the one
// with the smaller Sigma (fewer bends behind it: exact on flat meshes). The search is label
// correcting: a face may be improved several times; faces are processed in buckets of one mean
// edge length of distance, first in first out within a bucket. A vertex's distance is the smallest over the
// crossings that reach it: the straight line from the source when it passes through the edge
// crossed, else the bend around the nearer end.
//
// Past saddles a line is checked against the last two edges it crosses only, not every edge
// since the bend (bounding lines by saddles too makes closed meshes' errors larger, turning lines too
// short into bends too long): on a curved surface a vertex's distance may be a little below
// the geodesic one (a line no sequence of faces unfolds), and a bend at a vertex that is not a
// saddle a little above it. Exact on flat and developable meshes from most sources (behind a
// reflex corner a face whose centroid is in its shadow hands the bend on to faces that see the
// source: up to about 1% too long on the L-shaped plane); mean relative error 1e-3 ..
// 1.9e-3 on most real meshes measured, but 6e-3 .. 1e-2 where lines cross fields of saddle
// vertices: tori triangulated as regular grids, a CAD part with sharp creases (turbine)
// (Docs/BENCHMARKS.md gives the figures against the exact solver). The solve is
// sequential and deterministic; it touches each face a few times, so it is linear in practice.
//
// Departure angles (VirtualSourceOptions::Angles) come from the same unfoldings: exact on flat
// and developable meshes, but on curved ones a face's source sits off to the side by about the
// square root of the distance's relative error times the distance, so they are off by 1-4
// degrees on average (the graph engines' by a fraction of one). Geodesic polar coordinates keep
// the exact and graph engines for that reason (Docs/BENCHMARKS.md, "Virtual sources").
#pragma once

#include "Status.h"
#include "SurfaceCurve.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"
#include "WindowGeometry.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <vector>

namespace gs
{

struct VirtualSourceOptions
{
  // > 0 and finite: vertices farther than this stay unreached (infinite); the front stops a
  // longest edge beyond it.
  double MaximumDistance = 0.0;
  // Called now and then with the fraction of faces reached (non-decreasing, 0 .. 1); returning
  // false aborts the solve (every vertex is then unreached and Solve returns Status::Aborted()).
  std::function<bool(double)> Progress;
  // Also the departure angles from point sources (DepartureAngle); ignored when curves are
  // given.
  bool Angles = false;
};

struct VirtualSourceStatistics
{
  std::int64_t Crossings = 0;    // edges crossed (one per queue item processed)
  std::int64_t FaceUpdates = 0;  // crossings that improved a face
  std::int64_t FacesReached = 0; // faces given a source
};

class VirtualSourceSolver
{
public:
  static constexpr double Unreachable = std::numeric_limits<double>::infinity();

  // The mesh must outlive the solver. Sets up a record of 128 bytes per face (parallel), each
  // vertex's fan (12 bytes per face) and, at the first funnel a solve makes (a reflex boundary
  // corner), the funnels (32 bytes per face). The
  // front advances in buckets of `bucketWidth` of distance (0: the mesh's mean edge length; a
  // piece of a larger surface passes the whole surface's).
  explicit VirtualSourceSolver(const TriangleMesh& mesh, double bucketWidth = 0.0);

  // Distances from the nearest of the sources (vertices or face points). Fails (every vertex
  // unreached) when there is no source or a source is invalid (TriangleMesh::CheckPoint), the
  // message saying which, or when the progress callback aborts.
  Status Solve(const std::vector<SurfacePoint>& sources,
    const VirtualSourceOptions& options = VirtualSourceOptions());
  // The same from points and curves. Each run is the straight surface path between two
  // consecutive points of a curve (TraceSurfaceCurve of the two): each of its pieces seeds its
  // face with the whole run unfolded into that face's plane, a segment carried across the mesh
  // as one source (exact for a straight curve on a flat mesh). Fails as Solve does, or when a
  // piece's face does not exist or an end is not finite.
  Status Solve(const std::vector<SurfacePoint>& sources,
    const std::vector<std::vector<CurvePiece>>& runs,
    const VirtualSourceOptions& options = VirtualSourceOptions());

  // Distance of vertex v after the last solve (Unreachable when not reached or beyond
  // MaximumDistance).
  double Distance(int v) const { return Dist[v]; }
  const std::vector<double>& Distances() const { return Dist; }
  // The angle at which vertex v's path leaves its source, after a solve with Options.Angles (NaN
  // otherwise, for a source vertex and where unreached), in ExactGeodesicSolver::DepartureAngle's
  // convention: counter-clockwise about the outward normal from a vertex source's VertexHalfedge
  // (0 .. its total angle, up to a little rounding either way) or from a face point source's
  // first edge; behind a bend, the angle of the path to the first bend. The path is the one that
  // gave the distance: a line from the virtual source of the face crossed, so the angle is as
  // good as that face's source (Docs/BENCHMARKS.md gives its error against the exact solver).
  double DepartureAngle(int v) const;
  const VirtualSourceStatistics& Statistics() const { return Stats; }
  const TriangleMesh& Mesh() const { return Surface; }

private:
  // The solve on one piece of a surface partitioned over processes (VirtualSourcePieces.cpp)
  // drives the solver's queue.
  friend class VirtualSourcePieceSolve;
  // One record per face, two cache lines: the face's geometry (fixed) and its virtual source
  // (per solve). A crossing reads the record it leaves and the one it enters, and the distance of
  // one vertex: the solve is bound by memory latency, so everything a crossing needs of a face
  // sits on the face's own lines.
  struct alignas(64) FaceRecord
  {
    // The face's frame: corner 0 at (0, 0), corner 1 at (L[0], 0), corner 2 at (Cx, Cy), Cy > 0;
    // L[k] is the length of edge k (corner k to corner k + 1, half-edge 3 f + k).
    double L[3];
    double Cx, Cy;
    int Twin[3];            // the half-edge across edge k, -1 on the boundary
    unsigned int Corner[3]; // the vertex at corner k, with BendFlag where paths may bend
    // The virtual source, valid when Epoch is the solve's: a point (Sx, Sy), or a segment from it
    // to (Tx, Ty) unfolded from a piece of a curve source (a path starts at its point nearest to
    // where it goes); its distance Sigma from the real source; the distance of the face's
    // centroid through it (the face's key).
    double Sx, Sy, Sigma, Key, Tx, Ty;
    int Entry;  // the half-edge the source is seen through (-1: the source lies in the face)
    int Except; // the edge (0 .. 2) the front came in by, not crossed back; -1 for none
    unsigned int Epoch;
    bool Funneled; // the source has a funnel (Funnels), read only then
  };
  static constexpr unsigned int BendFlag = 0x80000000u; // a saddle or reflex boundary vertex
  static constexpr unsigned int EdgeFlag = 0x40000000u; // a reflex boundary vertex (funnels)
  static constexpr unsigned int VertexMask = ~(BendFlag | EdgeFlag); // (up to 2^30 vertices)
  // Edge k of a face in the face's frame: its origin (Ox, Oy) and unit direction (Ux, Uy), its
  // length, and the face's third corner (Px, Py) in the edge's own frame (origin at the edge's
  // start, x along it, y > 0 into the face).
  struct EdgeView
  {
    double Ox, Oy, Ux, Uy, Length, Px, Py;
  };
  [[gnu::always_inline]] static EdgeView ViewOf(const FaceRecord& r, int k);
  // A queue item: a face whose source is to cross its edges (or, -1 - v, vertex v's event) and
  // its key when queued, rounded to float, packed in 64 bits. An item whose face changed since
  // is skipped (one that rounds the same is processed with the face's current state, which is
  // what the newer item would do).
  using QueueItem = std::uint64_t;
  static QueueItem Item(int id, double key);
  static int ItemId(QueueItem item) { return static_cast<int>(static_cast<std::uint32_t>(item)); }
  static float ItemKey(QueueItem item)
  {
    const std::uint32_t bits = static_cast<std::uint32_t>(item >> 32);
    float k;
    std::memcpy(&k, &bits, sizeof(k));
    return k;
  }
  // The bucket of a key (null beyond the horizon).
  std::vector<QueueItem>* BucketFor(double key);
  void Prefetch(const std::vector<QueueItem>& bucket, std::size_t i) const;
  double KeyOf(const FaceRecord& r) const { return r.Epoch == Epoch ? r.Key : Unreachable; }
  // A face's funnel (point sources): the reflex boundary corners that bound, on the left and on
  // the right seen from its source, the lines that pass through every edge crossed since the
  // source (a line beyond one leaves the surface), in the face's frame (NaN x: no bound).
  struct Funnel
  {
    double Lx, Ly, Rx, Ry;
  };
  static Funnel Open()
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return { nan, 0.0, nan, 0.0 };
  }
  std::vector<Funnel> Funnels; // per face, valid while its record is Funneled (made at the first)
  void SetSource(FaceRecord& r, double sx, double sy, double tx, double ty, double sigma,
    double key, int entry, int except,
    const Funnel& funnel = Open());
  // Departure angles (Options.Angles), kept beside the records so that a solve without them
  // touches no more memory. A face's: where its source's paths leave the real source, Base plus
  // the angle of (x - S) from the direction (Rx, Ry) of its frame while the source is the real
  // one unfolded (Sigma 0), Base alone behind a bend (Rx NaN). A vertex's: a LazyAngle,
  // evaluated only when read (NaN Base: a source).
  struct FaceAngle
  {
    double Base, Rx, Ry;
  };
  using VertexAngle = window_geometry::LazyAngle;
  // The reference direction turned by the rotation (c, s) (cos, sin), as frames turn from face
  // to face (NaN stays NaN).
  static FaceAngle Turned(const FaceAngle& a, double c, double s)
  {
    return { a.Base, c * a.Rx - s * a.Ry, s * a.Rx + c * a.Ry };
  }
  // The departure towards (x, y) of the frame where the face's source is (sx, sy) and the
  // face's reference direction (rx, ry) (NaN: behind a bend).
  static VertexAngle Towards(const FaceAngle& a, double sx, double sy, double x, double y)
  {
    if (std::isnan(a.Rx))
    {
      return { a.Base, 1.0, 0.0 };
    }
    const double dx = x - sx, dy = y - sy;
    return { a.Base, a.Rx * dx + a.Ry * dy, a.Rx * dy - a.Ry * dx };
  }
  // Seeds face f with a point (or segment) source in its frame; its departure angles start
  // from `start` (the face's first edge for a point of it).
  void Seed(int f, double sx, double sy, double tx, double ty,
    const FaceAngle& start = FaceAngle{ 0.0, 1.0, 0.0 });
  // Corner k of a face in its frame.
  static double CornerX(const FaceRecord& r, int k) { return k == 0 ? 0.0 : k == 1 ? r.L[0] : r.Cx; }
  static double CornerY(const FaceRecord& r, int k) { return k == 2 ? r.Cy : 0.0; }
  // The crossing of edge k of face f (`from`), compiled with and without departure angles: the
  // solve without them pays nothing for them.
  template <bool Angles>
  void Cross(const FaceRecord& from, int f, int k);
  // The faces around v with v as their source: a source vertex (`source`: the departure angles
  // start there) or a vertex paths bend at.
  void SeedAround(int v, double sigma, bool source);
  void PushVertex(int v, double key);
  // Solve's steps: a fresh state (a new epoch, no distance, empty buckets); the faces and
  // vertices about the point sources; the faces of the curve pieces, each seeded with its whole
  // run; then the buckets in order, false when the progress callback aborts (every vertex then
  // unreached).
  void BeginSolve();
  void SeedPoints(const std::vector<SurfacePoint>& sources);
  // (`seeds`: whether to seed a piece in face f; null: every piece. A piece of a partitioned
  // surface seeds its own faces only.)
  void SeedRuns(const std::vector<std::vector<CurvePiece>>& runs,
    const std::function<bool(int)>& seeds = nullptr);
  template <bool Angles>
  bool ProcessBuckets(const VirtualSourceOptions& options);
  // One queue item: a face crosses its edges, or a vertex paths bend at seeds its faces.
  template <bool Angles>
  void ProcessItem(QueueItem item);
  // A shorter distance for the vertex of a corner. A vertex paths may bend at (BendFlag) is
  // queued at that distance: when the front gets there and no shorter distance came since, it
  // becomes the source of the faces around it (SeedAround).
  // `angle()` gives the path's departure (VertexAngle), asked only when angles are kept
  // (`angles`: TrackAngles, or a constant where the caller is compiled for one case).
  template <class AngleOf>
  void UpdateVertex(unsigned int corner, double d, bool angles, AngleOf&& angle)
  {
    const int v = static_cast<int>(corner & VertexMask);
    if (d < Dist[v])
    {
      Dist[v] = d;
      if (angles)
      {
        VertexAngles[v] = angle();
      }
      if (corner & BendFlag)
        PushVertex(v, d);
    }
  }

  const TriangleMesh& Surface;
  // Not value-initialized: the parallel setup touches each page first (no serial zeroing pass).
  std::unique_ptr<FaceRecord[]> Faces;
  // Each vertex's outgoing half-edges counter-clockwise (ForEachOutgoingHalfedge's order), the
  // fans one after another: a bend's seeding reads its fan's records without walking the mesh
  // from one to the next, and the queue fetches them ahead (Prefetch).
  std::vector<int> FanStart, FanHalfedges;
  unsigned int Epoch = 0;
  std::vector<double> Dist;
  bool TrackAngles = false; // this solve keeps departure angles
  std::vector<FaceAngle> FaceAngles;     // per face (sized at the first solve with angles)
  std::vector<VertexAngle> VertexAngles; // per vertex (likewise)
  std::vector<std::vector<QueueItem>> Buckets;
  std::size_t Current = 0;
  double BucketWidth = 1.0;
  double Tolerance = 0.0;  // a face takes a crossing only when it improves its key by more
  double Horizon = std::numeric_limits<double>::infinity(); // no face pushed beyond this key
  VirtualSourceStatistics Stats;
};

} // namespace gs
