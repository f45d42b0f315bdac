// Global ids for the pieces of a partitioned surface that carry none, as the gathered surface
// numbers them: the pieces' points put one after another in rank order (every point of every
// piece, as gathering to one process does), exactly coincident points welded to the one the
// triangles, taken in the same order, use first (TriangleMesh's welding). A point's id is the
// index in that list of the point it welds to; a triangle's, its index among the triangles. So a
// computation on pieces numbered so (SurfacePiece) visits the vertices in the order a serial run
// on the gathered surface does, and serial point ids (SourceVertexIds) keep their meaning.
//
// Coincident points are found without gathering: each process sends each of its distinct
// positions to the process a hash of the position names, which answers with the winner.
#pragma once

#include "PieceCommunicator.h"
#include "Status.h"
#include "Vector.h"

#include <array>
#include <cstdint>
#include <vector>

namespace gs
{

struct GatheredNumbering
{
  // Per point of the piece: its id (-1 when no triangle uses it).
  std::vector<std::int64_t> PointIds;
  // Per triangle of the piece: its id.
  std::vector<std::int64_t> TriangleIds;
  // The gathered index of the piece's first point, and the gathered list's length.
  std::int64_t FirstPoint = 0;
  std::int64_t TotalPoints = 0;
};

// Collective. Numbers this process's `points` and `triangles` (indices into `points`); fails on
// every process when a triangle of any process uses a point that does not exist.
Status NumberAsGathered(const std::vector<Vec3>& points,
  const std::vector<std::array<int, 3>>& triangles, PieceCommunicator& comm,
  GatheredNumbering& numbering);

// Collective. The id of the point of gathered index `index` (the same on every process), from
// each process's point ids and first point (GatheredNumbering's): -1 when no triangle uses it or
// when it is no point of any piece.
std::int64_t GatheredPointId(const std::vector<std::int64_t>& pointIds, std::int64_t firstPoint,
  std::int64_t index, PieceCommunicator& comm);

} // namespace gs
