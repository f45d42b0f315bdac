// Geodesic polar coordinates about a point: the solve, the log map and its inverse.
#include "GeodesicPolarCoordinatesImpl.h"

#include "GeodesicShooting.h"
#include "SurfaceCurve.h"
#include "GeodesicUnfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

GeodesicPolarCoordinates::GeodesicPolarCoordinates(const TriangleMesh& mesh,
  const SaddleVertexGraph* graph, double lengthScale, double meanEdgeLength)
  : Mesh(mesh)
  , MeanEdge(meanEdgeLength > 0.0 ? meanEdgeLength : mesh.MeanEdgeLength())
  , Solver(mesh, lengthScale)
  , WholeSurface(lengthScale == 0.0)
{
  if (graph)
  {
    // (A graph of another mesh: the error Compute and ComputeCurve return.)
    Result<std::unique_ptr<GeodesicEngine>> engine = MakeGeodesicEngine(GraphSolverOf(*graph), mesh, graph);
    GraphError = engine;
    GraphEngine = engine.Ok() ? std::move(*engine) : nullptr;
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
  if (GraphEngine || !std::isfinite(radius)) // (a graph engine, or the whole surface)
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
  // A chart reaching far over a large whole surface: the exact engine, which solves it in parts
  // on threads (ExactInParts.h; the same rho and theta up to rounding).
  const bool wide = !GraphEngine && !stopOnceFinal && WholeSurface && ExactSolvesInParts(Mesh, maxDistance);
  if (wide && !WideExact)
  {
    Result<std::unique_ptr<GeodesicEngine>> made = MakeGeodesicEngine(GeodesicSolver::Exact, Mesh);
    if (!made.Ok())
    {
      return made;
    }
    WideExact = std::move(*made);
  }
  Engine = GraphEngine ? GraphEngine.get() : wide ? WideExact.get() : nullptr;
  if (Engine)
  {
    GeodesicEngine& engine = *Engine;
    GeodesicSources sources;
    sources.Points = { source };
    GeodesicSolveOptions options;
    options.MaximumDistance = maxDistance;
    options.Angles = true;
    options.NumberOfThreads = 1; // (with angles, the refinement runs on one thread anyway)
    if (const Status solved = engine.Solve(sources, options); !solved.Ok())
    {
      return solved;
    }
    for (int v : engine.Reached())
    {
      if (engine.Distance(v) <= radius)
      {
        InsideList.push_back(v);
      }
    }
    std::sort(InsideList.begin(), InsideList.end(), [&](int a, int b) {
      return engine.Distance(a) < engine.Distance(b) || (engine.Distance(a) == engine.Distance(b) && a < b);
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
    VertexRho[v] = Engine ? Engine->Distance(v) : Solver.Distance(v);
    const double raw = Engine ? Engine->DepartureAngle(v) : Solver.DepartureAngle(v);
    // The source vertex itself is the pole: angle 0 by convention.
    VertexTheta[v] = std::isfinite(raw) ? RawToTheta(raw) : 0.0;
  }
  Solved = true;
  return Status();
}


namespace
{
// A snapshot's vertex coordinates (false beyond its radius).
struct SnapshotValues
{
  const LogMapSnapshot& Snapshot;
  bool operator()(int v, double& r, double& a) const
  {
    const auto& entries = Snapshot.Entries;
    const auto it = std::lower_bound(entries.begin(), entries.end(), v,
      [](const LogMapSnapshot::Entry& e, int vertex) { return e.Vertex < vertex; });
    if (it == entries.end() || it->Vertex != v || !std::isfinite(it->Rho))
    {
      r = a = NaN;
      return false;
    }
    r = it->Rho;
    a = it->Theta;
    return true;
  }
};

// The coordinates over face f of an engine or of a snapshot: `values(v, rho, theta)` gives
// vertex v's coordinates (false beyond the radius).
template <class Values>
FacePolarCoordinates FaceCoordinates(const TriangleMesh& mesh, const SurfacePoint& source,
  double reference, double turn, int f, const Values& values)
{
  std::array<double, 3> rho{ { NaN, NaN, NaN } }, theta{ { NaN, NaN, NaN } };
  const auto& t = mesh.Face(f);
  for (int k = 0; k < 3; ++k)
  {
    if (!values(t[k], rho[k], theta[k]))
    {
      rho[k] = theta[k] = NaN;
      break; // (beyond the radius: the face answers only where the source lies in it)
    }
  }
  return FacePolarCoordinates(mesh, source, reference, turn, f, rho, theta);
}

// The log map's point of polar coordinates (rho, theta) (theta scaled to the source's total angle).
Vec2 LogMapFromPolar(double rho, double theta, double turn)
{
  const double raw = theta * (turn / TwoPi);
  return Vec2{ rho * std::cos(raw), rho * std::sin(raw) };
}
} // namespace

FacePolarCoordinates::FacePolarCoordinates(const TriangleMesh& mesh, const SurfacePoint& source,
  double reference, double turn, int face, const std::array<double, 3>& cornerRho,
  const std::array<double, 3>& cornerTheta)
  : Mesh(&mesh)
  , Source(source)
  , Reference(reference)
  , Turn(turn)
  , FaceId(face)
  , CornerTheta(cornerTheta)
{
  const auto& t = mesh.Face(face);
  SourceFace = source.IsVertex() ? (t[0] == source.Vertex || t[1] == source.Vertex || t[2] == source.Vertex)
                                 : source.Face == face;
  Inside = SourceFace ||
    (std::isfinite(cornerRho[0]) && std::isfinite(cornerRho[1]) && std::isfinite(cornerRho[2]));
  if (SourceFace || !Inside)
  {
    return;
  }
  Unfolding = FaceUnfolding(mesh, face, cornerRho);
  // Without an unfolded source, the corner angles are interpolated.
  CornerTheta0 = cornerTheta[0];
  for (int k = 0; k < 3; ++k)
  {
    double d = cornerTheta[k] - cornerTheta[0];
    d -= TwoPi * std::round(d / TwoPi);
    CornerDelta[k] = d;
  }
}

bool FacePolarCoordinates::PolarAt(const std::array<double, 3>& bary, double& rho, double& theta) const
{
  rho = theta = NaN;
  if (!Inside)
  {
    return false;
  }
  if (SourceFace)
  {
    // Straight inside the face: exact.
    const Vec3 x = Mesh->Interpolate(FaceId, bary);
    const Vec3 s = Mesh->Position(Source);
    rho = Norm(x - s);
    if (rho == 0.0)
    {
      theta = 0.0;
      return true;
    }
    // The tangent angle at the source of the direction towards x, measured in x's face.
    const double raw = TangentAngle(*Mesh, Source, x - s);
    theta = std::isfinite(raw) ? Wrap((raw - Reference) * TwoPi / Turn) : 0.0;
    return true;
  }
  const UnfoldedTriangle u = Unfolding.At(bary);
  rho = u.Distance;
  // Theta: in the unfolding, the direction from the unfolded source to the point, turned by the
  // offset that maps the corners' unfolded directions onto their angles (the same for all
  // corners on a developable surface; averaged circularly otherwise). Without an unfolded
  // source, the corner angles are interpolated.
  double sum = 0.0;
  if (u.FromEdge)
  {
    EdgeOffsets& o = Offsets[u.Edge];
    if (!o.Known)
    {
      for (int k = 0; k < 3; ++k)
      {
        const Vec2 c = u.Corners[k] - u.Source;
        // Angles in the unfolding are true angles at the source: scale them like the raw ones.
        const double a = CornerTheta[k] - std::atan2(c.y, c.x) * TwoPi / Turn;
        if (k == 0)
        {
          o.Offset0 = a;
        }
        double d = a - o.Offset0;
        d -= TwoPi * std::round(d / TwoPi);
        o.Delta[k] = d;
      }
      o.Known = true;
    }
    for (int k = 0; k < 3; ++k)
    {
      sum += bary[k] * o.Delta[k];
    }
    const Vec2 toQ = u.Point - u.Source;
    theta = Wrap(o.Offset0 + sum + std::atan2(toQ.y, toQ.x) * TwoPi / Turn);
    return true;
  }
  for (int k = 0; k < 3; ++k)
  {
    sum += bary[k] * CornerDelta[k];
  }
  theta = Wrap(CornerTheta0 + sum);
  return true;
}

bool FacePolarCoordinates::LogMapAt(const std::array<double, 3>& bary, Vec2& p) const
{
  double rho = 0.0, theta = 0.0;
  if (!PolarAt(bary, rho, theta))
  {
    return false;
  }
  p = LogMapFromPolar(rho, theta, Turn);
  return true;
}

FacePolarCoordinates GeodesicPolarCoordinates::OnFace(int f) const
{
  if (CurveMode)
  {
    return FacePolarCoordinates(); // (PolarAt false everywhere)
  }
  return FaceCoordinates(Mesh, Source, Reference, Turn, f,
    [this](int v, double& r, double& a) { return VertexCoordinates(v, r, a); });
}

bool GeodesicPolarCoordinates::PolarAt(const SurfacePoint& q, double& rho, double& theta) const
{
  if (CurveMode)
  {
    rho = theta = NaN;
    return false; // curve coordinates: CurveCoordinatesAt
  }
  if (q.IsVertex())
  {
    return VertexCoordinates(q.Vertex, rho, theta);
  }
  return OnFace(q.Face).PolarAt(q.Bary, rho, theta);
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
  if (q.IsVertex())
  {
    return SnapshotValues{ *this }(q.Vertex, rho, theta);
  }
  return OnFace(mesh, q.Face).PolarAt(q.Bary, rho, theta);
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

FacePolarCoordinates LogMapSnapshot::OnFace(const TriangleMesh& mesh, int f) const
{
  if (Entries.empty())
  {
    return FacePolarCoordinates(); // (PolarAt false everywhere)
  }
  return FaceCoordinates(mesh, Source, Reference, Turn, f, SnapshotValues{ *this });
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

} // namespace gs
