// vtkSaddleVertexGraphCache: the process-wide store of geodesic graphs (gs::SaddleVertexGraph:
// saddle vertex graphs and discrete geodesic graphs), so that a graph is built once per mesh
// geometry and construction (K, or the accuracy) and then shared by every filter instance and
// every filter of the suite that needs it.
//
// Not a vtkObject and not wrapped (a private class of the GeodesicShapes::Filters module).
//  - Graphs are keyed by (gs::SaddleVertexGraph::HashMesh(mesh), construction, effective K or
//    accuracy), the effective K being gs::SaddleVertexGraph::EffectiveK (K clamped to the vertex
//    count). A pipeline that re-executes and produces a new vtkPolyData with identical points
//    and cells hashes to the same key: the graph is not rebuilt.
//  - The Capacity most recently used graphs are kept alive by the cache; any graph still held by
//    a filter (a shared_ptr) is found as well, however old.
//  - With a file name: a path holding anything but a graph cache file (a user's file, a
//    directory, a FIFO) is an error before any work, and is never read or written
//    (gs::SaddleVertexGraph::CheckCacheFileName). Otherwise a graph found in memory is written
//    there once (so the file exists for the next process), or the file is loaded when it
//    matches the mesh and the construction (each has its own file format) and passes
//    gs::SaddleVertexGraph::Verify against the mesh; a missing file is silent, a stale, corrupt
//    or forged one gets a warning and the graph is rebuilt, then saved (a failed save is a
//    warning). Saves replace the file whole (a temporary file renamed into place).
//  - An aborted build (the progress callback returned false) caches nothing.
// Thread-safe (one mutex around the store; builds and file I/O run outside it).
#ifndef vtkSaddleVertexGraphCache_h
#define vtkSaddleVertexGraphCache_h

#include "GeodesicShapesFiltersModule.h" // for export macro (tests reset the cache)

#include "SaddleVertexGraph.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

class vtkAlgorithm;

class GEODESICSHAPESFILTERS_EXPORT vtkSaddleVertexGraphCache
{
public:
  // Where a graph handed out by Get() came from.
  enum class Origin
  {
    Memory, // already in the process (this or another filter built or loaded it)
    File,   // loaded from the cache file
    Built   // built now
  };
  // "memory", "loaded", "built" (the values of the SVGGraphOrigin field data array).
  static const char* OriginName(Origin origin);

  struct Result
  {
    std::shared_ptr<const gs::SaddleVertexGraph> Graph; // null on error or abort
    Origin From = Origin::Built;
    gs::Status Status;                 // why there is no graph: the core's error, or aborted
    std::vector<std::string> Warnings; // stale/corrupt cache file, failed save
  };

  // The graph of `mesh` (whose HashMesh is `meshHash`) for `options` (construction, K or
  // accuracy; its thread count is used for a build), from memory, from `fileName` (if not
  // empty) or built. `progress` (may be empty) sees the build's fraction done and aborts it by
  // returning false. An invalid K or accuracy is an error (the core's message).
  static Result Get(const gs::TriangleMesh& mesh, std::uint64_t meshHash,
    const gs::SaddleVertexGraphOptions& options, const std::string& fileName,
    const gs::ProgressCallback& progress);

  // Get() for a filter (see vtkCachedSurface::UseSaddleVertexGraph): reports the build's
  // progress on `algorithm` from `progressStart` over `progressSpan` (and aborts the build when
  // the algorithm is aborted), and emits the warnings and the error there. Result::Graph is null
  // on error or abort.
  static Result GetFor(vtkAlgorithm* algorithm, const gs::TriangleMesh& mesh,
    std::uint64_t meshHash, const gs::SaddleVertexGraphOptions& options,
    const std::string& fileName, double progressStart, double progressSpan);

  // Number of most recently used graphs the cache keeps alive.
  static constexpr std::size_t Capacity = 4;
  // Forgets every graph (graphs still held by filters stay valid but are no longer found).
  static void Clear();
  // Graphs kept alive by the cache itself (at most Capacity).
  static std::size_t NumberOfGraphs();
};

#endif
