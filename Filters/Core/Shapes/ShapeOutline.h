// The drawn outline of a placed shape: its class outline (normalized class-frame rings) carried to
// the surface by the shape's map (class point -> surface point), and cut where the shape hangs
// over the mesh boundary.
//
// A short shape is drawn by the exponential map of its centre: class point p at polar angle
// theta goes to the end of the geodesic shot at angle theta for length |p| (times the shape's
// scale). Such a shot stops at the mesh boundary, so the part of the class plane the map reaches
// is star-shaped about the centre: D = {rho < rho_max(theta)}, rho_max the distance at which the
// ray meets the boundary. What is drawn is the region S of the shape within D; its outline
// consists of the pieces of S's outline inside D and the pieces of D's boundary (the mesh
// boundary) inside S. (Mapping every outline point to its clamped ray end instead would draw
// chords between clamped points that leave S wherever S is not star-shaped about its centre, an
// L tile whose circle centre lies in its notch: slivers that overlap a neighbour the tables
// rightly allowed there.)
//
// Long shapes are drawn by curve polar coordinates, whose reach is not star-shaped: their
// outline is returned as open pieces, those of its samples that lie on the surface.
#pragma once

#include "SurfacePoint.h"
#include "Vector.h"

#include <functional>
#include <vector>

namespace gs
{

/// One piece of a drawn outline, in order (a closed ring or, for long shapes over the boundary,
/// an open polyline).
struct OutlinePiece
{
  std::vector<SurfacePoint> Points;
  std::vector<Vec2> ClassPoints; ///< the class-frame point (normalized) of each surface point
  bool Closed = true;
};

/// Where the map takes class point p: the surface point, and whether it got there (false: it was
/// stopped by the mesh boundary, and `end` is where it stopped).
struct MappedPoint
{
  SurfacePoint End;
  bool Reached = true;
  double Reach = 1.0; ///< the fraction of the way to p that the map went (1 when reached)
};

/// The drawn outline of a short shape (see above). `rings`: the class outline (even-odd, any
/// orientation, normalized units); `spacing`: the largest distance between consecutive samples
/// (normalized units, > 0); `radius`: the class circumradius (normalized; every ring point is
/// within it); `map`: the exponential map of the centre in normalized class coordinates.
/// Crossings of the boundary are located by bisection to 1e-9 of the radius.
std::vector<OutlinePiece> DrawRadialOutline(const std::vector<std::vector<Vec2>>& rings,
  double spacing, double radius, const std::function<MappedPoint(const Vec2&)>& map);

/// The drawn outline of a shape whose map is not radial (long shapes): the rings sampled at
/// `spacing`, as closed rings where every sample is reached, otherwise as the open runs of
/// reached samples.
std::vector<OutlinePiece> DrawOutlinePieces(const std::vector<std::vector<Vec2>>& rings,
  double spacing, const std::function<MappedPoint(const Vec2&)>& map);

/// The rings oriented so that the even-odd region is on their left (outer rings
/// counter-clockwise, holes clockwise), by the parity of their nesting.
std::vector<std::vector<Vec2>> OrientRings(const std::vector<std::vector<Vec2>>& rings);

} // namespace gs
