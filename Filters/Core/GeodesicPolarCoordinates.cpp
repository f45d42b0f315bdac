#include "GeodesicPolarCoordinates.h"

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
constexpr double TwoPi = 6.28318530717958647692;
const double NaN = std::numeric_limits<double>::quiet_NaN();

double Wrap(double a)
{
  a = std::fmod(a, TwoPi);
  return a < 0.0 ? a + TwoPi : a;
}

Status RadiusError(double radius)
{
  return Status::Error("Radius must be > 0 (it is " + std::to_string(radius) + ")");
}

} // namespace

GeodesicPolarCoordinates::GeodesicPolarCoordinates(const TriangleMesh& mesh, const SaddleVertexGraph* graph)
  : Mesh(mesh)
  , Solver(mesh)
{
  GraphError = graph ? graph->CheckMesh(mesh) : Status();
  if (graph && GraphError.Ok())
  {
    Svg.reset(new SVGGeodesicSolver(mesh, *graph));
  }
  VertexRho.assign(Mesh.NumberOfVertices(), NaN);
  VertexTheta.assign(Mesh.NumberOfVertices(), NaN);
}

double GeodesicPolarCoordinates::RawToTheta(double raw) const
{
  return Wrap((raw - Reference) * TwoPi / Turn);
}

namespace
{
// Distance from p to the triangle (a, b, c) (the closest point by its Voronoi regions).
double PointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = Dot(ab, ap), d2 = Dot(ac, ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    return Norm(ap);
  }
  const Vec3 bp = p - b;
  const double d3 = Dot(ab, bp), d4 = Dot(ac, bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    return Norm(bp);
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    return Norm(p - (a + ab * (d1 / (d1 - d3))));
  }
  const Vec3 cp = p - c;
  const double d5 = Dot(ab, cp), d6 = Dot(ac, cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    return Norm(cp);
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    return Norm(p - (a + ac * (d2 / (d2 - d6))));
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
  {
    return Norm(p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)))));
  }
  const double denominator = 1.0 / (va + vb + vc);
  return Norm(p - (a + ab * (vb * denominator) + ac * (vc * denominator)));
}
} // namespace

Result<double> GeodesicPolarCoordinates::ComputeCoveringDisc(
  const SurfacePoint& source, double radius, double referenceAngle)
{
  if (!(radius > 0.0) || !Mesh.CheckPoint(source).Ok())
  {
    // (Compute's own message: the radius plus a margin would pass a negative radius.)
    if (Status refused = Compute(source, radius, referenceAngle); !refused.Ok())
    {
      return refused;
    }
  }
  const double bound = radius + 1.01 * Mesh.LongestEdgeLength();
  if (Svg || !std::isfinite(radius)) // (a graph engine, or the whole surface)
  {
    if (Status computed = Compute(source, bound, referenceAngle); !computed.Ok())
    {
      return computed;
    }
    return double(bound);
  }
  // The faces that may meet the geodesic disc: those meeting the ball of `radius` about the
  // source (no geodesic is shorter than the chord), connected to the source's faces across
  // edges (so are the faces a geodesic from the source crosses on its way into the disc).
  const Vec3 x = Mesh.Position(source);
  std::vector<int> faces, seen; // (seen: the faces to unmark)
  auto visit = [&](int f) {
    if (FaceSeen[f])
    {
      return;
    }
    FaceSeen[f] = 1;
    seen.push_back(f);
    const auto& c = Mesh.Face(f);
    if (PointTriangleDistance(x, Mesh.Position(c[0]), Mesh.Position(c[1]), Mesh.Position(c[2])) < radius)
    {
      faces.push_back(f);
    }
  };
  FaceSeen.resize(Mesh.NumberOfFaces(), 0);
  if (source.IsVertex())
  {
    Mesh.ForEachOutgoingHalfedge(source.Vertex, [&](int h) { visit(h / 3); });
  }
  else
  {
    visit(source.Face);
  }
  for (std::size_t k = 0; k < faces.size(); ++k)
  {
    for (int e = 0; e < 3; ++e)
    {
      const int twin = Mesh.Twin(3 * faces[k] + e);
      if (twin >= 0)
      {
        visit(twin / 3);
      }
    }
  }
  std::vector<int> corners;
  for (int f : faces)
  {
    const auto& c = Mesh.Face(f);
    corners.insert(corners.end(), c.begin(), c.end());
  }
  for (int f : seen)
  {
    FaceSeen[f] = 0;
  }
  if (Status computed = Solve(source, bound, referenceAngle, &corners); !computed.Ok())
  {
    return computed;
  }
  double reached = 0.0;
  for (int v : InsideList)
  {
    reached = std::max(reached, VertexRho[v]);
  }
  return reached;
}

Status GeodesicPolarCoordinates::Compute(
  const SurfacePoint& source, double radius, double referenceAngle)
{
  return Solve(source, radius, referenceAngle, nullptr);
}

Status GeodesicPolarCoordinates::Solve(const SurfacePoint& source, double radius,
  double referenceAngle, const std::vector<int>* stopOnceFinal)
{
  for (int v : InsideList)
  {
    VertexRho[v] = NaN;
    VertexTheta[v] = NaN;
  }
  InsideList.clear();
  CurveMode = false;
  IsoAngles = false;
  Solved = false;
  if (!GraphError.Ok())
  {
    return GraphError;
  }
  if (!(radius > 0.0))
  {
    return RadiusError(radius);
  }
  if (!std::isfinite(referenceAngle))
  {
    return Status::Error("the reference angle is not finite");
  }
  const double maxDistance = std::isfinite(radius) ? radius : 0.0;
  Turn = source.IsVertex() && source.Vertex >= 0 && source.Vertex < Mesh.NumberOfVertices()
    ? Mesh.TotalAngle(source.Vertex)
    : TwoPi;
  Reference = referenceAngle;
  if (Svg)
  {
    SVGSolveOptions options;
    options.MaximumDistance = maxDistance;
    options.Angles = true;
    if (const Status solved = Svg->Solve({ source }, options); !solved.Ok())
    {
      return solved;
    }
    for (int v : Svg->Reached())
    {
      if (Svg->Distance(v) <= radius)
      {
        InsideList.push_back(v);
      }
    }
    std::sort(InsideList.begin(), InsideList.end(), [&](int a, int b) {
      return Svg->Distance(a) < Svg->Distance(b) || (Svg->Distance(a) == Svg->Distance(b) && a < b);
    });
  }
  else
  {
    ExactGeodesicOptions options;
    options.MaximumDistance = maxDistance;
    options.StopOnceFinal = stopOnceFinal;
    if (const Status solved = Solver.Solve({ source }, options); !solved.Ok())
    {
      return solved;
    }
    InsideList = Solver.FinalVertices();
  }
  Source = source;
  for (int v : InsideList)
  {
    VertexRho[v] = Svg ? Svg->Distance(v) : Solver.Distance(v);
    const double raw = Svg ? Svg->DepartureAngle(v) : Solver.DepartureAngle(v);
    // The source vertex itself is the pole: angle 0 by convention.
    VertexTheta[v] = std::isfinite(raw) ? RawToTheta(raw) : 0.0;
  }
  Solved = true;
  return Status();
}

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
  const std::vector<CurvePiece>& pieces = CurvePieces;
  // Samples along the pieces (as SampleCurvePieces makes them), with their arc length and the
  // curve's tangent angle there.
  const double spacing = ExactCurveSampleSpacing * Mesh.MeanEdgeLength();
  std::vector<SurfacePoint> samples = SampleCurvePieces(Mesh, pieces, spacing);
  // Samples within rounding of a vertex (a curve through mesh vertices) are that vertex: a face
  // point a hair's breadth from a corner makes needle-thin windows.
  for (SurfacePoint& sample : samples)
  {
    for (int k = 0; k < 3 && !sample.IsVertex(); ++k)
    {
      if (sample.Bary[k] > 1.0 - 1e-7)
      {
        sample = SurfacePoint::AtVertex(Mesh.Face(sample.Face)[k]);
      }
    }
  }
  std::vector<double> arc;
  std::vector<Vec3> direction; // the curve's direction at each sample (0 on a zero-length piece)
  for (const CurvePiece& piece : pieces)
  {
    const double length = Norm(piece.B - piece.A);
    const int steps = std::max(1, static_cast<int>(std::ceil(length / spacing)));
    for (int i = 0; i <= steps; ++i)
    {
      arc.push_back(CurveResult.Length + length * i / steps);
      direction.push_back(piece.B - piece.A);
      if (length == 0.0)
      {
        break;
      }
    }
    CurveResult.Length += length;
  }
  if (!(CurveResult.Length > 0.0) || arc.size() != samples.size())
  {
    return Status::Error("the curve has zero length");
  }
  // A zero-length piece (a point of the curve alone) takes the direction of its nearest
  // neighbour along the curve. Then each direction becomes a tangent angle in the convention
  // the solver uses for that sample (its face's frame, or the fan of the vertex it is).
  // (Pieces shorter than a millionth of an edge, e.g. the tracer's steps off a vertex, count as
  // points: their direction is noise.)
  const double tiny = 1e-6 * Mesh.MeanEdgeLength();
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
    tangent[i] = TangentAngle(Mesh, at, d);
  }
  // A few edges beyond the radius, so that the offset curves near the radius can be traced.
  // Straight runs of the curve: consecutive samples whose directions agree. A foot that
  // projects past the end of its run, where the curve turns, is the turning point itself (the
  // offset curve goes round it on the outer side).
  std::vector<double> runStart(samples.size(), 0.0), runEnd(samples.size(), CurveResult.Length);
  {
    std::size_t first = 0;
    Vec3 runDirection;
    for (std::size_t i = 0; i <= samples.size(); ++i)
    {
      bool turns = i == samples.size();
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
        if (i < samples.size())
        {
          runDirection = direction[i] / Norm(direction[i]);
        }
      }
    }
  }
  ExactGeodesicOptions options;
  options.MaximumDistance = std::isfinite(radius) ? radius + 3.0 * Mesh.MeanEdgeLength() : 0.0;
  if (const Status solved = Solver.Solve(samples, options); !solved.Ok())
  {
    return solved;
  }
  InsideList = Solver.FinalVertices();
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
  // Corners of the faces the curve crosses: the exact straight distance to the piece inside the
  // face (the samples are 1/16 edge apart: close to the curve that matters).
  double start = 0.0;
  for (const CurvePiece& piece : pieces)
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
  Solved = true;
  return Status();
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

namespace
{
// PolarAt of an engine or of a snapshot: `values(v, rho, theta)` gives vertex v's coordinates
// (false outside the radius); the rest as GeodesicPolarCoordinates::PolarAt says.
template <class Values>
bool PolarAtImpl(const TriangleMesh& mesh, const SurfacePoint& source, double reference, double turn,
  const SurfacePoint& q, double& rho, double& theta, const Values& values)
{
  rho = theta = NaN;
  auto rawToTheta = [reference, turn](double raw) { return Wrap((raw - reference) * TwoPi / turn); };
  if (q.IsVertex())
  {
    return values(q.Vertex, rho, theta);
  }
  const auto& t = mesh.Face(q.Face);
  const Vec3 x = mesh.Interpolate(q.Face, q.Bary);
  const bool sourceFace = source.IsVertex()
    ? (t[0] == source.Vertex || t[1] == source.Vertex || t[2] == source.Vertex)
    : source.Face == q.Face;
  if (sourceFace)
  {
    // Straight inside the face: exact.
    const Vec3 s = mesh.Position(source);
    rho = Norm(x - s);
    if (rho == 0.0)
    {
      theta = 0.0;
      return true;
    }
    // The tangent angle at the source of the direction towards x, measured in x's face.
    const double raw = TangentAngle(mesh, source, x - s);
    theta = std::isfinite(raw) ? rawToTheta(raw) : 0.0;
    return true;
  }
  double cornerRho[3], cornerTheta[3];
  for (int k = 0; k < 3; ++k)
  {
    if (!values(t[k], cornerRho[k], cornerTheta[k]))
    {
      rho = theta = NaN;
      return false;
    }
  }
  const UnfoldedTriangle u =
    UnfoldTriangle(mesh, q.Face, q.Bary, { { cornerRho[0], cornerRho[1], cornerRho[2] } });
  rho = u.Distance;
  // Theta: in the unfolding, the direction from the unfolded source to q, turned by the offset
  // that maps the corners' unfolded directions onto their angles (the same for all corners on a
  // developable surface; averaged circularly otherwise). Without an unfolded source, the corner
  // angles are interpolated.
  double sum = 0.0;
  if (u.FromEdge)
  {
    const Vec2 toQ = u.Point - u.Source;
    double offset0 = 0.0;
    for (int k = 0; k < 3; ++k)
    {
      const Vec2 c = u.Corners[k] - u.Source;
      // Angles in the unfolding are true angles at the source: scale them like the raw ones.
      const double o = cornerTheta[k] - std::atan2(c.y, c.x) * TwoPi / turn;
      if (k == 0)
      {
        offset0 = o;
      }
      double d = o - offset0;
      d -= TwoPi * std::round(d / TwoPi);
      sum += q.Bary[k] * d;
    }
    theta = Wrap(offset0 + sum + std::atan2(toQ.y, toQ.x) * TwoPi / turn);
    return true;
  }
  for (int k = 0; k < 3; ++k)
  {
    double d = cornerTheta[k] - cornerTheta[0];
    d -= TwoPi * std::round(d / TwoPi);
    sum += q.Bary[k] * d;
  }
  theta = Wrap(cornerTheta[0] + sum);
  return true;
}

// The log map's point of polar coordinates (rho, theta) (theta scaled to the source's total angle).
Vec2 LogMapFromPolar(double rho, double theta, double turn)
{
  const double raw = theta * (turn / TwoPi);
  return Vec2{ rho * std::cos(raw), rho * std::sin(raw) };
}
} // namespace

bool GeodesicPolarCoordinates::PolarAt(const SurfacePoint& q, double& rho, double& theta) const
{
  if (CurveMode)
  {
    rho = theta = NaN;
    return false; // curve coordinates: CurveCoordinatesAt
  }
  return PolarAtImpl(Mesh, Source, Reference, Turn, q, rho, theta, [this](int v, double& r, double& a) {
    r = VertexRho[v];
    a = VertexTheta[v];
    return std::isfinite(r);
  });
}

bool GeodesicPolarCoordinates::LogMapAt(const SurfacePoint& q, Vec2& p) const
{
  double rho = 0.0, theta = 0.0;
  if (!PolarAt(q, rho, theta))
  {
    return false;
  }
  p = LogMapFromPolar(rho, theta, Turn);
  return true;
}

LogMapSnapshot GeodesicPolarCoordinates::Snapshot() const
{
  LogMapSnapshot s;
  if (CurveMode || !Solved)
  {
    return s;
  }
  s.Source = Source;
  s.Reference = Reference;
  s.Turn = Turn;
  s.Entries.reserve(InsideList.size());
  for (int v : InsideList)
  {
    s.Entries.push_back({ v, VertexRho[v], VertexTheta[v] });
  }
  std::sort(s.Entries.begin(), s.Entries.end(),
    [](const LogMapSnapshot::Entry& a, const LogMapSnapshot::Entry& b) { return a.Vertex < b.Vertex; });
  return s;
}

bool LogMapSnapshot::PolarAt(const TriangleMesh& mesh, const SurfacePoint& q, double& rho, double& theta) const
{
  if (Entries.empty())
  {
    rho = theta = NaN;
    return false;
  }
  return PolarAtImpl(mesh, Source, Reference, Turn, q, rho, theta, [this](int v, double& r, double& a) {
    const auto it = std::lower_bound(Entries.begin(), Entries.end(), v,
      [](const Entry& e, int vertex) { return e.Vertex < vertex; });
    if (it == Entries.end() || it->Vertex != v || !std::isfinite(it->Rho))
    {
      r = a = NaN;
      return false;
    }
    r = it->Rho;
    a = it->Theta;
    return true;
  });
}

bool LogMapSnapshot::LogMapAt(const TriangleMesh& mesh, const SurfacePoint& q, Vec2& p) const
{
  double rho = 0.0, theta = 0.0;
  if (!PolarAt(mesh, q, rho, theta))
  {
    return false;
  }
  p = LogMapFromPolar(rho, theta, Turn);
  return true;
}

namespace
{
// Whether segments [p, q] and [a, b], lying in one face's plane with normal n, cross; the
// crossing's parameter along [p, q] in t.
bool SegmentsCross(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& n, double& t)
{
  const Vec3 r = q - p, s = b - a;
  const double den = Dot(Cross(r, s), n);
  if (den == 0.0)
  {
    return false;
  }
  t = Dot(Cross(a - p, s), n) / den;
  const double u = Dot(Cross(a - p, r), n) / den;
  return t >= 0.0 && t <= 1.0 && u >= 0.0 && u <= 1.0;
}
} // namespace

bool GeodesicPolarCoordinates::TraceIsoCurve(int v,
  const std::vector<std::vector<std::pair<Vec3, Vec3>>>& reference, double& toReference,
  double& length) const
{
  const double c = VertexRho[v];
  // Distances just beyond the radius come from an exact solve a few edges further.
  auto rho = [&](int w) { return std::isfinite(VertexRho[w]) ? VertexRho[w] : Solver.Distance(w); };
  // Below the level: strictly closer than v (vertices at exactly the level count as above; v
  // itself is where the loop starts and ends).
  auto below = [&](int w) { return w != v && rho(w) < c; };
  // Point on half-edge h where the level is reached (one end below, the other above).
  auto crossing = [&](int h) {
    const int a = Mesh.Origin(h), b = Mesh.Destination(h);
    const double ra = a == v ? c : rho(a), rb = b == v ? c : rho(b);
    const double t = std::isfinite(rb) && std::abs(rb - ra) > 0.0 ? (c - ra) / (rb - ra) : 1.0;
    return Mesh.Position(a) + (Mesh.Position(b) - Mesh.Position(a)) * std::min(1.0, std::max(0.0, t));
  };
  // Start: the face around v whose far edge goes from above to below counter-clockwise, so that
  // the walk keeps the source (below) on its left.
  int h0 = -1;
  for (int h : Mesh.OutgoingHalfedges(v))
  {
    const int a = Mesh.Destination(h), b = Mesh.Opposite(h);
    if (!below(a) && below(b))
    {
      h0 = TriangleMesh::Next(h); // edge a -> b, crossed from v
      break;
    }
  }
  if (h0 < 0)
  {
    return false;
  }
  Vec3 x = Mesh.Position(v);
  int h = h0; // the edge the walk leaves its current face through
  length = 0.0;
  toReference = -1.0;
  const int maxSteps = 4 * Mesh.NumberOfFaces() + 8;
  for (int step = 0; step < maxSteps; ++step)
  {
    const int f = h / 3;
    // Every edge the walk leaves through runs from above to below; when its upper end is v, the
    // level is reached at v itself: the loop is closed.
    const bool closing = Mesh.Origin(h) == v && step > 0;
    const Vec3 y = closing ? Mesh.Position(v) : crossing(h);
    const double piece = Norm(y - x);
    double t = 0.0;
    for (const auto& seg : reference[f])
    {
      if (toReference < 0.0 && SegmentsCross(x, y, seg.first, seg.second, Mesh.FaceNormal(f), t))
      {
        toReference = length + t * piece;
      }
    }
    length += piece;
    x = y;
    if (closing)
    {
      return toReference >= 0.0 && length > 0.0;
    }
    const int twin = Mesh.Twin(h);
    if (twin < 0)
    {
      return false; // the iso-curve meets the mesh boundary: not a loop
    }
    // In the next face, leave through the other edge that changes side.
    const int e1 = TriangleMesh::Next(twin), e2 = TriangleMesh::Prev(twin);
    const int third = Mesh.Destination(e1);
    // twin runs from the shared edge's lower end to its upper end; the level leaves through e1
    // (upper end to third) when third is below, through e2 (third to the lower end) otherwise.
    h = below(third) == below(Mesh.Origin(e1)) ? e2 : e1;
  }
  return false;
}

Result<int> GeodesicPolarCoordinates::UseIsoCurveAngles()
{
  if (!Solved || CurveMode)
  {
    return Status::Error("iso-curve angles need the coordinates about a point (a successful "
                         "Compute, not ComputeCurve)");
  }
  IsoAngles = true;
  // The reference geodesic: from the source in direction theta = 0 to the radius.
  std::vector<std::vector<std::pair<Vec3, Vec3>>> reference(Mesh.NumberOfFaces());
  double radius = 0.0;
  for (int v : InsideList)
  {
    radius = std::max(radius, VertexRho[v]);
  }
  const GeodesicShot ray = ShootGeodesic(Mesh, Source, Reference, radius * 1.01 + Mesh.MeanEdgeLength());
  ExactGeodesicOptions beyond;
  beyond.MaximumDistance = radius + 3.0 * Mesh.MeanEdgeLength();
  static_cast<void>(Solver.Solve({ Source }, beyond)); // Compute accepted Source
  for (const CurvePiece& piece : ray.Pieces)
  {
    reference[piece.Face].push_back({ piece.A, piece.B });
  }
  int kept = 0;
  for (int v : InsideList)
  {
    if (!(VertexRho[v] > 0.0))
    {
      continue;
    }
    double toReference = 0.0, length = 0.0;
    if (TraceIsoCurve(v, reference, toReference, length))
    {
      VertexTheta[v] = std::fmod(TwoPi * (length - toReference) / length, TwoPi);
    }
    else
    {
      ++kept;
    }
  }
  return kept;
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
  const double tiny = 1e-6 * Mesh.MeanEdgeLength();
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

Result<SurfacePoint> GeodesicPolarCoordinates::ToSurface(double rho, double theta) const
{
  if (!Solved || CurveMode)
  {
    return Status::Error("the inverse map of polar coordinates needs the coordinates about a "
                         "point (a successful Compute, not ComputeCurve)");
  }
  if (!std::isfinite(rho) || !std::isfinite(theta))
  {
    return Status::Error("polar coordinates (" + std::to_string(rho) + ", " +
      std::to_string(theta) + ") are not finite");
  }
  if (rho <= 0.0)
  {
    return SurfacePoint(Source);
  }
  if (IsoAngles)
  {
    return InverseIsoCurve(rho, theta);
  }
  return ShootGeodesic(Mesh, Source, Reference + theta * Turn / TwoPi, rho).End;
}

SurfacePoint GeodesicPolarCoordinates::InverseIsoCurve(double c, double theta) const
{
  // The level loop at rho = c, traced counter-clockwise from where it crosses the reference
  // geodesic (as UseIsoCurveAngles measured it), walked to the fraction theta / 2 pi of its length.
  auto rho = [&](int w) { return std::isfinite(VertexRho[w]) ? VertexRho[w] : Solver.Distance(w); };
  auto below = [&](int w) { return rho(w) < c; };
  auto crossing = [&](int h) {
    const int a = Mesh.Origin(h), b = Mesh.Destination(h);
    const double ra = rho(a), rb = rho(b);
    const double t = std::isfinite(rb) && std::abs(rb - ra) > 0.0 ? (c - ra) / (rb - ra) : 1.0;
    return Mesh.Position(a) + (Mesh.Position(b) - Mesh.Position(a)) * std::min(1.0, std::max(0.0, t));
  };
  auto toSurface = [&](int f, const Vec3& x) {
    SurfacePoint p = SurfacePoint::InFace(f, 0, 0, 0);
    p.Bary = Mesh.ClampedBarycentric(f, x);
    return p;
  };
  // 1. Where the reference geodesic reaches the level.
  const GeodesicShot ray = ShootGeodesic(Mesh, Source, Reference, c * 1.01 + Mesh.MeanEdgeLength());
  int f0 = -1;
  Vec3 start;
  for (const CurvePiece& piece : ray.Pieces)
  {
    const auto& t = Mesh.Face(piece.Face);
    auto interpolated = [&](const Vec3& x) {
      const SurfacePoint p = toSurface(piece.Face, x);
      return p.Bary[0] * rho(t[0]) + p.Bary[1] * rho(t[1]) + p.Bary[2] * rho(t[2]);
    };
    const double ra = interpolated(piece.A), rb = interpolated(piece.B);
    if (std::isfinite(ra) && std::isfinite(rb) && (ra - c) * (rb - c) <= 0.0 && ra != rb)
    {
      f0 = piece.Face;
      start = piece.A + (piece.B - piece.A) * ((c - ra) / (rb - ra));
      break;
    }
  }
  if (f0 < 0)
  {
    return ShootGeodesic(Mesh, Source, Reference + theta * Turn / TwoPi, c).End;
  }
  // 2. The loop, as points (with their faces) and cumulative lengths.
  int h = -1;
  for (int k = 0; k < 3; ++k)
  {
    const int e = 3 * f0 + k;
    if (!below(Mesh.Origin(e)) && below(Mesh.Destination(e)))
    {
      h = e;
    }
  }
  if (h < 0)
  {
    return toSurface(f0, start);
  }
  std::vector<Vec3> points{ start };
  std::vector<int> faces;
  std::vector<double> cumulative{ 0.0 };
  const int maxSteps = 4 * Mesh.NumberOfFaces() + 8;
  for (int step = 0; step < maxSteps; ++step)
  {
    const Vec3 y = crossing(h);
    faces.push_back(h / 3);
    cumulative.push_back(cumulative.back() + Norm(y - points.back()));
    points.push_back(y);
    const int twin = Mesh.Twin(h);
    if (twin < 0)
    {
      break; // not a loop: walk what there is
    }
    const int g = twin / 3;
    if (g == f0)
    {
      // Back in the start face: close the loop at the start point.
      faces.push_back(f0);
      cumulative.push_back(cumulative.back() + Norm(start - points.back()));
      points.push_back(start);
      break;
    }
    const int e1 = TriangleMesh::Next(twin), e2 = TriangleMesh::Prev(twin);
    const int third = Mesh.Destination(e1);
    h = below(third) == below(Mesh.Origin(e1)) ? e2 : e1;
  }
  // 3. The point at the fraction theta / 2 pi of the loop's length.
  double a = std::fmod(theta, TwoPi);
  if (a < 0.0)
  {
    a += TwoPi;
  }
  const double target = a / TwoPi * cumulative.back();
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
  {
    if (target <= cumulative[i + 1] || i + 2 == points.size())
    {
      const double piece = cumulative[i + 1] - cumulative[i];
      const double t = piece > 0.0 ? std::min(1.0, std::max(0.0, (target - cumulative[i]) / piece)) : 0.0;
      return toSurface(faces[i], points[i] + (points[i + 1] - points[i]) * t);
    }
  }
  return toSurface(f0, start);
}

} // namespace gs
