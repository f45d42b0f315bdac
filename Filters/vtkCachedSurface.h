// vtkCachedSurface: a filter's input surface, converted once (vtkSurfaceMeshConverter), and what
// every filter derives from it on demand: its mesh hash, the saddle vertex graph in use (from the
// process-wide vtkSaddleVertexGraphCache) and the surface point locator.
//
// Not a vtkObject and not wrapped (a private class of the GeodesicShapes::Filters module). Each
// filter keeps one through vtkSurfaceMeshConverter::Update, which replaces it (and so drops all
// of the above) when the input's points or cells change; a filter's own cache derives from it
// and adds the engines it builds over the mesh (and the graph).
#ifndef vtkCachedSurface_h
#define vtkCachedSurface_h

#include "vtkSaddleVertexGraphCache.h"
#include "vtkSurfaceMeshConverter.h"

#include "GeodesicEngine.h"
#include "Status.h"
#include "SurfacePoint.h"

#include <vtkType.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkPoints;
class vtkSurfacePointLocator;

class vtkCachedSurface : public vtkSurfaceMeshConverter::Cached
{
public:
  vtkCachedSurface();
  ~vtkCachedSurface();

  // The locator over the converted surface (Mesh must be a successful conversion); built on
  // first use.
  vtkSurfacePointLocator& Locator();

  // A polyline of `points` (ids[0 .. n)) snapped as a curve on the surface, sampled every
  // vtkSurfacePointLocator::CurveSampleSpacing mean edge lengths (see SnapCurve there).
  gs::Result<std::vector<gs::SurfacePoint>> SnapCurve(
    vtkPoints* points, vtkIdType n, const vtkIdType* ids);

  // The core mesh vertex of input point `pointId` (a filter's source vertex id). Fails when the
  // id is out of range or the point is used by no triangle, with a message that follows the
  // property's name: "<pointId> is out of range [0, n)", "<pointId> is not used by any triangle".
  gs::Result<int> VertexOfPoint(vtkIdType pointId) const;

  // gs::SaddleVertexGraph::HashMesh of the converted mesh; computed on first use.
  std::uint64_t MeshHash();

  // Makes the geodesic graph of `options` (a saddle vertex graph of K, or a discrete geodesic
  // graph of an accuracy) the one in use: from vtkSaddleVertexGraphCache (memory,
  // `fileName` if not empty, or built with progress `progressStart` .. + `progressSpan` on
  // `algorithm`, which may abort it). False on error or abort (the error and any warnings are
  // reported on `algorithm`); the graph in use is then unchanged. `changed` says whether the
  // graph in use is now another one (an engine built over the previous one must be rebuilt);
  // `origin` (may be null) where it came from.
  bool UseSaddleVertexGraph(vtkAlgorithm* algorithm, const gs::SaddleVertexGraphOptions& options,
    const std::string& fileName,
    double progressStart, double progressSpan, bool& changed,
    vtkSaddleVertexGraphCache::Origin* origin = nullptr);
  // The filters' engine properties, one vocabulary: Solver (gs::GeodesicSolver's values and
  // names), K (graph solvers) and GraphAccuracy (DGG). Checks that Solver is one of `allowed`
  // (the engines the filter offers) and K is at least 1 for a graph solver; false with an error
  // reported on `algorithm` otherwise.
  static bool CheckEngine(vtkAlgorithm* algorithm, int solver,
    const std::vector<gs::GeodesicSolver>& allowed, int k);
  // The graph Solver solves on: the saddle vertex graph of K, or for DGG the discrete geodesic
  // graph of K and GraphAccuracy (whose range the core checks) and `reachedStencil`.
  static gs::SaddleVertexGraphOptions GraphOptions(
    int solver, int k, double graphAccuracy, bool reachedStencil = false);
  // The graph of `solver` in use (UseSaddleVertexGraph with GraphOptions), or none for an
  // engine without one (UseNoSaddleVertexGraph, `changed` then says whether one was in use).
  bool UseEngineGraph(vtkAlgorithm* algorithm, int solver, int k, double graphAccuracy,
    const std::string& fileName, double progressStart, double progressSpan, bool& changed,
    vtkSaddleVertexGraphCache::Origin* origin = nullptr);
  // No saddle vertex graph in use (an exact engine); true when one was.
  bool UseNoSaddleVertexGraph();
  // The saddle vertex graph in use (null: none).
  const gs::SaddleVertexGraph* Graph() const { return this->GraphInUse.get(); }

  vtkCachedSurface(const vtkCachedSurface&) = delete;
  vtkCachedSurface& operator=(const vtkCachedSurface&) = delete;

private:
  std::unique_ptr<vtkSurfacePointLocator> PointLocator; // refers to Mesh; on demand
  std::uint64_t Hash = 0;                                // of Mesh.Build.Mesh; on demand
  bool HashValid = false;
  std::shared_ptr<const gs::SaddleVertexGraph> GraphInUse; // kept alive while in use
};

#endif
