// The saddle vertex graph or discrete geodesic graph of a surface partitioned over processes,
// and shortest paths on it, without any process holding the whole surface or the whole graph.
//
// PieceGraph: each process solves from the vertices it owns (SurfacePiece) on its piece, as
// SaddleVertexGraph::Build does on the whole surface, with the piece's faces that have an
// incomplete vertex as a fence: a solve that stayed inside it computed what the whole surface
// gives (the same faces and vertices in the same relative order, the same tolerance); the
// vertices whose solve reached the fence are solved again once the band has grown where they
// reached it (SurfacePiece::GrowAround, by rings that double each time). Each link then goes to
// the owner of its other end, so that every process holds the whole adjacency and the polar
// stencils of its vertices: both directions of every link and mesh edge, the smallest weight
// per target, as in the serial graph.
//
// PieceDistanceSolver: shortest paths by rounds. Each process runs the serial label-correcting
// search on its vertices; a link to another process's vertex sends the distance it offers (and
// its source, for the predecessor rule of ties) to that process at the end of the round; the
// rounds end when no process sent anything. The result is the serial graph's shortest path
// distances to the bit: with positive weights and rounded additions that are monotone, every
// order of relaxation reaches the same smallest fixed point. The unfolding refinement then runs
// by rounds too (GraphPiecesRefinement.cpp), with the serial sweep's kernel.
//
// Surface-point and curve sources are not here (the filter gathers the surface for those).
#pragma once

#include "PieceCommunicator.h"
#include "SaddleVertexGraph.h"
#include "Status.h"
#include "SurfaceCurve.h"
#include "SurfacePiece.h"

#include <cmath>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gs
{

class PieceGraph
{
public:
  // Collective. Builds the adjacency of the vertices `piece` owns, growing the piece's band until
  // every solve stays inside it. Fails on every process when one fails (invalid options, a piece
  // that cannot grow) or aborts (the progress callback, called on the calling thread with the
  // fraction of this process's vertices done, returned false). K is clamped to the whole
  // surface's vertex count, as SaddleVertexGraph::Build does.
  Status Build(SurfacePiece& piece, const SaddleVertexGraphOptions& options,
    PieceCommunicator& comm, const ProgressCallback& progress = nullptr);

  // Owned vertices are numbered 0 .. NumberOfOwned() - 1 in increasing global id.
  int NumberOfOwned() const { return static_cast<int>(OwnedIds.size()); }
  std::int64_t OwnedId(int i) const { return OwnedIds[static_cast<std::size_t>(i)]; }
  // The owned number of a global id (-1 when this process does not own it).
  int OwnedIndex(std::int64_t globalId) const;
  // Adjacency of owned vertex i: entries Begin(i) .. End(i), sorted by target global id.
  std::int64_t Begin(int i) const { return Offsets[static_cast<std::size_t>(i)]; }
  std::int64_t End(int i) const { return Offsets[static_cast<std::size_t>(i) + 1]; }
  // The target's owned number on this process, or -1 - r for the remote vertex r (a vertex of
  // another process: RemoteId, RemoteOwner).
  int Target(std::int64_t e) const { return Targets[static_cast<std::size_t>(e)]; }
  double Weight(std::int64_t e) const { return Weights[static_cast<std::size_t>(e)]; }
  std::int64_t TargetId(std::int64_t e) const
  {
    const int t = Target(e);
    return t >= 0 ? OwnedId(t) : RemoteId(-1 - t);
  }
  int NumberOfRemote() const { return static_cast<int>(RemoteIds.size()); }
  // A global id as Target encodes it: its owned number, or -1 - its remote slot (an id that is
  // neither gives a slot that is not its own).
  int Encode(std::int64_t globalId) const;
  // The polar stencil of owned vertex i, as SaddleVertexGraph's (its targets encoded as Target's):
  // what the unfolding refinement reads (StencilUnfolding.h).
  std::int64_t StencilBegin(int i) const { return StencilOffsets[static_cast<std::size_t>(i)]; }
  std::int64_t StencilEnd(int i) const { return StencilOffsets[static_cast<std::size_t>(i) + 1]; }
  int StencilTarget(std::int64_t e) const { return Stencil[static_cast<std::size_t>(e)].Target; }
  double StencilX(std::int64_t e) const { return Stencil[static_cast<std::size_t>(e)].X; }
  double StencilY(std::int64_t e) const { return Stencil[static_cast<std::size_t>(e)].Y; }
  double StencilDistance(std::int64_t e) const
  {
    const StencilEntry& s = Stencil[static_cast<std::size_t>(e)];
    return std::sqrt(s.X * s.X + s.Y * s.Y);
  }
  double StencilWrapX(int i) const { return WrapXY[2 * static_cast<std::size_t>(i)]; }
  double StencilWrapY(int i) const { return WrapXY[2 * static_cast<std::size_t>(i) + 1]; }
  // Whether owned vertex i's stencil is a closed fan (not a boundary vertex).
  bool IsInterior(int i) const { return Interior[static_cast<std::size_t>(i)] != 0; }
  // The construction and accuracy the graph was built with.
  GraphConstruction GetConstruction() const { return Construction; }
  // SaddleVertexGraph::LocalDiskSize of the serial graph on the whole surface.
  int LocalDiskSize() const { return DiskSize; }
  double GetAccuracy() const { return Accuracy; }
  std::int64_t RemoteId(int r) const { return RemoteIds[static_cast<std::size_t>(r)]; }
  int RemoteOwner(int r) const { return RemoteOwners[static_cast<std::size_t>(r)]; }
  // Directed entries over all processes (as SaddleVertexGraph::NumberOfEntries).
  std::int64_t GlobalNumberOfEntries() const { return GlobalEntries; }
  // Vertices solved again after the band grew, over all processes, and the band's final width.
  std::int64_t GlobalResolved() const { return Resolved; }
  int Rings() const { return BandRings; }
  double BuildSeconds() const { return Seconds; }

private:
  // What an owned vertex's solve found: its links and its polar stencil (targets' global ids).
  struct FoundLink
  {
    std::int64_t Target;
    double Weight;
  };
  struct StencilItem
  {
    double X, Y;
    std::int64_t Target;
  };
  struct OwnedSolve
  {
    std::vector<FoundLink> Links;
    std::vector<StencilItem> Stencil;
    double WrapX = 0.0, WrapY = 0.0;
    bool Interior = false;
  };
  struct VertexSolver;
  // Build's steps: the owned vertices' solves (again for those that reached the fence, after the
  // band has grown), into `found` by owned number; then the adjacency from them.
  Status SolveOwned(SurfacePiece& piece, const SaddleVertexGraphOptions& options, int k,
    PieceCommunicator& comm, const ProgressCallback& progress, std::vector<OwnedSolve>& found);
  void Assemble(const SurfacePiece& piece, std::vector<OwnedSolve>& found, PieceCommunicator& comm);
  // An entry of a vertex's bucket before the adjacency is made.
  struct RawEntry
  {
    std::int64_t Target;
    double Weight;
    bool operator<(const RawEntry& o) const
    {
      return Target < o.Target || (Target == o.Target && Weight < o.Weight);
    }
  };
  // Assemble's last step: each owned vertex's bucket of `raw` (count: the buckets' offsets)
  // sorted, the smallest weight kept per target, into the adjacency; remote targets get slots
  // (their owners from the piece, else from `sentBy`, the process that sent the link); the
  // stencils of `found` into one array. Returns the entries kept.
  std::int64_t Compact(const SurfacePiece& piece, std::vector<RawEntry>& raw,
    const std::vector<std::int64_t>& count, const std::unordered_map<std::int64_t, int>& sentBy,
    std::vector<OwnedSolve>& found);

  std::vector<std::int64_t> OwnedIds;
  std::vector<std::int64_t> Offsets;
  std::vector<int> Targets;
  std::vector<double> Weights;
  std::vector<std::int64_t> RemoteIds; // sorted
  std::vector<int> RemoteOwners;
  struct StencilEntry
  {
    double X, Y;
    int Target;
  };
  std::vector<std::int64_t> StencilOffsets;
  std::unique_ptr<StencilEntry[]> Stencil;
  std::vector<double> WrapXY;
  std::vector<unsigned char> Interior;
  GraphConstruction Construction = GraphConstruction::SaddleVertex;
  double Accuracy = 0.0;
  int DiskSize = 1;
  std::int64_t GlobalEntries = 0, Resolved = 0;
  int BandRings = 0;
  double Seconds = 0.0;
};

// Collective. The seeds SVGGeodesicSolver searches the graph from when its sources include
// surface points or curves: the exact distances (window propagation on the pieces) of the
// graph.LocalDiskSize() x n vertices nearest to the sources (the vertex ids `sources`, the same
// list on every process, and the surface points `points` of every process: each passes those
// of its own faces; n their number, or `disks` when > 0), within maxDistance (> 0), and the
// corners of the faces of `pieces` (each process those on its own faces; none given: the
// points' faces) at their straight distance. Curves (SVGGeodesicSolver::SolveCurves) pass
// their samples as points, their traced pieces, and the number of faces the curves cross as
// `disks`. Every process gets the whole list, as PieceDistanceSolver::Solve takes it. Ties at
// the last vertex taken go to the smaller global id (the serial solve takes the one its windows
// finalize first). Fails on every process as ComputeExactOnPieces does.
Status GraphSeedsFromPoints(SurfacePiece& piece, const PieceGraph& graph,
  const std::vector<std::int64_t>& sources, const std::vector<SurfacePoint>& points,
  double maxDistance, PieceCommunicator& comm, std::vector<std::pair<std::int64_t, double>>& seeds,
  const std::vector<CurvePiece>& pieces = {}, std::int64_t disks = 0);

class PieceDistanceSolver
{
public:
  // The graph must outlive the solver.
  explicit PieceDistanceSolver(const PieceGraph& graph);

  // Collective. Seeds: (global vertex id, initial distance); every process passes the whole
  // list (each keeps those it owns). Vertices farther than maxDistance (> 0) stay unreached
  // (infinite). With `refine`, the graph distances are refined by geodesic triangle unfolding
  // as SVGGeodesicSolver refines them from vertex sources (the seeds keep theirs). Fails on
  // every process when a seed's id is owned by no process.
  Status Solve(const std::vector<std::pair<std::int64_t, double>>& seeds, double maxDistance,
    PieceCommunicator& comm, bool refine = false);
  // Distance of owned vertex i (infinite where unreached).
  double Distance(int i) const { return Dist[static_cast<std::size_t>(i)]; }
  // Collective. The distance of every vertex of `piece` listed in `wanted` (local vertices of
  // the piece, each complete), from their owners; infinite where unreached.
  std::vector<double> Fetch(
    const SurfacePiece& piece, const std::vector<int>& wanted, PieceCommunicator& comm) const;
  // Rounds of the last solve (exchanges of distances), and of its refinement.
  int Rounds() const { return NumRounds; }
  int Refinements() const { return RefinementRounds; }

private:
  // Solve's steps: the label-correcting search by rounds from the seeds (owned numbers, their
  // distances set), with predecessors; then the refinement sweep by rounds
  // (GraphPiecesRefinement.cpp).
  void SolveGraph(const std::vector<int>& seeds, double limit, PieceCommunicator& comm);
  void Refine(const std::vector<int>& seeds, double limit, PieceCommunicator& comm);
  struct Sweep;
  struct SweepRounds;

  const PieceGraph& Graph;
  std::vector<double> Dist;
  std::vector<std::int64_t> Pred; // global id of the predecessor (-1: a seed or unreached)
  int NumRounds = 0, RefinementRounds = 0;
};

} // namespace gs
