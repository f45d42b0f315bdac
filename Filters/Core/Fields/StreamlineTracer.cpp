// Streamlines of an N-direction field, traced face to face.
#include "DirectionFieldImpl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace gs
{

Streamline DirectionFieldSolver::TraceStreamline(int n, const std::vector<double>& angles,
  const SurfacePoint& start, double initialAngle, double length, const std::vector<double>* indices,
  double maxTurn) const
{
  StreamlineTracer tracer(*this, n, angles, start, initialAngle, length, indices, maxTurn);
  tracer.Continue();
  return std::move(tracer.Line());
}

DirectionFieldSolver::StreamlineTracer::StreamlineTracer(const DirectionFieldSolver& solver, int n,
  const std::vector<double>& angles, const SurfacePoint& start, double initialAngle, double length,
  const std::vector<double>* indices, double maxTurn)
  : Solver(solver)
  , Angles(angles)
  , Indices(indices)
  , Symmetry(n)
  , MaxTurn(maxTurn < 0 ? 0.9 * Pi / std::max(n, 1) : maxTurn)
{
  const TriangleMesh& surface = Solver.Surface;
  const int nf = surface.NumberOfFaces();
  if (n < 1 || static_cast<int>(angles.size()) != nf || nf == 0 || !(length >= 0.0) ||
    !std::isfinite(length))
  {
    Traced.Reason = Streamline::Stuck;
    Done = true;
    return;
  }
  Face = start.Face;
  if (start.IsVertex())
  {
    Face = TriangleMesh::FaceOf(surface.VertexHalfedge(start.Vertex));
    Point = surface.Position(start.Vertex);
  }
  else
  {
    Point = surface.Interpolate(Face, start.Bary);
  }
  Traced.End = SurfacePoint::InFace(Face, 0, 0, 0);
  Traced.End.Bary = surface.ClampedBarycentric(Face, Point);
  if (Singular(Face))
  {
    Traced.Reason = Streamline::ReachedSingularity;
    Done = true;
    return;
  }
  // Representative closest to the wanted angle.
  Angle = initialAngle + WrapSymmetric(Angles[Face] - initialAngle, Symmetry);
  Direction = Solver.DirectionInFace(Face, Angle);
  Remaining = length;
  // (At most 10 nf + 1000 faces crossed, whatever the stages.)
  StepsLeft = 10LL * nf + 1000;
}

bool DirectionFieldSolver::StreamlineTracer::Singular(int face) const
{
  if (!Indices)
  {
    return false;
  }
  const TriangleMesh& surface = Solver.Surface;
  for (int c = 0; c < 3; ++c)
  {
    if (std::abs((*Indices)[surface.Face(face)[c]]) > 1e-9 &&
      !surface.IsBoundaryVertex(surface.Face(face)[c]))
    {
      return true;
    }
  }
  return false;
}

void DirectionFieldSolver::StreamlineTracer::Finish()
{
  Done = true;
  Traced.End = SurfacePoint::InFace(Face, 0, 0, 0);
  Traced.End.Bary = Solver.Surface.ClampedBarycentric(Face, Point);
}

bool DirectionFieldSolver::StreamlineTracer::Continue(double until)
{
  const TriangleMesh& surface = Solver.Surface;
  while (!Done && !(Traced.Length >= until))
  {
    if (StepsLeft-- <= 0)
    {
      Finish(); // (Reason stays ReachedLength, as the loop of old ended)
      break;
    }
    const FaceExit out = FindFaceExit(surface, Face, Point, Direction, Entry);
    if (out.Edge < 0)
    {
      Traced.Reason = Streamline::Stuck;
      Finish();
      break;
    }
    if (out.T >= Remaining)
    {
      const Vec3 y = Point + Direction * Remaining;
      Traced.Pieces.push_back({ Face, Point, y });
      Traced.Length += Remaining;
      Point = y;
      Traced.Reason = Streamline::ReachedLength;
      Finish();
      break;
    }
    const double s = std::min(1.0 - 1e-9, std::max(1e-9, out.S));
    const Vec3 P = surface.Position(surface.Origin(out.Edge)),
               Q = surface.Position(surface.Destination(out.Edge));
    const Vec3 y = P + (Q - P) * s;
    Traced.Pieces.push_back({ Face, Point, y });
    Traced.Length += out.T;
    Remaining -= out.T;
    Point = y;
    const int t = surface.Twin(out.Edge);
    if (t < 0)
    {
      Traced.Reason = Streamline::ReachedBoundary;
      Finish();
      break;
    }
    const int g = TriangleMesh::FaceOf(t);
    // Incoming direction transported into g, then the field's closest representative.
    const double incoming = Angle + Solver.Transport[out.Edge];
    const double next = incoming + WrapSymmetric(Angles[g] - incoming, Symmetry);
    if (std::abs(next - incoming) > MaxTurn || Singular(g))
    {
      Traced.Reason = Streamline::ReachedSingularity;
      Finish();
      break;
    }
    Face = g;
    Angle = next;
    Direction = Solver.DirectionInFace(Face, Angle);
    Entry = t;
  }
  return !Done;
}

} // namespace gs
