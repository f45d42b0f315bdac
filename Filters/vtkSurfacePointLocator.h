// vtkSurfacePointLocator: snaps points in space to the closest point of a converted surface, as
// a core gs::SurfacePoint (a face of the core mesh with barycentric coordinates).
//
// Not a vtkObject and not wrapped (a private class of the GeodesicShapes::Filters module): every
// filter that takes sources or queries as points in space (source points, curve samples) snaps
// them with it. Built on a vtkStaticCellLocator over vtkSurfaceMeshConverter::Result::Triangles,
// whose cell i is core face i.
#ifndef vtkSurfacePointLocator_h
#define vtkSurfacePointLocator_h

#include "vtkSurfaceMeshConverter.h"

#include "Status.h"
#include "SurfacePoint.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

class vtkGenericCell;
class vtkPoints;
class vtkStaticCellLocator;

class vtkSurfacePointLocator
{
public:
  // `mesh` must be a successful conversion and outlive the locator. Builds the cell locator.
  explicit vtkSurfacePointLocator(const vtkSurfaceMeshConverter::Result& mesh);
  ~vtkSurfacePointLocator();

  // The closest surface point to x (on a vertex, an edge or inside a face; always returned as a
  // face point with barycentric coordinates in the core face's corner order). Fails, saying why,
  // for non-finite coordinates, when x cannot be snapped, or when x is farther from the surface
  // than `maximumFraction` of the mesh's bounding box diagonal (a point in the wrong units or
  // frame, not a point on this surface; infinity: any distance).
  gs::Result<gs::SurfacePoint> Snap(
    const double x[3], double maximumFraction = MaximumDistanceFraction);
  static constexpr double MaximumDistanceFraction = 0.25;

  // What Snap says of a point `distance` from a surface of bounding box diagonal `diagonal`,
  // beyond maximumFraction of it.
  static std::string TooFar(double distance, double maximumFraction, double diagonal);
  // The surface point `closest` of the triangle `triangle` (a cell of three points) as a face
  // point of the core face `face` of corners `corners`: the cell's weights matched to the
  // corners by vertex (`vertexOf` a cell point id: the mesh builder may have re-oriented the
  // face). Fails when the triangle's points are not the face's corners.
  static gs::Result<gs::SurfacePoint> OnFace(vtkGenericCell* triangle, double closest[3],
    int face, const std::array<int, 3>& corners, const std::function<int(vtkIdType)>& vertexOf);

  // A polyline of `points` (ids[0 .. n)) as a curve on the surface: each segment is sampled at
  // most CurveSampleSpacing mean edge lengths apart in space and every sample snapped
  // (consecutive duplicates dropped), so that consecutive surface points are close. Fails,
  // saying why, for an id out of range, non-finite coordinates or a point that cannot be
  // snapped. (Every filter's curve sources and strokes.)
  gs::Result<std::vector<gs::SurfacePoint>> SnapCurve(
    vtkPoints* points, vtkIdType n, const vtkIdType* ids);
  static constexpr double CurveSampleSpacing = 0.25;

  vtkSurfacePointLocator(const vtkSurfacePointLocator&) = delete;
  vtkSurfacePointLocator& operator=(const vtkSurfacePointLocator&) = delete;

private:
  const vtkSurfaceMeshConverter::Result& Mesh;
  vtkSmartPointer<vtkStaticCellLocator> Locator;
  vtkSmartPointer<vtkGenericCell> Cell; // scratch cell for the queries
  double Diagonal = 0.0;                 // of the mesh's bounding box
};

#endif
