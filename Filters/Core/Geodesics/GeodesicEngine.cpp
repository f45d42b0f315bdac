// The engines behind GeodesicEngine: exact window propagation, shortest paths on a saddle
// vertex (or discrete geodesic) graph, and virtual source propagation; and how each takes
// curve sources.
#include "GeodesicEngine.h"

#include "ExactGeodesic.h"
#include "ExactInParts.h"
#include "SVGGeodesicSolver.h"
#include "SaddleVertexGraph.h"
#include "SurfaceCurve.h"
#include "VirtualSourceGeodesic.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>

namespace gs
{

const char* GeodesicSolverName(GeodesicSolver solver)
{
  switch (solver)
  {
    case GeodesicSolver::Exact:
      return "Exact";
    case GeodesicSolver::SVGLabelCorrecting:
      return "SVG (label-correcting)";
    case GeodesicSolver::SVGDijkstra:
      return "SVG (Dijkstra)";
    case GeodesicSolver::DGG:
      return "DGG (accuracy-bounded)";
    case GeodesicSolver::VirtualSources:
      return "Virtual sources (no precompute)";
  }
  return "";
}

bool GeodesicSolverUsesGraph(GeodesicSolver solver)
{
  return solver == GeodesicSolver::SVGLabelCorrecting || solver == GeodesicSolver::SVGDijkstra ||
    solver == GeodesicSolver::DGG;
}

GeodesicSolver GraphSolverOf(const SaddleVertexGraph& graph)
{
  return graph.GetConstruction() == GraphConstruction::DiscreteGeodesic ? GeodesicSolver::DGG
                                                                        : GeodesicSolver::SVGLabelCorrecting;
}

bool ExactSolvesInParts(const TriangleMesh& mesh, double maximumDistance)
{
  // (A solve bounded to a small disc is local: serial, without making the parts.)
  const bool wide = !(maximumDistance > 0.0 && std::isfinite(maximumDistance)) ||
    maximumDistance >= ExactInPartsMinimumReach * mesh.BoundingBoxDiagonal();
  return mesh.NumberOfFaces() >= ExactInPartsMinimumFaces && wide;
}

double GeodesicEngine::DepartureAngle(int) const
{
  return std::numeric_limits<double>::quiet_NaN();
}

namespace
{
/// Exact window propagation; curves are densely sampled (ExactCurveSampleSpacing), the exact
/// reference for distances to a curve. On a large mesh, solves that are not local are solved in
/// parts on threads (ExactSolverInParts: the same distances and single-source departure angles
/// up to rounding, with progress and abort); angles from several sources by the serial solver.
class ExactEngine final : public GeodesicEngine
{
public:
  explicit ExactEngine(const TriangleMesh& mesh)
    : GeodesicEngine(mesh)
  {
  }
  GeodesicSolver Solver() const override { return GeodesicSolver::Exact; }
  Status Solve(const GeodesicSources& sources, const GeodesicSolveOptions& options) override
  {
    std::vector<SurfacePoint> points = sources.Points;
    for (const auto& curve : sources.Curves)
    {
      const std::vector<CurvePiece> traced = TraceSurfaceCurve(Surface, curve);
      const std::vector<SurfacePoint> samples =
        SampleCurvePieces(Surface, traced, ExactCurveSampleSpacing * Surface.MeanEdgeLength());
      points.insert(points.end(), samples.begin(), samples.end());
    }
    InParts = false;
    // (Angles come from the parts for a single point source.)
    const bool anglesKnown = !options.Angles || (points.size() == 1 && sources.Curves.empty());
    if (ExactSolvesInParts(Surface, options.MaximumDistance) && anglesKnown)
    {
      return SolveInParts(points, options);
    }
    return SolveSerially(points, options);
  }
  // (Before any solve: no vertex reached.)
  double Distance(int v) const override
  {
    return InParts ? Parts->Distance(v)
      : Serial     ? Serial->Distance(v)
                   : std::numeric_limits<double>::infinity();
  }
  std::vector<double> Distances() const override
  {
    return InParts ? Parts->Distances()
      : Serial     ? Serial->Distances()
                   : std::vector<double>(static_cast<std::size_t>(Surface.NumberOfVertices()),
                       std::numeric_limits<double>::infinity());
  }
  const std::vector<int>& Reached() const override
  {
    if (!InParts && Serial)
    {
      return Serial->FinalVertices();
    }
    if (InParts && !ReachedListed)
    {
      // In order of distance, as the serial solver makes them final (ties by vertex); listed
      // when first asked for (the filters read distances only).
      ReachedListed = true;
      for (int v = 0; v < Surface.NumberOfVertices(); ++v)
      {
        if (std::isfinite(Parts->Distance(v)))
        {
          ReachedInParts.push_back(v);
        }
      }
      std::sort(ReachedInParts.begin(), ReachedInParts.end(), [&](int a, int b) {
        const double da = Parts->Distance(a), db = Parts->Distance(b);
        return da < db || (da == db && a < b);
      });
    }
    return ReachedInParts;
  }
  double DepartureAngle(int v) const override
  {
    return InParts ? Parts->DepartureAngle(v)
      : Serial     ? Serial->DepartureAngle(v)
                   : std::numeric_limits<double>::quiet_NaN();
  }

private:
  Status SolveSerially(const std::vector<SurfacePoint>& points, const GeodesicSolveOptions& options)
  {
    if (!Serial)
    {
      Serial = std::make_unique<ExactGeodesicSolver>(Surface);
    }
    ExactGeodesicOptions exact;
    exact.MaximumDistance = options.MaximumDistance;
    return Serial->Solve(points, exact);
  }
  Status SolveInParts(const std::vector<SurfacePoint>& points, const GeodesicSolveOptions& options)
  {
    if (!Parts)
    {
      Parts = std::make_unique<ExactSolverInParts>(Surface);
    }
    InParts = true;
    ReachedInParts.clear();
    ReachedListed = false;
    const Status solved = Parts->Solve(points, options.MaximumDistance, options.Progress);
    if (solved.Ok() && options.Angles && !Parts->AnglesKept())
    {
      // (The part holding the source measured angles otherwise: the serial solver gives them.)
      InParts = false;
      return SolveSerially(points, options);
    }
    return solved;
  }

  // Each made at its first solve: a large mesh's distances need only the parts.
  std::unique_ptr<ExactGeodesicSolver> Serial;
  std::unique_ptr<ExactSolverInParts> Parts;
  bool InParts = false; // the last solve was
  // The last solve in parts' reached vertices, listed by Reached (empty before any solve).
  mutable std::vector<int> ReachedInParts;
  mutable bool ReachedListed = false;
};

/// Shortest paths on a graph (SVG or DGG, as built), refined by geodesic triangle unfolding;
/// curves are solved as curves, points joining them as one-point curves.
class GraphEngine final : public GeodesicEngine
{
public:
  GraphEngine(GeodesicSolver solver, const TriangleMesh& mesh, const SaddleVertexGraph& graph)
    : GeodesicEngine(mesh)
    , Kind(solver)
    , Solver_(mesh, graph)
  {
  }
  GeodesicSolver Solver() const override { return Kind; }
  Status Solve(const GeodesicSources& sources, const GeodesicSolveOptions& options) override
  {
    SVGSolveOptions svg;
    svg.Algorithm =
      Kind == GeodesicSolver::SVGDijkstra ? GraphAlgorithm::Dijkstra : GraphAlgorithm::LabelCorrecting;
    svg.MaximumDistance = options.MaximumDistance;
    svg.Refine = options.UnfoldingRefinement;
    svg.NumberOfThreads = options.NumberOfThreads;
    svg.Angles = options.Angles;
    if (sources.Curves.empty())
    {
      return Solver_.Solve(sources.Points, svg);
    }
    std::vector<std::vector<SurfacePoint>> curves = sources.Curves;
    for (const SurfacePoint& p : sources.Points)
    {
      curves.push_back({ p });
    }
    return Solver_.SolveCurves(curves, svg);
  }
  double Distance(int v) const override { return Solver_.Distance(v); }
  std::vector<double> Distances() const override { return Solver_.Distances(); }
  const std::vector<int>& Reached() const override { return Solver_.Reached(); }
  double DepartureAngle(int v) const override { return Solver_.DepartureAngle(v); }

private:
  GeodesicSolver Kind;
  SVGGeodesicSolver Solver_;
};

/// Virtual source propagation; a curve goes in as runs, each as long as the curve goes straight
/// in space (a straight line snapped onto a flat part of the mesh is one run, its distance
/// exact), carried as segments.
class VirtualSourceEngine final : public GeodesicEngine
{
public:
  explicit VirtualSourceEngine(const TriangleMesh& mesh)
    : GeodesicEngine(mesh)
    , Solver_(mesh)
  {
  }
  GeodesicSolver Solver() const override { return GeodesicSolver::VirtualSources; }
  Status Solve(const GeodesicSources& sources, const GeodesicSolveOptions& options) override
  {
    std::vector<SurfacePoint> points = sources.Points;
    std::vector<std::vector<CurvePiece>> runs;
    for (const auto& curve : sources.Curves)
    {
      AppendStraightRuns(Surface, curve, runs);
      if (curve.size() == 1)
      {
        points.push_back(curve[0]);
      }
    }
    VirtualSourceOptions vsp;
    vsp.MaximumDistance = options.MaximumDistance;
    vsp.Progress = options.Progress;
    vsp.Angles = options.Angles;
    return Solver_.Solve(points, runs, vsp);
  }
  double Distance(int v) const override { return Solver_.Distance(v); }
  double DepartureAngle(int v) const override { return Solver_.DepartureAngle(v); }
  std::vector<double> Distances() const override { return Solver_.Distances(); }
  const std::vector<int>& Reached() const override
  {
    ReachedVertices.clear();
    for (int v = 0; v < Surface.NumberOfVertices(); ++v)
    {
      if (std::isfinite(Solver_.Distance(v)))
      {
        ReachedVertices.push_back(v);
      }
    }
    return ReachedVertices;
  }

private:
  mutable std::vector<int> ReachedVertices; // Reached()'s buffer
  VirtualSourceSolver Solver_;
};
} // namespace

Result<std::unique_ptr<GeodesicEngine>> MakeGeodesicEngine(
  GeodesicSolver solver, const TriangleMesh& mesh, const SaddleVertexGraph* graph)
{
  std::unique_ptr<GeodesicEngine> engine;
  switch (solver)
  {
    case GeodesicSolver::Exact:
      engine.reset(new ExactEngine(mesh));
      break;
    case GeodesicSolver::VirtualSources:
      engine.reset(new VirtualSourceEngine(mesh));
      break;
    case GeodesicSolver::SVGLabelCorrecting:
    case GeodesicSolver::SVGDijkstra:
    case GeodesicSolver::DGG:
    {
      if (!graph)
      {
        return Status::Error(std::string("the ") + GeodesicSolverName(solver) + " solver needs a graph");
      }
      if (Status fits = graph->CheckMesh(mesh); !fits.Ok())
      {
        return fits;
      }
      engine.reset(new GraphEngine(solver, mesh, *graph));
      break;
    }
    default:
      return Status::Error("unknown geodesic solver " + std::to_string(static_cast<int>(solver)));
  }
  return Result<std::unique_ptr<GeodesicEngine>>(std::move(engine));
}

} // namespace gs
