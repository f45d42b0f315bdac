// A surface partitioned over "processes" that are threads of one test (the core's ThreadHub):
// the pieces of a whole mesh by a face partition, with the whole mesh's vertex and face numbers
// as global ids (the serial run the pieces must match).
#pragma once

#include "SurfacePiece.h"
#include "ThreadCommunicator.h"
#include "TriangleMesh.h"

#include <vector>

namespace gs_test
{

using gs::ThreadHub;

// The faces of `mesh` whose part is `rank`, with the mesh's own vertex and face numbers as ids.
inline gs::PieceTriangles PieceOf(
  const gs::TriangleMesh& mesh, const std::vector<int>& partOfFace, int rank)
{
  return gs::PieceOfMesh(mesh, partOfFace, rank);
}

// A partition of the faces into `parts` slabs along the direction (dx, dy, dz) of their
// centroids (equal face counts), then each slab's faces dealt in runs of `run` faces of the
// face order to the next part (run 0: none), which leaves pieces with holes and islands.
inline std::vector<int> PartitionFaces(
  const gs::TriangleMesh& mesh, int parts, const gs::Vec3& direction, int run = 0)
{
  std::vector<int> part = gs::SlabPartition(mesh, parts, direction);
  if (run > 0)
  {
    for (int f = 0; f < mesh.NumberOfFaces(); ++f)
    {
      if ((f / run) % 7 == 3)
      {
        part[static_cast<std::size_t>(f)] = (part[static_cast<std::size_t>(f)] + 1) % parts;
      }
    }
  }
  return part;
}

} // namespace gs_test
