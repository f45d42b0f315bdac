#include "SVGGeodesicSolver.h"

#include "GeodesicUnfolding.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
const double NaN = std::numeric_limits<double>::quiet_NaN();

} // namespace

SVGGeodesicSolver::SVGGeodesicSolver(const TriangleMesh& mesh, const SaddleVertexGraph& graph)
  : Mesh(mesh)
  , Graph(graph)
  , Local(mesh)
  , GraphSolver(graph)
{
  Exact.assign(Mesh.NumberOfVertices(), 0);
  Angle.assign(Mesh.NumberOfVertices(), NaN);
  if (Graph.GetConstruction() == GraphConstruction::DiscreteGeodesic)
  {
    RefinementFloor = 1.0 / (1.0 + Graph.GetAccuracy());
  }
  // Per node (the sweep's numbering): whether the vertex's stencil closes into a full fan.
  if (Graph.NumberOfVertices() == Mesh.NumberOfVertices())
  {
    Interior.resize(Mesh.NumberOfVertices());
    for (int n = 0; n < Mesh.NumberOfVertices(); ++n)
    {
      Interior[n] = !Mesh.IsBoundaryVertex(Graph.Vertex(n));
    }
  }
}

Status SVGGeodesicSolver::Reject(Status why, GraphAlgorithm algorithm)
{
  GraphSolver.Solve({}, algorithm);
  return why;
}

Status SVGGeodesicSolver::SolveFromPieces(const std::vector<SurfacePoint>& exactSources,
  int finalVertices, const SVGSolveOptions& options)
{
  std::sort(Pieces.begin(), Pieces.end(), [](const Piece& a, const Piece& b) { return a.Face < b.Face; });
  std::vector<std::pair<int, double>> seeds;
  if (!exactSources.empty())
  {
    ExactGeodesicOptions local;
    local.MaximumFinalVertices = std::min(finalVertices, Mesh.NumberOfVertices());
    local.MaximumDistance = options.MaximumDistance;
    if (const Status solved = Local.Solve(exactSources, local); !solved.Ok())
    {
      return solved;
    }
    for (int v : Local.FinalVertices())
    {
      seeds.emplace_back(Graph.Node(v), Local.Distance(v));
    }
  }
  // Corners of faces holding a piece: the exact in-face distance to the piece.
  for (const Piece& p : Pieces)
  {
    const auto& t = Mesh.Face(p.Face);
    for (int k = 0; k < 3; ++k)
    {
      seeds.emplace_back(Graph.Node(t[k]), PointSegmentDistance(Mesh.Position(t[k]), p.A, p.B));
    }
  }
  GraphSolver.Solve(seeds, options.Algorithm, options.MaximumDistance);
  // Departure angles only make sense from a single point.
  const bool angles = options.Angles && exactSources.size() == 1 && Pieces.size() <= 1;
  if (options.Refine || angles)
  {
    // The exact local solve's vertices need no refinement, and their angles are exact.
    for (int v : Local.FinalVertices())
    {
      Exact[Graph.Node(v)] = !exactSources.empty();
      if (angles)
      {
        Angle[Graph.Node(v)] = Local.DepartureAngle(v);
        AngleSet.push_back(Graph.Node(v));
      }
    }
    if (angles)
    {
      const SurfacePoint& s = exactSources.front();
      AnglePeriod = s.IsVertex() ? Mesh.TotalAngle(s.Vertex) : 2.0 * 3.14159265358979323846;
    }
    Refine(options.MaximumDistance, options.Refine, angles, options.NumberOfThreads,
      options.ParallelRefinementMinimum);
    for (int v : Local.FinalVertices())
    {
      Exact[Graph.Node(v)] = 0;
    }
  }
  return Status();
}

void SVGGeodesicSolver::ClearAngles()
{
  for (int v : AngleSet)
  {
    Angle[v] = NaN;
  }
  AngleSet.clear();
}

Status SVGGeodesicSolver::Solve(
  const std::vector<SurfacePoint>& sources, const SVGSolveOptions& options)
{
  Pieces.clear();
  ClearAngles();
  if (sources.empty())
  {
    return Reject(Status::Error("no source given"), options.Algorithm);
  }
  if (const Status fits = Graph.CheckMesh(Mesh); !fits.Ok())
  {
    return Reject(fits, options.Algorithm);
  }
  if (const Status valid = Mesh.CheckPoints(sources, "source"); !valid.Ok())
  {
    return Reject(valid, options.Algorithm);
  }
  std::vector<SurfacePoint> facePoints;
  std::vector<std::pair<int, double>> vertexSeeds;
  for (const SurfacePoint& s : sources)
  {
    if (s.IsVertex())
    {
      vertexSeeds.emplace_back(Graph.Node(s.Vertex), 0.0);
    }
    else
    {
      facePoints.push_back(s);
      const Vec3 p = Mesh.Position(s);
      Pieces.push_back({ s.Face, p, p });
    }
  }
  // (A single vertex source with angles goes through the exact local solve, like a point.)
  if (facePoints.empty() && !(options.Angles && sources.size() == 1))
  {
    GraphSolver.Solve(vertexSeeds, options.Algorithm, options.MaximumDistance);
    if (options.Refine)
    {
      for (const auto& v : vertexSeeds)
      {
        Exact[v.first] = 1;
      }
      Refine(options.MaximumDistance, true, false, options.NumberOfThreads,
        options.ParallelRefinementMinimum);
      for (const auto& v : vertexSeeds)
      {
        Exact[v.first] = 0;
      }
    }
    return Status();
  }
  // Vertex sources join the exact local solve so that its truncation sees all sources.
  for (const auto& v : vertexSeeds)
  {
    facePoints.push_back(SurfacePoint::AtVertex(Graph.Vertex(v.first)));
  }
  const int k = Graph.LocalDiskSize();
  return SolveFromPieces(facePoints, k * static_cast<int>(facePoints.size()), options);
}

Status SVGGeodesicSolver::SolveCurves(
  const std::vector<std::vector<SurfacePoint>>& curves, const SVGSolveOptions& options)
{
  Pieces.clear();
  ClearAngles();
  if (curves.empty())
  {
    return Reject(Status::Error("no curve given"), options.Algorithm);
  }
  if (const Status fits = Graph.CheckMesh(Mesh); !fits.Ok())
  {
    return Reject(fits, options.Algorithm);
  }
  for (std::size_t c = 0; c < curves.size(); ++c)
  {
    const std::string curve = "curve " + std::to_string(c);
    if (curves[c].empty())
    {
      return Reject(Status::Error(curve + " has no point"), options.Algorithm);
    }
    if (const Status valid = Mesh.CheckPoints(curves[c], curve + ", point"); !valid.Ok())
    {
      return Reject(valid, options.Algorithm);
    }
  }
  std::vector<CurvePiece> pieces;
  for (const auto& curve : curves)
  {
    const std::vector<CurvePiece> traced = TraceSurfaceCurve(Mesh, curve);
    pieces.insert(pieces.end(), traced.begin(), traced.end());
  }
  // The exact local solve starts from samples along the pieces, dense enough that the sampled
  // curve is within a small fraction of an edge of the true one; the pieces themselves give the
  // exact in-face distances.
  const std::vector<SurfacePoint> samples =
    SampleCurvePieces(Mesh, pieces, CurveSeedSpacing * Mesh.MeanEdgeLength());
  std::vector<int> faces;
  for (const CurvePiece& p : pieces)
  {
    Pieces.push_back({ p.Face, p.A, p.B });
    faces.push_back(p.Face);
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  const long long wanted = static_cast<long long>(Graph.LocalDiskSize()) * static_cast<long long>(faces.size());
  return SolveFromPieces(
    samples, static_cast<int>(std::min<long long>(wanted, Mesh.NumberOfVertices())), options);
}

double SVGGeodesicSolver::DistanceAt(const SurfacePoint& q) const
{
  if (!Mesh.CheckPoint(q).Ok())
  {
    return Inf;
  }
  if (q.IsVertex())
  {
    return Distance(q.Vertex);
  }
  const auto& t = Mesh.Face(q.Face);
  double best =
    UnfoldedDistance(Mesh, q.Face, q.Bary, { { Distance(t[0]), Distance(t[1]), Distance(t[2]) } });
  // Sources in the same face: the straight segment inside the face.
  auto it = std::lower_bound(Pieces.begin(), Pieces.end(), q.Face,
    [](const Piece& p, int f) { return p.Face < f; });
  if (it != Pieces.end() && it->Face == q.Face)
  {
    const Vec3 x = Mesh.Position(q);
    for (; it != Pieces.end() && it->Face == q.Face; ++it)
    {
      best = std::min(best, PointSegmentDistance(x, it->A, it->B));
    }
  }
  return best;
}

std::vector<double> SVGGeodesicSolver::Distances() const
{
  std::vector<double> d(Mesh.NumberOfVertices(), Inf);
  if (Graph.NumberOfVertices() == Mesh.NumberOfVertices())
  {
    for (int n = 0; n < Mesh.NumberOfVertices(); ++n)
    {
      d[Graph.Vertex(n)] = GraphSolver.Distance(n);
    }
  }
  return d;
}

const std::vector<int>& SVGGeodesicSolver::Reached() const
{
  ReachedVertices.clear();
  for (int n : GraphSolver.Reached())
  {
    ReachedVertices.push_back(Graph.Vertex(n));
  }
  return ReachedVertices;
}

double SVGGeodesicSolver::Distance(const SurfacePoint& a, const SurfacePoint& b)
{
  if (!Solve({ a }).Ok())
  {
    return Inf;
  }
  return DistanceAt(b);
}

std::vector<double> SVGGeodesicSolver::DistancesTo(
  const SurfacePoint& a, const std::vector<SurfacePoint>& targets)
{
  std::vector<double> out(targets.size(), Inf);
  if (!Solve({ a }).Ok())
  {
    return out;
  }
  for (std::size_t i = 0; i < targets.size(); ++i)
  {
    out[i] = DistanceAt(targets[i]);
  }
  return out;
}

} // namespace gs
