/**
 * @class vtkShapeDistributor
 * @brief Conflict-free, anisotropic, multi-class distribution of 2D shapes on a triangle mesh.
 *
 * A thin wrapper over gs::ShapeDistributor (Filters/Core/Distribution/ShapeDistributor.h; Wang et al. 2016,
 * Section 4 and Algorithm 3): parallel dart throwing whose candidates are oriented by a direction
 * field, scaled by a density field and accepted only when no placed shape and no higher-priority
 * candidate conflicts with them, conflicts being read from minimum safe distance tables (MSDT
 * Source) at the geodesic distance and relative angles of the two shapes (geodesic polar
 * coordinates about each shape's centre, from the engine Solver: the discrete geodesic graph by
 * default, the saddle vertex graph, or exact geodesics). Long shapes (classes split into parts by MSDT Source) lie along a streamline of the
 * field and bend with it.
 *
 * Input port 0 ("Input", vtkPolyData): the surface (polygons triangulated, as in the other
 * filters) with a direction array (DirectionArray: a cell array of tangent vectors such as
 * Cross Field's Direction, or a point array, averaged per triangle; its field data "Symmetry"
 * (N) says how streamlines may turn it, 1 by default) and an optional density array
 * (DensityArray: point scalars f, a shape at factor f is f times its base size; points with
 * f <= 0 get no shape). A density brush (BrushCenter, BrushRadius, BrushDensity) shrinks the
 * shapes around a point of the surface, multiplying the density array's factors.
 * Input port 1 ("Table", vtkImageData): the tables of MSDT Source (port 0).
 *
 * Output port 0 ("Placements"): one vertex per shape at its centre; point arrays ClassId,
 * Scale, Direction (the shape's +x axis), Normal, FaceId (input cell). Field data:
 * NumberOfCandidates, NumberOfCharts, Maximal (1 when ended by the failure count), Seconds,
 * CandidatesWithoutShape, CandidatesRejectedByTables, CandidatesRejectedByFaithfulCheck,
 * CandidatesRejectedByDrawnCheck (a warning names a check that rejects most of the candidates
 * the tables accepted), DirectionArrayUsed, PhaseSeconds;
 * with VerifyOverlaps, the point array Overlaps and field data OverlappingPairs and
 * OverlapCheckSeconds.
 * Output port 1 ("Decals"): per shape, copies of the triangles it covers with texture
 * coordinates ("TextureCoordinates") mapping the square around its class circle onto [0, 1]^2
 * (the convention of MSDT Source's Silhouettes image); cell arrays ShapeId and ClassId.
 * Output port 2 ("Outlines"): each shape's contours drawn on the surface (through the polar
 * coordinates of its centre, or of its curve for long shapes) as closed polylines (a shape over
 * the mesh boundary: its outline within the surface closed along the boundary; a long shape
 * over the boundary: the open pieces on the surface); cell arrays
 * ShapeId and ClassId. Decals and outlines are lifted off the surface by 0.2% of ShapeSize
 * along the face normals so that they render over the mesh.
 *
 * The mesh conversion and the saddle vertex graph are kept while the mesh is unchanged (and the
 * graph is shared with the other filters and CacheFileName): changing the density, the
 * direction field's values, the tables or any parameter re-runs only the distribution.
 * Results are identical for any NumberOfThreads for a given Seed.
 *
 * Errors (vtkErrorMacro, empty outputs): a mesh the core rejects, missing or wrong-typed
 * arrays, missing or inconsistent tables, ShapeSize < 0 or absurdly small for the mesh,
 * ClassWeights of the wrong length or all zero, unknown Mode or Solver, K < 1 for a graph solver, negative MaximumShapes or
 * NumberOfThreads. Progress is reported and the run can be aborted.
 *
 * Example (pvpython):
 * @code
 * msdt = MSDTSource(ShapeFileNames=["star.png"])
 * field = CrossField(Input=mesh)
 * shapes = ShapeDistributor(Input=field, Table=msdt, ShapeSize=0.05)
 * @endcode
 */
#ifndef vtkShapeDistributor_h
#define vtkShapeDistributor_h

#include "GeodesicShapesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class vtkImageData;

class GEODESICSHAPESFILTERS_EXPORT vtkShapeDistributor : public vtkPolyDataAlgorithm
{
public:
  static vtkShapeDistributor* New();
  vtkTypeMacro(vtkShapeDistributor, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum Modes
  {
    RANDOM = 0,
    GREEDY = 1,
    CIRCUMCIRCLE_POISSON_DISK = 2
  };

  ///@{
  /// Circumradius (world units) of the first class at density 1. Default 0: automatic, 4% of
  /// the input's largest bounding-box side (field data ShapeSizeUsed of Placements).
  vtkSetMacro(ShapeSize, double);
  vtkGetMacro(ShapeSize, double);
  ///@}

  ///@{
  /// Relative frequencies of the classes (empty: all equal).
  void SetNumberOfClassWeights(int n);
  void SetClassWeight(int i, double w);
  void RemoveAllClassWeights() { this->ClassWeights.clear(); this->Modified(); }
  int GetNumberOfClassWeights() const { return static_cast<int>(this->ClassWeights.size()); }
  double GetClassWeight(int i) const { return this->ClassWeights[i]; }
  ///@}

  ///@{
  /// RANDOM (dart throwing, default), GREEDY (fronts growing at the safe distance) or
  /// CIRCUMCIRCLE_POISSON_DISK (the baseline: shapes as their circumcircles).
  vtkSetMacro(Mode, int);
  vtkGetMacro(Mode, int);
  ///@}

  ///@{
  /// How Random and Circumcircle Poisson disk modes draw candidates: ROUNDS (default: rounds
  /// drawn from the faces still alive, until MaximalFailures consecutive failures) or
  /// PLACE_KEYED (every candidate and its priority a function of the seed and its place; an
  /// Apply after a change of the density only, brush or DensityArray values, re-decides what
  /// the change reaches and keeps the rest: the same shapes as a fresh run, bit for bit; field
  /// data CandidatesRedecided and IncrementalRun say what it did). Greedy uses rounds.
  enum CandidateOrders
  {
    ROUNDS = 0,
    PLACE_KEYED = 1
  };
  vtkSetMacro(CandidateOrder, int);
  vtkGetMacro(CandidateOrder, int);
  ///@}

  ///@{
  /// Random seed. Default 0.
  vtkSetMacro(Seed, int);
  vtkGetMacro(Seed, int);
  ///@}

  ///@{
  /// Stop after this many shapes (0, default: until maximal).
  vtkSetMacro(MaximumShapes, int);
  vtkGetMacro(MaximumShapes, int);
  ///@}

  ///@{
  /// Consecutive rejected candidates that end the run (default 10000; the chance that more than 0.1% of positions still fit is then e^-10): a shape then fits in
  /// about 1 / MaximalFailures of random probes.
  vtkSetMacro(MaximalFailures, int);
  vtkGetMacro(MaximalFailures, int);
  ///@}

  ///@{
  /// Safety on curved and noisy surfaces (see gs::ShapeDistributionOptions): pairs whose chart
  /// is stretched by more than DistortionLimit (default 0.01) are judged by circumcircles, and
  /// safe distances grow by HolonomyMargin (default 1) times the turn a shape's outline can take
  /// from the curvature it encloses with its neighbour. HolonomyMargin 0 packs tighter on noisy
  /// meshes at the risk of small overlaps of the drawn outlines.
  vtkSetMacro(DistortionLimit, double);
  vtkGetMacro(DistortionLimit, double);
  vtkSetMacro(HolonomyMargin, double);
  vtkGetMacro(HolonomyMargin, double);
  ///@}

  ///@{
  /// Keep every shape's circle on the surface (no shape hangs over the mesh boundary).
  /// Default off.
  vtkSetMacro(KeepInside, bool);
  vtkGetMacro(KeepInside, bool);
  vtkBooleanMacro(KeepInside, bool);
  ///@}

  ///@{
  /// After the tables accept a shape, check its outline as drawn against its neighbours'
  /// (gs::ShapeDistributionOptions::DrawnCheck): the tables assume rigid planar copies, which
  /// long shapes bending with their curve on curved meshes are not. Default on; off: the
  /// tables alone (faster: up to 25% with many long shapes).
  vtkSetMacro(DrawnCheck, bool);
  vtkGetMacro(DrawnCheck, bool);
  vtkBooleanMacro(DrawnCheck, bool);
  ///@}

  ///@{
  /// With DrawnCheck: place a shape only where its map is one-to-one over its silhouette
  /// (gs::ShapeDistributionOptions::FaithfulCheck), so that its decal draws the outline it is
  /// checked with: every point of its drawn outline, read back through the inverse of its map,
  /// gives the silhouette point it was drawn from, within 5% of the circumradius. It is not where
  /// a long shape's curve turns more tightly than its width (the map folds) or a large short
  /// shape reaches around bumps or thin parts. Default on; off: such shapes are placed, their
  /// decals drawing something else than their outlines.
  vtkSetMacro(FaithfulCheck, bool);
  vtkGetMacro(FaithfulCheck, bool);
  vtkBooleanMacro(FaithfulCheck, bool);
  ///@}

  ///@{
  /// Decals: a face is split (to depth 5) where the shape's map departs from the face's affine
  /// texture map by more than this fraction of the circumradius (a long shape bending inside a
  /// face); 0: whole faces only. Default 0.01; negative or not finite is an error.
  vtkSetMacro(DecalTolerance, double);
  vtkGetMacro(DecalTolerance, double);
  ///@}

  ///@{
  /// Check the finished result for overlaps independently of the tables (gs::CheckOverlaps: the
  /// drawn outlines of neighbouring shapes, each carried into the other's polar chart and tested
  /// against its silhouette, deeper than 0.5% of the smaller circumradius). Adds the point array
  /// Overlaps (per shape, how many others it overlaps) and the field data OverlappingPairs and
  /// OverlapCheckSeconds to Placements, with a warning naming the count when it is not zero.
  /// Default off.
  vtkSetMacro(VerifyOverlaps, bool);
  vtkGetMacro(VerifyOverlaps, bool);
  vtkBooleanMacro(VerifyOverlaps, bool);
  ///@}

  ///@{
  /// Threads (0, default: all cores). The result does not depend on it.
  vtkSetMacro(NumberOfThreads, int);
  vtkGetMacro(NumberOfThreads, int);
  ///@}

  /// Values of the Solver property: the engines of the shapes' polar charts, numbered as SVG
  /// Geodesic Distance's Solver (gs::GeodesicSolver).
  enum SolverType
  {
    EXACT = 0,                ///< exact geodesics (no graph, slower charts)
    SVG_LABEL_CORRECTING = 1, ///< the saddle vertex graph of K
    DGG = 3                   ///< the discrete geodesic graph of K and GraphAccuracy
  };
  ///@{
  /// Engine of the shapes' geodesic polar charts (and the brush's distance): DGG (default),
  /// SVG_LABEL_CORRECTING or EXACT. Graphs are built once per mesh geometry and parameters and
  /// shared with the other filters. Other values are an error.
  vtkSetMacro(Solver, int);
  vtkGetMacro(Solver, int);
  ///@}

  ///@{
  /// Graph solvers: the number of nearest vertices each vertex is linked within (at least 1;
  /// default 50; clamped to the number of vertices).
  vtkSetMacro(K, int);
  vtkGetMacro(K, int);
  ///@}

  ///@{
  /// DGG: the graph's largest relative error, 1e-5 .. 0.1 (default 0.1); other values are an
  /// error.
  vtkSetMacro(GraphAccuracy, double);
  vtkGetMacro(GraphAccuracy, double);
  ///@}

  ///@{
  /// Optional saddle vertex graph cache file (see vtkSVGGeodesicDistance).
  vtkSetStdStringFromCharMacro(CacheFileName);
  vtkGetCharFromStdStringMacro(CacheFileName);
  ///@}

  ///@{
  /// The density brush (Wang et al. 2016, Fig. 10): around BrushCenter (world coordinates,
  /// snapped to the closest surface point; farther from the surface than its bounding box
  /// diagonal is an error) shapes shrink to BrushDensity times their size and
  /// grow back linearly with the geodesic distance d from it, to their full size at BrushRadius:
  /// f = max(BrushDensity, min(1, d / BrushRadius)), d from the distributor's own engine (its
  /// graph; the exact solver with Solver EXACT), multiplied by DensityArray's factors where both are
  /// given. BrushRadius 0 (the default): no brush; otherwise it must be positive and finite,
  /// BrushDensity (default 0.25) in (0, 1] and BrushCenter finite. In the GUI the brush is a
  /// sphere widget the user drags in the render view.
  vtkSetVector3Macro(BrushCenter, double);
  vtkGetVector3Macro(BrushCenter, double);
  vtkSetMacro(BrushRadius, double);
  vtkGetMacro(BrushRadius, double);
  vtkSetMacro(BrushDensity, double);
  vtkGetMacro(BrushDensity, double);
  ///@}

  /// Connect the tables (MSDT Source port 0) to port 1.
  void SetTableConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }

protected:
  vtkShapeDistributor();
  ~vtkShapeDistributor() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  // RequestData's work on the whole surface (the input itself, or under MPI the gathered
  // surface on process 0); the outputs are empty on entry.
  int Execute(vtkPolyData* input, vtkImageData* tables, vtkPolyData* placements,
    vtkPolyData* decals, vtkPolyData* outlines);

  double ShapeSize = 0.0; // 0: automatic (4% of the largest bounding-box side)
  std::vector<double> ClassWeights;
  int Mode = RANDOM;
  int CandidateOrder = ROUNDS;
  int Seed = 0;
  int MaximumShapes = 0;
  int MaximalFailures = 10000;
  int NumberOfThreads = 0;
  double DistortionLimit = 0.01;
  double HolonomyMargin = 1.0;
  bool KeepInside = false;
  bool DrawnCheck = true;
  bool FaithfulCheck = true;
  double DecalTolerance = 0.01;
  bool VerifyOverlaps = false;
  int Solver = DGG;
  int K = 50;
  double GraphAccuracy = 0.1;
  std::string CacheFileName;
  double BrushCenter[3] = { 0.0, 0.0, 0.0 };
  double BrushRadius = 0.0; // 0: no brush
  double BrushDensity = 0.25;

private:
  vtkShapeDistributor(const vtkShapeDistributor&) = delete;
  void operator=(const vtkShapeDistributor&) = delete;

  struct Cache;
  std::unique_ptr<Cache> MeshCache;

  // Execute's steps (vtkShapeDistributor.cxx); each reports its own errors.
  struct Run; // one Execute's inputs, results and phase times
  bool CheckParameters();
  // NumberOfThreads capped at the processors (0 stays 0: OpenMP's default).
  int UsedThreads() const;
  bool ResolveShapeSize(const Cache& cache, Run& run);
  bool ReadDirections(vtkPolyData* input, const Cache& cache, Run& run);
  // The direction array to read (DirectionArray, or the input's Direction or vectors) and its
  // association (points or cells); false (with an error) when there is none.
  bool ChooseDirectionArray(vtkPolyData* surface, std::string& name, int& association);
  bool ReadDensity(const Cache& cache, Run& run);
  bool UseGraph(Cache& cache);
  bool ApplyBrush(Cache& cache, Run& run);
  bool Distribute(Cache& cache, Run& run);
  bool DrawShapes(const Cache& cache, Run& run, vtkPolyData* placements, vtkPolyData* decals,
    vtkPolyData* outlines);
};

#endif
