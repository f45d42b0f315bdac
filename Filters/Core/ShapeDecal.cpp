// Decals: the faces a shape covers with texture coordinates (the inverse of its map: a short
// shape's polar chart, a long shape's CurveGrid), split where the map is not affine over a face.
#include "ShapeDistributorImpl.h"

#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace gs
{
using namespace distribution;

namespace
{
// Whether triangle t (texture coordinates) meets the box [lo, hi] (separating axes).
bool MeetsBox(const std::array<Vec2, 3>& t, const Vec2& lo, const Vec2& hi)
{
  const double minX = std::min({ t[0].x, t[1].x, t[2].x }), maxX = std::max({ t[0].x, t[1].x, t[2].x });
  const double minY = std::min({ t[0].y, t[1].y, t[2].y }), maxY = std::max({ t[0].y, t[1].y, t[2].y });
  if (maxX < lo.x || minX > hi.x || maxY < lo.y || minY > hi.y)
  {
    return false;
  }
  const Vec2 box[4] = { lo, { hi.x, lo.y }, hi, { lo.x, hi.y } };
  for (int k = 0; k < 3; ++k)
  {
    const Vec2 a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
    const Vec2 axis{ -(b.y - a.y), b.x - a.x };
    const double side = Dot(axis, c - a);
    bool allOut = true;
    for (const Vec2& q : box)
    {
      allOut = allOut && Dot(axis, q - a) * side < 0.0;
    }
    if (allOut && side != 0.0)
    {
      return false;
    }
  }
  return true;
}

double SignedArea(const std::array<Vec2, 3>& t)
{
  return 0.5 * Cross(t[1] - t[0], t[2] - t[0]);
}
} // namespace

bool ShapeDecal::TextureCoordinate(const SurfacePoint& p, Vec2& uv) const
{
  if (p.Face < 0)
  {
    return false;
  }
  for (std::size_t k = 0; k < Faces.size(); ++k)
  {
    if (Faces[k] != p.Face)
    {
      continue;
    }
    // p's barycentric coordinates in the triangle: solve in the first two face coordinates.
    const auto& B = Corners[k];
    const double ax = B[0][0] - B[2][0], bx = B[1][0] - B[2][0], ay = B[0][1] - B[2][1],
                 by = B[1][1] - B[2][1];
    const double det = ax * by - bx * ay;
    if (det == 0.0)
    {
      continue;
    }
    const double px = p.Bary[0] - B[2][0], py = p.Bary[1] - B[2][1];
    const double l0 = (px * by - bx * py) / det, l1 = (ax * py - px * ay) / det, l2 = 1.0 - l0 - l1;
    const double eps = -1e-9;
    if (l0 >= eps && l1 >= eps && l2 >= eps)
    {
      const auto& U = TextureCoordinates[k];
      uv = U[0] * l0 + U[1] * l1 + U[2] * l2;
      return true;
    }
  }
  return false;
}

ShapeDecal ShapeDistributor::Decal(int shape, double tolerance) const
{
  const Impl& I = *P;
  ShapeDecal decal;
  const PlacedShape& s = I.Placed.at(shape);
  const SafeDistanceClass& c = I.T.Classes[s.ClassId];
  const double scale = I.O.ShapeSize * s.Scale;
  const double reach = c.Radius * scale + I.MaxEdge;
  // Class-frame coordinates (normalized) of the vertices near the shape.
  std::vector<std::pair<int, Vec2>> local;
  std::shared_ptr<const CurveGrid> grid;
  if (s.Curve.empty())
  {
    const Impl::Record& r = I.Accepted.at(shape);
    if (r.Charts.empty())
    {
      return decal;
    }
    for (const ChartEntry& e : r.Charts[0].Entries)
    {
      const Vec2 q{ e.X, e.Y };
      if (Norm(q) <= reach)
      {
        local.emplace_back(e.V, q * (1.0 / scale));
      }
    }
  }
  else
  {
    grid = Frame(shape); // the grid the drawn check built (indexed), or a new one
    if (!grid)
    {
      return decal;
    }
    I.CurveShapeVertices(*grid, local);
  }
  std::sort(local.begin(), local.end(),
    [](const std::pair<int, Vec2>& a, const std::pair<int, Vec2>& b) { return a.first < b.first; });
  auto find = [&](int v) -> const Vec2* {
    auto it = std::lower_bound(local.begin(), local.end(), v,
      [](const std::pair<int, Vec2>& e, int value) { return e.first < value; });
    return it != local.end() && it->first == v ? &it->second : nullptr;
  };
  const auto toTexture = [&c](const Vec2& q) {
    return Vec2{ 0.5 * (q.x / c.Radius + 1.0), 0.5 * (q.y / c.Radius + 1.0) };
  };
  // The texels that draw: the silhouette's bounding box (2% of the circumradius around it, for
  // texture filtering) within the class square. Faces whose texture triangle misses it would
  // draw only transparent texels: not in the decal.
  Vec2 lo{ 1.0, 1.0 }, hi{ 0.0, 0.0 };
  for (const auto& ring : c.Outline.Rings)
  {
    for (const Vec2& p : ring)
    {
      const Vec2 u = toTexture(p);
      lo = Vec2{ std::min(lo.x, u.x), std::min(lo.y, u.y) };
      hi = Vec2{ std::max(hi.x, u.x), std::max(hi.y, u.y) };
    }
  }
  lo = Vec2{ std::max(0.0, lo.x - 0.01), std::max(0.0, lo.y - 0.01) };
  hi = Vec2{ std::min(1.0, hi.x + 0.01), std::min(1.0, hi.y + 0.01) };
  if (!(lo.x <= hi.x && lo.y <= hi.y))
  {
    lo = Vec2{ 0.0, 0.0 };
    hi = Vec2{ 1.0, 1.0 };
  }
  int hint = -1, firstValid = -1;
  if (grid)
  {
    for (int k = 0; k < static_cast<int>(grid->Nodes.size()) && firstValid < 0; ++k)
    {
      firstValid = grid->Nodes[k].Valid ? k : -1;
    }
  }
  // The shape's map at a point of face f: on the grid, or beyond it its affine extension (what
  // the corners' values are, CurveShapeVertices).
  const auto classAt = [&](int f, const std::array<double, 3>& b, Vec2& q) {
    // (Not from the previous point's node: where the map folds, at a kink of the curve, the
    // globally nearest node decides the sheet, the same for every point.)
    if (grid->ClassPoint(SurfacePoint::InFace(f, b[0], b[1], b[2]), q))
    {
      return true;
    }
    if (hint < 0)
    {
      hint = firstValid;
    }
    return grid->Locate(I.M.Interpolate(f, b), hint, q, nullptr, &hint);
  };
  // Faces checked for splitting: a long shape's faces wider than its grid's step (on smaller
  // faces the grid, affine per grid triangle, knows the map no better than the face's corners).
  const double tolUV = tolerance > 0.0 ? 0.5 * tolerance : 0.0; // texture units per circumradius
  const auto splits = [&](int f) {
    if (!grid || !(tolUV > 0.0))
    {
      return false;
    }
    const auto& v = I.M.Face(f);
    const double longest = std::max({ Norm(I.M.Position(v[1]) - I.M.Position(v[0])),
      Norm(I.M.Position(v[2]) - I.M.Position(v[1])), Norm(I.M.Position(v[0]) - I.M.Position(v[2])) });
    return longest > grid->Step;
  };
  // Faces with all corners known, near the shape (each face visited once, from its corner of
  // smallest index), whose texture triangle meets the class square.
  std::vector<int> faces;
  for (const auto& e : local)
  {
    for (int h : I.M.OutgoingHalfedges(e.first))
    {
      const auto& corners = I.M.Face(h / 3);
      if (e.first == std::min(corners[0], std::min(corners[1], corners[2])))
      {
        faces.push_back(h / 3);
      }
    }
  }
  std::sort(faces.begin(), faces.end());
  std::vector<std::pair<int, std::array<Vec2, 3>>> whole;
  std::unordered_map<int, Vec2> cornerValues; // vertices of faces to split, on the grid
  double orientation = 0.0; // the map's sense: the area-weighted sign of the texture triangles
  for (int f : faces)
  {
    std::array<Vec2, 3> uv;
    bool all = true;
    for (int k = 0; k < 3 && all; ++k)
    {
      const int v = I.M.Face(f)[k];
      const Vec2* q = find(v);
      all = q != nullptr;
      if (all)
      {
        // (The corners of a face to split are read like the points inside it, on the grid where
        // it reaches: where the map folds the grid decides the sheet, the same for all.)
        Vec2 value = *q;
        if (splits(f))
        {
          auto known = cornerValues.find(v);
          if (known == cornerValues.end())
          {
            Vec2 onGrid;
            known = cornerValues.emplace(v, grid->ClassPoint(SurfacePoint::AtVertex(v), onGrid) ? onGrid : *q).first;
          }
          value = known->second;
        }
        uv[k] = toTexture(value);
      }
    }
    if (all && MeetsBox(uv, lo, hi))
    {
      whole.emplace_back(f, uv);
      orientation += SignedArea(uv);
    }
  }
  // Each face's texture map is affine; where the true map departs from it by more than the
  // tolerance at an edge midpoint (a long shape's map along its curve, read on its grid), the
  // triangle is split in four, to depth 5 (1024 pieces per face). A piece whose texture
  // triangle is turned over (the map folds there) or stretched far beyond its size on the
  // surface (a jump across a seam of the map) is dropped.
  const int maxDepth = 5;
  const double sense = orientation >= 0.0 ? 1.0 : -1.0;
  const double unit = 2.0 * c.Radius * scale; // world length of one texture unit
  struct Piece
  {
    std::array<std::array<double, 3>, 3> B;
    std::array<Vec2, 3> U;
    int Depth;
  };
  std::vector<Piece> stack;
  std::unordered_map<std::uint64_t, std::pair<bool, Vec2>> midpoints; // face edges' midpoints
  for (const auto& entry : whole)
  {
    const int f = entry.first;
    const auto& corners = I.M.Face(f);
    const Vec3 X[3] = { I.M.Position(corners[0]), I.M.Position(corners[1]), I.M.Position(corners[2]) };
    const bool split = splits(f);
    stack.clear();
    stack.push_back(Piece{ { { { 1.0, 0.0, 0.0 }, { 0.0, 1.0, 0.0 }, { 0.0, 0.0, 1.0 } } }, entry.second, 0 });
    while (!stack.empty())
    {
      const Piece t = stack.back();
      stack.pop_back();
      if (!MeetsBox(t.U, lo, hi))
      {
        continue;
      }
      auto at = [&X](const std::array<double, 3>& b) { return X[0] * b[0] + X[1] * b[1] + X[2] * b[2]; };
      if (split)
      {
        std::array<std::array<double, 3>, 3> mid;
        std::array<Vec2, 3> trueUV;
        double error = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          const auto& a = t.B[k];
          const auto& b = t.B[(k + 1) % 3];
          mid[k] = { 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]) };
          const Vec2 linear = (t.U[k] + t.U[(k + 1) % 3]) * 0.5;
          // (A face's edge midpoints are shared with the neighbour across: read once.)
          const std::uint64_t edge = t.Depth == 0
            ? (static_cast<std::uint64_t>(std::min(corners[k], corners[(k + 1) % 3])) << 32) |
              static_cast<std::uint32_t>(std::max(corners[k], corners[(k + 1) % 3]))
            : 0;
          const auto known = t.Depth == 0 ? midpoints.find(edge) : midpoints.end();
          Vec2 q;
          bool found = false;
          if (known != midpoints.end())
          {
            found = known->second.first;
            q = known->second.second;
          }
          else
          {
            found = classAt(f, mid[k], q);
            if (t.Depth == 0)
            {
              midpoints.emplace(edge, std::make_pair(found, q));
            }
          }
          if (found)
          {
            trueUV[k] = toTexture(q);
            error = std::max(error, Norm(trueUV[k] - linear));
          }
          else
          {
            trueUV[k] = linear;
          }
        }
        // Finest: depth 5, or pieces as small as half the grid's step (it cannot tell more).
        const double size = std::max({ Norm(at(t.B[1]) - at(t.B[0])), Norm(at(t.B[2]) - at(t.B[1])),
          Norm(at(t.B[0]) - at(t.B[2])) });
        if (error > tolUV && (t.Depth == maxDepth || size <= 0.5 * grid->Step))
        {
          if (error > 5.0 * tolUV)
          {
            continue; // still not affine at the finest: the map folds or jumps here
          }
        }
        else if (error > tolUV)
        {
          // Corners 0, 1, 2 and midpoints m01, m12, m20.
          stack.push_back(Piece{ { { t.B[0], mid[0], mid[2] } }, { { t.U[0], trueUV[0], trueUV[2] } }, t.Depth + 1 });
          stack.push_back(Piece{ { { mid[0], t.B[1], mid[1] } }, { { trueUV[0], t.U[1], trueUV[1] } }, t.Depth + 1 });
          stack.push_back(Piece{ { { mid[2], mid[1], t.B[2] } }, { { trueUV[2], trueUV[1], t.U[2] } }, t.Depth + 1 });
          stack.push_back(Piece{ { { mid[0], mid[1], mid[2] } }, { { trueUV[0], trueUV[1], trueUV[2] } }, t.Depth + 1 });
          continue;
        }
      }
      // Folded or torn: dropped.
      if (SignedArea(t.U) * sense < 0.0)
      {
        continue;
      }
      bool torn = false;
      for (int k = 0; k < 3 && !torn; ++k)
      {
        const double onSurface = Norm(at(t.B[(k + 1) % 3]) - at(t.B[k]));
        const double inTexture = Norm(t.U[(k + 1) % 3] - t.U[k]) * unit;
        torn = inTexture > 4.0 * onSurface + 0.05 * unit;
      }
      if (torn)
      {
        continue;
      }
      decal.Faces.push_back(f);
      decal.Corners.push_back(t.B);
      decal.TextureCoordinates.push_back(t.U);
    }
  }
  return decal;
}

} // namespace gs
