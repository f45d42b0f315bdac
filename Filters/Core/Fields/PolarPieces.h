// Geodesic polar coordinates about a vertex or surface point of a surface partitioned over processes
// (SurfacePiece), without any process holding the whole surface: the chart spans pieces within
// its radius. The process owning the source grows its band where the exact solve truncated at
// the radius reaches the band's edge (the fence), until it stays inside; it then computes the
// coordinates on its piece as GeodesicPolarCoordinates does on the whole surface (the same
// faces in the same order, the same tolerance: the same bits) and sends every process the
// chart's vertices (global id, rho, theta). A chart over the whole surface (an infinite radius)
// is the exact distances and departure angles on the pieces instead (ComputeExactOnPieces).
#pragma once

#include "PieceCommunicator.h"
#include "Status.h"
#include "SurfacePiece.h"
#include "SurfacePoint.h"
#include "Vector.h"

#include <cstdint>
#include <vector>

namespace gs
{

struct PiecePolarCoordinates
{
  // Per vertex of the piece: rho and theta (GeodesicPolarCoordinates::Rho, Theta); NaN outside
  // the radius (a whole chart: at the vertices of this process's own faces, NaN elsewhere).
  std::vector<double> Rho, Theta;
  double SourceAngleSum = 0.0;
  // Whether the reference direction was normal to the surface at the source (the first edge is
  // used instead, as GeodesicPolarCoordinates' callers do).
  bool ReferenceNormal = false;
  // Faces of the chart's process's piece once its band covered the chart.
  int ChartFaces = 0;
  // With iso-curve angles: the vertices that kept their geodesic-direction angle
  // (GeodesicPolarCoordinates::UseIsoCurveAngles).
  int IsoCurveKept = 0;
  // About a curve: Rho and Theta are the offset and the normalized arc length
  // (GeodesicPolarCoordinates::Curve), and this is the curve's length.
  double CurveLength = 0.0;
};

// Collective. Coordinates about the vertex of global id `source` within `radius` (> 0; infinite:
// the whole surface, from the exact distances and departure angles on the pieces, no process
// holding more than its piece: the serial chart's up to rounding),
// theta's zero the tangent projection of `referenceDirection` at the source (all zero: the
// source's first edge). Fails on every process when the id is no vertex of the surface or the
// coordinates cannot be computed (the message of the process that computed them).
// With `isoCurveAngles`, theta is the iso-curve arc-length angle (UseIsoCurveAngles; the band
// then covers what it reads beyond the chart, GeodesicPolarCoordinates::IsoCurveReach).
Status ComputePolarOnPieces(SurfacePiece& piece, std::int64_t source, double radius,
  const Vec3& referenceDirection, PieceCommunicator& comm, PiecePolarCoordinates& result,
  bool isoCurveAngles = false);

// Collective. The same about a surface point: `point` is this process's (a point of one of its
// own faces, or a vertex it owns, in its piece's mesh; a face point at a corner is that
// vertex), null on every other process. Fails on every process unless exactly one process
// passes one.
Status ComputePolarOnPieces(SurfacePiece& piece, const SurfacePoint* point, double radius,
  const Vec3& referenceDirection, PieceCommunicator& comm, PiecePolarCoordinates& result,
  bool isoCurveAngles = false);

// Collective. Geodesic curve coordinates (GeodesicPolarCoordinates::ComputeCurve) about the
// curve of points `curve` (named by global ids, the same list on every process) within `radius`
// (finite, > 0): process 0 grows its band around the curve until its trace and the exact solve
// from its samples within the radius (and the margin ComputeCurve solves beyond) stay inside,
// computes them there (the whole surface's mean edge length: the serial result to the bit) and
// sends every process the chart's vertices. Fails on every process as ComputeCurve fails.
Status ComputeCurveCoordinatesOnPieces(SurfacePiece& piece,
  const std::vector<PiecePointName>& curve, double radius, PieceCommunicator& comm,
  PiecePolarCoordinates& result);

} // namespace gs
