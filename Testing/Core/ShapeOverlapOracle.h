// An exact overlap test between two placed polygonal regions, written independently of the
// safe distance table code (Filters/Core/Shapes/SafeDistanceTable.cpp) to check it: used by
// TestSafeDistanceTable and Benchmarks/MSDTBenchmark.
//
// Regions are even-odd sets of closed rings, in coordinates relative to the shape's circle
// centre, or the part of such a region within a slab (PartOfRegion: a long shape's part).
// Interiors overlap iff two boundary edges cross properly, or a boundary piece of one region
// lies inside the other region (tested with one seed point per piece). Touching (common points
// only on the boundaries) is not an overlap.
#pragma once

#include "Vector.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gs_test
{
using gs::Vec2;

struct BoundarySegment
{
  Vec2 A, B;
};

/// A region's boundary as segments (a closed 1-cycle, any order) plus seed points: at least one
/// point on every connected piece of the boundary.
struct RegionBoundary
{
  std::vector<BoundarySegment> Segments;
  std::vector<Vec2> Seeds;
};

/// The part of the even-odd region `rings` where lo <= Dot(p, axis) <= hi (|bound| >= 1e299:
/// no cut on that side), written independently of the table code's StripBoundary: ring edges
/// clipped to the slab, plus the pieces of each cut line inside the region (crossings of the
/// line sorted along it and paired, even-odd), all with the region on their left when the rings
/// are oriented so (outer rings counter-clockwise, holes clockwise). Seeds: the first clipped edge of every run of
/// consecutive surviving edges of a ring, and every cut piece.
inline RegionBoundary PartOfRegion(
  const std::vector<std::vector<Vec2>>& rings, const Vec2& axis, double lo, double hi)
{
  RegionBoundary part;
  const Vec2 across{ -axis.y, axis.x };
  const bool cutLo = lo > -1e299, cutHi = hi < 1e299;
  auto at = [](const Vec2& a, const Vec2& b, double t) { return a + (b - a) * t; };
  for (const auto& ring : rings)
  {
    bool previousReachedEnd = false; // the previous edge survived up to its end point
    bool firstStartsAtStart = false;
    std::size_t firstSeed = part.Seeds.size();
    for (std::size_t k = 0, n = ring.size(); k < n; ++k)
    {
      const Vec2& a = ring[k];
      const Vec2& b = ring[(k + 1) % n];
      const double sa = gs::Dot(a, axis), sb = gs::Dot(b, axis);
      double t0 = 0.0, t1 = 1.0;
      if (sa == sb)
      {
        if (sa < lo || sa > hi)
          t1 = -1.0;
      }
      else
      {
        for (double bound : { lo, hi })
        {
          if (std::abs(bound) >= 1e299)
            continue;
          const double t = (bound - sa) / (sb - sa);
          // Keep the side of the bound inside the slab.
          const bool enteringAtT = (bound == lo) == (sb > sa);
          if (enteringAtT)
            t0 = std::max(t0, t);
          else
            t1 = std::min(t1, t);
        }
      }
      if (!(t0 < t1))
      {
        previousReachedEnd = false;
        continue;
      }
      const Vec2 p = at(a, b, t0), q = at(a, b, t1);
      part.Segments.push_back({ p, q });
      const bool startsAtStart = t0 == 0.0;
      if (k == 0)
        firstStartsAtStart = startsAtStart;
      if (!(startsAtStart && previousReachedEnd))
        part.Seeds.push_back((p + q) * 0.5); // a new run of surviving edges
      previousReachedEnd = t1 == 1.0;
    }
    // The run through the ring's first vertex was counted twice (its start and its end).
    if (previousReachedEnd && firstStartsAtStart && part.Seeds.size() > firstSeed + 1)
      part.Seeds.erase(part.Seeds.begin() + static_cast<std::ptrdiff_t>(firstSeed));
  }
  for (double bound : { lo, hi })
  {
    if (!((bound == lo && cutLo) || (bound == hi && cutHi)))
      continue;
    std::vector<double> along;
    for (const auto& ring : rings)
    {
      for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      {
        const Vec2& a = ring[k];
        const Vec2& b = ring[(k + 1) % n];
        const double sa = gs::Dot(a, axis), sb = gs::Dot(b, axis);
        if ((sa < bound) != (sb < bound))
          along.push_back(gs::Dot(at(a, b, (bound - sa) / (sb - sa)), across));
      }
    }
    std::sort(along.begin(), along.end());
    for (std::size_t k = 0; k + 1 < along.size(); k += 2)
    {
      // Oriented with the part on the left (as the rings are): -across on the lo line.
      const Vec2 p = axis * bound + across * along[k], q = axis * bound + across * along[k + 1];
      if (bound == lo)
        part.Segments.push_back({ q, p });
      else
        part.Segments.push_back({ p, q });
      part.Seeds.push_back((p + q) * 0.5);
    }
  }
  return part;
}

class OverlapOracle
{
public:
  /// `rings` relative to the circle centre; `radius`: the circle radius (all points within).
  OverlapOracle(std::vector<std::vector<Vec2>> rings, double radius)
    : Radius(radius)
  {
    for (const auto& ring : rings)
    {
      if (!ring.empty())
        this->Seeds.push_back(ring[0]);
      for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      {
        this->AddEdge(ring[k], ring[(k + 1) % n]);
      }
    }
    this->BuildGrid();
  }

  /// A region given by its boundary (e.g. PartOfRegion), relative to the circle centre.
  OverlapOracle(const RegionBoundary& boundary, double radius)
    : Seeds(boundary.Seeds), Radius(radius)
  {
    for (const BoundarySegment& s : boundary.Segments)
    {
      this->AddEdge(s.A, s.B);
    }
    this->BuildGrid();
  }

  /// The farthest boundary point from the centre (at most the radius for a valid circle).
  double GetReach() const { return this->Edges.empty() ? 0.0 : this->Edges.front().Reach; }

private:
  void AddEdge(const Vec2& a, const Vec2& b)
  {
    Edge e{ a, b, std::max(gs::Norm(a), gs::Norm(b)) };
    this->Edges.push_back(e);
  }

  void BuildGrid()
  {
    const double radius = this->Radius;
    std::sort(this->Edges.begin(), this->Edges.end(),
      [](const Edge& x, const Edge& y) { return x.Reach > y.Reach; });
    // Uniform grid over [-R, R]^2 holding the edges by bounding box.
    this->Cells = std::max(8, std::min(256, static_cast<int>(std::sqrt(this->Edges.size()) * 2)));
    this->CellSize = 2.0 * radius * (1.0 + 1e-9) / this->Cells;
    this->Grid.assign(static_cast<std::size_t>(this->Cells) * this->Cells, {});
    for (std::size_t k = 0; k < this->Edges.size(); ++k)
    {
      const Edge& e = this->Edges[k];
      int x0, y0, x1, y1;
      this->CellRange(e.A, e.B, x0, y0, x1, y1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
          this->Grid[static_cast<std::size_t>(y) * this->Cells + x].push_back(static_cast<int>(k));
    }
  }

public:
  double GetRadius() const { return this->Radius; }

  /// Does A (this, centre at the origin, rotated by alphaA) overlap B (centre at (d, 0),
  /// rotated by alphaB)?
  bool Overlaps(double alphaA, const OverlapOracle& B, double alphaB, double d) const
  {
    if (d >= this->Radius + B.Radius)
      return false;
    // B's local coordinates -> A's local coordinates: p -> R(-alphaA) (R(alphaB) p + (d, 0)).
    const double rel = alphaB - alphaA;
    const double c = std::cos(rel), s = std::sin(rel);
    const Vec2 t{ d * std::cos(-alphaA), d * std::sin(-alphaA) };
    auto toA = [&](const Vec2& p) { return Vec2{ c * p.x - s * p.y + t.x, s * p.x + c * p.y + t.y }; };
    const double minReach = d - this->Radius; // B edges closer to B's centre cannot reach A
    for (const Edge& e : B.Edges)
    {
      if (e.Reach < minReach)
        break;
      const Vec2 a = toA(e.A), b = toA(e.B);
      if (SegmentPointDistance(a, b, Vec2{ 0.0, 0.0 }) > this->Radius)
        continue;
      if (this->Crosses(a, b))
        return true;
    }
    // No crossing: each boundary piece is entirely inside or outside the other region, so one
    // seed point per piece decides.
    for (const Vec2& seed : B.Seeds)
    {
      const Vec2 p = toA(seed);
      if (gs::Norm(p) <= this->Radius && this->Contains(p))
        return true;
    }
    // A's seeds in B's frame: q -> R(-alphaB) (R(alphaA) q - (d, 0)) = R(-rel) (q - t).
    for (const Vec2& seed : this->Seeds)
    {
      const Vec2 q = seed - t;
      const Vec2 p{ c * q.x + s * q.y, -s * q.x + c * q.y };
      if (gs::Norm(p) <= B.Radius && B.Contains(p))
        return true;
    }
    return false;
  }

  /// Does this region (local coordinates) overlap the even-odd region bounded by `rings`, given
  /// in the same local coordinates (any shape, e.g. another region mapped through a chart)?
  /// Proper boundary crossings, or a boundary piece of one inside the other.
  bool OverlapsRings(const std::vector<std::vector<Vec2>>& rings) const
  {
    for (const auto& ring : rings)
    {
      for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      {
        const Vec2& a = ring[k];
        const Vec2& b = ring[(k + 1) % n];
        if (SegmentPointDistance(a, b, Vec2{ 0.0, 0.0 }) > this->Radius)
          continue;
        if (this->Crosses(a, b))
          return true;
      }
    }
    for (const auto& ring : rings)
    {
      if (!ring.empty() && gs::Norm(ring[0]) <= this->Radius && this->Contains(ring[0]))
        return true;
    }
    for (const Vec2& seed : this->Seeds)
    {
      bool inside = false;
      for (const auto& ring : rings)
      {
        for (std::size_t k = 0, n = ring.size(); k < n; ++k)
        {
          const Vec2& a = ring[k];
          const Vec2& b = ring[(k + 1) % n];
          if ((a.y > seed.y) != (b.y > seed.y) &&
            a.x + (seed.y - a.y) / (b.y - a.y) * (b.x - a.x) > seed.x)
            inside = !inside;
        }
      }
      if (inside)
        return true;
    }
    return false;
  }

  /// Even-odd point-in-region test (local coordinates).
  bool Contains(const Vec2& p) const
  {
    bool inside = false;
    for (const Edge& e : this->Edges)
    {
      if ((e.A.y > p.y) != (e.B.y > p.y))
      {
        const double x = e.A.x + (p.y - e.A.y) / (e.B.y - e.A.y) * (e.B.x - e.A.x);
        if (x > p.x)
          inside = !inside;
      }
    }
    return inside;
  }

private:
  struct Edge
  {
    Vec2 A, B;
    double Reach; // farthest distance from the centre
  };

  static double Orient(const Vec2& a, const Vec2& b, const Vec2& c) { return gs::Cross(b - a, c - a); }

  static double SegmentPointDistance(const Vec2& a, const Vec2& b, const Vec2& p)
  {
    const Vec2 ab = b - a;
    const double l2 = gs::Dot(ab, ab);
    double t = l2 > 0 ? gs::Dot(p - a, ab) / l2 : 0.0;
    t = std::min(1.0, std::max(0.0, t));
    return gs::Norm(a + ab * t - p);
  }

  void CellRange(const Vec2& a, const Vec2& b, int& x0, int& y0, int& x1, int& y1) const
  {
    const double o = -this->Radius * (1.0 + 1e-9);
    auto cell = [&](double v) {
      return std::min(this->Cells - 1, std::max(0, static_cast<int>(std::floor((v - o) / this->CellSize))));
    };
    x0 = cell(std::min(a.x, b.x));
    x1 = cell(std::max(a.x, b.x));
    y0 = cell(std::min(a.y, b.y));
    y1 = cell(std::max(a.y, b.y));
  }

  // Proper crossing of segment ab with any edge (strict orientation signs on both sides).
  bool Crosses(const Vec2& a, const Vec2& b) const
  {
    int x0, y0, x1, y1;
    this->CellRange(a, b, x0, y0, x1, y1);
    for (int y = y0; y <= y1; ++y)
    {
      for (int x = x0; x <= x1; ++x)
      {
        for (int k : this->Grid[static_cast<std::size_t>(y) * this->Cells + x])
        {
          const Edge& e = this->Edges[k];
          const double o1 = Orient(a, b, e.A), o2 = Orient(a, b, e.B);
          if ((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0))
          {
            const double o3 = Orient(e.A, e.B, a), o4 = Orient(e.A, e.B, b);
            if ((o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0))
              return true;
          }
        }
      }
    }
    return false;
  }

  std::vector<Vec2> Seeds; // at least one point on every boundary piece
  double Radius;
  std::vector<Edge> Edges;
  int Cells = 8;
  double CellSize = 1.0;
  std::vector<std::vector<int>> Grid;
};

} // namespace gs_test
