// A shape's decal (ShapeDistributor::Decal, code in ShapeDecal.cpp): the triangles it is drawn
// on, with texture coordinates in the convention of MSDT Source's silhouettes.
#pragma once

#include "SurfacePoint.h"
#include "Vector.h"

#include <array>
#include <cstddef>
#include <vector>

namespace gs
{

/// A decal: triangles on the mesh faces a shape covers, with texture coordinates per corner
/// mapping the square around the class circle onto [0, 1]^2 (the convention of MSDT Source's
/// silhouettes: class point r (2 u - 1, 2 v - 1)); every texture coordinate lies in [0, 1]^2
/// (triangles are cut at the square's border, so that no renderer, texture setting or exporter
/// draws a neighbouring repeat of the texture). A triangle is a whole mesh face or, where the
/// shape's map is not affine over the face (a long shape bending inside a face), a piece of one:
/// its corners are barycentric coordinates in that face.
struct ShapeDecal
{
  std::vector<int> Faces; ///< the mesh face of each triangle
  std::vector<std::array<std::array<double, 3>, 3>> Corners; ///< per corner, barycentric in the face
  std::vector<std::array<Vec2, 3>> TextureCoordinates;
  /// The texture coordinate at surface point p as a renderer draws it (linear in the triangle
  /// holding p); false when no triangle holds it.
  bool TextureCoordinate(const SurfacePoint& p, Vec2& uv) const;
  /// The same for the point of barycentric coordinates `bary` in face Faces[k], when it lies in
  /// triangle k.
  bool TextureCoordinateIn(std::size_t k, const std::array<double, 3>& bary, Vec2& uv) const;
};

/// The decals' texture convention, both ways (the convention of MSDT Source's silhouettes): the
/// texture square [0, 1]^2 is the square about the class circle of radius r, the class point q
/// at (q / r + 1) / 2.
inline Vec2 DecalTextureCoordinate(const Vec2& q, double r)
{
  return Vec2{ 0.5 * (q.x / r + 1.0), 0.5 * (q.y / r + 1.0) };
}
inline Vec2 DecalClassPoint(const Vec2& uv, double r)
{
  return Vec2{ (2.0 * uv.x - 1.0) * r, (2.0 * uv.y - 1.0) * r };
}

} // namespace gs
