// A long shape's drawing map sampled on a grid and inverted near the shape (code in
// ShapeMap.cpp, with the maps of placed shapes).
#pragma once

#include "SurfacePoint.h"
#include "TriangleMesh.h"
#include "Vector.h"

#include <array>
#include <utility>
#include <vector>

namespace gs
{

/// A long shape's drawing map (arc length along its curve, then across along the perpendicular
/// geodesic) sampled on a grid of (along, across) nodes, and its inverse near the shape.
struct CurveGrid
{
  struct Node
  {
    bool Valid = false;
    SurfacePoint At;
    Vec3 Position;
    Vec2 ClassPoint; ///< normalized units
  };
  const TriangleMesh* Mesh = nullptr;
  int Columns = 0, Rows = 0;
  double Step = 0.0; ///< the larger grid spacing (world units)
  std::vector<Node> Nodes; ///< column-major: node (i, j) is Nodes[i * Rows + j]

  /// The class point of position X, the nearest node searched from node `start` by descent
  /// over the grid: the affine map of the grid triangle nearest X (extended beyond the grid's
  /// border). `distance` (optional): X's distance to that triangle. False without valid nodes.
  bool Locate(const Vec3& X, int start, Vec2& p, double* distance, int* nearest = nullptr) const;
  /// Indexes the nodes by position (needed by ClassPoint).
  void Index();
  /// The class point of a surface point near the shape; false when it lies farther than half a
  /// grid step from the grid (beyond the shape and its margin, or on another sheet nearby).
  /// `hint` (optional, in and out): a node to start from (the previous point's, for points
  /// along a curve); -1: none.
  bool ClassPoint(const SurfacePoint& x, Vec2& p, int* hint = nullptr) const;
  /// The vertices the shape is drawn on (its decal's faces have all three corners among them),
  /// each once with a node near it: the corners of the faces holding nodes (with that node,
  /// nodes in order), then their neighbours (with the node of the corner reaching them first).
  std::vector<std::pair<int, int>> Vertices() const;

private:
  // Valid nodes by cells of twice the grid step over the nodes' bounding box.
  double CellSize = 1.0;
  Vec3 Origin;
  std::array<int, 3> Dims{ { 0, 0, 0 } };
  std::vector<int> CellStart, CellNodes;
};

} // namespace gs
