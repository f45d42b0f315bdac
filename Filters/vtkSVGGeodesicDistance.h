/**
 * @class vtkSVGGeodesicDistance
 * @brief Geodesic distance on a triangle mesh from source vertices or surface points.
 *
 * Computes, for every point of the input surface, the length of the shortest path on the
 * surface (not through space) to the nearest source. This release ships one solver, `Exact`:
 * exact polyhedral geodesics by window propagation (Chen-Han / ICH family, see
 * Filters/Core/ExactGeodesic.h), the ground truth the saddle-vertex-graph (SVG) solvers of later
 * releases are measured against.
 *
 * Input port 0 ("Input", vtkPolyData): the surface. Polygons with more than three points and
 * triangle strips are triangulated (with a warning); vertex and line cells are ignored. Exactly
 * coincident points are welded for the computation (meshes read from OBJ files with normals or
 * texture coordinates come as a soup of separate triangles), and the result is mapped back to
 * every input point. Empty, non-finite, degenerate, duplicate or non-manifold input is rejected
 * with an error and an empty output.
 *
 * Input port 1 ("Sources", optional, vtkPointSet): when connected, each of its points is
 * snapped to the closest point of the surface (a vertex, edge or face point) and used as a
 * source; SourceVertexIds is then ignored. Otherwise the sources are the input points listed in
 * SourceVertexIds.
 *
 * Output (vtkPolyData): the input surface (its triangulation when it had to be triangulated)
 * with a vtkDoubleArray point array named ResultArrayName (default "GeodesicDistance", also
 * made the active scalars). Points that are unreachable (another connected component), beyond
 * MaximumDistance, or not used by any triangle get NaN.
 *
 * Example (pvpython, see also Examples/geodesic_distance.py):
 * @code
 * LoadPlugin("build/lib/paraview-5.11/plugins/GeodesicShapes/GeodesicShapes.so", ns=globals())
 * mesh = PLYReader(FileNames=["Data/torus.ply"])
 * dist = SVGGeodesicDistance(Input=mesh, SourceVertexIds=[0])
 * @endcode
 */
#ifndef vtkSVGGeodesicDistance_h
#define vtkSVGGeodesicDistance_h

#include "GeodesicShapesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr
#include <string> // for std::string
#include <vector> // for std::vector

class GEODESICSHAPESFILTERS_EXPORT vtkSVGGeodesicDistance : public vtkPolyDataAlgorithm
{
public:
  static vtkSVGGeodesicDistance* New();
  vtkTypeMacro(vtkSVGGeodesicDistance, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Values of the Solver property.
  enum SolverType
  {
    EXACT = 0 ///< exact polyhedral geodesics (window propagation)
  };

  ///@{
  /// Which geodesic solver to use. Default EXACT (the only one in this release).
  vtkSetClampMacro(Solver, int, EXACT, EXACT);
  vtkGetMacro(Solver, int);
  void SetSolverToExact() { this->SetSolver(EXACT); }
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
  vtkSetClampMacro(MaximumDistance, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumDistance, double);
  ///@}

  ///@{
  /// Name of the output point array. Default "GeodesicDistance".
  vtkSetStdStringFromCharMacro(ResultArrayName);
  vtkGetCharFromStdStringMacro(ResultArrayName);
  ///@}

  /// Connect the optional source points (port 1).
  void SetSourcesConnection(vtkAlgorithmOutput* output) { this->SetInputConnection(1, output); }
  void SetSourcesData(vtkDataObject* sources) { this->SetInputData(1, sources); }

protected:
  vtkSVGGeodesicDistance();
  ~vtkSVGGeodesicDistance() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

private:
  vtkSVGGeodesicDistance(const vtkSVGGeodesicDistance&) = delete;
  void operator=(const vtkSVGGeodesicDistance&) = delete;

  int Solver = EXACT;
  std::vector<vtkIdType> SourceVertexIds;
  double MaximumDistance = 0.0;
  std::string ResultArrayName = "GeodesicDistance";

  // Converted mesh and solver, reused while the input mesh is unchanged.
  struct Cache;
  std::unique_ptr<Cache> MeshCache;
};

#endif
