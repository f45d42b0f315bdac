#include "DensityBrush.h"

#include "GeodesicEngine.h"
#include "SaddleVertexGraph.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace gs
{

Status CheckBrushParameters(double radius, double density)
{
  if (!(radius > 0.0) || !std::isfinite(radius))
  {
    std::ostringstream message;
    message << "the brush radius must be positive and finite (it is " << radius << ")";
    return Status::Error(message.str());
  }
  if (!(density > 0.0 && density <= 1.0))
  {
    std::ostringstream message;
    message << "the brush density (the size factor at its centre) must lie in (0, 1] (it is "
            << density << ")";
    return Status::Error(message.str());
  }
  return Status();
}

Result<std::vector<double>> BrushFactors(const TriangleMesh& mesh, const SaddleVertexGraph* graph,
  const DensityBrush& brush, int threads)
{
  if (const Status checked = CheckBrushParameters(brush.Radius, brush.Density); !checked.Ok())
  {
    return checked;
  }
  if (const Status valid = mesh.CheckPoint(brush.Center); !valid.Ok())
  {
    return Status::Error("the brush centre: " + valid.Message());
  }
  // The distance from the centre by the caller's engine: its graph's, or exact geodesics.
  Result<std::unique_ptr<GeodesicEngine>> engine =
    MakeGeodesicEngine(graph ? GraphSolverOf(*graph) : GeodesicSolver::Exact, mesh, graph);
  if (!engine.Ok())
  {
    return Status(engine);
  }
  GeodesicSources sources;
  sources.Points = { brush.Center };
  GeodesicSolveOptions options;
  options.MaximumDistance = brush.Radius;
  options.NumberOfThreads = threads;
  if (const Status solved = (*engine)->Solve(sources, options); !solved.Ok())
  {
    return solved;
  }
  const std::vector<double> distance = (*engine)->Distances();
  std::vector<double> factors(distance.size(), 1.0);
  for (std::size_t v = 0; v < distance.size(); ++v)
  {
    // (Unreached, infinite: 1.)
    factors[v] = std::max(brush.Density, std::min(1.0, distance[v] / brush.Radius));
  }
  return factors;
}

void ApplyBrushFactors(const std::vector<double>& factors, std::vector<double>& density)
{
  if (density.empty())
  {
    density = factors;
    return;
  }
  for (std::size_t v = 0; v < density.size() && v < factors.size(); ++v)
  {
    density[v] *= factors[v];
  }
}

} // namespace gs
