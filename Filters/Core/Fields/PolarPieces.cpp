#include "PolarPieces.h"

#include "ExactGeodesic.h"
#include "ExactPieces.h"
#include "GeodesicPolarCoordinatesImpl.h"
#include "GeodesicShooting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace gs
{

namespace
{
// The chart's process's result as it sends it: a status, the source's angle sum, the reference
// flag, its faces, the iso-curve count, the curve's length, then (id, rho, theta) per vertex of
// the chart (about a curve: the offset and the arc length).
ByteBuffer Pack(const Status& status, const PiecePolarCoordinates& result,
  const GeodesicPolarCoordinates* polar, const SurfacePiece& piece)
{
  ByteBuffer bytes;
  ByteWriter w(bytes);
  const std::int32_t ok = status.Ok() ? 1 : 0;
  w.Put(ok);
  if (!status.Ok())
  {
    for (const char c : status.Message())
    {
      w.Put(c);
    }
    return bytes;
  }
  w.Put(result.SourceAngleSum);
  w.Put(static_cast<std::int32_t>(result.ReferenceNormal ? 1 : 0));
  w.Put(static_cast<std::int32_t>(result.ChartFaces));
  w.Put(static_cast<std::int32_t>(result.IsoCurveKept));
  w.Put(result.CurveLength);
  const bool curve = result.CurveLength > 0.0;
  for (const int v : polar->Inside())
  {
    w.Put(piece.GlobalId(v));
    w.Put(curve ? polar->Curve().Offset[static_cast<std::size_t>(v)] : polar->Rho(v));
    w.Put(curve ? polar->Curve().ArcLength[static_cast<std::size_t>(v)] : polar->Theta(v));
  }
  return bytes;
}
} // namespace

Status ComputePolarOnPieces(SurfacePiece& piece, std::int64_t source, double radius,
  const Vec3& referenceDirection, PieceCommunicator& comm, PiecePolarCoordinates& result,
  bool isoCurveAngles)
{
  const int local = piece.Vertex(source);
  const bool mine = local >= 0 && piece.IsOwned(local);
  if (comm.Sum(mine ? 1 : 0) != 1)
  {
    result = PiecePolarCoordinates();
    return Status::Error("vertex " + std::to_string(source) + " is not a point of the surface");
  }
  const SurfacePoint at = SurfacePoint::AtVertex(local);
  return ComputePolarOnPieces(
    piece, mine ? &at : nullptr, radius, referenceDirection, comm, result, isoCurveAngles);
}

namespace
{
// Collective. Grows the band of the process holding `at` (null elsewhere) where the exact solve
// about it truncated at `radius` reaches the band's edge, by rings that double, until it stays
// inside; `at` then names the point in the grown piece.
Status GrowToChart(SurfacePiece& piece, SurfacePoint* at, double radius, PieceCommunicator& comm)
{
  const std::unique_ptr<PiecePointName> named = at ? std::make_unique<PiecePointName>(piece, *at) : nullptr;
  return piece.GrowUntilInside({}, comm, [&]() -> std::vector<int> {
    if (!at)
    {
      return {};
    }
    *at = named->In(piece);
    ExactGeodesicSolver solver(piece.Mesh(), piece.LengthScale());
    ExactGeodesicOptions options;
    options.MaximumDistance = radius;
    options.Fence = &piece.Fence();
    static_cast<void>(solver.Solve({ *at }, options)); // (a point of the piece: accepted)
    return solver.FenceFacesEntered();
  });
}

// What the chart's process sent (Pack), into every process's result.
Status Unpack(const ByteBuffer& bytes, const SurfacePiece& piece, PiecePolarCoordinates& result)
{
  ByteReader r(bytes);
  std::int32_t ok = 0;
  r.Get(ok);
  if (!ok)
  {
    std::string message;
    char c = 0;
    while (r.Get(c))
    {
      message += c;
    }
    return Status::Error(message.empty() ? "the polar coordinates failed" : message);
  }
  std::int32_t normal = 0, faces = 0, kept = 0;
  r.Get(result.SourceAngleSum);
  r.Get(normal);
  r.Get(faces);
  r.Get(kept);
  r.Get(result.CurveLength);
  result.ReferenceNormal = normal != 0;
  result.ChartFaces = faces;
  result.IsoCurveKept = kept;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const int nv = piece.Mesh().NumberOfVertices();
  result.Rho.assign(static_cast<std::size_t>(nv), nan);
  result.Theta.assign(static_cast<std::size_t>(nv), nan);
  std::int64_t id = 0;
  double rho = 0.0, theta = 0.0;
  while (r.Get(id) && r.Get(rho) && r.Get(theta))
  {
    const int v = piece.Vertex(id);
    if (v >= 0)
    {
      result.Rho[static_cast<std::size_t>(v)] = rho;
      result.Theta[static_cast<std::size_t>(v)] = theta;
    }
  }
  return Status();
}
// Collective. The chart over the whole surface (an infinite radius): the exact distances and
// departure angles on the pieces (ComputeExactOnPieces, the source's process measuring the
// angles in its mesh's frame), theta from them as GeodesicPolarCoordinates makes it, the source's
// turn and the reference angle sent by the process of `at` (null elsewhere).
Status WholeChart(SurfacePiece& piece, const SurfacePoint* at, const Vec3& referenceDirection,
  PieceCommunicator& comm, PiecePolarCoordinates& result)
{
  // Two rings before the point is named in the piece's mesh (ComputeExactOnPieces).
  const std::unique_ptr<PiecePointName> named = at ? std::make_unique<PiecePointName>(piece, *at) : nullptr;
  if (const Status grown = piece.GrowTo(1, 0, comm); !grown.Ok())
  {
    return grown;
  }
  std::vector<SurfacePoint> mine;
  double turn = -1.0, reference = -std::numeric_limits<double>::infinity(), normal = 0.0;
  if (named)
  {
    mine.push_back(named->In(piece));
    const SurfacePoint& p = mine.front();
    turn = p.IsVertex() ? piece.Mesh().TotalAngle(p.Vertex) : TwoPi;
    reference = 0.0;
    const Vec3& d = referenceDirection;
    if (!(d.x == 0.0 && d.y == 0.0 && d.z == 0.0))
    {
      const double angle = TangentAngle(piece.Mesh(), p, d);
      normal = std::isfinite(angle) ? 0.0 : 1.0;
      reference = std::isfinite(angle) ? angle : 0.0;
    }
  }
  turn = comm.Max(turn);
  reference = comm.Max(reference);
  result.ReferenceNormal = comm.Max(normal) > 0.0;
  result.SourceAngleSum = turn;
  result.ChartFaces = static_cast<int>(comm.Max(named ? piece.Mesh().NumberOfFaces() : 0.0));
  ExactPiecesResult exact;
  if (const Status solved = ComputeExactOnPieces(piece, {}, 0.0, comm, exact, nullptr, mine);
      !solved.Ok())
  {
    return solved;
  }
  const TriangleMesh& mesh = piece.Mesh();
  const int nv = mesh.NumberOfVertices();
  result.Rho.assign(static_cast<std::size_t>(nv), NaN);
  result.Theta.assign(static_cast<std::size_t>(nv), NaN);
  std::int64_t lost = 0;
  for (int v = 0; v < nv; ++v)
  {
    const double rho = exact.Distance[static_cast<std::size_t>(v)];
    if (!piece.IsOwned(v) || !std::isfinite(rho))
    {
      continue;
    }
    const double raw = exact.Departure[static_cast<std::size_t>(v)];
    // The source vertex itself is the pole: angle 0 by convention.
    lost += !std::isfinite(raw) && rho > 0.0 ? 1 : 0;
    result.Rho[static_cast<std::size_t>(v)] = rho;
    result.Theta[static_cast<std::size_t>(v)] =
      std::isfinite(raw) ? Wrap((raw - reference) * TwoPi / turn) : 0.0;
  }
  if (comm.Sum(lost) > 0)
  {
    return Status::Error("the pieces orient their faces against each other, so the angles "
                         "cannot be carried across them; give the pieces one orientation or a "
                         "finite Radius");
  }
  piece.ValuesFromOwners(result.Rho, comm);
  piece.ValuesFromOwners(result.Theta, comm);
  return Status();
}
} // namespace

Status ComputePolarOnPieces(SurfacePiece& piece, const SurfacePoint* point, double radius,
  const Vec3& referenceDirection, PieceCommunicator& comm, PiecePolarCoordinates& result,
  bool isoCurveAngles)
{
  result = PiecePolarCoordinates();
  const bool mine = point != nullptr;
  if (comm.Sum(mine ? 1 : 0) != 1)
  {
    return Status::Error("the source point lies on no process's faces, or on several");
  }
  if (!(radius > 0.0) || (isoCurveAngles && !std::isfinite(radius)))
  {
    return Status::Error(isoCurveAngles ? "iso-curve angles need a finite radius"
                                        : "the radius must be above 0");
  }
  const int chartRank = static_cast<int>(comm.Max(mine ? comm.Rank() : -1.0));
  SurfacePoint at = mine ? ExactGeodesicSolver::SourcePoint(piece.Mesh(), *point) : SurfacePoint();
  if (!std::isfinite(radius))
  {
    return WholeChart(piece, mine ? &at : nullptr, referenceDirection, comm, result);
  }
  // Iso-curve angles read the surface a few edges beyond the chart (of the whole surface's).
  const double meanEdge = isoCurveAngles ? piece.MeanEdgeLength(comm) : 0.0;
  const double reach =
    isoCurveAngles ? GeodesicPolarCoordinates::IsoCurveReach(radius, meanEdge) : radius;
  if (const Status grown = GrowToChart(piece, mine ? &at : nullptr, reach, comm); !grown.Ok())
  {
    return grown;
  }

  // The chart, on its process's piece; every process gets it.
  std::vector<ByteBuffer> outgoing(static_cast<std::size_t>(comm.Size())), incoming;
  if (mine)
  {
    const TriangleMesh& mesh = piece.Mesh();
    double reference = 0.0;
    const Vec3& d = referenceDirection;
    if (!(d.x == 0.0 && d.y == 0.0 && d.z == 0.0))
    {
      const double angle = TangentAngle(mesh, at, d);
      result.ReferenceNormal = !std::isfinite(angle);
      reference = std::isfinite(angle) ? angle : 0.0;
    }
    GeodesicPolarCoordinates polar(mesh, nullptr, piece.LengthScale(), meanEdge);
    Status computed = polar.Compute(at, radius, reference);
    if (computed.Ok() && isoCurveAngles)
    {
      const Result<int> kept = polar.UseIsoCurveAngles();
      computed = kept.Ok() ? Status() : Status::Error("iso-curve angles: " + kept.Message());
      result.IsoCurveKept = kept.Ok() ? *kept : 0;
    }
    result.SourceAngleSum = polar.SourceAngleSum();
    result.ChartFaces = mesh.NumberOfFaces();
    const ByteBuffer packed = Pack(computed, result, &polar, piece);
    for (ByteBuffer& b : outgoing)
    {
      b = packed;
    }
  }
  comm.Exchange(outgoing, incoming);
  return Unpack(incoming[static_cast<std::size_t>(chartRank)], piece, result);
}

Status ComputeCurveCoordinatesOnPieces(SurfacePiece& piece,
  const std::vector<PiecePointName>& curve, double radius, PieceCommunicator& comm,
  PiecePolarCoordinates& result)
{
  result = PiecePolarCoordinates();
  if (!(radius > 0.0) || !std::isfinite(radius))
  {
    return Status::Error("the radius must be finite and above 0");
  }
  if (curve.empty())
  {
    return Status::Error("the curve has no point");
  }
  const double mean = piece.MeanEdgeLength(comm);
  const bool chart = comm.Rank() == 0;
  // Process 0's band grows around the curve's points, then where its trace or the exact solve
  // from its samples to what ComputeCurve solves reaches the fence.
  std::vector<std::int64_t> around;
  for (const PiecePointName& p : curve)
  {
    if (chart)
    {
      p.AppendVertexIds(around);
    }
  }
  std::vector<SurfacePoint> local;
  const Status grown = piece.GrowUntilInside(around, comm, [&]() -> std::vector<int> {
    if (!chart)
    {
      return {};
    }
    local.clear();
    for (const PiecePointName& p : curve)
    {
      local.push_back(p.In(piece));
    }
    const std::vector<CurvePiece> traced = TraceSurfaceCurve(piece.Mesh(), local);
    std::vector<int> faces;
    for (const CurvePiece& step : traced)
    {
      faces.push_back(step.Face);
    }
    ExactGeodesicSolver solver(piece.Mesh(), piece.LengthScale());
    ExactGeodesicOptions options;
    options.MaximumDistance = radius + 3.0 * mean + 1.01 * piece.Mesh().LongestEdgeLength();
    options.Fence = &piece.Fence();
    const std::vector<SurfacePoint> samples =
      SampleCurvePieces(piece.Mesh(), traced, ExactCurveSampleSpacing * mean);
    static_cast<void>(solver.Solve(samples, options)); // (points of the piece: accepted)
    faces.insert(faces.end(), solver.FenceFacesEntered().begin(), solver.FenceFacesEntered().end());
    return faces;
  });
  if (!grown.Ok())
  {
    return grown;
  }
  // The coordinates, on process 0's piece; every process gets them.
  std::vector<ByteBuffer> outgoing(static_cast<std::size_t>(comm.Size())), incoming;
  if (chart)
  {
    GeodesicPolarCoordinates polar(piece.Mesh(), nullptr, piece.LengthScale(), mean);
    const Status computed = polar.ComputeCurve(local, radius);
    result.CurveLength = computed.Ok() ? polar.Curve().Length : 0.0;
    result.ChartFaces = piece.Mesh().NumberOfFaces();
    const ByteBuffer packed = Pack(computed, result, &polar, piece);
    for (ByteBuffer& b : outgoing)
    {
      b = packed;
    }
  }
  comm.Exchange(outgoing, incoming);
  return Unpack(incoming[0], piece, result);
}

} // namespace gs
