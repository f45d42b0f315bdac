// libFuzzer harness: random small meshes through the mesh core and the geodesic engines.
// Bytes -> up to 24 points (coordinates from signed bytes, some repeated or degenerate) and up
// to 40 triangles (indices modulo the point count, possibly out of range or repeated) ->
// TriangleMeshBuilder (must reject bad input with a message, never crash) -> exact geodesics,
// a saddle vertex graph (K = 6) and SVG distances, polar coordinates, a discrete geodesic graph
// (accuracy 0.05; with reached stencils for inputs of odd size) with its distances and polar
// coordinates, and a streamline traced whole and in stages (the same pieces bit for bit).
#include "DirectionField.h"
#include "ExactGeodesic.h"
#include "GeodesicPolarCoordinates.h"
#include "MeshGenerators.h"
#include "SVGGeodesicSolver.h"
#include "SaddleVertexGraph.h"
#include "TriangleMesh.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 4)
  {
    return 0;
  }
  std::size_t at = 0;
  auto next = [&]() -> std::uint8_t { return at < size ? data[at++] : 0; };
  const int np = 3 + next() % 22;
  const int nt = 1 + next() % 40;
  std::vector<gs::Vec3> points;
  for (int i = 0; i < np; ++i)
  {
    const double x = static_cast<std::int8_t>(next()), y = static_cast<std::int8_t>(next()),
                 z = static_cast<std::int8_t>(next());
    points.emplace_back(x / 16.0, y / 16.0, z / 64.0);
  }
  std::vector<std::array<long long, 3>> triangles;
  for (int t = 0; t < nt && at + 3 <= size; ++t)
  {
    // Mostly valid indices, sometimes out of range.
    auto index = [&]() -> long long {
      const std::uint8_t b = next();
      return b == 255 ? -1 : (b == 254 ? np + 5 : b % np);
    };
    triangles.push_back({ index(), index(), index() });
  }
  const gs::Result<gs::MeshBuild> built = gs::TriangleMeshBuilder::Build(points, triangles);
  if (!built.Ok())
  {
    return 0; // rejected with a message: fine
  }
  const gs::TriangleMesh& mesh = built->Mesh;
  gs::ExactGeodesicSolver exact(mesh);
  static_cast<void>(exact.Solve({ gs::SurfacePoint::AtVertex(0) }, gs::ExactGeodesicOptions()));
  for (int v = 0; v < mesh.NumberOfVertices(); ++v)
  {
    const double d = exact.Distance(v);
    if (std::isnan(d))
    {
      __builtin_trap(); // distances are finite or +inf (unreached), never NaN
    }
  }
  gs::SaddleVertexGraph graph;
  gs::SaddleVertexGraphOptions options;
  options.K = 6;
  options.NumberOfThreads = 1;
  if (graph.Build(mesh, options, nullptr).Ok())
  {
    gs::SVGGeodesicSolver svg(mesh, graph);
    static_cast<void>(svg.Solve({ gs::SurfacePoint::InFace(0, 0.2, 0.3, 0.5) }));
    gs::GeodesicPolarCoordinates polar(mesh, &graph);
    // Only crashes matter: a source the solver rejects is an answer too.
    static_cast<void>(polar.Compute(gs::SurfacePoint::InFace(0, 1.0 / 3, 1.0 / 3, 1.0 / 3), 2.0, 0.0));
  }
  // The discrete geodesic graph's propagation (anchors, coverage) on the same mesh.
  gs::SaddleVertexGraph dgg;
  options.Construction = gs::GraphConstruction::DiscreteGeodesic;
  options.Accuracy = 0.05;
  options.ReachedStencil = (size & 1) != 0;
  if (dgg.Build(mesh, options, nullptr).Ok())
  {
    gs::GeodesicPolarCoordinates polar(mesh, &dgg);
    static_cast<void>(polar.Compute(gs::SurfacePoint::InFace(0, 0.2, 0.3, 0.5), 2.0, 0.0));
    gs::SVGGeodesicSolver solver(mesh, dgg);
    if (solver.Solve({ gs::SurfacePoint::AtVertex(0) }).Ok())
    {
      for (int v = 0; v < mesh.NumberOfVertices(); ++v)
      {
        if (std::isnan(solver.Distance(v)))
        {
          __builtin_trap();
        }
      }
    }
  }
  gs::DirectionFieldSolver field(mesh);
  std::vector<double> angles(mesh.NumberOfFaces(), 0.3);
  const gs::SurfacePoint start = gs::SurfacePoint::InFace(0, 0.2, 0.3, 0.5);
  const gs::Streamline whole = field.TraceStreamline(1, angles, start, 0.0, 3.0);
  gs::DirectionFieldSolver::StreamlineTracer tracer(field, 1, angles, start, 0.0, 3.0);
  for (double until : { 0.1, 0.5, 1.5 })
  {
    tracer.Continue(until);
  }
  tracer.Continue();
  const gs::Streamline& staged = tracer.Line();
  if (staged.Pieces.size() != whole.Pieces.size() || staged.Length != whole.Length ||
    staged.Reason != whole.Reason)
  {
    __builtin_trap();
  }
  for (std::size_t k = 0; k < whole.Pieces.size(); ++k)
  {
    const gs::CurvePiece &a = whole.Pieces[k], &b = staged.Pieces[k];
    if (a.Face != b.Face || a.A.x != b.A.x || a.A.y != b.A.y || a.A.z != b.A.z || a.B.x != b.B.x ||
      a.B.y != b.B.y || a.B.z != b.B.z)
    {
      __builtin_trap();
    }
  }
  return 0;
}
