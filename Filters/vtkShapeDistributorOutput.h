// vtkShapeDistributorOutput: Shape Distributor's three outputs written from the core's result
// (Placements, Decals, Outlines) and VerifyOverlaps' arrays.
//
// Not a vtkObject and not wrapped (a private class of the GeodesicShapes::Filters module).
// Decals and outlines are written straight into arrays sized beforehand (per shape, its first
// cell and point), in parallel over the shapes, lifted `lift` off the surface.
#ifndef vtkShapeDistributorOutput_h
#define vtkShapeDistributorOutput_h

#include "OverlapCheck.h"
#include "ShapeDecal.h"
#include "ShapeDistributor.h"
#include "ShapeDrawing.h"

#include <vtkType.h>

#include <string>
#include <vector>

class vtkPolyData;

namespace vtkShapeDistributorOutput
{
// Fills Placements: one vertex per shape with its class, scale, direction, normal and face (the
// input's cell id), and the run's statistics as field data.
void WritePlacements(const gs::ShapeDistribution& result, vtkIdType firstPolygon, double shapeSize,
  const std::string& directionChoice, vtkPolyData* placements);

// VerifyOverlaps' result on Placements: Overlaps per shape, OverlappingPairs, OverlapCheckSeconds.
void WriteOverlaps(const gs::OverlapCheckResult& found, int ns, vtkPolyData* placements);

// Decals: the triangles of every shape's decal with their texture coordinates; cell arrays
// ShapeId and ClassId.
void WriteDecals(const gs::TriangleMesh& mesh, const std::vector<gs::PlacedShape>& shapes,
  const std::vector<gs::ShapeDecal>& decalOf, double lift, int threads, vtkPolyData* decals);

// Outlines: one polyline per outline piece (closed pieces repeat their first point); cell
// arrays ShapeId and ClassId.
void WriteOutlines(const gs::TriangleMesh& mesh, const std::vector<gs::PlacedShape>& shapes,
  const std::vector<std::vector<gs::OutlinePiece>>& outlineOf, double lift, int threads,
  vtkPolyData* outlines);
} // namespace vtkShapeDistributorOutput

#endif
