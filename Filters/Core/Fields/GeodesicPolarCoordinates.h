// Geodesic polar coordinates about a surface point (Wang et al. 2016, Section 3.3): for every
// vertex within a radius, rho = geodesic distance and theta = direction in which the geodesic
// leaves the source (the log map), counter-clockwise about the outward normal from a reference
// direction, in [0, 2 pi). At a source vertex whose angle sum is not 2 pi (a cone point or a
// saddle), angles are scaled so that a full turn is 2 pi. The inverse map shoots the geodesic
// back, so that a shape given in polar coordinates can be drawn on the surface.
//
// Two engines: the exact solver truncated at the radius (exact distances and departure angles;
// behind a saddle or reflex boundary vertex, the angle of the path to it), or, given a saddle
// vertex graph, the SVG solver (exact in the source's K-disk, near-exact beyond, several times
// faster on large patches). Not the virtual sources: their departure angles are off by 1-4
// degrees on average (VirtualSourceGeodesic.h). Theta can be replaced by the iso-curve arc-length angle
// (UseIsoCurveAngles). About a curve instead of a point (ComputeCurve), the coordinates are
// (offset, arc length), a CurveCoordinates of their own.
#pragma once

#include "ExactGeodesic.h"
#include "GeodesicEngine.h"
#include "GeodesicUnfolding.h"
#include "SaddleVertexGraph.h"
#include "Status.h"
#include "SurfaceCurve.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

namespace gs
{

/// Coordinates about a curve (GeodesicPolarCoordinates::ComputeCurve), per vertex; NaN beyond the
/// radius (or unreachable).
struct CurveCoordinates
{
  /// delta: the signed geodesic distance to the curve, positive on the left of the curve's
  /// direction (with the outward normal up).
  std::vector<double> Offset;
  /// u in [0, 1]: the normalized arc length along the vertex's own offset curve (0 and 1 in the
  /// caps beyond the curve's ends).
  std::vector<double> ArcLength;
  double Length = 0.0; ///< the curve's length
};

/// Polar coordinates over one face, set up once for many points of it (a decal reads hundreds
/// per face where it subdivides): the corners' coordinates, the face unfolded (FaceUnfolding)
/// and, for each edge whose unfolded source is read, the corners' angle offsets from it.
/// PolarAt and LogMapAt give what the engine's (or the snapshot's) give at
/// SurfacePoint::InFace(face, bary), to the bit. Made by GeodesicPolarCoordinates::OnFace or
/// LogMapSnapshot::OnFace; it fills its offsets as it reads, so one thread uses it.
class FacePolarCoordinates
{
public:
  FacePolarCoordinates() = default;
  /// `cornerRho`, `cornerTheta`: the coordinates of the face's corners (rho not finite: beyond
  /// the radius, and PolarAt is false unless the source lies in the face).
  FacePolarCoordinates(const TriangleMesh& mesh, const SurfacePoint& source, double reference,
    double turn, int face, const std::array<double, 3>& cornerRho,
    const std::array<double, 3>& cornerTheta);
  int Face() const { return FaceId; }
  bool PolarAt(const std::array<double, 3>& bary, double& rho, double& theta) const;
  bool LogMapAt(const std::array<double, 3>& bary, Vec2& p) const;

private:
  const TriangleMesh* Mesh = nullptr;
  SurfacePoint Source;
  double Reference = 0.0, Turn = 0.0;
  int FaceId = -1;
  bool SourceFace = false; // the source lies in the face (or is a corner): straight lines
  bool Inside = false;     // PolarAt can answer
  FaceUnfolding Unfolding;
  double CornerTheta0 = 0.0;
  std::array<double, 3> CornerDelta{ {} }; // corner angles less corner 0's, wrapped
  std::array<double, 3> CornerTheta{ {} };
  // Per edge: the offsets that map the corners' unfolded directions from its source onto their
  // angles (Offset0: corner 0's; Delta: the others' less it, wrapped), once read.
  struct EdgeOffsets
  {
    bool Known = false;
    double Offset0 = 0.0;
    std::array<double, 3> Delta{ {} };
  };
  mutable EdgeOffsets Offsets[3];
};

/// The polar coordinates of a GeodesicPolarCoordinates::Compute, kept without the engine (its
/// per-mesh arrays): the vertices inside the radius, sorted, with the source and the angle
/// convention. PolarAt and LogMapAt give what the engine's give, to the bit.
struct LogMapSnapshot
{
  struct Entry
  {
    int Vertex;
    double Rho, Theta;
  };
  std::vector<Entry> Entries; ///< by vertex
  SurfacePoint Source;
  double Reference = 0.0, Turn = 0.0;
  bool PolarAt(const TriangleMesh& mesh, const SurfacePoint& q, double& rho, double& theta) const;
  bool LogMapAt(const TriangleMesh& mesh, const SurfacePoint& q, Vec2& p) const;
  /// The coordinates over face f, for many points of it.
  FacePolarCoordinates OnFace(const TriangleMesh& mesh, int f) const;
};

class GeodesicPolarCoordinates
{
public:
  // The mesh (and graph) must outlive this object. Without a graph: the exact engine. A graph
  // built for another mesh (another number of vertices) makes Compute and ComputeCurve fail.
  // `lengthScale`: the exact engine's tolerance scale (ExactGeodesicSolver; 0: the mesh's
  // bounding box diagonal; a piece of a partitioned surface passes the whole surface's), and
  // `meanEdgeLength` the length iso-curve angles and curve coordinates measure their spacings
  // and margins in (0: the mesh's mean edge length; a piece passes the whole surface's).
  explicit GeodesicPolarCoordinates(const TriangleMesh& mesh,
    const SaddleVertexGraph* graph = nullptr, double lengthScale = 0.0, double meanEdgeLength = 0.0);
  // How far beyond a chart of `radius` UseIsoCurveAngles reads the surface: its further exact
  // solve and its reference geodesic, with the mean edge length `meanEdge`.
  static double IsoCurveReach(double radius, double meanEdge)
  {
    return std::max(radius + 3.0 * meanEdge, 1.01 * radius + meanEdge);
  }

  // Coordinates about `source` of every vertex closer than `radius` (> 0; infinity: the whole
  // reachable surface). `referenceAngle` is theta's zero, as a tangent angle at the source (see
  // TangentAngle in GeodesicShooting.h; 0: the source's first edge). Fails for an invalid source,
  // radius or reference angle (then every vertex is outside, and ToSurface and
  // UseIsoCurveAngles fail until the next successful Compute).
  Status Compute(const SurfacePoint& source, double radius, double referenceAngle = 0.0);

  // Compute over every face that meets the geodesic disc of `radius` (so that the map reads
  // every point of the disc): the exact solve stops once the corners of every face that meets
  // the ball of that radius about the source (and is connected to the source's faces through
  // such faces) are final, at most radius + 1.01 times the mesh's longest edge. A single Compute
  // would need that bound everywhere, and on a mesh with long edges anywhere (a noisy scan)
  // it made every map cover 10-30 times the disc's area. Returns the largest rho computed. With
  // a graph: Compute to the bound.
  Result<double> ComputeCoveringDisc(const SurfacePoint& source, double radius, double referenceAngle = 0.0);

  // Coordinates about a curve (a polyline of surface points, consecutive points joined by the
  // straight surface path; the paper's Fig. 3 and 4): for every vertex closer than `radius` to
  // the curve, Offset = signed geodesic distance delta (positive on the left of the curve's
  // direction, with the outward normal up) and ArcLength = u in [0, 1], the normalized arc
  // length along the vertex's own offset curve (the level set of |delta| on its side), from
  // where it leaves the curve's start to where it reaches its end (the paper's Fig. 3); points
  // beyond the ends (in the caps) get 0 or 1. Exact solver from the curve sampled every
  // ExactCurveSampleSpacing edge (SurfaceCurve.h); each point's foot (where its geodesic leaves
  // the curve perpendicularly) is placed by the departure angle, exact for straight pieces on
  // developable surfaces. Fails for an empty or zero-length curve, an invalid point
  // (TriangleMesh::CheckPoints: "curve point k is invalid: ...") or radius. The coordinates
  // (Curve()) stay valid until the next Compute or ComputeCurve. In this mode Rho() and Theta()
  // are NaN, PolarAt is false, ToSurface and UseIsoCurveAngles fail (use CurveCoordinatesAt,
  // ToSurfaceFromCurve).
  Status ComputeCurve(const std::vector<SurfacePoint>& curve, double radius);
  bool IsCurve() const { return CurveMode; }
  // The coordinates of the last successful ComputeCurve.
  const CurveCoordinates& Curve() const { return CurveResult; }
  // Curve coordinates of any surface point (interpolated inside its face: both vary linearly
  // across a face beside a straight piece). False outside the radius or after Compute.
  bool CurveCoordinatesAt(const SurfacePoint& q, double& offset, double& arcLength) const;
  // The inverse map of curve coordinates: the surface point at signed offset delta from the
  // curve point at normalized arc length u along the curve, along the geodesic leaving it
  // perpendicularly (the exact inverse where the offset curves are parallel to the curve:
  // straight curves, circular arcs). Fails unless the last Compute or ComputeCurve was a
  // successful ComputeCurve, or for non-finite coordinates.
  Result<SurfacePoint> ToSurfaceFromCurve(double u, double delta) const;

  // Per vertex, NaN outside the radius (or unreachable).
  double Rho(int v) const { return VertexRho[v]; }
  double Theta(int v) const { return VertexTheta[v]; }
  // Vertices inside the radius, by increasing rho.
  const std::vector<int>& Inside() const { return InsideList; }

  // Coordinates of any surface point (interpolated inside its face: rho by geodesic triangle
  // unfolding, theta circularly; exact in the source's own face). False outside the radius.
  bool PolarAt(const SurfacePoint& q, double& rho, double& theta) const;
  // The same as a point of the tangent plane at the source: (rho cos a, rho sin a), with a the
  // true angle from the reference (theta times SourceAngleSum / 2 pi: not scaled at a cone or
  // saddle source), so that ShootGeodesic(source, reference + a, rho) draws it. False where
  // PolarAt is.
  bool LogMapAt(const SurfacePoint& q, Vec2& p) const;
  // The coordinates over face f, for many points of it (PolarAt is false everywhere after a
  // ComputeCurve or a failed Compute).
  FacePolarCoordinates OnFace(int f) const;
  // The coordinates of the last successful Compute, to keep (empty after ComputeCurve or a
  // failed Compute).
  LogMapSnapshot Snapshot() const;

  // The inverse map: the surface point at (rho, theta): geodesic shooting, or after
  // UseIsoCurveAngles, the point at the fraction theta / 2 pi along the level loop rho (the
  // source itself for rho <= 0). Fails unless the last Compute or ComputeCurve was a
  // successful Compute, or for non-finite coordinates.
  Result<SurfacePoint> ToSurface(double rho, double theta) const;

  // Full turn of raw tangent angles at the source (its angle sum, or 2 pi for a face point).
  double SourceAngleSum() const { return Turn; }

  // Replaces theta by the iso-curve arc-length angle (Section 3.3 of the paper): for each vertex,
  // 2 pi times the arc length along its own iso-distance curve (the level set of the piecewise
  // linear distance, traced face by face), counter-clockwise from where that curve crosses the
  // reference geodesic, over the curve's length. Vertices whose iso-curve is not a closed loop
  // (it meets the mesh boundary) or does not go round the source (it misses the reference
  // geodesic, e.g. a level set split around a limb) keep their
  // geodesic-direction angle; the count is returned. Fails, changing nothing, unless the last
  // Compute or ComputeCurve was a successful Compute. Unlike the geodesic direction, it does not
  // fold past saddles and cut loci wherever the level sets are single loops around the source
  // (tested on a bumpy sphere and a torus); on a plane it equals the polar angle. Costs one loop
  // trace per vertex (O(n sqrt n) for a patch of n vertices).
  Result<int> UseIsoCurveAngles();

private:
  // Compute, the exact solve stopping once `stopOnceFinal`'s vertices are final (if given).
  Status Solve(const SurfacePoint& source, double radius, double referenceAngle,
    const std::vector<int>* stopOnceFinal);
  std::vector<unsigned char> FaceSeen; // ComputeCoveringDisc's scratch (all zero between calls)
  double RawToTheta(double raw) const;
  // Curve mode: arc length along v's offset curve until the foot parameter reaches stopAt,
  // walking with the curve on the left or right; -1 if it cannot.
  double WalkOffsetCurve(int v, bool curveOnLeft, double stopAt) const;
  // ComputeCurve's steps after the solve from the curve's samples: each vertex's offset, arc
  // length, foot and distance from the foot's tangent line from its source sample (arc length,
  // tangent angle, straight run of each sample); the exact distance for the corners of the
  // faces the curve crosses (pieces longer than tiny); then u along each offset curve, and only
  // the vertices within the radius kept.
  void PlaceCurveFeet(const std::vector<double>& arc, const std::vector<double>& tangent,
    const std::vector<double>& runStart, const std::vector<double>& runEnd);
  void SnapCurveCorners(double tiny);
  void KeepWithinCurveRadius(double radius);
  SurfacePoint InverseIsoCurve(double rho, double theta) const;
  // Arc length along the iso-curve of v's level from v round to where it crosses the reference
  // geodesic, and the loop's length; false if it is not a closed loop or misses the reference.
  bool TraceIsoCurve(int v, const std::vector<std::vector<std::pair<Vec3, Vec3>>>& reference,
    double& toReference, double& length) const;

  const TriangleMesh& Mesh;
  double MeanEdge = 0.0; // (see the constructor)
  ExactGeodesicSolver Solver;
  std::unique_ptr<GeodesicEngine> GraphEngine; // point sources on the graph (null: exact)
  // Without a graph, charts reaching far over a large whole surface (not a piece of one): the
  // exact engine, in parts on threads (made at the first such chart).
  const bool WholeSurface;
  std::unique_ptr<GeodesicEngine> WideExact;
  GeodesicEngine* Engine = nullptr; // the last Compute's engine (null: Solver)
  // Iso-curve angles: the distances a few edges beyond the chart, from the solver or (a chart
  // solved in parts) the wide engine, as UseIsoCurveAngles last solved them.
  bool BeyondInParts = false;
  double BeyondRho(int v) const { return BeyondInParts ? WideExact->Distance(v) : Solver.Distance(v); }
  std::vector<int> InsideList;
  SurfacePoint Source;
  double Reference = 0.0;
  double Turn = 0.0;
  std::vector<double> VertexRho, VertexTheta; // per vertex (Compute)
  // Vertex v's coordinates (false beyond the radius), as PolarAt reads them.
  bool VertexCoordinates(int v, double& rho, double& theta) const
  {
    rho = VertexRho[v];
    theta = VertexTheta[v];
    return std::isfinite(rho);
  }
  bool CurveMode = false;
  bool Solved = false; // the last Compute or ComputeCurve succeeded
  bool IsoAngles = false;
  std::vector<CurvePiece> CurvePieces;
  std::vector<double> Foot;   // curve mode: arc length of each vertex's foot, unclamped
  std::vector<double> Across; // curve mode: signed offset from the foot's tangent line
  CurveCoordinates CurveResult; // ComputeCurve's
  Status GraphError;            // a graph of another mesh was given
};

} // namespace gs
