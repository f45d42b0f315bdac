// Near-exact geodesic distance on a saddle vertex graph, from any surface points or curves.
//
//  - Vertex sources seed the graph directly.
//  - Point sources inside faces (and curves) first get an exact window-propagation solve
//    truncated to their own K-nearest vertices, which seeds the graph with exact distances: the
//    source behaves as if it were a graph node with its direct geodesics.
//  - Curve sources: a polyline on the surface, as a sequence of surface points; consecutive
//    points are joined by the straight surface path between them (traced across faces), and
//    each piece of it inside a face is a source.
//  - Queries at arbitrary surface points use geodesic triangle unfolding, and the exact
//    in-face distance to point or curve sources lying in the same face.
#pragma once

#include "ExactGeodesic.h"
#include "SaddleVertexGraph.h"
#include "SurfaceCurve.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

namespace gs
{

struct SVGSolveOptions
{
  GraphAlgorithm Algorithm = GraphAlgorithm::LabelCorrecting;
  // Refine graph distances by geodesic triangle unfolding over the vertices' polar stencils
  // (see SVGGeodesicSolver::Refine): exact on developable surfaces, about 2x more accurate on
  // curved ones, for about the cost of a second graph solve.
  bool Refine = true;
  // Also compute, for a single point or vertex source, the direction in which each vertex's
  // geodesic leaves the source (see DepartureAngle). Exact in the source's K-disk, carried
  // beyond it along the graph and interpolated across the unfolded geodesic triangles.
  bool Angles = false;
  double MaximumDistance = 0.0; // > 0: vertices farther stay unreached (infinite)
  // Threads for the refinement of distances (without Angles) when it reaches at least
  // ParallelRefinementMinimum vertices (below, the threads' waiting and sharing of memory
  // cost more than they save: 2 threads took 0.81x the time of one at 44K vertices, 0.87x at
  // 13K, 1.11x at 178K); the distances are the same to the bit whatever the number (0:
  // OpenMP's default, 1: none).
  int NumberOfThreads = 1;
  std::int64_t ParallelRefinementMinimum = 100000;
};

class SVGGeodesicSolver
{
public:
  // The mesh and the graph (built or loaded for this mesh before the solver is made: the solver
  // sizes its arrays and derives per-node data from it) must outlive the solver.
  SVGGeodesicSolver(const TriangleMesh& mesh, const SaddleVertexGraph& graph);

  // Distances from the sources to every vertex. Fails (every vertex unreached) when there is no
  // source, a source is invalid (TriangleMesh::CheckPoint) or the graph is of another mesh; the
  // message says which source and why.
  Status Solve(const std::vector<SurfacePoint>& sources, const SVGSolveOptions& options = {});
  // Distances from curves (see the class comment) to every vertex. Fails likewise when there is
  // no curve, a curve has no point or a point is invalid.
  Status SolveCurves(
    const std::vector<std::vector<SurfacePoint>>& curves, const SVGSolveOptions& options = {});
  Status SolveCurve(const std::vector<SurfacePoint>& curve, const SVGSolveOptions& options = {})
  {
    return SolveCurves({ curve }, options);
  }
  // Refinement unfolds the stencil triangles within this cone (cosine of its half angle, 15
  // degrees) about the direction of the graph predecessor. (25 degrees: the same mean and
  // maximum errors on the benchmark meshes, 18% slower; 40 degrees: a 3x larger maximum on
  // mannequin-devil from spurious pairs far from the arrival direction; 10 degrees: 3% larger
  // mean and 20% larger maximum errors on armadillo.)
  static constexpr double ConeCosine = 0.966;
  // The cone is tried once more about the stencil neighbour of its pairs that gives the
  // shortest route, when that route is shorter than the arrival's by more than this fraction
  // (StencilUnfolding::RefineVertex; 0: re-centred for any shorter route, 20-30% slower on
  // curved meshes with reached stencils for no smaller error; 3e-3: half the gain on the
  // jittered plane).
  static constexpr double ArrivalMoveMargin = 1e-3;
  // Spacing of the samples seeding the exact solve near a curve, in mean edge lengths.
  static constexpr double CurveSeedSpacing = 0.125;

  double Distance(int v) const { return GraphSolver.Distance(Graph.Node(v)); }
  // With SVGSolveOptions::Angles: the departure angle at the source of v's geodesic, in the
  // convention of ExactGeodesicSolver::DepartureAngle (modulo the source's angle sum); NaN for
  // the source itself, unreached vertices, or when not computed.
  double DepartureAngle(int v) const { return Angle[Graph.Node(v)]; }
  // Distances of all vertices (infinite where unreached), by mesh vertex.
  std::vector<double> Distances() const;
  // Mesh vertices reached by the last solve (unordered; translated from the graph's nodes by
  // each call, into a buffer the next call reuses).
  const std::vector<int>& Reached() const;
  // Distance of any surface point from the last solve's sources.
  double DistanceAt(const SurfacePoint& q) const;

  // One-off queries (each runs a solve from a).
  double Distance(const SurfacePoint& a, const SurfacePoint& b);
  std::vector<double> DistancesTo(const SurfacePoint& a, const std::vector<SurfacePoint>& targets);

  // Number of curve pieces (segments inside one face) of the last curve solve.
  int NumberOfCurvePieces() const { return static_cast<int>(Pieces.size()); }

private:
  struct Piece
  {
    int Face;
    Vec3 A, B; // a segment (A == B for a point source) inside Face
  };
  // Geodesic triangle unfolding over the polar stencils, in order of distance.
  void Refine(double maxDistance, bool unfold, bool angles, int threads = 1,
    std::int64_t parallelMinimum = 0);
  // The same sweep (distances only) on several threads, with the same result.
  void RefineInParallel(double limit, int threads);
  // The solve's per-vertex state as the unfolding kernel (StencilUnfolding.h) reads it: graph
  // distances, predecessors and their places in the stencils, closed fans, angles, the floor.
  struct SolveState;
  // The place of v's graph predecessor in v's stencil (-1: none).
  int StencilIndexOfPredecessor(int v) const;
  // A sweep follows the distance order, random in memory: for the positions of Order it visits
  // in the order `next` gives, the graph predecessor is prefetched 3 * SweepAhead positions
  // ahead, the stencil offsets 2 * SweepAhead and the stencil about the predecessor's place
  // SweepAhead (a third of the sweep's time on 26K-vertex meshes). StartPrefetch from the
  // sweep's first position, then Prefetch before each.
  static constexpr int SweepAhead = 6;
  struct SweepPrefetch
  {
    std::int64_t Stencil, Offsets, Predecessor; // the next positions to fetch
  };
  template <class Next>
  SweepPrefetch StartPrefetch(std::int64_t first, std::int64_t count, const Next& next) const;
  template <class Next>
  void Prefetch(SweepPrefetch& p, std::int64_t count, const Next& next) const;
  void ClearAngles();
  // Leaves every vertex unreached and returns `why` (a failed Status).
  Status Reject(Status why, GraphAlgorithm algorithm);
  Status SolveFromPieces(const std::vector<SurfacePoint>& exactSources, int finalVertices,
    const SVGSolveOptions& options);

  const TriangleMesh& Mesh;
  const SaddleVertexGraph& Graph;
  ExactGeodesicSolver Local;
  GraphDistanceSolver GraphSolver;
  std::vector<Piece> Pieces; // sorted by face
  // Per graph node (SaddleVertexGraph::Node), like the graph solver's arrays:
  std::vector<unsigned char> Exact;    // seeds with exact distances (left alone by Refine)
  std::vector<unsigned char> Interior; // not a boundary vertex (its stencil is a closed fan)
  std::vector<double> Angle;           // departure angles (Angles option)
  std::vector<int> AngleSet;           // nodes whose Angle is set
  mutable std::vector<int> ReachedVertices; // Reached()'s buffer
  double AnglePeriod = 0.0; // full turn of the source's tangent angles
  // Refinement keeps a vertex's distance at or above this fraction of its graph distance:
  // 1 / (1 + accuracy) for a discrete geodesic graph (whose distances are at most that far
  // above the geodesic distance), 0 (no floor) for a saddle vertex graph.
  double RefinementFloor = 0.0;
  // The sweep's order: reached nodes sorted by distance (radix sort on 32-bit keys).
  std::vector<std::pair<std::uint32_t, int>> Order, OrderScratch;
  std::vector<std::size_t> OrderCounts; // the sort's digit counts
  std::vector<std::pair<int, double>> Lowered; // the sequential sweep's refined distances of a key
  // RefineInParallel, per node: its refined distance (NaN until its thread has refined it, and
  // between solves).
  std::unique_ptr<std::atomic<double>[]> Refined;
  std::size_t RefinedCount = 0;
};

} // namespace gs
