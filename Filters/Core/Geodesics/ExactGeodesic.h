// Exact polyhedral geodesic distance by window propagation (the Chen-Han family: windows carry
// an unfolded pseudo-source across faces; saddle and boundary vertices become pseudo-sources).
//
// What it implements, and the pruning that makes it fast (all of it provably exact):
//  - windows are processed in increasing order of their smallest distance (a priority queue),
//    so a vertex whose distance is <= the queue's smallest key is final: the solve can stop after
//    the K nearest vertices (saddle vertex graph) or past a maximum distance;
//  - "one angle, one split" (Xin and Wang 2009, ICH): a window that reaches the opposite vertex
//    later than the best known path through the same edge keeps only the child on its own side;
//  - vertex trimming: the part of a window where a path through an edge end point (or the
//    opposite vertex) is already shorter is cut off before propagation.
// Boundary vertices act as pseudo-sources like saddles; disconnected parts stay unreachable.
//
// The solver is built once per mesh and reused: each Solve() resets only what it touched, so
// thousands of small truncated solves (one per vertex) cost only their own work.
#pragma once

#include "SurfacePoint.h"
#include "TriangleMesh.h"
#include "WindowGeometry.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace gs
{

struct ExactGeodesicOptions
{
  // Stop once every vertex closer than this is final (0 or infinity: unlimited). Vertices beyond
  // it are reported unreachable.
  double MaximumDistance = 0.0;
  // Stop once this many vertices are final (0: unlimited). The K nearest vertices are then exact;
  // the others are unreachable.
  int MaximumFinalVertices = 0;
  // Stop once every vertex listed is final (null or empty: no such stop; MaximumDistance still
  // bounds the solve). The vertices final by then are exact; the others are unreachable.
  const std::vector<int>* StopOnceFinal = nullptr;
  // Faces the solve must not enter, one flag per face (null: none). A solve on a piece of a
  // larger surface marks the faces that have a vertex whose other faces are missing: one that
  // enters none of them computed what it would on the whole surface (FenceFacesEntered says
  // where it did; the solve itself goes on regardless).
  const std::vector<unsigned char>* Fence = nullptr;
};

struct ExactGeodesicStatistics
{
  std::int64_t WindowsCreated = 0;
  std::int64_t WindowsPropagated = 0;
  std::int64_t PseudoSourceEvents = 0;
  std::int64_t MaximumQueueSize = 0;
};

class ExactGeodesicSolver
{
public:
  static constexpr double Unreachable = std::numeric_limits<double>::infinity();

  // The mesh must outlive the solver. Distances are compared with an absolute tolerance of
  // 1e-11 times `lengthScale`, the mesh's bounding box diagonal when 0 (a piece of a larger
  // surface passes the whole surface's, so that it decides as a solve on the whole would).
  explicit ExactGeodesicSolver(const TriangleMesh& mesh, double lengthScale = 0.0);

  // Multi-source solve. Fails (and leaves every distance unreachable) when there is no source or
  // a source is invalid (see TriangleMesh::CheckPoint), the message saying which and why.
  Status Solve(const std::vector<SurfacePoint>& sources,
    const ExactGeodesicOptions& options = ExactGeodesicOptions());
  Status Solve(int sourceVertex, const ExactGeodesicOptions& options = ExactGeodesicOptions())
  {
    return this->Solve(std::vector<SurfacePoint>{ SurfacePoint::AtVertex(sourceVertex) }, options);
  }
  // A source as Solve takes it: a face point's weights clamped to >= 0 and normalized, and a
  // point at a corner (a weight above 1 - 1e-12) that vertex.
  static SurfacePoint SourcePoint(const TriangleMesh& mesh, SurfacePoint s);

  // Distance of vertex v after the last solve (Unreachable if not reached or beyond the limits).
  double Distance(int v) const
  {
    return Final[v] ? Dist[v] : Unreachable;
  }
  // All distances (copy), Unreachable where not reached.
  std::vector<double> Distances() const;
  // Vertices made final by the last solve, in non-decreasing distance order.
  const std::vector<int>& FinalVertices() const { return FinalOrder; }
  // The pseudo-source of the shortest path found to v: a source index (>= 0: the path is direct,
  // through no saddle or boundary vertex) or -(1 + w) for a saddle/boundary vertex w passed
  // through last. Undefined for unreachable vertices.
  int PathOrigin(int v) const { return Origin[v]; }
  // True when the shortest path to v passes through no saddle or boundary vertex (other than a
  // source itself): the edges of the saddle vertex graph.
  bool IsDirect(int v) const { return Final[v] && Origin[v] >= 0; }
  // The direction in which the shortest path to v leaves its source (the log-map angle), for
  // every reached vertex other than the sources: counter-clockwise about the outward normal from
  // the source's VertexHalfedge (vertex source, 0 .. its total angle) or from the face's first
  // edge, corner 0 to corner 1 (face point source). A path through saddles or reflex boundary
  // vertices leaves in the direction of the first of them. NaN where unknown.
  double DepartureAngle(int v) const
  {
    return Final[v] ? Departure[v].Value() : std::numeric_limits<double>::quiet_NaN();
  }

  // The index (in the sources given to Solve) of the source v's shortest path starts from,
  // through saddles too; -1 for unreached vertices.
  int SourceOf(int v) const { return Final[v] ? Root[v] : -1; }

  const ExactGeodesicStatistics& Statistics() const { return Stats; }
  const TriangleMesh& Mesh() const { return Surface; }
  // The faces of ExactGeodesicOptions::Fence the last solve entered (a window propagated into
  // it or a vertex of it spread its windows), each once or more; empty when none.
  const std::vector<int>& FenceFacesEntered() const { return Fenced.Entered; }

private:
  // The solve on one piece of a surface partitioned over processes (ExactPieces.cpp) drives the
  // solver through its Route.
  friend class ExactPieceSolve;
  struct Window
  {
    double Key;    // smallest distance over the window (priority)
    double B0, B1; // interval along half-edge H, measured from Origin(H)
    double Ix, Iy; // unfolded pseudo-source in H's frame (x along H, y > 0 towards face(H))
    double Sigma;  // distance from the real source to the pseudo-source
    double Phi;    // departure angle: Phi + angle of (x - I) in this frame for a real source
                   // (Src >= 0), Phi itself behind a pseudo-source
    int H;         // half-edge the window lies on; it propagates into face(H). <0: vertex event
    int Src;       // PathOrigin code of the pseudo-source
    int Root;      // index of the source the window's paths start from
  };
  using LazyAngle = window_geometry::LazyAngle;
  void Reset();
  // inAngle: direction (in v's fan, see FanAngle) towards where the path comes from; NaN if
  // unknown. It limits which directions v spreads into when it becomes a pseudo-source.
  void UpdateVertex(int v, double d, int origin, int viaHalfedge, double crossing,
    const LazyAngle& inAngle, const LazyAngle& departure, int root);
  void PushWindow(Window w);
  // Processes a window taken from the queue: a vertex event spreads the vertex's windows, an
  // edge window is trimmed again (vertex distances may have dropped since it was queued) and
  // propagated.
  void Handle(Window w);
  // After UpdateVertex improved v on a piece (Route set): a vertex of another process leaves
  // for its owner; an own pseudo-source vertex spreads again from its new distance.
  void RouteImprovement(int v, double d, int root);
  // Queues pseudo-source vertex v's event: it spreads its windows from distance d when taken.
  void QueueVertexEvent(int v, double d, int root);
  void Enqueue(const Window& w);
  Window Dequeue();
  void Propagate(Window w);
  // Queues the child of w on half-edge t (nothing when it is empty); (towardsX, towardsY) is the
  // direction of t's frame x axis in w's frame, which turns a real source's departure angle.
  void PushChild(const Window& w, int t, const window_geometry::ChildWindow& child,
    double towardsY, double towardsX);
  void PropagateFromVertex(int v, double sigma, int src);
  void AddFaceSourceWindows(int f, const Vec3& p, int src, int sourceFace);
  bool Trim(Window& w) const;
  void FinalizeUpTo(double key);
  // Solve's steps. Source i: a vertex source spreads its windows, a face point (or a point on an
  // edge) seeds the windows of its face (and of the face across the edge).
  void AddSource(int i, SurfacePoint s);
  // Marks StopOnceFinal's vertices in Target; returns how many distinct ones there are.
  std::size_t MarkTargets(const ExactGeodesicOptions& options);
  // Propagates windows in order of their keys until the queue is empty or past maxDistance;
  // true when it stopped early instead (maxFinal vertices final, or the targetsLeft marked
  // targets all final).
  bool ProcessWindows(double maxDistance, std::size_t maxFinal, std::size_t targetsLeft);

  const TriangleMesh& Surface; // (Mesh() returns it)
  // What a window on half-edge h reads of h, kept together so that a face's three half-edges
  // (3f, 3f + 1, 3f + 2) fill two cache lines instead of one line in each of five arrays: the
  // opposite vertex in h's frame (Cx, Cy), h's length, origin and twin. The other corners of
  // face(h) are the origins of Next(h) (h's destination) and of Prev(h) (its opposite vertex).
  struct alignas(32) HalfedgeRecord
  {
    double Cx, Cy, Length;
    int Origin, Twin;
  };
  std::vector<HalfedgeRecord> Edges;
  int Destination(int h) const { return Edges[TriangleMesh::Next(h)].Origin; }
  int Opposite(int h) const { return Edges[TriangleMesh::Prev(h)].Origin; }
  // Angle of each half-edge's direction about its origin, counter-clockwise from the origin's
  // VertexHalfedge (0 .. total angle).
  std::vector<double> FanAngle;

  std::vector<double> Dist;
  std::vector<int> Origin;
  std::vector<int> CrossHalfedge; // half-edge crossed by the best path to v in its last face
  std::vector<LazyAngle> InAngle;   // where the best path to v arrives from (NaN: several/unknown)
  std::vector<LazyAngle> Departure; // departure angle at the source of the best path to v
  std::vector<int> Root;          // source index of the best path to v
  std::vector<double> CrossX;     // where it crossed (in that half-edge's frame)
  std::vector<unsigned char> Final;
  std::vector<unsigned char> Target; // StopOnceFinal's vertices during a solve
  std::vector<unsigned char> Propagated; // pseudo-source vertex already spread its windows
  std::vector<int> Touched;
  std::vector<int> FinalOrder;
  window_geometry::WindowQueue<Window> Queue;
  struct VertexKey
  {
    double D;
    int V;
  };
  std::vector<VertexKey> VertexQueue; // binary heap of tentative vertex distances
  double Tolerance = 0.0;             // absolute distance tolerance (scaled to the mesh)
  window_geometry::FenceWatch Fenced; // the solve's fence (options)
  ExactGeodesicStatistics Stats;
  // A solve on a piece: windows entering other processes' faces, and improved distances of
  // their vertices, leave instead of being processed here; nothing is final before the end.
  struct PieceRoute
  {
    const std::vector<unsigned char>* OtherFace = nullptr;   // one flag per face
    const std::vector<unsigned char>* OtherVertex = nullptr; // one flag per vertex
    std::vector<Window> Leaving;
    std::vector<int> LeavingVertices;   // each once until taken
    std::vector<unsigned char> Listed; // per vertex: in LeavingVertices
  };
  PieceRoute* Route = nullptr;
};

} // namespace gs
