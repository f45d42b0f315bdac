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

#include "TriangleMesh.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <memory>

#include <string>
#include <vector>

class vtkObject;
class vtkPolyData;

class vtkSurfaceMeshConverter
{
public:
  struct Result
  {
    bool Ok = false;
    std::string Error;                 // why the input was rejected (empty when Ok)
    std::vector<std::string> Warnings; // triangulation, re-oriented faces, ...
    // The mesh to output: the input (shallow copy) or its triangulation, same point ids.
    vtkSmartPointer<vtkPolyData> Surface;
    // Only the triangles of Surface, cell i = core face i (for vtkStaticCellLocator).
    vtkSmartPointer<vtkPolyData> Triangles;
    // The core mesh plus the maps input point <-> mesh vertex.
    gs::MeshBuildResult Build;
  };

  // Converts `input`; never throws on bad input (Result::Ok false, Result::Error set).
  static Result Convert(vtkPolyData* input);

  // A conversion kept while its input is unchanged (same object, same modification time). Each
  // filter's cache derives from it and adds what the filter builds on the mesh.
  struct Cached
  {
    vtkPolyData* Input = nullptr;
    vtkMTimeType InputTime = 0;
    Result Mesh;
  };

  // The cache for `input` as it is now: the kept one, or a new conversion (a new C, so that
  // everything derived from the old mesh is dropped with it).
  template <class C>
  static C& Update(std::unique_ptr<C>& cache, vtkPolyData* input)
  {
    if (!cache || !IsCurrent(*cache, input))
    {
      cache.reset(new C);
      cache->Input = input;
      cache->InputTime = InputTime(input);
      cache->Mesh = Convert(input);
    }
    return *cache;
  }

  // Emits the conversion's warnings and, if it failed, its error through `algorithm` (as
  // vtkWarningMacro / vtkErrorMacro would); true when the mesh is usable.
  static bool Report(const Result& result, vtkObject* algorithm);

private:
  static bool IsCurrent(const Cached& cache, vtkPolyData* input);
  static vtkMTimeType InputTime(vtkPolyData* input);
};

#endif
