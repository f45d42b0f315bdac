#include "OverlapCheck.h"

#include "GeodesicPolarCoordinates.h"
#include "GeodesicShooting.h"
#include "ParallelFor.h"
#include "PhasePoll.h"
#include "SafeDistanceTable.h"
#include "ShapeDistributor.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>

namespace gs
{
namespace
{
double SegmentDistance(const Vec2& a, const Vec2& b, const Vec2& p)
{
  const Vec2 ab = b - a;
  const double l2 = Dot(ab, ab);
  const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, Dot(p - a, ab) / l2)) : 0.0;
  const Vec2 d = a + ab * t - p;
  return std::sqrt(Dot(d, d)); // (not Norm: std::hypot is several times slower, and this is the hot loop)
}

// The cell of coordinate v on a grid of `count` cells of `size` covering [-halfWidth, halfWidth]
// (clamped to the grid).
int GridCell(double v, double halfWidth, double size, int count)
{
  const double c = std::floor((v + halfWidth) / size);
  return static_cast<int>(std::min(static_cast<double>(count - 1), std::max(0.0, c)));
}

// The centre of cell (x, y) of that grid.
Vec2 CellCentre(int x, int y, double halfWidth, double size)
{
  return Vec2{ -halfWidth + (x + 0.5) * size, -halfWidth + (y + 0.5) * size };
}

// Calls visit(y * count + x) for each cell (x, y) of that grid whose centre is within `reach` of
// the segment ab, row by row.
template <class Visit>
void ForEachCellNear(const Vec2& a, const Vec2& b, double reach, double halfWidth, double size, int count,
  Visit&& visit)
{
  const int x0 = GridCell(std::min(a.x, b.x) - reach, halfWidth, size, count);
  const int x1 = GridCell(std::max(a.x, b.x) + reach, halfWidth, size, count);
  const int y0 = GridCell(std::min(a.y, b.y) - reach, halfWidth, size, count);
  const int y1 = GridCell(std::max(a.y, b.y) + reach, halfWidth, size, count);
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      if (SegmentDistance(a, b, CellCentre(x, y, halfWidth, size)) <= reach)
      {
        visit(y * count + x);
      }
    }
  }
}
} // namespace

ClassRegion::ClassRegion(const std::vector<std::vector<Vec2>>& rings, double radius, double maximumDepth)
  : HalfWidth(radius * (1.0 + 1e-9))
{
  for (const auto& ring : rings)
  {
    for (std::size_t k = 0, n = ring.size(); k < n && n >= 3; ++k)
    {
      EdgeStart.push_back(ring[k]);
      EdgeEnd.push_back(ring[(k + 1) % n]);
    }
  }
  const double edges = static_cast<double>(EdgeStart.size());
  Cells = std::max(8, std::min(128, static_cast<int>(2.0 * std::sqrt(edges))));
  CellSize = 2.0 * HalfWidth / Cells;
  Rows.assign(Cells, {});
  Near.assign(static_cast<std::size_t>(Cells) * Cells, {});
  State.assign(static_cast<std::size_t>(Cells) * Cells, 0);
  const double reach = 0.5 * std::sqrt(2.0) * CellSize + std::max(0.0, maximumDepth);
  for (int e = 0; e < static_cast<int>(EdgeStart.size()); ++e)
  {
    const Vec2& a = EdgeStart[e];
    const Vec2& b = EdgeEnd[e];
    const int y0 = CellOf(std::min(a.y, b.y)), y1 = CellOf(std::max(a.y, b.y));
    for (int y = y0; y <= y1; ++y)
    {
      Rows[y].push_back(e);
    }
    ForEachCellNear(a, b, reach, HalfWidth, CellSize, Cells, [&](int c) { Near[c].push_back(e); });
  }
  for (int y = 0; y < Cells; ++y)
  {
    for (int x = 0; x < Cells; ++x)
    {
      const std::size_t c = static_cast<std::size_t>(y) * Cells + x;
      if (Near[c].empty())
      {
        State[c] = Inside(CellCentre(x, y, HalfWidth, CellSize)) ? 2 : 1;
      }
    }
  }
  BuildFineGrid();
}

void ClassRegion::BuildFineGrid()
{
  FineReachDepth = 0.005 * HalfWidth;
  FineCells = std::max(64, std::min(512, 8 * Cells));
  FineCellSize = 2.0 * HalfWidth / FineCells;
  const std::size_t cells = static_cast<std::size_t>(FineCells) * FineCells;
  // Every edge that can come within FineReachDepth of a point of the cell is within `reach` of
  // its centre (a hair more: rounding, and points that FineCellOf puts in the cell by a hair).
  const double reach = (0.5 * std::sqrt(2.0) * FineCellSize + FineReachDepth) * (1.0 + 1e-6) + 1e-6 * FineCellSize;
  std::vector<std::pair<int, int>> links; // (cell, edge)
  for (int e = 0; e < static_cast<int>(EdgeStart.size()); ++e)
  {
    ForEachCellNear(EdgeStart[e], EdgeEnd[e], reach, HalfWidth, FineCellSize, FineCells,
      [&](int c) { links.emplace_back(c, e); });
  }
  FineOffsets.assign(cells + 1, 0);
  for (const auto& l : links)
  {
    ++FineOffsets[l.first + 1];
  }
  for (std::size_t c = 0; c < cells; ++c)
  {
    FineOffsets[c + 1] += FineOffsets[c];
  }
  FineEdges.assign(links.size(), 0);
  {
    std::vector<int> fill(FineOffsets.begin(), FineOffsets.end() - 1);
    for (const auto& l : links) // (edges in increasing order within each cell, as Near)
    {
      FineEdges[fill[l.first]++] = l.second;
    }
  }
  // Pure cells take the inside-ness of their centre, row by row: Inside(centre) counts the
  // edges spanning the centre's y whose crossing lies beyond its x (the same expression).
  FineState.assign(cells, 0);
  std::vector<double> crossings;
  for (int y = 0; y < FineCells; ++y)
  {
    const double py = CellCentre(0, y, HalfWidth, FineCellSize).y;
    crossings.clear();
    for (int e : Rows[CellOf(py)])
    {
      const Vec2& a = EdgeStart[e];
      const Vec2& b = EdgeEnd[e];
      if ((a.y > py) != (b.y > py))
      {
        crossings.push_back(a.x + (b.x - a.x) * (py - a.y) / (b.y - a.y));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    std::size_t passed = 0; // crossings at or before the centre's x
    for (int x = 0; x < FineCells; ++x)
    {
      const double px = CellCentre(x, y, HalfWidth, FineCellSize).x;
      while (passed < crossings.size() && !(px < crossings[passed]))
      {
        ++passed;
      }
      const std::size_t c = static_cast<std::size_t>(y) * FineCells + x;
      if (FineOffsets[c] == FineOffsets[c + 1])
      {
        FineState[c] = (crossings.size() - passed) % 2 == 1 ? 2 : 1;
      }
    }
  }
}

int ClassRegion::FineCellOf(double v) const
{
  return GridCell(v, HalfWidth, FineCellSize, FineCells);
}

int ClassRegion::CellOf(double v) const
{
  return GridCell(v, HalfWidth, CellSize, Cells);
}

bool ClassRegion::Inside(const Vec2& p) const
{
  if (!(std::abs(p.x) < HalfWidth && std::abs(p.y) < HalfWidth))
  {
    return false;
  }
  bool in = false;
  for (int e : Rows[CellOf(p.y)])
  {
    const Vec2& a = EdgeStart[e];
    const Vec2& b = EdgeEnd[e];
    if ((a.y > p.y) != (b.y > p.y) && p.x < a.x + (b.x - a.x) * (p.y - a.y) / (b.y - a.y))
    {
      in = !in;
    }
  }
  return in;
}

bool ClassRegion::DeeplyInside(const Vec2& p, double depth) const
{
  if (!(std::abs(p.x) < HalfWidth && std::abs(p.y) < HalfWidth))
  {
    return false;
  }
  if (depth <= FineReachDepth)
  {
    const std::size_t c = static_cast<std::size_t>(FineCellOf(p.y)) * FineCells + FineCellOf(p.x);
    if (FineState[c] != 0)
    {
      return FineState[c] == 2;
    }
    for (int k = FineOffsets[c], end = FineOffsets[c + 1]; k < end; ++k)
    {
      const int e = FineEdges[k];
      if (SegmentDistance(EdgeStart[e], EdgeEnd[e], p) <= depth)
      {
        return false;
      }
    }
    return Inside(p);
  }
  const std::size_t c = static_cast<std::size_t>(CellOf(p.y)) * Cells + CellOf(p.x);
  if (State[c] != 0)
  {
    return State[c] == 2; // the whole cell is farther than the largest depth from the outline
  }
  for (int e : Near[c])
  {
    if (SegmentDistance(EdgeStart[e], EdgeEnd[e], p) <= depth)
    {
      return false;
    }
  }
  return Inside(p);
}

bool ClassRegion::Within(const Vec2& p, double distance) const
{
  if (!(std::abs(p.x) < HalfWidth + distance && std::abs(p.y) < HalfWidth + distance))
  {
    return false;
  }
  const bool inGrid = std::abs(p.x) < HalfWidth && std::abs(p.y) < HalfWidth;
  const std::size_t c = static_cast<std::size_t>(CellOf(p.y)) * Cells + CellOf(p.x);
  if (inGrid && State[c] != 0)
  {
    return State[c] == 2; // farther than the largest depth from the outline: inside or not
  }
  if (inGrid && Inside(p))
  {
    return true;
  }
  // Outside: an edge within `distance` (those near the cell; beyond the grid, all of them).
  if (inGrid)
  {
    for (int e : Near[c])
    {
      if (SegmentDistance(EdgeStart[e], EdgeEnd[e], p) <= distance)
      {
        return true;
      }
    }
    return false;
  }
  for (std::size_t e = 0; e < EdgeStart.size(); ++e)
  {
    if (SegmentDistance(EdgeStart[e], EdgeEnd[e], p) <= distance)
    {
      return true;
    }
  }
  return false;
}

bool OutlineEnters(const ClassRegion& region, const std::vector<OutlinePiece>& pieces,
  const std::function<bool(const SurfacePoint&, Vec2&)>& toClass, double depth,
  const TriangleMesh* mesh, double classPerWorld)
{
  const double step = depth; // samples along the outline
  std::vector<Vec2> local;
  std::vector<char> known;
  for (const OutlinePiece& piece : pieces)
  {
    const std::size_t m = piece.Points.size();
    local.assign(m, Vec2{ 0.0, 0.0 });
    known.assign(m, 0);
    for (std::size_t k = 0; k < m; ++k)
    {
      known[k] = toClass(piece.Points[k], local[k]) ? 1 : 0;
    }
    const std::size_t segments = piece.Closed ? m : (m > 0 ? m - 1 : 0);
    for (std::size_t k = 0; k < segments; ++k)
    {
      const std::size_t next = (k + 1) % m;
      if (!known[k] || !known[next])
      {
        // A point beyond the chart is farther than the circle: only the known end can be inside.
        if (known[k] && region.DeeplyInside(local[k], depth))
        {
          return true;
        }
        continue;
      }
      const Vec2 p = local[k], q = local[next];
      if (SegmentDistance(p, q, Vec2{ 0.0, 0.0 }) >= region.Radius())
      {
        continue;
      }
      if (mesh)
      {
        const double space = Norm(mesh->Position(piece.Points[next]) - mesh->Position(piece.Points[k]));
        if (Norm(q - p) > 3.0 * classPerWorld * space + 0.1 * region.Radius())
        {
          // A jump across the frame's cut locus: the ends only.
          if (region.DeeplyInside(p, depth) || region.DeeplyInside(q, depth))
          {
            return true;
          }
          continue;
        }
      }
      const Vec2 pq = q - p;
      const int n = std::max(1, std::min(100000, static_cast<int>(std::ceil(std::sqrt(Dot(pq, pq)) / step))));
      for (int j = 0; j < n; ++j)
      {
        if (region.DeeplyInside(p + (q - p) * (static_cast<double>(j) / n), depth))
        {
          return true;
        }
      }
    }
  }
  return false;
}

namespace
{
using CellKey = std::array<long long, 3>;
using CellGrid = std::vector<std::pair<CellKey, int>>;

// The cell of the candidate-pair grid (cubes of side `cell`) that holds x.
CellKey PairCellOf(const Vec3& x, double cell)
{
  return CellKey{ static_cast<long long>(std::floor(x.x / cell)),
    static_cast<long long>(std::floor(x.y / cell)), static_cast<long long>(std::floor(x.z / cell)) };
}

// The circumradius of every shape (world units); `largest` receives the largest of them.
std::vector<double> ShapeRadii(const std::vector<PlacedShape>& shapes,
  const SafeDistanceTables& tables, double size, double& largest)
{
  const int n = static_cast<int>(shapes.size());
  std::vector<double> radius(n);
  largest = 0.0;
  for (int s = 0; s < n; ++s)
  {
    radius[s] = tables.Classes[shapes[s].ClassId].Radius * size * shapes[s].Scale;
    largest = std::max(largest, radius[s]);
  }
  return radius;
}

// Every shape's (cell, index) on the candidate-pair grid, sorted: the shapes of a cell are
// found by binary search.
CellGrid SortedCellGrid(const std::vector<PlacedShape>& shapes, double cell)
{
  CellGrid grid;
  for (int s = 0; s < static_cast<int>(shapes.size()); ++s)
  {
    grid.emplace_back(PairCellOf(shapes[s].Position, cell), s);
  }
  std::sort(grid.begin(), grid.end());
  return grid;
}

// Long shapes: the inverse of their drawing map near them (`frames`), and the sorted vertices
// of that frame (`drawnOn`). A long shape is drawn on the faces whose corners are all among its
// frame's vertices (its decal's): a point elsewhere, though near the frame in space (another
// layer of the surface, geodesically far), is not in it.
void LoadLongShapeFrames(const ShapeDistributor& distributor, int threads,
  std::vector<std::shared_ptr<const CurveGrid>>& frames, std::vector<std::vector<int>>& drawnOn)
{
  const std::vector<PlacedShape>& shapes = distributor.Shapes();
  const int n = static_cast<int>(shapes.size());
  ParallelFor(n, threads, 8, [&](int s, int) {
    if (!shapes[s].Curve.empty())
    {
      frames[s] = distributor.Frame(s);
      if (frames[s])
      {
        for (const auto& vertexNode : frames[s]->Vertices())
        {
          drawnOn[s].push_back(vertexNode.first);
        }
        std::sort(drawnOn[s].begin(), drawnOn[s].end());
      }
    }
  });
}

// Each shape's neighbours, sorted: the shapes whose centres are closer in space than the sum of
// the circumradii (the geodesic distance is never shorter), from the cells around its own.
std::vector<std::vector<int>> FindNeighbours(const std::vector<PlacedShape>& shapes,
  const CellGrid& grid, const std::vector<double>& radius, double cell, int threads)
{
  const int n = static_cast<int>(shapes.size());
  std::vector<std::vector<int>> neighbours(n);
  ParallelFor(n, threads, 16, [&](int a, int) {
    const CellKey c = PairCellOf(shapes[a].Position, cell);
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz)
        {
          const CellKey q{ c[0] + dx, c[1] + dy, c[2] + dz };
          auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(q, 0));
          for (; it != grid.end() && it->first == q; ++it)
          {
            const int b = it->second;
            if (b != a && Norm(shapes[b].Position - shapes[a].Position) < radius[a] + radius[b])
            {
              neighbours[a].push_back(b);
            }
          }
        }
    std::sort(neighbours[a].begin(), neighbours[a].end());
  });
  return neighbours;
}

// Reads the drawn outline of one shape in the class frame of another, through the inverse of
// the map that draws the latter.
struct OutlineReader
{
  const ShapeDistributor& Distributor;
  const std::vector<PlacedShape>& Shapes;
  const std::vector<std::vector<OutlinePiece>>& Outlines;
  const std::vector<ClassRegion>& Regions;
  const std::vector<double>& Radius;
  const std::vector<std::shared_ptr<const CurveGrid>>& Frames;
  const std::vector<std::vector<int>>& DrawnOn;
  const TriangleMesh& Mesh;
  double Size; // the distribution's shape size (world units per class unit at scale 1)

  // Does the drawn outline of `b` reach deeper than `depth` (a's class units) into `a`'s
  // silhouette? (Points farther in space from a's centre than sqrt(2) times its circumradius
  // are outside it: a's outline is drawn along paths of length |along| + |across| at most.)
  // `exact`: a's exact log map, or null.
  bool Enters(int a, int b, double depth, const GeodesicPolarCoordinates* exact) const
  {
    const Vec3 centre = Shapes[a].Position;
    const double reach = 1.4143 * Radius[a] + Mesh.MeanEdgeLength();
    const TriangleMesh& mesh = Mesh;
    auto near = [&](const SurfacePoint& x) { return Norm(mesh.Position(x) - centre) <= reach; };
    if (!Shapes[a].Curve.empty())
    {
      return EntersLong(a, b, depth, near);
    }
    if (exact)
    {
      // a's exact log map (computed by the caller), in class units.
      const double inverse = 1.0 / (Size * Shapes[a].Scale);
      return OutlineEnters(Regions[Shapes[a].ClassId], Outlines[b],
        [exact, inverse, &near](const SurfacePoint& x, Vec2& p) {
          if (!near(x) || !exact->LogMapAt(x, p))
          {
            return false;
          }
          p = p * inverse;
          return true;
        },
        depth, &mesh, inverse);
    }
    // (The placement's reading: the exact log map the drawn check kept, or the chart; a jump
    // across the map's cut locus is tested at its ends only, as above.)
    const ShapeDistributor& distributor = Distributor;
    return OutlineEnters(Regions[Shapes[a].ClassId], Outlines[b],
      [&distributor, a, &near](const SurfacePoint& x, Vec2& p) { return near(x) && distributor.ClassPoint(a, x, p); },
      depth, &mesh, 1.0 / (Size * Shapes[a].Scale));
  }

  // Enters for a long shape `a`: read through its frame, on the faces it is drawn on.
  template <class Near>
  bool EntersLong(int a, int b, double depth, const Near& near) const
  {
    const CurveGrid& frame = *Frames[a];
    const std::vector<int>& vertices = DrawnOn[a];
    const TriangleMesh& mesh = Mesh;
    auto in = [&vertices, &mesh](const SurfacePoint& x) {
      auto has = [&vertices](int v) { return std::binary_search(vertices.begin(), vertices.end(), v); };
      if (x.IsVertex())
      {
        return has(x.Vertex);
      }
      const auto& c = mesh.Face(x.Face);
      return has(c[0]) && has(c[1]) && has(c[2]);
    };
    int hint = -1;
    return OutlineEnters(Regions[Shapes[a].ClassId], Outlines[b],
      [&frame, &near, &in, &hint](
        const SurfacePoint& x, Vec2& p) { return near(x) && in(x) && frame.ClassPoint(x, p, &hint); },
      depth);
  }
};

// Per shape a, the sorted neighbours whose outlines enter it (read in a's frame, computed
// once: short shapes through their exact log map when `options.ExactCharts` and it computes).
// Shapes that `poll` skips are left empty.
std::vector<std::vector<int>> FindEntering(const OutlineReader& reader,
  const std::vector<std::vector<int>>& neighbours, double spacing, double tolerance,
  const OverlapCheckOptions& options, int threads, PhasePoll& poll)
{
  const std::vector<PlacedShape>& shapes = reader.Shapes;
  const std::vector<double>& radius = reader.Radius;
  const TriangleMesh& mesh = reader.Mesh;
  const double size = reader.Size;
  const int n = static_cast<int>(shapes.size());
  std::vector<std::vector<int>> entering(n);
  ParallelForEachThread<std::unique_ptr<GeodesicPolarCoordinates>>(n, threads, 8,
    [&](int a, std::unique_ptr<GeodesicPolarCoordinates>& engine) {
      if (neighbours[a].empty() || poll.Skip(a))
      {
        return;
      }
      const GeodesicPolarCoordinates* exact = nullptr;
      if (options.ExactCharts && shapes[a].Curve.empty())
      {
        if (!engine)
        {
          engine.reset(new GeodesicPolarCoordinates(mesh));
        }
        // Every face that meets the circle (and an outline spacing beyond it) has its corners in
        // the map (ComputeCoveringDisc).
        const double reference = TangentAngle(mesh, shapes[a].Centre, shapes[a].Direction);
        if (std::isfinite(reference) &&
          engine->ComputeCoveringDisc(shapes[a].Centre, radius[a] + spacing, reference).Ok())
        {
          exact = engine.get();
        }
      }
      for (int b : neighbours[a])
      {
        const double depth = tolerance * std::min(radius[a], radius[b]);
        if (reader.Enters(a, b, depth / (size * shapes[a].Scale), exact))
        {
          entering[a].push_back(b);
        }
      }
    });
  return entering;
}

// The overlapping pairs (a < b: either outline enters the other shape) into `result`, with each
// shape's count of overlaps; returns the number of neighbouring pairs examined.
long long CollectOverlappingPairs(const std::vector<std::vector<int>>& neighbours,
  const std::vector<std::vector<int>>& entering, OverlapCheckResult& result)
{
  long long examined = 0;
  for (int a = 0; a < static_cast<int>(neighbours.size()); ++a)
  {
    for (int b : neighbours[a])
    {
      if (b < a)
      {
        continue;
      }
      ++examined;
      if (std::binary_search(entering[a].begin(), entering[a].end(), b) ||
        std::binary_search(entering[b].begin(), entering[b].end(), a))
      {
        result.Pairs.emplace_back(a, b);
        ++result.Overlaps[a];
        ++result.Overlaps[b];
      }
    }
  }
  return examined;
}
} // namespace

Result<OverlapCheckResult> CheckOverlaps(const ShapeDistributor& distributor,
  const std::vector<std::vector<OutlinePiece>>& outlines, const OverlapCheckOptions& options)
{
  const auto start = std::chrono::steady_clock::now();
  OverlapCheckResult result;
  const std::vector<PlacedShape>& shapes = distributor.Shapes();
  const SafeDistanceTables& tables = distributor.Tables();
  const double size = distributor.Options().ShapeSize;
  const int n = static_cast<int>(shapes.size());
  if (outlines.size() != shapes.size())
  {
    return Status::Error("the overlap check needs one outline per shape: " +
      std::to_string(outlines.size()) + " outline(s) for " + std::to_string(n) + " shape(s)");
  }
  result.Overlaps.assign(n, 0);
  if (n == 0)
  {
    return result;
  }
  const double tolerance = std::max(0.0, options.Tolerance);
  std::vector<ClassRegion> regions;
  for (const SafeDistanceClass& c : tables.Classes)
  {
    regions.emplace_back(c.Outline.Rings, c.Radius, tolerance * c.Radius);
  }
  // Circumradius of every shape (world units), and candidate pairs from a grid of cells as
  // wide as the largest circle diameter.
  double rmax = 0.0;
  const std::vector<double> radius = ShapeRadii(shapes, tables, size, rmax);
  const double cell = 2.0 * rmax;
  const CellGrid grid = SortedCellGrid(shapes, cell);
  std::vector<std::shared_ptr<const CurveGrid>> frames(n);
  std::vector<std::vector<int>> drawnOn(n);
  const int threads = ThreadCount(options.NumberOfThreads);
  LoadLongShapeFrames(distributor, threads, frames, drawnOn);
  const OutlineReader reader{ distributor, shapes, outlines, regions, radius, frames, drawnOn,
    distributor.Mesh(), size };
  const std::vector<std::vector<int>> neighbours = FindNeighbours(shapes, grid, radius, cell, threads);
  // Which neighbours' outlines enter each shape (read in its frame, computed once).
  PhasePoll poll(options.Progress, n);
  const std::vector<std::vector<int>> entering = FindEntering(
    reader, neighbours, distributor.OutlineSpacing(), tolerance, options, threads, poll);
  if (poll.WasAborted())
  {
    return Status::Aborted();
  }
  result.PairsExamined = CollectOverlappingPairs(neighbours, entering, result);
  result.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

} // namespace gs
