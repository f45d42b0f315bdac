// Geodesic polar coordinates about a curve: offset and arc length along each offset curve.
#include "GeodesicPolarCoordinatesImpl.h"

#include "GeodesicShooting.h"
#include "SurfaceCurve.h"
#include "GeodesicUnfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

namespace
{
// Samples within rounding of a vertex (a curve through mesh vertices) are that vertex: a face
// point a hair's breadth from a corner makes needle-thin windows.
void SnapSamplesToVertices(const TriangleMesh& mesh, std::vector<SurfacePoint>& samples)
{
  for (SurfacePoint& sample : samples)
  {
    for (int k = 0; k < 3 && !sample.IsVertex(); ++k)
    {
      if (sample.Bary[k] > 1.0 - 1e-7)
      {
        sample = SurfacePoint::AtVertex(mesh.Face(sample.Face)[k]);
      }
    }
  }
}

// The arc length of each sample SampleCurvePieces makes along `pieces`, and the curve's
// direction there (0 on a zero-length piece); `length` (0 on entry) becomes the curve's length.
void SampleArcs(const std::vector<CurvePiece>& pieces, double spacing, std::vector<double>& arc,
  std::vector<Vec3>& direction, double& length)
{
  for (const CurvePiece& piece : pieces)
  {
    const double pieceLength = Norm(piece.B - piece.A);
    const int steps = std::max(1, static_cast<int>(std::ceil(pieceLength / spacing)));
    for (int i = 0; i <= steps; ++i)
    {
      arc.push_back(length + pieceLength * i / steps);
      direction.push_back(piece.B - piece.A);
      if (pieceLength == 0.0)
      {
        break;
      }
    }
    length += pieceLength;
  }
}

// The curve's tangent angle at each sample. A zero-length piece (a point of the curve alone)
// takes the direction of its nearest neighbour along the curve. Then each direction becomes a
// tangent angle in the convention the solver uses for that sample (its face's frame, or the fan
// of the vertex it is). (Pieces shorter than `tiny`, a millionth of an edge, e.g. the tracer's
// steps off a vertex, count as points: their direction is noise.)
std::vector<double> SampleTangents(const TriangleMesh& mesh,
  const std::vector<SurfacePoint>& samples, const std::vector<Vec3>& direction, double tiny)
{
  std::vector<double> tangent(samples.size(), NaN);
  for (std::size_t i = 0; i < samples.size(); ++i)
  {
    Vec3 d = direction[i];
    for (std::size_t j = 1; j < samples.size() && !(Norm(d) > tiny); ++j)
    {
      if (i + j < samples.size() && Norm(direction[i + j]) > tiny)
        d = direction[i + j];
      else if (j <= i && Norm(direction[i - j]) > tiny)
        d = direction[i - j];
    }
    const SurfacePoint at = samples[i].IsVertex()
      ? samples[i]
      : SurfacePoint::InFace(samples[i].Face, 1.0 / 3, 1.0 / 3, 1.0 / 3);
    tangent[i] = TangentAngle(mesh, at, d);
  }
  return tangent;
}

// Straight runs of the curve: consecutive samples whose directions agree. Each sample gets the
// arc lengths of its run's first and last samples (runStart and runEnd, sized by the caller). A
// foot that projects past the end of its run, where the curve turns, is the turning point
// itself (the offset curve goes round it on the outer side).
void StraightRuns(const std::vector<Vec3>& direction, const std::vector<double>& arc, double tiny,
  std::vector<double>& runStart, std::vector<double>& runEnd)
{
  const std::size_t n = runStart.size();
  std::size_t first = 0;
  Vec3 runDirection;
  for (std::size_t i = 0; i <= n; ++i)
  {
    bool turns = i == n;
    if (!turns && Norm(direction[i]) > tiny)
    {
      const Vec3 u = direction[i] / Norm(direction[i]);
      turns = Norm(runDirection) > 0.0 && Norm(Cross(u, runDirection)) + (Dot(u, runDirection) < 0.0 ? 1.0 : 0.0) > 1e-9;
      if (!turns)
      {
        runDirection = u;
      }
    }
    if (turns)
    {
      // Samples first .. i-1 form a run from arc[first] to arc[i-1].
      for (std::size_t j = first; j < i; ++j)
      {
        runStart[j] = arc[first];
        runEnd[j] = arc[i - 1];
      }
      first = i;
      if (i < n)
      {
        runDirection = direction[i] / Norm(direction[i]);
      }
    }
  }
}
} // namespace

Status GeodesicPolarCoordinates::ComputeCurve(const std::vector<SurfacePoint>& curve, double radius)
{
  for (int v : InsideList)
  {
    VertexRho[v] = NaN;
    VertexTheta[v] = NaN;
  }
  InsideList.clear();
  CurveMode = true;
  Solved = false;
  CurveResult.Length = 0.0;
  CurveResult.Offset.assign(Mesh.NumberOfVertices(), NaN);
  CurveResult.ArcLength.assign(Mesh.NumberOfVertices(), NaN);
  Foot.assign(Mesh.NumberOfVertices(), NaN);
  Across.assign(Mesh.NumberOfVertices(), NaN);
  if (!GraphError.Ok())
  {
    return GraphError;
  }
  if (!(radius > 0.0))
  {
    return RadiusError(radius);
  }
  if (curve.empty())
  {
    return Status::Error("the curve has no point");
  }
  if (const Status valid = Mesh.CheckPoints(curve, "curve point"); !valid.Ok())
  {
    return valid;
  }
  CurvePieces = TraceSurfaceCurve(Mesh, curve);
  // Samples along the pieces (as SampleCurvePieces makes them), with their arc length and the
  // curve's tangent angle there.
  const double spacing = ExactCurveSampleSpacing * MeanEdge;
  std::vector<SurfacePoint> samples = SampleCurvePieces(Mesh, CurvePieces, spacing);
  SnapSamplesToVertices(Mesh, samples);
  std::vector<double> arc;
  std::vector<Vec3> direction;
  SampleArcs(CurvePieces, spacing, arc, direction, CurveResult.Length);
  if (!(CurveResult.Length > 0.0) || arc.size() != samples.size())
  {
    return Status::Error("the curve has zero length");
  }
  const double tiny = 1e-6 * MeanEdge;
  const std::vector<double> tangent = SampleTangents(Mesh, samples, direction, tiny);
  std::vector<double> runStart(samples.size(), 0.0), runEnd(samples.size(), CurveResult.Length);
  StraightRuns(direction, arc, tiny, runStart, runEnd);
  // A few edges beyond the radius, so that the offset curves near the radius can be traced.
  ExactGeodesicOptions options;
  options.MaximumDistance = std::isfinite(radius) ? radius + 3.0 * MeanEdge : 0.0;
  if (const Status solved = Solver.Solve(samples, options); !solved.Ok())
  {
    return solved;
  }
  InsideList = Solver.FinalVertices();
  PlaceCurveFeet(arc, tangent, runStart, runEnd);
  SnapCurveCorners(tiny);
  KeepWithinCurveRadius(radius);
  Solved = true;
  return Status();
}

void GeodesicPolarCoordinates::PlaceCurveFeet(const std::vector<double>& arc,
  const std::vector<double>& tangent, const std::vector<double>& runStart,
  const std::vector<double>& runEnd)
{
  for (int v : InsideList)
  {
    const double d = Solver.Distance(v);
    const int root = Solver.SourceOf(v);
    const double departure = Solver.DepartureAngle(v);
    // Left of the curve when the geodesic leaves its foot counter-clockwise from the tangent
    // (angles in the foot face's frame: samples are face points of their piece's face).
    if (root < 0)
    {
      CurveResult.Offset[v] = CurveResult.ArcLength[v] = NaN;
      continue;
    }
    double side = 1.0, along = 0.0, across = d;
    if (std::isfinite(departure) && std::isfinite(tangent[root]))
    {
      // In the foot's tangent plane the vertex lies at angle alpha from the curve's direction:
      // the foot of the perpendicular is d cos(alpha) further along (exact for a straight piece,
      // removing the samples' spacing from both coordinates), at distance d |sin(alpha)|.
      const double alpha = departure - tangent[root];
      side = std::sin(alpha) < 0.0 ? -1.0 : 1.0;
      along = d * std::cos(alpha);
      across = d * std::abs(std::sin(alpha));
    }
    double foot = arc[root] + along;
    // Past a turn of the curve: the foot is the turning point, the offset the distance to it.
    if ((foot > runEnd[root] && runEnd[root] < CurveResult.Length) ||
      (foot < runStart[root] && runStart[root] > 0.0))
    {
      foot = foot > runEnd[root] ? runEnd[root] : runStart[root];
      across = d;
    }
    // Beyond an end of the curve the closest point is that end: the distance itself.
    const bool cap = foot < 0.0 || foot > CurveResult.Length;
    CurveResult.Offset[v] = d == 0.0 ? 0.0 : side * (cap ? d : across);
    CurveResult.ArcLength[v] = std::min(1.0, std::max(0.0, foot / CurveResult.Length));
    Foot[v] = foot; // unclamped: continues past the ends along the end's direction
    Across[v] = d == 0.0 ? 0.0 : side * across; // offset from the (extended) curve's line
  }
}

void GeodesicPolarCoordinates::SnapCurveCorners(double tiny)
{
  // Corners of the faces the curve crosses: the exact straight distance to the piece inside the
  // face (the samples are 1/16 edge apart: close to the curve that matters).
  double start = 0.0;
  for (const CurvePiece& piece : CurvePieces)
  {
    const Vec3 ab = piece.B - piece.A;
    const double length = Norm(ab);
    const Vec3 n = Mesh.FaceNormal(piece.Face);
    // (A piece of a millionth of an edge is a point: its direction cannot tell the side.)
    for (int k = 0; length > tiny && k < 3; ++k)
    {
      const int v = Mesh.Face(piece.Face)[k];
      if (!std::isfinite(CurveResult.Offset[v]))
      {
        continue;
      }
      const Vec3 p = Mesh.Position(v);
      const double t = std::min(1.0, std::max(0.0, Dot(p - piece.A, ab) / (length * length)));
      const Vec3 foot = piece.A + ab * t;
      const double d = Norm(p - foot);
      if (d < std::abs(CurveResult.Offset[v]))
      {
        CurveResult.Offset[v] = Dot(Cross(ab, p - foot), n) < 0.0 ? -d : d;
        CurveResult.ArcLength[v] =
          std::min(1.0, std::max(0.0, (start + t * length) / CurveResult.Length));
        // (A foot clamped to the piece's end keeps the solver's unclamped value.)
        if (t > 0.0 && t < 1.0)
        {
          Foot[v] = start + t * length;
          Across[v] = CurveResult.Offset[v];
        }
      }
    }
    start += length;
  }
}

void GeodesicPolarCoordinates::KeepWithinCurveRadius(double radius)
{
  // u along each offset curve (the paper's Fig. 3): for every vertex beside the curve, the arc
  // length along its own offset curve (the level set of |delta| on its side) back to where its
  // foot reaches the curve's start, over the length between the two ends.
  std::vector<double> offsetU(InsideList.size(), NaN);
  for (std::size_t i = 0; i < InsideList.size(); ++i)
  {
    const int v = InsideList[i];
    if (!(std::abs(CurveResult.Offset[v]) <= radius) || CurveResult.Offset[v] == 0.0 ||
      !(CurveResult.ArcLength[v] > 0.0 && CurveResult.ArcLength[v] < 1.0))
    {
      continue;
    }
    // Walking with the curve on the left runs towards the start for points on the left.
    const double towardsStart = WalkOffsetCurve(v, CurveResult.Offset[v] > 0.0, 0.0);
    const double towardsEnd = WalkOffsetCurve(v, CurveResult.Offset[v] < 0.0, 1.0);
    if (towardsStart >= 0.0 && towardsEnd >= 0.0 && towardsStart + towardsEnd > 0.0)
    {
      offsetU[i] = towardsStart / (towardsStart + towardsEnd);
    }
  }
  // Keep what lies within the radius.
  std::vector<int> inside;
  for (std::size_t i = 0; i < InsideList.size(); ++i)
  {
    const int v = InsideList[i];
    if (std::abs(CurveResult.Offset[v]) <= radius)
    {
      if (std::isfinite(offsetU[i]))
      {
        CurveResult.ArcLength[v] = offsetU[i];
      }
      inside.push_back(v);
    }
    else
    {
      CurveResult.Offset[v] = CurveResult.ArcLength[v] = NaN;
    }
  }
  InsideList = std::move(inside);
}

double GeodesicPolarCoordinates::WalkOffsetCurve(int v, bool curveOnLeft, double stopAt) const
{
  // The offset curve through v, traced face by face like the iso-curves about a point
  // (vertices at exactly the level count as above), until the interpolated foot parameter
  // reaches `stopAt` (0: the start, 1: the end). -1 when it cannot (a boundary, back at v).
  // The level function is the offset measured positive on v's side (signed, so that it stays
  // linear across the curve, where |delta| has a kink).
  // Beyond the curve's ends the offset from the extended end lines keeps the level sets
  // straight up to where they are cut off.
  const double side = CurveResult.Offset[v] < 0.0 ? -1.0 : 1.0;
  const double c = side * Across[v];
  auto level = [&](int w) { return w == v ? c : side * Across[w]; };
  auto below = [&](int w) { return w != v && side * Across[w] < c; };
  auto valid = [&](int w) { return w == v || (std::isfinite(Across[w]) && std::isfinite(Foot[w])); };
  // The foot's arc length, unclamped: linear across the ends of straight curves, so that where
  // an offset curve leaves the curve's span is found exactly.
  const double end = stopAt * CurveResult.Length;
  int h = -1;
  for (int out : Mesh.OutgoingHalfedges(v))
  {
    const int a = Mesh.Destination(out), b = Mesh.Opposite(out);
    if (valid(a) && valid(b) && (curveOnLeft ? (!below(a) && below(b)) : (below(a) && !below(b))))
    {
      h = TriangleMesh::Next(out);
      break;
    }
  }
  if (h < 0)
  {
    return -1.0;
  }
  Vec3 x = Mesh.Position(v);
  double ux = Foot[v], length = 0.0;
  const int maxSteps = 4 * Mesh.NumberOfFaces() + 8;
  for (int step = 0; step < maxSteps; ++step)
  {
    const int a = Mesh.Origin(h), b = Mesh.Destination(h);
    if (!valid(a) || !valid(b) || (curveOnLeft ? b : a) == v)
    {
      return -1.0; // left the solved band, or back at the start without reaching an end
    }
    const double la = level(a), lb = level(b);
    const double t = std::abs(lb - la) > 0.0 ? std::min(1.0, std::max(0.0, (c - la) / (lb - la))) : 0.5;
    const Vec3 y = Mesh.Position(a) + (Mesh.Position(b) - Mesh.Position(a)) * t;
    const double uy = Foot[a] + (Foot[b] - Foot[a]) * t;
    const double piece = Norm(y - x);
    if ((stopAt == 0.0 && uy <= end) || (stopAt == 1.0 && uy >= end))
    {
      // The end is reached within this piece: where the foot meets it.
      const double f = std::abs(uy - ux) > 0.0 ? std::min(1.0, std::abs(end - ux) / std::abs(uy - ux)) : 1.0;
      return length + f * piece;
    }
    length += piece;
    x = y;
    ux = uy;
    const int twin = Mesh.Twin(h);
    if (twin < 0)
    {
      return -1.0;
    }
    const int e1 = TriangleMesh::Next(twin), e2 = TriangleMesh::Prev(twin);
    const int third = Mesh.Destination(e1);
    if (!valid(third))
    {
      return -1.0;
    }
    h = below(third) == below(Mesh.Origin(e1)) ? e2 : e1;
  }
  return -1.0;
}

bool GeodesicPolarCoordinates::CurveCoordinatesAt(
  const SurfacePoint& q, double& offset, double& arcLength) const
{
  offset = arcLength = NaN;
  if (!CurveMode)
  {
    return false;
  }
  // (Offset, ArcLength) inside a face: both vary linearly across a face beside a straight
  // piece; interpolated.
  if (q.IsVertex())
  {
    offset = CurveResult.Offset[q.Vertex];
    arcLength = CurveResult.ArcLength[q.Vertex];
    return std::isfinite(offset);
  }
  const auto& t = Mesh.Face(q.Face);
  if (!std::isfinite(CurveResult.Offset[t[0]]) || !std::isfinite(CurveResult.Offset[t[1]]) ||
    !std::isfinite(CurveResult.Offset[t[2]]))
  {
    return false;
  }
  offset = q.Bary[0] * CurveResult.Offset[t[0]] + q.Bary[1] * CurveResult.Offset[t[1]] +
    q.Bary[2] * CurveResult.Offset[t[2]];
  arcLength = q.Bary[0] * CurveResult.ArcLength[t[0]] + q.Bary[1] * CurveResult.ArcLength[t[1]] +
    q.Bary[2] * CurveResult.ArcLength[t[2]];
  return true;
}


Result<SurfacePoint> GeodesicPolarCoordinates::ToSurfaceFromCurve(double u, double delta) const
{
  if (!Solved || !CurveMode)
  {
    return Status::Error("the inverse map of curve coordinates needs the coordinates about a "
                         "curve (a successful ComputeCurve)");
  }
  if (!std::isfinite(u) || !std::isfinite(delta))
  {
    return Status::Error("curve coordinates (" + std::to_string(u) + ", " +
      std::to_string(delta) + ") are not finite");
  }
  // The curve point at arc length u L, and the curve's direction there.
  const double target = std::min(1.0, std::max(0.0, u)) * CurveResult.Length;
  const double tiny = 1e-6 * MeanEdge;
  double start = 0.0;
  const CurvePiece* at = nullptr;
  double t = 0.0;
  for (const CurvePiece& piece : CurvePieces)
  {
    const double length = Norm(piece.B - piece.A);
    if (length > tiny)
    {
      at = &piece;
      t = std::min(1.0, std::max(0.0, (target - start) / length));
      if (target <= start + length)
      {
        break;
      }
    }
    start += length;
  }
  if (!at)
  {
    return Status::Error("the curve has no piece longer than a millionth of an edge");
  }
  const Vec3 x = at->A + (at->B - at->A) * t;
  SurfacePoint foot = SurfacePoint::InFace(at->Face, 0, 0, 0);
  foot.Bary = Mesh.ClampedBarycentric(at->Face, x);
  if (delta == 0.0)
  {
    return foot;
  }
  // Perpendicular to the curve: a quarter turn left of its direction for delta > 0.
  const double tangentAngle = TangentAngle(Mesh, foot, at->B - at->A);
  const double quarter = 0.5 * 3.14159265358979323846;
  return ShootGeodesic(Mesh, foot, tangentAngle + (delta > 0.0 ? quarter : -quarter), std::abs(delta)).End;
}

} // namespace gs
