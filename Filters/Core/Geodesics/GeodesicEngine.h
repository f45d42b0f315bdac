// One seam for the geodesic distance engines: a solver is chosen by GeodesicSolver and asked the
// same questions whatever it is (distances from point and curve sources, the departure angle
// where the engine knows it, the vertices reached). Each engine stays a class of its own with
// its own options (ExactGeodesic.h, SVGGeodesicSolver.h over a SaddleVertexGraph,
// VirtualSourceGeodesic.h); this header adapts them, and owns how each takes curve sources.
// Adding an engine: a value of GeodesicSolver, its name, and one adapter in GeodesicEngine.cpp.
#pragma once

#include "Status.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"

#include <functional>
#include <memory>
#include <vector>

namespace gs
{
class SaddleVertexGraph;

/// The engines, numbered as SVG Geodesic Distance's Solver property.
enum class GeodesicSolver
{
  Exact = 0,              // window propagation (ExactGeodesicSolver): the ground truth
  SVGLabelCorrecting = 1, // shortest paths on a saddle vertex graph, SLF/LLL queue
  SVGDijkstra = 2,        // the same with a binary heap
  DGG = 3,                // shortest paths on a discrete geodesic graph (accuracy-bounded)
  VirtualSources = 4      // virtual source propagation: no precompute
};
constexpr int NumberOfGeodesicSolvers = 5;

/// The exact engine solves on meshes of at least this many faces in parts on threads
/// (ExactSolverInParts, four threads whatever NumberOfThreads says: the same bits for any
/// number of cores), unless MaximumDistance bounds the solve to less than this fraction of the
/// bounding box's diagonal (a local solve, serial) or angles are asked from several sources.
constexpr int ExactInPartsMinimumFaces = 100000;
constexpr double ExactInPartsMinimumReach = 0.25;
/// Whether an exact solve bounded by `maximumDistance` (<= 0 or infinite: unbounded) on `mesh`
/// is one the exact engine solves in parts (a large mesh, a solve that is not local).
bool ExactSolvesInParts(const TriangleMesh& mesh, double maximumDistance);

/// The name users see ("Exact", "SVG (label-correcting)", ...); "" for no engine.
const char* GeodesicSolverName(GeodesicSolver solver);
/// Whether the engine solves on a graph built beforehand (SaddleVertexGraph, DGG's included).
bool GeodesicSolverUsesGraph(GeodesicSolver solver);
/// The engine that solves on `graph` as it was built: DGG for a discrete geodesic graph, SVG
/// (label-correcting) for a saddle vertex graph.
GeodesicSolver GraphSolverOf(const SaddleVertexGraph& graph);

/// Sources of a solve: points (vertices or face points) and curves (polylines of surface points,
/// consecutive points joined by the straight surface path, TraceSurfaceCurve). A one-point curve
/// is a point.
struct GeodesicSources
{
  std::vector<SurfacePoint> Points;
  std::vector<std::vector<SurfacePoint>> Curves;
};

struct GeodesicSolveOptions
{
  /// > 0 and finite: vertices farther stay unreached (infinite).
  double MaximumDistance = 0.0;
  /// Graph engines: refine graph distances by geodesic triangle unfolding (SVGSolveOptions).
  bool UnfoldingRefinement = true;
  /// Graph engines: threads of the refinement of large solves (0: every core; the same
  /// distances to the bit for any number).
  int NumberOfThreads = 0;
  /// Also the departure angles from a single point source (DepartureAngle): graph engines and
  /// the virtual sources compute them only when asked (the graphs' refinement then runs on one
  /// thread); the exact engine always does below ExactInPartsMinimumFaces faces, and on larger
  /// meshes when asked (in parts from a single point source, else serially).
  bool Angles = false;
  /// Called with the fraction done (engines that report it); false aborts the solve
  /// (Status::Aborted(), every vertex unreached).
  std::function<bool(double)> Progress;
};

class GeodesicEngine
{
public:
  virtual ~GeodesicEngine() = default;
  virtual GeodesicSolver Solver() const = 0;
  /// Distances from the nearest source to every vertex. Fails (every vertex unreached) when
  /// there is no source or a source is invalid, the message saying which, or when aborted.
  virtual Status Solve(const GeodesicSources& sources, const GeodesicSolveOptions& options) = 0;
  /// Vertex v's distance after the last solve (infinity: not reached).
  virtual double Distance(int v) const = 0;
  /// Every vertex's distance (infinity where unreached).
  virtual std::vector<double> Distances() const = 0;
  /// The vertices the last solve reached: the exact engine's in the order they became final
  /// (by distance), the others' in no particular order.
  virtual const std::vector<int>& Reached() const = 0;
  /// The angle at which v's geodesic leaves a single point source, where the engine computes it
  /// (ExactGeodesicSolver::DepartureAngle's convention); NaN otherwise.
  virtual double DepartureAngle(int v) const;
  const TriangleMesh& Mesh() const { return Surface; }

protected:
  explicit GeodesicEngine(const TriangleMesh& mesh)
    : Surface(mesh)
  {
  }
  const TriangleMesh& Surface;
};

/// The engine `solver` over `mesh`; graph engines need the graph built for it (null or of
/// another mesh: an error). The mesh and graph must outlive the engine.
Result<std::unique_ptr<GeodesicEngine>> MakeGeodesicEngine(
  GeodesicSolver solver, const TriangleMesh& mesh, const SaddleVertexGraph* graph = nullptr);

} // namespace gs
