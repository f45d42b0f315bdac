// Minimal readers and writers for the mesh formats the project uses outside VTK (benchmarks,
// data generation): OFF (libcgal-demo meshes) and ASCII PLY.
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
