// Independent checks of shape distributions (used by TestShapeDistributor and the distributor
// benchmark): no safe distance table, no polar chart.
//
// Planar meshes: every placed shape is its class outline (the tables' normalized outline, times
// ShapeSize * Scale), rigidly placed at its centre and turned by its direction (a long shape on
// a constant field lies along a straight streamline: also rigid). Two shapes overlap when their
// regions' interiors intersect (ShapeOverlapOracle.h: exact crossing and containment tests).
#pragma once

#include "SafeDistanceTable.h"
#include "ShapeDistributor.h"
#include "ShapeOverlapOracle.h"
#include "TriangleMesh.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace gs_test
{

/// Number of overlapping pairs among shapes placed on a planar mesh (any plane orientation).
inline int CountPlanarOverlaps(const gs::TriangleMesh& mesh, const gs::SafeDistanceTables& tables,
  const std::vector<gs::PlacedShape>& shapes, double shapeSize, int* pairsChecked = nullptr)
{
  std::vector<std::unique_ptr<OverlapOracle>> oracles;
  std::vector<double> radius;
  for (const gs::PlacedShape& s : shapes)
  {
    const double k = shapeSize * s.Scale;
    std::vector<std::vector<gs::Vec2>> rings = tables.Classes[s.ClassId].Outline.Rings;
    for (auto& ring : rings)
      for (gs::Vec2& p : ring)
        p = p * k;
    radius.push_back(tables.Classes[s.ClassId].Radius * k * (1.0 + 1e-9));
    oracles.emplace_back(new OverlapOracle(rings, radius.back()));
  }
  // Sort by x for a sweep.
  std::vector<int> order(shapes.size());
  for (std::size_t i = 0; i < order.size(); ++i)
    order[i] = static_cast<int>(i);
  std::sort(order.begin(), order.end(),
    [&](int a, int b) { return shapes[a].Position.x < shapes[b].Position.x; });
  double rmax = 0.0;
  for (double r : radius)
    rmax = std::max(rmax, r);
  int overlaps = 0, checked = 0;
  for (std::size_t ia = 0; ia < order.size(); ++ia)
  {
    const gs::PlacedShape& A = shapes[order[ia]];
    for (std::size_t ib = ia + 1; ib < order.size(); ++ib)
    {
      const gs::PlacedShape& B = shapes[order[ib]];
      if (B.Position.x - A.Position.x > 2.0 * rmax)
        break;
      const gs::Vec3 delta = B.Position - A.Position;
      const double d = gs::Norm(delta);
      if (d >= radius[order[ia]] + radius[order[ib]])
        continue;
      ++checked;
      const gs::Vec3 n = mesh.FaceNormal(A.Centre.Face);
      auto angleTo = [&](const gs::Vec3& from, const gs::Vec3& to) {
        return std::atan2(gs::Dot(n, gs::Cross(from, to)), gs::Dot(from, to));
      };
      const gs::Vec3 u = d > 0.0 ? delta / d : A.Direction;
      // Class +x axes: a long shape's Direction is its class axis too.
      const double alphaA = angleTo(u, A.Direction), alphaB = angleTo(u, B.Direction);
      if (oracles[order[ia]]->Overlaps(alphaA, *oracles[order[ib]], alphaB, d))
        ++overlaps;
    }
  }
  if (pairsChecked)
    *pairsChecked = checked;
  return overlaps;
}

} // namespace gs_test
