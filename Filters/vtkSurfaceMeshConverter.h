// vtkSurfaceMeshConverter: vtkPolyData -> gs::TriangleMesh, done once per pipeline update.
//
// Not a vtkObject and not wrapped (a private class of the GeodesicShapes::Filters module). It
//  - triangulates polygons with more than three points and triangle strips (vtkTriangleFilter,
//    vertices and lines dropped) and says so in Warnings; otherwise lines and vertices are ignored;
//  - hands the points and triangles to gs::TriangleMeshBuilder, which welds exactly coincident
//    points and rejects empty, non-finite, degenerate, duplicate and non-manifold input;
//  - keeps the polydata the filters output (the input itself, or its triangulation) and a
//    triangles-only polydata whose cell i is core face i, for point location.
#ifndef vtkSurfaceMeshConverter_h
#define vtkSurfaceMeshConverter_h

#include "Status.h"
#include "TriangleMesh.h"

#include <vtkPolyData.h> // Update() reads its modification times
#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <cstdint>
#include <memory>

#include <string>
#include <vector>

class vtkDataArray;
class vtkObject;

class vtkSurfaceMeshConverter
{
public:
  struct Result
  {
    // Ok, or why the input was rejected (then only Warnings may hold something).
    gs::Status Status = gs::Status::Error("not converted");
    std::vector<std::string> Warnings; // triangulation, re-oriented faces, ...
    // The mesh to output: the input (shallow copy) or its triangulation, same point ids.
    vtkSmartPointer<vtkPolyData> Surface;
    // Only the triangles of Surface, cell i = core face i (for vtkStaticCellLocator).
    vtkSmartPointer<vtkPolyData> Triangles;
    // The core mesh plus the maps input point <-> mesh vertex.
    gs::MeshBuild Build;
    // Surface is the input's triangulation (not a shallow copy of the input).
    bool Triangulated = false;
  };

  // Converts `input`; never throws on bad input (Result::Status says why it is rejected).
  static Result Convert(vtkPolyData* input);

  // A point array of a converted Surface read onto the mesh's vertices: values[v * components +
  // c] (components of `a`), `fill` where no point maps to v; of points welded into one vertex,
  // the last one's tuple.
  static std::vector<double> PointArrayOnVertices(
    vtkDataArray* a, const gs::MeshBuild& build, double fill);

  // A conversion kept while its input's points and cells are unchanged (same object, same
  // modification times); when only its arrays changed, Surface takes the new ones (a
  // triangulated input is converted again). Each filter's cache derives from it and adds what
  // the filter builds on the mesh (from points and cells only).
  struct Cached
  {
    vtkPolyData* Input = nullptr;
    vtkMTimeType GeometryTime = 0;
    vtkMTimeType AttributeTime = 0;
    vtkMTimeType ObjectTime = 0;    // the data object's own (Modified() after editing in place)
    std::uint64_t ContentHash = 0;  // of the points and cells, checked when ObjectTime moved
    Result Mesh;
  };

  // The cache for `input` as it is now: the kept one, or a new conversion (a new C, so that
  // everything derived from the old mesh is dropped with it).
  template <class C>
  static C& Update(std::unique_ptr<C>& cache, vtkPolyData* input)
  {
    bool same = cache && cache->Input == input && input && cache->GeometryTime == GeometryTime(input);
    if (same && cache->ObjectTime != input->vtkObject::GetMTime())
    {
      // Modified as a whole (an upstream filter ran again, or points edited in place): the
      // same mesh when its points and cells hash the same.
      same = cache->ContentHash == ContentHash(input);
      cache->ObjectTime = input->vtkObject::GetMTime();
    }
    if (same && cache->AttributeTime != AttributeTime(input) && !cache->Mesh.Triangulated)
    {
      TakeAttributes(cache->Mesh, input);
      cache->AttributeTime = AttributeTime(input);
    }
    else if (!same || cache->AttributeTime != AttributeTime(input))
    {
      cache.reset(new C);
      cache->Input = input;
      cache->Mesh = Convert(input);
      // (After the conversion: reading the input may build its cells, which modifies it.)
      cache->GeometryTime = GeometryTime(input);
      cache->AttributeTime = AttributeTime(input);
      cache->ObjectTime = input ? input->vtkObject::GetMTime() : 0;
      cache->ContentHash = ContentHash(input);
    }
    return *cache;
  }

  // Emits the conversion's warnings and, if it failed, its error through `algorithm` (as
  // vtkWarningMacro / vtkErrorMacro would); true when the mesh is usable.
  static bool Report(const Result& result, vtkObject* algorithm);

private:
  // Modification times of the points and cells, and of the point, cell and field data. (Not
  // the data object's own time, which includes its information, touched by pipeline requests.)
  static vtkMTimeType GeometryTime(vtkPolyData* input);
  static vtkMTimeType AttributeTime(vtkPolyData* input);
  static void TakeAttributes(Result& mesh, vtkPolyData* input);
  static std::uint64_t ContentHash(vtkPolyData* input);
};

#endif
