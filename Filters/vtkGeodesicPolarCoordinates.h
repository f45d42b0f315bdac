/**
 * @class vtkGeodesicPolarCoordinates
 * @brief Geodesic polar coordinates (rho, theta) about a point of a triangle mesh, and decal
 * texture coordinates.
 *
 * A thin wrapper over gs::GeodesicPolarCoordinates (Filters/Core/Fields/GeodesicPolarCoordinates.h;
 * Wang et al. 2016, Section 3.3): for every point of the input surface closer than Radius to the
 * source, rho is the geodesic distance (exact polyhedral geodesics, truncated at Radius) and
 * theta the direction in which the shortest geodesic leaves the source (the log map), measured
 * counter-clockwise about the outward normal from a reference direction, in [0, 2 pi). At a
 * source vertex whose angle sum is not 2 pi (a cone point or a saddle) the angles are scaled so
 * that a full turn is 2 pi (the original angle sum is reported as SourceAngleSum).
 *
 * Curve sources (the first polyline of the Source port): coordinates (u, delta), delta the signed
 * geodesic offset (positive on the left of the curve's direction, normal up) and u in [0, 1] the
 * normalized arc length along the point's own offset curve between the curve's ends (Offset and
 * ArcLength arrays; DecalCoordinates (u, delta / DecalSize + 0.5); field data CurveLength;
 * computed with exact geodesics whatever the Solver).
 *
 * Input port 0 ("Input", vtkPolyData): the surface. As in vtkSVGGeodesicDistance, polygons with
 * more than three points and triangle strips are triangulated (with a warning), vertex and line
 * cells are ignored, exactly coincident points are welded for the computation and the result is
 * mapped back to every input point. Empty, non-finite, degenerate, duplicate or non-manifold
 * input is rejected with an error and an empty output.
 *
 * Input port 1 ("Source", optional, vtkPointSet): its first point is snapped to the closest
 * surface point (a vertex when it lands on one, otherwise an edge or face point) and is the
 * source; SourceVertexId is then ignored. A Source with line cells is a curve source: its first
 * polyline, sampled every quarter edge and snapped (other cells ignored, with a warning).
 *
 * Properties:
 *  - SourceVertexId (default 0): the input point used as the source when port 1 is not
 *    connected; out of range or not used by a triangle: error, empty output.
 *  - Radius (default 1, > 0, may be infinite): points farther than this get NaN.
 *  - ReferenceDirection (default (0, 0, 0)): theta's zero. (0, 0, 0): the source's first edge
 *    (a vertex's first outgoing edge in the core mesh, or the first edge of the source's face).
 *    Otherwise a 3D direction projected onto the tangent plane at the source (gs::TangentAngle);
 *    a direction normal to the surface there gets a warning and falls back to the first edge;
 *    a non-finite one is an error.
 *  - AngleMode: GEODESIC_DIRECTION (0, "Geodesic direction": the log map) or
 *    ISO_CURVE_ARC_LENGTH (1, "Iso-curve arc length": arc length along each iso-distance curve
 *    from the reference geodesic over the curve's length; does not fold past saddles and cut
 *    loci; points whose iso-curve is not a closed loop keep the geodesic direction, with a
 *    warning).
 *  - DecalSize (default 1, > 0): side of the square image mapped by DecalCoordinates.
 *  - Solver (default EXACT), K (default 50), GraphAccuracy (default 1e-3): the geodesic engine,
 *    in SVG Geodesic Distance's vocabulary: EXACT (0) exact geodesics truncated at Radius (on
 *    surfaces of gs::ExactInPartsMinimumFaces faces or more, a Radius of a quarter of the
 *    bounding box's diagonal or more is solved in parts on threads: ExactInParts.h);
 *    SVG_LABEL_CORRECTING (1) the saddle vertex graph of K; DGG (3) the discrete geodesic graph
 *    of K and GraphAccuracy (graphs shared process-wide with the other filters; faster on large
 *    patches once built).
 *
 * Output (vtkPolyData): the input surface (its triangulation when it had to be triangulated)
 * with double point arrays
 *  - GeodesicDistance (rho, the active scalars),
 *  - PolarAngle (theta, radians in [0, 2 pi); 0 at the source itself),
 *  - DecalCoordinates (2 components, the active texture coordinates):
 *    (rho cos theta, rho sin theta) / DecalSize + (0.5, 0.5), so that a square image of side
 *    DecalSize centred on the source, its x axis along the reference direction, maps to
 *    [0, 1]^2,
 * all NaN for points beyond Radius, unreachable (another connected component) or not used by
 * any triangle; and the field data array SourceAngleSum (double, the angle sum at the source:
 * 2 pi for a face point or a flat vertex).
 *
 * Example (pvpython):
 * @code
 * LoadPlugin("build/lib/paraview-5.11/plugins/GeodesicShapes/GeodesicShapes.so", ns=globals())
 * mesh = PLYReader(FileNames=["Data/torus.ply"])
 * polar = GeodesicPolarCoordinates(Input=mesh, SourceVertexId=0, Radius=0.9,
 *                                  ReferenceDirection=[0, 1, 0], DecalSize=1.8)
 * # then colour by PolarAngle, or texture-map an image through DecalCoordinates
 * @endcode
 */
#ifndef vtkGeodesicPolarCoordinates_h
#define vtkGeodesicPolarCoordinates_h

#include "GeodesicShapesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <vector> // for std::vector

class vtkDoubleArray;
class vtkSurfacePieces;
namespace gs
{
struct PiecePolarCoordinates;
}

class GEODESICSHAPESFILTERS_EXPORT vtkGeodesicPolarCoordinates : public vtkPolyDataAlgorithm
{
public:
  static vtkGeodesicPolarCoordinates* New();
  vtkTypeMacro(vtkGeodesicPolarCoordinates, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Values of the AngleMode property.
  enum AngleModeType
  {
    /// theta = direction of the shortest geodesic at the source (the log map).
    GEODESIC_DIRECTION = 0,
    /// theta proportional to the arc length along each vertex's iso-distance curve, from the
    /// reference geodesic (bijective past saddles and cut loci where level sets are loops).
    ISO_CURVE_ARC_LENGTH = 1
  };

  ///@{
  /// Input point used as the source when the Source port is not connected. Default 0.
  vtkSetMacro(SourceVertexId, vtkIdType);
  vtkGetMacro(SourceVertexId, vtkIdType);
  ///@}

  ///@{
  /// Geodesic radius of the parameterized disc (> 0; infinity: the whole reachable surface).
  /// Points farther away get NaN. Default 1.
  vtkSetMacro(Radius, double);
  vtkGetMacro(Radius, double);
  ///@}

  ///@{
  /// Direction of theta = 0, projected onto the tangent plane at the source. (0, 0, 0), the
  /// default: the direction of the source's first edge.
  vtkSetVector3Macro(ReferenceDirection, double);
  vtkGetVector3Macro(ReferenceDirection, double);
  ///@}

  ///@{
  /// How theta is defined: GEODESIC_DIRECTION (0, the default) or ISO_CURVE_ARC_LENGTH (1).
  vtkSetMacro(AngleMode, int);
  vtkGetMacro(AngleMode, int);
  void SetAngleModeToGeodesicDirection() { this->SetAngleMode(GEODESIC_DIRECTION); }
  void SetAngleModeToIsoCurveArcLength() { this->SetAngleMode(ISO_CURVE_ARC_LENGTH); }
  /// The AngleMode's name as in the ParaView property ("Geodesic direction").
  static const char* GetAngleModeName(int mode);
  ///@}

  ///@{
  /// Side of the square image (centred on the source) that DecalCoordinates map to [0, 1]^2.
  /// Must be > 0. Default 1.
  vtkSetMacro(DecalSize, double);
  vtkGetMacro(DecalSize, double);
  ///@}

  /// Values of the Solver property: the engines with departure angles, numbered as SVG
  /// Geodesic Distance's Solver (gs::GeodesicSolver).
  enum SolverType
  {
    EXACT = 0,                ///< exact geodesics truncated at Radius (no set-up)
    SVG_LABEL_CORRECTING = 1, ///< the saddle vertex graph of K
    DGG = 3                   ///< the discrete geodesic graph of K and GraphAccuracy
  };
  ///@{
  /// Engine for point sources: EXACT (default: exact rho and theta, nothing to build),
  /// SVG_LABEL_CORRECTING or DGG (graphs built once per mesh and shared with the other filters
  /// of the suite; rho near-exact, theta within a fraction of a degree; several times faster on
  /// large patches once the graph exists). Other values are an error.
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
  /// DGG: the graph's largest relative error, 1e-5 .. 0.1 (default 1e-3); other values are an
  /// error.
  vtkSetMacro(GraphAccuracy, double);
  vtkGetMacro(GraphAccuracy, double);
  ///@}

  /// Connect the optional source (port 1): its first point is the source.
  void SetSourceConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSourceData(vtkDataObject* source) { this->SetInputData(1, source); }

protected:
  vtkGeodesicPolarCoordinates();
  ~vtkGeodesicPolarCoordinates() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  // RequestData's work on the whole surface (the input itself, or under MPI the gathered
  // surface on process 0).
  int Execute(vtkPolyData* input, vtkPointSet* source, vtkPolyData* output);
  // Under MPI, the exact chart about SourceVertexId or the Source input's first point (`curve`:
  // its first line cell, the same on every process: curve coordinates) on pieces:
  // each process outputs its own cells (`own`), the chart's process grows its band to the chart
  // (vtkSurfacePieces::Polar), nothing gathered. `sourceXyz`: the Source input's points (x, y, z, ...) gathered to every process, or null
  // for SourceVertexId.
  int ExecutePieces(vtkPolyData* input, vtkPolyData* own, vtkPolyData* output,
    const std::vector<double>* sourceXyz, vtkPolyData* curve);
  // ExecutePieces' output: the arrays as WriteOutput names and fills them (`curve`: a curve
  // source's offset and arc length), at the points of `own`, and the field data.
  int WritePieceOutput(vtkPolyData* own, vtkPolyData* output, const std::vector<double>& rho,
    const std::vector<double>& theta, const gs::PiecePolarCoordinates& chart, bool curve);
  // The warning that ReferenceDirection is normal to the surface at the source.
  void WarnReferenceNormal();
  // The warning that `kept` points keep the geodesic-direction angle (iso-curve angles).
  void WarnIsoCurveKept(int kept);
  // The output: `surface` (shallow) with the coordinates' arrays (rho the active scalars, the
  // decal coordinates the texture coordinates).
  static void SetOutputArrays(vtkPolyData* output, vtkPolyData* surface, vtkDoubleArray* rho,
    vtkDoubleArray* theta, vtkDoubleArray* decal);


private:
  vtkGeodesicPolarCoordinates(const vtkGeodesicPolarCoordinates&) = delete;
  void operator=(const vtkGeodesicPolarCoordinates&) = delete;

  vtkIdType SourceVertexId = 0;
  double Radius = 1.0;
  double ReferenceDirection[3] = { 0.0, 0.0, 0.0 };
  int AngleMode = GEODESIC_DIRECTION;
  double DecalSize = 1.0;
  int Solver = EXACT;
  int K = 50;
  double GraphAccuracy = 1e-3;

  // Converted mesh, locator and polar-coordinate solver, reused while the input is unchanged.
  struct Cache;
  std::unique_ptr<Cache> MeshCache;
  // Under MPI: this process's piece, reused while the input is unchanged.
  std::unique_ptr<vtkSurfacePieces> Pieces;

  // Execute's steps (vtkGeodesicPolarCoordinates.cxx); each reports its own errors.
  struct Run; // one Execute's source and results
  bool CheckParameters();
  bool FindSource(Cache& cache, vtkPointSet* source, Run& run);
  void ResolveReferenceAngle(const Cache& cache, Run& run);
  bool Solve(Cache& cache, Run& run);
  int WriteOutput(const Cache& cache, const Run& run, vtkPolyData* output);
};

#endif
