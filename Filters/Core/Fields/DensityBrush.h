// The density brush of Wang et al. 2016 (Fig. 10): around a centre on the surface, shapes shrink
// to Density times their size at the centre and grow back linearly with the geodesic distance d
// from it, to their full size at Radius:
//
//   f = max(Density, min(1, d / Radius))
//
// a size factor per vertex, as a density array gives (f = 0.25: sixteen times as many shapes per
// unit area). d comes from the engine the distributor's charts use: the geodesic graph (SVG or
// DGG, refined by geodesic triangle unfolding), or the exact solver when there is no graph.
#pragma once

#include "SaddleVertexGraph.h"
#include "Status.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"

#include <vector>

namespace gs
{

struct DensityBrush
{
  SurfacePoint Center;
  double Radius = 0.0;   // world units; > 0 and finite
  double Density = 0.25; // the factor at the centre, in (0, 1]
};

// Ok when the radius is positive and finite and the density lies in (0, 1]; otherwise an error
// saying which is wrong.
Status CheckBrushParameters(double radius, double density);

// The brush's factor at every vertex: 1 at and beyond Radius and on parts of the mesh the centre
// does not reach. Fails on a radius that is not positive and finite, a density outside (0, 1],
// an invalid centre (TriangleMesh::CheckPoint), or a graph of another mesh. `threads`: for the
// graph solve's refinement (the factors do not depend on it).
Result<std::vector<double>> BrushFactors(const TriangleMesh& mesh, const SaddleVertexGraph* graph,
  const DensityBrush& brush, int threads = 1);

// density[v] *= factors[v] (an empty density, f = 1 everywhere, becomes the factors). Factors and
// density have one value per vertex.
void ApplyBrushFactors(const std::vector<double>& factors, std::vector<double>& density);

} // namespace gs
