// An overlap check of a finished distribution that does not use the safe distance tables: the
// shapes are judged by their outlines as drawn on the surface (ShapeDistributor::Outline, each
// outline point the end of a geodesic shot from its own shape's centre or curve).
//
// For every pair of shapes whose centres are closer in space than the sum of their
// circumradii (the geodesic distance is never shorter), the drawn outline of one shape B is
// carried into the class frame of the other, A, through the inverse of the map that draws A (a
// short shape: the exact log map of its centre, unless OverlapCheckOptions::ExactCharts is off;
// a long shape: its drawing
// map along its curve sampled on a grid and inverted, ShapeDistributor::Frame), and sampled
// along its polyline every Tolerance; the pair overlaps when a sample lies inside A's
// silhouette deeper than Tolerance (distance to A's class outline), or the same with A and B
// exchanged. Crossing outlines, one shape inside the other and slivers of any length thicker
// than about 2 Tolerance are found; shapes that touch are not overlaps. Every pair is checked,
// long or short.
#pragma once

#include "ShapeOutline.h"
#include "Status.h"
#include "TriangleMesh.h"
#include "Vector.h"

#include <functional>
#include <utility>
#include <vector>

namespace gs
{

class ShapeDistributor;
struct SafeDistanceTables;

struct OverlapCheckOptions
{
  /// Depth that counts as an overlap, relative to the smaller circumradius of the pair.
  double Tolerance = 0.005;
  int NumberOfThreads = 0; ///< 0: all
  /// Short shapes are read through the exact geodesic polar coordinates of their centres (the
  /// exact solver truncated a longest edge beyond the circumradius: the inverse of the geodesic
  /// shots that draw the outline), not through the distributor's charts (computed on its
  /// geodesic graph, whose departure angles can be off by degrees behind saddles): the check
  /// then shares nothing with the placement but the drawn outlines. False: what the placement's
  /// own drawn check read (ShapeDistributor::ClassPoint: the exact log maps it kept with
  /// DrawnCheck, the distributor's charts without).
  bool ExactCharts = true;
  /// Optional: sees the fraction of shapes checked (from the calling thread, at most every
  /// 0.1 s); returning false aborts the check (CheckOverlaps returns Status::Aborted()).
  std::function<bool(double)> Progress;
};

struct OverlapCheckResult
{
  std::vector<std::pair<int, int>> Pairs; ///< overlapping shapes (first < second), sorted
  std::vector<int> Overlaps;              ///< per shape: the number of shapes it overlaps
  long long PairsExamined = 0;            ///< pairs closer than their circumradii
  double Seconds = 0.0;
};

class ClassRegion;

/// Does the drawn outline `pieces` reach deeper than `depth` (class units) into `region`?
/// `toClass` carries a surface point into the region's class frame (false: beyond the frame's
/// chart, so farther than its circle). The outline is sampled along its polyline every `depth`.
/// With `mesh`, a segment between consecutive outline points whose class-frame length exceeds
/// 3 times their distance in space (times `classPerWorld`, the frame's class units per world
/// unit) plus a tenth of the circumradius jumps across the frame's cut locus (the map is not
/// continuous there): only its ends are tested, not the straight line between them.
bool OutlineEnters(const ClassRegion& region, const std::vector<OutlinePiece>& pieces,
  const std::function<bool(const SurfacePoint&, Vec2&)>& toClass, double depth,
  const TriangleMesh* mesh = nullptr, double classPerWorld = 0.0);

/// Checks the shapes of `distributor` (after its Run) against their drawn outlines
/// (`outlines[s]`: ShapeDistributor::Outline of shape s). Deterministic: the same pairs whatever
/// the number of threads. Fails when `outlines` does not hold one entry per shape.
Result<OverlapCheckResult> CheckOverlaps(const ShapeDistributor& distributor,
  const std::vector<std::vector<OutlinePiece>>& outlines, const OverlapCheckOptions& options = {});

/// A class silhouette (even-odd rings, normalized class frame) with a grid for point queries.
class ClassRegion
{
public:
  /// `radius`: every ring point lies within it; `maximumDepth`: the largest depth that
  /// DeeplyInside will be asked for (cells farther than that from the outline answer at once).
  /// Depths up to FineDepth() (the drawn check's and VerifyOverlaps') are answered on a finer
  /// grid whose cells are pure unless within that depth of the outline: the same answers.
  ClassRegion(const std::vector<std::vector<Vec2>>& rings, double radius, double maximumDepth);
  /// Inside the region, and farther than `depth` (<= maximumDepth) from its outline.
  bool DeeplyInside(const Vec2& p, double depth) const;
  /// Even-odd point-in-region test.
  bool Inside(const Vec2& p) const;
  /// Inside the region dilated by `distance` (0 <= distance <= maximumDepth): inside, or within
  /// `distance` of its outline.
  bool Within(const Vec2& p, double distance) const;
  double Radius() const { return HalfWidth; }
  /// The largest depth that the fine grid answers (0.005 radius).
  double FineDepth() const { return FineReachDepth; }

private:
  int CellOf(double v) const;
  int FineCellOf(double v) const;
  void BuildFineGrid();
  double HalfWidth = 0.0; // the grid covers [-HalfWidth, HalfWidth]^2 (radius, a hair more)
  double CellSize = 1.0;
  int Cells = 1;
  std::vector<Vec2> EdgeStart, EdgeEnd;   // the rings' edges
  std::vector<std::vector<int>> Rows;     // per row of cells: edges spanning it in y
  std::vector<std::vector<int>> Near;     // per cell: edges within the cell's reach
  std::vector<char> State;                // per cell: 0 mixed, 1 all outside, 2 all deep inside
  // The fine grid (FineCells^2 cells): per cell, the edges within its reach for depths up to
  // FineReachDepth (CSR) and its state, as above. Most drawn-check samples fall in pure cells
  // there, where the coarse grid (whose reach is the largest clearance) leaves them mixed.
  double FineReachDepth = 0.0;
  double FineCellSize = 1.0;
  int FineCells = 1;
  std::vector<int> FineOffsets, FineEdges;
  std::vector<char> FineState;
};

} // namespace gs
