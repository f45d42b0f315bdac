// An exact overlap test between two placed polygonal regions, written independently of the
// safe distance table code (Filters/Core/SafeDistanceTable.cpp) to check it: used by
// TestSafeDistanceTable and Benchmarks/MSDTBenchmark.
//
// Regions are even-odd sets of closed rings, in coordinates relative to the shape's circle
// centre. Interiors overlap iff two boundary edges cross properly, or a ring of one region lies
// inside the other region. Touching (common points only on the boundaries) is not an overlap.
#pragma once

#include "Vector.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace gs_test
{
using gs::Vec2;

class OverlapOracle
{
public:
  /// `rings` relative to the circle centre; `radius`: the circle radius (all points within).
  OverlapOracle(std::vector<std::vector<Vec2>> rings, double radius)
    : Rings(std::move(rings)), Radius(radius)
  {
    for (const auto& ring : this->Rings)
    {
      for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      {
        Edge e{ ring[k], ring[(k + 1) % n], 0.0 };
        e.Reach = std::max(gs::Norm(e.A), gs::Norm(e.B));
        this->Edges.push_back(e);
      }
    }
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
    // No crossing: each ring is entirely inside or outside the other region.
    for (const auto& ring : B.Rings)
    {
      bool outsideCircle = false;
      for (const Vec2& p : ring)
      {
        if (gs::Norm(toA(p)) > this->Radius)
        {
          outsideCircle = true;
          break;
        }
      }
      if (!outsideCircle && this->Contains(toA(ring[0])))
        return true;
    }
    // A's rings in B's frame: q -> R(-alphaB) (R(alphaA) q - (d, 0)) = R(-rel) (q - t).
    for (const auto& ring : this->Rings)
    {
      bool outsideCircle = false;
      Vec2 first;
      for (std::size_t k = 0; k < ring.size(); ++k)
      {
        const Vec2 q = ring[k] - t;
        const Vec2 p{ c * q.x + s * q.y, -s * q.x + c * q.y };
        if (k == 0)
          first = p;
        if (gs::Norm(p) > B.Radius)
        {
          outsideCircle = true;
          break;
        }
      }
      if (!outsideCircle && B.Contains(first))
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

  std::vector<std::vector<Vec2>> Rings;
  double Radius;
  std::vector<Edge> Edges;
  int Cells = 8;
  double CellSize = 1.0;
  std::vector<std::vector<int>> Grid;
};

} // namespace gs_test
