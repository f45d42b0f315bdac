// Minimal readers and writers for the mesh formats the project uses outside VTK (benchmarks,
// data generation): OFF (libcgal-demo meshes) and ASCII PLY.
//
// Why a reader of our own next to VTK's (vtkPLYReader, ParaView's OFF reader): the core
// (GeodesicShapesCore) and everything linked only to it stay free of VTK. It lives in the
// test-support library (GeodesicShapesTestSupport), which the plugin does not link. The core unit tests
// (GeodesicShapesCoreTests: TestOverlapCheck reads Data/bumpy_sphere.ply), the benchmarks
// (Benchmarks/*: the CGAL OFF meshes, refined_elephant.off) and Tools/generate_data (writes the
// bundled PLY files) build and run without ParaView. The filters read meshes with VTK; VTK tests
// use this reader only to compare with the core on the very same triangles
// (Testing/Cxx/FilterTestSupport.h). Keep it as small as the formats these files use.
#pragma once

#include "MeshGenerators.h"

#include <string>

namespace gs
{

// Reads an OFF file (triangles; larger polygons are fan-triangulated). Returns false and sets
// error on failure.
bool ReadOFF(const std::string& path, TriangleSoup& soup, std::string& error);
// Reads an ASCII or binary little-endian PLY file (vertex x y z, face vertex_indices).
bool ReadPLY(const std::string& path, TriangleSoup& soup, std::string& error);
// Reads by extension (.off or .ply).
bool ReadMesh(const std::string& path, TriangleSoup& soup, std::string& error);
// Writes ASCII PLY.
bool WritePLY(const std::string& path, const TriangleSoup& soup, std::string& error);

} // namespace gs
