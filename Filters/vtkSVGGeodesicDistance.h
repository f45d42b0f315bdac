/**
 * @class vtkSVGGeodesicDistance
 * @brief Geodesic distance on a triangle mesh from source vertices, surface points or curves.
 *
 * Computes, for every point of the input surface, the length of the shortest path on the
 * surface (not through space) to the nearest source. Five solvers (property Solver):
 *  - SVG_LABEL_CORRECTING (1) and SVG_DIJKSTRA (2): shortest paths on a saddle vertex
 *    graph (Ying, Wang, He 2013; Filters/Core/Geodesics/SaddleVertexGraph.h, SVGGeodesicSolver.h), built
 *    once per mesh geometry and K and then reused: near-exact (mean relative error about 1e-3 at
 *    K = 50) and much faster per solve than the exact solver. Both give the same distances; the
 *    label-correcting search (SLF insertion, LLL extraction) is the faster one.
 *  - DGG (3): shortest paths on a discrete geodesic graph (Wang, Fang, Wu, Xin, He 2017;
 *    Filters/Core/Geodesics/DiscreteGeodesicGraph.h) built for the relative error GraphAccuracy (default 1e-3):
 *    only the direct geodesics that no route through another vertex approximates within it,
 *    reaching as far as needed; the same solve (label-correcting, unfolding refinement) and
 *    cache as the SVG solvers.
 *  - EXACT (0): exact polyhedral geodesics by window propagation (Chen-Han / ICH family,
 *    Filters/Core/Geodesics/ExactGeodesic.h), the ground truth the graph solvers are measured against;
 *    on meshes of gs::ExactInPartsMinimumFaces faces or more, the distances are solved in parts
 *    on threads (Filters/Core/Geodesics/ExactInParts.h), with progress and abort, unless
 *    MaximumDistance keeps the solve local (gs::ExactInPartsMinimumReach).
 *  - VIRTUAL_SOURCES (4, default): virtual source propagation (after Trettner, Bommes,
 *    Kobbelt 2021; Filters/Core/Geodesics/VirtualSourceGeodesic.h): nothing to build, linear time, exact
 *    on flat and developable meshes and a mean relative error of 1e-3 to 2.3e-3 on the real
 *    meshes measured (1e-2 on a CAD part with sharp creases, 6-9e-3 on regular-grid tori: DGG
 *    there): the soonest first answer
 *    (Benchmarks/geodesic_engines.py).
 *
 * Input port 0 ("Input", vtkPolyData): the surface. Polygons with more than three points and
 * triangle strips are triangulated (with a warning); vertex and line cells are ignored. Exactly
 * coincident points are welded for the computation (meshes read from OBJ files with normals or
 * texture coordinates come as a soup of separate triangles), and the result is mapped back to
 * every input point. Empty, non-finite, degenerate, duplicate or non-manifold input is rejected
 * with an error and an empty output.
 *
 * Input port 1 ("Sources", optional, vtkPointSet): when connected, SourceVertexIds is ignored.
 *  - Curve sources: each line or polyline cell of a vtkPolyData is one curve. Its segments are
 *    sampled in space at most a quarter of the mesh's mean edge length apart, each sample is
 *    snapped to the closest surface point, and the distance is to the whole curve (the straight
 *    surface path between consecutive samples, traced across faces).
 *  - Point sources: every point not used by a line cell is snapped to the closest surface point
 *    (a vertex, edge or face point) and used as a source.
 *  Points and curves can be mixed (the points then become one-point curves of the same solve).
 *  Virtual sources carry each run of a curve that is straight in space as one segment source
 *  (exact for straight pieces on flat parts of the mesh). For the Exact solver, curves are
 *  traced on the surface and sampled every 1/16 of the mean edge length, and the solver runs
 *  from all the samples (the reference the SVG curve
 *  solve is measured against).
 * Otherwise the sources are the input points listed in SourceVertexIds.
 *
 * Properties: Solver; SourceVertexIds; MaximumDistance (0: unlimited); ResultArrayName;
 * for the SVG solvers K (geodesic disk size of the graph, default 50, at least 1, clamped to the
 * number of vertices), for DGG GraphAccuracy (1e-5 .. 0.1) and ReachedStencil (advanced), for both
 * CacheFileName (optional file the graph is loaded from when it matches the mesh and K, or
 * GraphAccuracy and ReachedStencil, and saved to otherwise; a stale or corrupt file is rebuilt with
 * a warning) and
 * UnfoldingRefinement (refine graph distances by geodesic triangle unfolding: exact on
 * developable surfaces, 2-8x more accurate on curved ones; default on).
 *
 * Output (vtkPolyData): the input surface (its triangulation when it had to be triangulated)
 * with a vtkDoubleArray point array named ResultArrayName (default "GeodesicDistance", also
 * made the active scalars). Points that are unreachable (another connected component), beyond
 * MaximumDistance, or not used by any triangle get NaN. With a graph solver the field data also
 * describes the graph: SVGMeanDegree (double, graph links per vertex), SVGBuildSeconds (double,
 * time of the build, also for a graph read from a cache file) and SVGGraphOrigin (string: "built",
 * "loaded" from the cache file, or "memory" when an earlier execution made it).
 *
 * Progress: the graph build reports 0.1 to 0.8 and can be aborted (empty output, nothing
 * cached).
 *
 * Example (pvpython, see also Examples/geodesic_distance.py):
 * @code
 * LoadPlugin("build/lib/paraview-5.11/plugins/GeodesicShapes/GeodesicShapes.so", ns=globals())
 * mesh = PLYReader(FileNames=["Data/torus.ply"])
 * dist = SVGGeodesicDistance(Input=mesh, SourceVertexIds=[0], K=50)
 * curve = PolyLineSource(Points=[1.2, 0, 0.5, 0, 1.2, 0.5])
 * fromCurve = SVGGeodesicDistance(Input=mesh, Sources=curve, Solver="SVG (Dijkstra)")
 * @endcode
 */
#ifndef vtkSVGGeodesicDistance_h
#define vtkSVGGeodesicDistance_h

#include "GeodesicShapesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class vtkSurfacePieces;

class GEODESICSHAPESFILTERS_EXPORT vtkSVGGeodesicDistance : public vtkPolyDataAlgorithm
{
public:
  static vtkSVGGeodesicDistance* New();
  vtkTypeMacro(vtkSVGGeodesicDistance, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Values of the Solver property.
  enum SolverType
  {
    EXACT = 0,                ///< exact polyhedral geodesics (window propagation)
    SVG_LABEL_CORRECTING = 1, ///< saddle vertex graph, label-correcting search (SLF/LLL)
    SVG_DIJKSTRA = 2,         ///< saddle vertex graph, binary-heap Dijkstra
    DGG = 3,                  ///< discrete geodesic graph of GraphAccuracy, label-correcting search
    VIRTUAL_SOURCES = 4       ///< virtual source propagation: no precomputation, approximate
  };

  ///@{
  /// Which geodesic solver to use. Default SVG_LABEL_CORRECTING.
  vtkSetClampMacro(Solver, int, EXACT, VIRTUAL_SOURCES);
  vtkGetMacro(Solver, int);
  void SetSolverToExact() { this->SetSolver(EXACT); }
  void SetSolverToSVGLabelCorrecting() { this->SetSolver(SVG_LABEL_CORRECTING); }
  void SetSolverToSVGDijkstra() { this->SetSolver(SVG_DIJKSTRA); }
  void SetSolverToDGG() { this->SetSolver(DGG); }
  void SetSolverToVirtualSources() { this->SetSolver(VIRTUAL_SOURCES); }
  /// The Solver's name as in the ParaView property ("Exact", "SVG (label-correcting)", ...).
  static const char* GetSolverName(int solver);
  ///@}

  ///@{
  /// Input point ids used as sources when the Sources port is not connected.
  void AddSourceVertexId(vtkIdType id);
  void RemoveAllSourceVertexIds();
  vtkIdType GetNumberOfSourceVertexIds() const
  {
    return static_cast<vtkIdType>(this->SourceVertexIds.size());
  }
  vtkIdType GetSourceVertexId(vtkIdType i) const
  {
    return this->SourceVertexIds[static_cast<size_t>(i)];
  }
  ///@}

  ///@{
  /// Distances larger than this are not computed (NaN in the output). 0 (default): unlimited.
  // (Not clamped: a negative or NaN value is an error when the filter runs, naming it.)
  vtkSetMacro(MaximumDistance, double);
  vtkGetMacro(MaximumDistance, double);
  ///@}

  ///@{
  /// Name of the output point array. Default "GeodesicDistance".
  vtkSetStdStringFromCharMacro(ResultArrayName);
  vtkGetCharFromStdStringMacro(ResultArrayName);
  ///@}

  ///@{
  /// SVG solvers: size of the geodesic disk (number of nearest vertices) each vertex is linked
  /// within. Default 50. Clamped to the number of vertices; K < 1 is an error (empty output).
  vtkSetMacro(K, int);
  vtkGetMacro(K, int);
  ///@}

  ///@{
  /// DGG solver: the largest relative error the discrete geodesic graph aims at (its links are
  /// the direct geodesics that no route through another vertex approximates within it). Default
  /// 1e-3; 1e-5 .. 0.1 (outside is an error). Measured against the exact solver: the largest
  /// error stays below it, the mean is 10-20 times smaller (README, "Geodesic engines").
  vtkSetMacro(GraphAccuracy, double);
  vtkGetMacro(GraphAccuracy, double);
  ///@}

  ///@{
  /// DGG solver (advanced): each vertex's polar stencil, over which UnfoldingRefinement
  /// unfolds, also holds the vertices the graph's construction reached along direct geodesics
  /// but did not link (the graph itself, hence the distances without refinement, are the same).
  /// Off by default. On: at GraphAccuracy 0.1 the refined mean error is 2-3x smaller (below the
  /// saddle vertex graph's with K = 50 on the meshes measured), for about twice the graph's
  /// memory, a build about 1.2x longer and a refined solve 20-30% slower (README, "Geodesic
  /// engines"). On irregular flat meshes, where the refinement over the links alone is exact or
  /// nearly, it is near-exact too but a little less accurate (mean error about 3e-6 on a
  /// jittered plane). A graph of its own (cache and
  /// CacheFileName).
  vtkSetMacro(ReachedStencil, bool);
  vtkGetMacro(ReachedStencil, bool);
  vtkBooleanMacro(ReachedStencil, bool);
  ///@}

  ///@{
  /// SVG solvers: optional cache file for the graph. When set, the graph is loaded from it if
  /// it was saved for the same mesh geometry and K (DGG: GraphAccuracy and ReachedStencil);
  /// otherwise it is built and saved there. A missing file is silent, a stale or corrupt one
  /// gets a warning (and is rebuilt), a failed save is a warning. Default empty (no file).
  vtkSetStdStringFromCharMacro(CacheFileName);
  vtkGetCharFromStdStringMacro(CacheFileName);
  ///@}

  ///@{
  /// SVG solvers: refine the graph distances by geodesic triangle unfolding over the polar
  /// stencils. Exact on developable surfaces (planes, cylinders, cones), 2-8x more accurate on
  /// curved ones, for about three times the cost of a graph solve. Default on.
  vtkSetMacro(UnfoldingRefinement, bool);
  vtkGetMacro(UnfoldingRefinement, bool);
  vtkBooleanMacro(UnfoldingRefinement, bool);
  ///@}

  /// Connect the optional sources (port 1): points and/or polylines.
  void SetSourcesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSourcesData(vtkDataObject* sources) { this->SetInputData(1, sources); }

protected:
  vtkSVGGeodesicDistance();
  ~vtkSVGGeodesicDistance() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  // RequestData's work on the whole surface (the input itself, or under MPI the gathered
  // surface on process 0).
  int Execute(vtkPolyData* input, vtkPointSet* sources, vtkPolyData* output);
  // Under MPI, on pieces: each process works on its own cells (`own`, ghost cells dropped) and a
  // band of its neighbours' (vtkSurfacePieces), nothing gathered; the sources are
  // SourceVertexIds, or, when `sourceXyz` is not null, the Sources port's points (x, y, z of
  // each, the same on every process) and `curves` (its line cells, the same on every process).
  int ExecutePieces(vtkPolyData* input, vtkPolyData* own, vtkPolyData* output,
    const std::vector<double>* sourceXyz, vtkPolyData* curves);


private:
  vtkSVGGeodesicDistance(const vtkSVGGeodesicDistance&) = delete;
  void operator=(const vtkSVGGeodesicDistance&) = delete;

  int Solver = VIRTUAL_SOURCES;
  std::vector<vtkIdType> SourceVertexIds;
  double MaximumDistance = 0.0;
  std::string ResultArrayName = "GeodesicDistance";
  int K = 50;
  double GraphAccuracy = 1e-3;
  bool ReachedStencil = false;
  std::string CacheFileName;
  bool UnfoldingRefinement = true;

  // Converted mesh, locator, solvers and graph, reused while the input mesh is unchanged.
  struct Cache;
  std::unique_ptr<Cache> MeshCache;
  // Under MPI: this process's piece, band and graph, reused while the input is unchanged.
  std::unique_ptr<vtkSurfacePieces> Pieces;

  // Execute's steps (vtkSVGGeodesicDistance.cxx); each reports its own errors.
  struct Run; // one Execute's sources
  bool FindSources(Cache& cache, vtkPointSet* sources, Run& run);
  /// The graph solvers (SVG, DGG): a graph built or loaded before the first distance.
  bool UsesGraph() const;
  bool UseGraph(Cache& cache, Run& run);
  bool Solve(Cache& cache, Run& run);
  void WriteOutput(const Cache& cache, const Run& run, vtkPolyData* output);
};

#endif
