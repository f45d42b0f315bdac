/**
 * @class vtkCrossField
 * @brief Smooth N-direction fields (vector, line or cross fields) on a triangle mesh, with user
 * singularities and stroke constraints.
 *
 * A thin wrapper over gs::DirectionFieldSolver (Filters/Core/Fields/DirectionField.h). The field is
 * piecewise constant per triangle, expressed with the discrete Levi-Civita connection.
 *
 * Modes:
 *  - SMOOTHEST (0, "Smoothest"): the globally smoothest field (Knoppel, Crane, Pinkall, Schroder
 *    2013), singularities placed automatically; with CurvatureAlignment > 0 (N = 2 or 4) it is
 *    pulled towards the principal curvature directions.
 *  - PRESCRIBED_SINGULARITIES (1, "Prescribed singularities"): trivial connections (Crane,
 *    Desbrun, Schroder 2010): exactly the singularities of the Singularities input, the smoothest
 *    field with them (homology generators of higher genus by tree-cotree). Indices must sum to
 *    the Euler characteristic of each connected component, with this boundary convention: an
 *    index given to a boundary vertex is the field's turning against the boundary tangent there
 *    (1/4 at each corner of a rectangle for the boundary-aligned cross field); a boundary loop
 *    without such vertices keeps the field at a constant angle to it on average.
 *
 * Input port 0 ("Input", vtkPolyData): the surface (polygons are triangulated, lines and vertices
 * ignored; bad meshes rejected as in the other filters of the suite).
 * Input port 1 ("Singularities", optional, vtkPointSet): points snapped to the nearest vertex,
 * with the point array "Index" (multiples of 1/N; several points on one vertex add up). Used in
 * the Prescribed singularities mode only.
 * Input port 2 ("Strokes", optional, vtkPolyData): polylines drawn on or near the surface; the
 * field follows each stroke's direction in every triangle it crosses over at least a tenth of
 * the mean edge length (hard constraints; the direction is that of the stroke's closest segment,
 * projected onto the triangle).
 *
 * Properties: Symmetry (1, 2 or 4; default 4), Mode (default SMOOTHEST), CurvatureAlignment
 * (weight >= 0, default 0).
 *
 * Output: the surface with
 *  - cell array Direction (3 components): a unit tangent vector per triangle, one representative
 *    of the N directions (NaN for vertex and line cells);
 *  - point array Direction: the N-symmetric average of the adjacent triangles' directions (the
 *    N-th powers averaged), a unit vector (zero where they cancel, at singularities);
 *  - point array SingularityIndex: the index of each vertex, 0 except at singularities (a
 *    multiple of 1/N; at boundary vertices the field's turning against the boundary, rounded to
 *    the nearest 1/N);
 *  - field data EulerCharacteristic and SingularityIndexSum (interior indices plus the turning
 *    of every boundary loop: equal by the Poincare-Hopf theorem), and Symmetry (N).
 *
 * The solver (and its factorization) is kept while the input mesh does not change: moving
 * singularities or changing stroke directions re-solves without factorizing again.
 */
#ifndef vtkCrossField_h
#define vtkCrossField_h

#include "GeodesicShapesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr

class GEODESICSHAPESFILTERS_EXPORT vtkCrossField : public vtkPolyDataAlgorithm
{
public:
  static vtkCrossField* New();
  vtkTypeMacro(vtkCrossField, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  enum ModeType
  {
    SMOOTHEST = 0,
    PRESCRIBED_SINGULARITIES = 1
  };

  ///@{
  /// Number of directions N: 1 (vector field), 2 (line field) or 4 (cross field). Default 4.
  vtkSetMacro(Symmetry, int);
  vtkGetMacro(Symmetry, int);
  ///@}

  ///@{
  /// SMOOTHEST (default) or PRESCRIBED_SINGULARITIES.
  vtkSetMacro(Mode, int);
  vtkGetMacro(Mode, int);
  void SetModeToSmoothest() { this->SetMode(SMOOTHEST); }
  void SetModeToPrescribedSingularities() { this->SetMode(PRESCRIBED_SINGULARITIES); }
  ///@}

  ///@{
  /// Weight of the alignment with the principal curvature directions in the Smoothest mode
  /// (N = 2 or 4): 0 (default) ignores curvature, 1 balances smoothness and alignment.
  vtkSetMacro(CurvatureAlignment, double);
  vtkGetMacro(CurvatureAlignment, double);
  ///@}

  void SetSingularitiesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSingularitiesData(vtkDataObject* data) { this->SetInputData(1, data); }
  void SetStrokesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(2, output); }
  void SetStrokesData(vtkDataObject* data) { this->SetInputData(2, data); }

protected:
  vtkCrossField();
  ~vtkCrossField() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;
  // RequestData's work on the whole surface (the input itself, or under MPI the gathered
  // surface on process 0).
  int Execute(vtkPolyData* input, vtkPointSet* singularities, vtkPolyData* strokes, vtkPolyData* output);


private:
  vtkCrossField(const vtkCrossField&) = delete;
  void operator=(const vtkCrossField&) = delete;

  int Symmetry = 4;
  int Mode = SMOOTHEST;
  double CurvatureAlignment = 0.0;

  struct Cache;
  std::unique_ptr<Cache> MeshCache;

  // Execute's steps (vtkCrossField.cxx); each reports its own errors.
  bool CheckParameters(vtkPointSet* singularities);
  struct Run; // one Execute's singularities, stroke constraints and angles
  bool FindSingularities(Cache& cache, vtkPointSet* singularities, Run& run);
  bool ReadStrokes(Cache& cache, vtkPolyData* strokes, Run& run);
  void WriteOutput(const Cache& cache, const Run& run, vtkPolyData* output);
};

#endif
