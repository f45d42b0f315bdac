// Independent checks of shape distributions (used by TestShapeDistributor and the distributor
// benchmark): no safe distance table, no polar chart.
//
// Planar meshes: every placed shape is its class outline (the tables' normalized outline, times
// ShapeSize * Scale), rigidly placed at its centre and turned by its direction (a long shape on
// a constant field lies along a straight streamline: also rigid). Two shapes overlap when their
// regions' interiors intersect (ShapeOverlapOracle.h: exact crossing and containment tests).
#pragma once

#include "SafeDistanceTable.h"
#include "ShapeDecal.h"
#include "ShapeDistributor.h"
#include "ShapeOverlapOracle.h"
#include "GeodesicPolarCoordinates.h"
#include "GeodesicShooting.h"
#include "Hash.h"
#include "OverlapCheck.h"
#include "TriangleMesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <ostream>
#include <cmath>
#include <memory>
#include <vector>

namespace gs_test
{

/// Hashes of a run's results over every shape: Placements (position, direction, class, scale,
/// parts with their centres and axes, the curve of a long shape), Decals (faces, corners,
/// texture coordinates) and Outlines (surface points, class points, closure, at the drawn
/// check's spacing); Probe is left to the caller (ProbeFitFraction).
struct RunHashes
{
  std::uint64_t Placements = 0, Decals = 0, Outlines = 0;
  int Shapes = 0;
  double Probe = 0.0;
  bool operator==(const RunHashes& o) const
  {
    return Placements == o.Placements && Decals == o.Decals && Outlines == o.Outlines &&
      Shapes == o.Shapes && Probe == o.Probe;
  }
  bool operator!=(const RunHashes& o) const { return !(*this == o); }
};

inline std::ostream& operator<<(std::ostream& os, const RunHashes& h)
{
  return os << h.Shapes << " shapes, hashes " << std::hex << h.Placements << " " << h.Decals
            << " " << h.Outlines << std::dec << ", probe " << h.Probe;
}

inline void AddPoint(gs::Hasher& h, const gs::SurfacePoint& p)
{
  h.AddValue(p.Vertex);
  h.AddValue(p.Face);
  h.AddValue(p.Bary);
}

inline RunHashes HashRun(const gs::ShapeDistributor& d, const std::vector<gs::PlacedShape>& shapes)
{
  gs::Hasher placements, decals, outlines;
  for (const gs::PlacedShape& s : shapes)
  {
    placements.AddValue(s.Position);
    placements.AddValue(s.Direction);
    placements.AddValue(s.ClassId);
    placements.AddValue(s.Scale);
    for (const gs::PlacedPart& p : s.Parts)
    {
      placements.AddValue(p.Part);
      AddPoint(placements, p.Centre);
      placements.AddValue(p.Axis);
    }
    for (const gs::CurvePiece& c : s.Curve)
    {
      placements.AddValue(c.Face);
      placements.AddValue(c.A);
      placements.AddValue(c.B);
    }
    placements.AddValue(s.CurveCentre);
  }
  for (int s = 0; s < static_cast<int>(shapes.size()); ++s)
  {
    const gs::ShapeDecal decal = d.Decal(s);
    decals.AddVector(decal.Faces);
    decals.AddVector(decal.Corners);
    decals.AddVector(decal.TextureCoordinates);
    for (const gs::OutlinePiece& piece : d.Outline(s, d.OutlineSpacing()))
    {
      for (const gs::SurfacePoint& p : piece.Points)
      {
        AddPoint(outlines, p);
      }
      outlines.AddVector(piece.ClassPoints);
      outlines.AddValue(piece.Closed);
    }
  }
  return { placements.H, decals.H, outlines.H, static_cast<int>(shapes.size()), 0.0 };
}

/// Every shape's drawn outline at `spacing` (ShapeDistributor::Outline), as CheckOverlaps takes
/// them.
inline std::vector<std::vector<gs::OutlinePiece>> Outlines(const gs::ShapeDistributor& d, double spacing)
{
  std::vector<std::vector<gs::OutlinePiece>> out(d.Shapes().size());
  for (std::size_t s = 0; s < out.size(); ++s)
    out[s] = d.Outline(static_cast<int>(s), spacing);
  return out;
}

/// The class point (normalized class frame) a decal's texture coordinate uv stands for (the
/// convention of ShapeDecal.h).
inline gs::Vec2 ClassPointOfTexture(const gs::Vec2& uv, double radius)
{
  return gs::DecalClassPoint(uv, radius);
}

/// What a decal draws, read on a fixed lattice of every decal triangle's face (28 barycentric
/// points, (i + 1/3) / 7): calls f(k, index, bary, uv, q) for each lattice point of face
/// decal.Faces[k] that triangle k holds and renders inside the silhouette (`region`, the class
/// of `c`): its index in the face's lattice, barycentric coordinates, texture coordinate and
/// class point q. A point on the edge of two triangles of one face is given by both.
template <class F>
void ForEachDrawnLatticePoint(const gs::ShapeDecal& decal, const gs::SafeDistanceClass& c,
  const gs::ClassRegion& region, F&& f)
{
  const int L = 6;
  for (std::size_t k = 0; k < decal.Faces.size(); ++k)
  {
    int index = 0;
    for (int i = 0; i <= L; ++i)
      for (int j = 0; i + j <= L; ++j, ++index)
      {
        const double b0 = (i + 1.0 / 3.0) / (L + 1.0), b1 = (j + 1.0 / 3.0) / (L + 1.0);
        const std::array<double, 3> bary{ { b0, b1, 1.0 - b0 - b1 } };
        gs::Vec2 uv;
        if (!decal.TextureCoordinateIn(k, bary, uv))
          continue;
        const gs::Vec2 q = ClassPointOfTexture(uv, c.Radius);
        if (region.Inside(q))
          f(k, index, bary, uv, q);
      }
  }
}

/// Shapes whose decal does not draw their outline: a point of the drawn outline (`outlines`,
/// one per shape) outside the decal, or read in it (its texture coordinate, as rendered) farther
/// than `tolerance` (a fraction of the class circumradius) from the class point it was drawn
/// from (a point within `tolerance` of the texture square's border that the decal, cut at the
/// border, leaves out counts as drawn). `points` (optional) gets the number of such outline
/// points.
inline int CountUnfaithfulDecals(const gs::SafeDistanceTables& tables, const gs::ShapeDistributor& d,
  const std::vector<std::vector<gs::OutlinePiece>>& outlines, double tolerance, long long* points = nullptr)
{
  int shapes = 0;
  long long off = 0;
  for (std::size_t s = 0; s < outlines.size(); ++s)
  {
    const gs::SafeDistanceClass& c = tables.Classes[d.Shapes()[s].ClassId];
    const gs::ShapeDecal decal = d.Decal(static_cast<int>(s));
    long long mine = 0;
    for (const gs::OutlinePiece& piece : outlines[s])
      for (std::size_t i = 0; i < piece.Points.size() && i < piece.ClassPoints.size(); ++i)
      {
        gs::Vec2 uv;
        if (!decal.TextureCoordinate(piece.Points[i], uv))
        {
          // (A decal ends at its texture square's border: a point of the outline within the
          // tolerance of that border, which the decal's map puts just outside it, is drawn as
          // far as the texture goes, within the tolerance.)
          const gs::Vec2& p = piece.ClassPoints[i];
          mine += std::max(std::abs(p.x), std::abs(p.y)) < (1.0 - tolerance) * c.Radius ? 1 : 0;
          continue;
        }
        const gs::Vec2 q = ClassPointOfTexture(uv, c.Radius);
        mine += gs::Norm(q - piece.ClassPoints[i]) > tolerance * c.Radius ? 1 : 0;
      }
    shapes += mine > 0 ? 1 : 0;
    off += mine;
  }
  if (points)
    *points = off;
  return shapes;
}

/// Number of overlapping pairs among shapes placed on a planar mesh (any plane orientation).
inline int CountPlanarOverlaps(const gs::TriangleMesh& mesh, const gs::SafeDistanceTables& tables,
  const std::vector<gs::PlacedShape>& shapes, double shapeSize, int* pairsChecked = nullptr,
  std::vector<std::pair<int, int>>* overlapping = nullptr)
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
      {
        ++overlaps;
        if (overlapping)
          overlapping->emplace_back(std::min(order[ia], order[ib]), std::max(order[ia], order[ib]));
      }
    }
  }
  if (pairsChecked)
    *pairsChecked = checked;
  return overlaps;
}

/// Curved meshes: every pair of short shapes closer (in space) than the sum of their
/// circumradii is mapped into one chart, the exact geodesic polar coordinates of the first
/// shape's centre (x axis: its direction), where the first shape is its planar silhouette by
/// construction; the second shape's outline, drawn on the surface as the filter draws it
/// (ShapeDistributor::MapToSurface: the exponential map of its own centre, edges subdivided to
/// `spacing` in normalized units), is carried into that chart and intersected with the
/// silhouette (crossings and containment). Pairs whose centres are at least r_A + r_B apart
/// geodesically (exact distance) cannot overlap and are not mapped. A long shape is checked
/// against its short neighbours (its outline, drawn along its curve, in their charts); pairs of
/// two long shapes are skipped. Returns the overlapping
/// pairs; `pairsChecked` gets the number of pairs examined.
inline int CountSurfaceOverlaps(const gs::TriangleMesh& mesh, const gs::SafeDistanceTables& tables,
  const gs::ShapeDistributor& distributor, double shapeSize, double spacing,
  long long* pairsChecked = nullptr)
{
  const std::vector<gs::PlacedShape>& shapes = distributor.Shapes();
  const int n = static_cast<int>(shapes.size());
  std::vector<std::unique_ptr<OverlapOracle>> oracles;
  double rmax = 0.0;
  for (const gs::SafeDistanceClass& c : tables.Classes)
  {
    oracles.emplace_back(new OverlapOracle(c.Outline.Rings, c.Radius * (1.0 + 1e-9)));
    rmax = std::max(rmax, c.Radius);
  }
  double fmax = 0.0;
  for (const gs::PlacedShape& s : shapes)
    fmax = std::max(fmax, s.Scale);
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i)
    order[i] = i;
  std::sort(order.begin(), order.end(),
    [&](int a, int b) { return shapes[a].Position.x < shapes[b].Position.x; });
  std::vector<int> rank(n);
  for (int i = 0; i < n; ++i)
    rank[order[i]] = i;
  long long checked = 0;
  int overlaps = 0;
#pragma omp parallel reduction(+ : checked, overlaps)
  {
    gs::GeodesicPolarCoordinates chart(mesh);
#pragma omp for schedule(dynamic, 8)
    for (int a = 0; a < n; ++a)
    {
      const gs::PlacedShape& A = shapes[a];
      if (!A.Curve.empty())
        continue;
      const double ra = tables.Classes[A.ClassId].Radius * shapeSize * A.Scale;
      std::vector<int> near;
      for (int k = rank[a] - 1; k >= 0 && A.Position.x - shapes[order[k]].Position.x < 2 * rmax * shapeSize * fmax; --k)
        near.push_back(order[k]);
      for (int k = rank[a] + 1; k < n && shapes[order[k]].Position.x - A.Position.x < 2 * rmax * shapeSize * fmax; ++k)
        near.push_back(order[k]);
      bool computed = false;
      for (int b : near)
      {
        const gs::PlacedShape& B = shapes[b];
        // (A long B is checked from its short neighbours' side; two long shapes are not.)
        if ((b < a && B.Curve.empty()) || b == a)
          continue;
        const double rb = tables.Classes[B.ClassId].Radius * shapeSize * B.Scale;
        if (gs::Norm(B.Position - A.Position) >= ra + rb)
          continue;
        if (!computed)
        {
          const double reference = gs::TangentAngle(mesh, A.Centre, A.Direction);
          // A chart that fails holds no point: PolarAt then skips A's pairs.
          static_cast<void>(chart.Compute(
            A.Centre, ra + 4.0 * rmax * shapeSize * fmax + 2.0 * mesh.MeanEdgeLength(), reference));
          computed = true;
        }
        // Rigorous on any surface: geodesic disks of radii r_A, r_B hold the shapes (their
        // outlines are drawn at geodesic distance at most r from the centre), so centres
        // r_A + r_B apart or more cannot overlap.
        double rhoB = 0.0, thetaB = 0.0;
        if (!chart.PolarAt(B.Centre, rhoB, thetaB) || rhoB >= ra + rb)
          continue;
        ++checked;
        const double unitA = shapeSize * A.Scale;
        std::vector<std::vector<gs::Vec2>> mapped;
        for (const auto& ring : tables.Classes[B.ClassId].Outline.Rings)
        {
          std::vector<gs::Vec2> out;
          for (std::size_t k = 0; k < ring.size(); ++k)
          {
            const gs::Vec2 p = ring[k], q = ring[(k + 1) % ring.size()];
            const int pieces = std::max(1, static_cast<int>(std::ceil(gs::Norm(q - p) / spacing)));
            for (int j = 0; j < pieces; ++j)
            {
              const gs::SurfacePoint x = distributor.MapToSurface(b, p + (q - p) * (static_cast<double>(j) / pieces));
              double rho = 0.0, theta = 0.0;
              if (!chart.PolarAt(x, rho, theta))
              {
                rho = 1e6 * ra; // beyond the chart: far from A
              }
              out.push_back(gs::Vec2{ rho * std::cos(theta), rho * std::sin(theta) } * (1.0 / unitA));
            }
          }
          mapped.push_back(std::move(out));
        }
        if (oracles[A.ClassId]->OverlapsRings(mapped))
          ++overlaps;
      }
    }
  }
  if (pairsChecked)
    *pairsChecked = checked;
  return overlaps;
}

/// Area common to two even-odd polygon sets in the plane, by scanlines: on each of `rows` rows
/// across the common bounding box, the exact intervals of both sets at the row's centre line,
/// intersected. (Shared boundary pieces, such as two outlines cut along the same mesh boundary,
/// add nothing.)
inline double CommonArea(const std::vector<std::vector<gs::Vec2>>& a,
  const std::vector<std::vector<gs::Vec2>>& b, int rows)
{
  auto box = [](const std::vector<std::vector<gs::Vec2>>& rings, double* lo, double* hi) {
    lo[0] = lo[1] = 1e300;
    hi[0] = hi[1] = -1e300;
    for (const auto& ring : rings)
      for (const gs::Vec2& p : ring)
      {
        lo[0] = std::min(lo[0], p.x);
        lo[1] = std::min(lo[1], p.y);
        hi[0] = std::max(hi[0], p.x);
        hi[1] = std::max(hi[1], p.y);
      }
  };
  double loA[2], hiA[2], loB[2], hiB[2];
  box(a, loA, hiA);
  box(b, loB, hiB);
  const double y0 = std::max(loA[1], loB[1]), y1 = std::min(hiA[1], hiB[1]);
  if (!(y1 > y0) || std::max(loA[0], loB[0]) >= std::min(hiA[0], hiB[0]))
    return 0.0;
  auto crossings = [](const std::vector<std::vector<gs::Vec2>>& rings, double y) {
    std::vector<double> xs;
    for (const auto& ring : rings)
      for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      {
        const gs::Vec2& p = ring[k];
        const gs::Vec2& q = ring[(k + 1) % n];
        if ((p.y > y) != (q.y > y))
          xs.push_back(p.x + (q.x - p.x) * (y - p.y) / (q.y - p.y));
      }
    std::sort(xs.begin(), xs.end());
    return xs;
  };
  const double h = (y1 - y0) / rows;
  double area = 0.0;
  for (int r = 0; r < rows; ++r)
  {
    const double y = y0 + (r + 0.5) * h;
    const std::vector<double> xa = crossings(a, y), xb = crossings(b, y);
    for (std::size_t i = 0; i + 1 < xa.size(); i += 2)
      for (std::size_t j = 0; j + 1 < xb.size(); j += 2)
        area += std::max(0.0, std::min(xa[i + 1], xb[j + 1]) - std::max(xa[i], xb[j])) * h;
  }
  return area;
}

/// Planar meshes (z = 0): pairs of shapes whose drawn outlines (the polygons `drawn[s]`, world
/// x and y) share more than `fraction` of the smaller shape's circle area, by CommonArea.
inline int CountDrawnOverlaps(const std::vector<gs::PlacedShape>& shapes,
  const std::vector<std::vector<std::vector<gs::Vec2>>>& drawn, const std::vector<double>& radius,
  double fraction = 1e-5, std::vector<std::pair<int, int>>* overlapping = nullptr)
{
  int overlaps = 0;
  for (std::size_t a = 0; a < shapes.size(); ++a)
    for (std::size_t b = a + 1; b < shapes.size(); ++b)
    {
      if (gs::Norm(shapes[a].Position - shapes[b].Position) >= radius[a] + radius[b])
        continue;
      const double r = std::min(radius[a], radius[b]);
      if (CommonArea(drawn[a], drawn[b], 400) > fraction * 3.14159265358979 * r * r)
      {
        ++overlaps;
        if (overlapping)
          overlapping->emplace_back(static_cast<int>(a), static_cast<int>(b));
      }
    }
  return overlaps;
}

/// The drawn outlines of every shape as polygons in the plane z = 0 (ShapeDistributor::Outline).
inline std::vector<std::vector<std::vector<gs::Vec2>>> DrawnPlanarOutlines(
  const gs::TriangleMesh& mesh, const gs::ShapeDistributor& distributor, double spacing)
{
  std::vector<std::vector<std::vector<gs::Vec2>>> drawn(distributor.Shapes().size());
  for (std::size_t s = 0; s < drawn.size(); ++s)
    for (const gs::OutlinePiece& piece : distributor.Outline(static_cast<int>(s), spacing))
    {
      std::vector<gs::Vec2> ring;
      for (const gs::SurfacePoint& q : piece.Points)
      {
        const gs::Vec3 x = mesh.Interpolate(q.Face, q.Bary);
        ring.push_back(gs::Vec2{ x.x, x.y });
      }
      drawn[s].push_back(std::move(ring));
    }
  return drawn;
}

} // namespace gs_test
