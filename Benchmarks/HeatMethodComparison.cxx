// Our saddle vertex graph against CGAL's heat method (Crane et al. 2013; CGAL::Heat_method_3,
// prefactored once, then solved from each new source), both measured against the exact solver
// in the same run, on the same welded mesh and sources.
//
//   HeatMethodComparison mesh.off|mesh.ply [...] [--sources N] [--k K]
#include "ExactGeodesic.h"
#include "MeshIO.h"
#include "SVGGeodesicSolver.h"
#include "SaddleVertexGraph.h"
#include "TriangleMesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Heat_method_3/Surface_mesh_geodesic_distances_3.h>
#include <CGAL/Surface_mesh.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;

namespace
{
double Now()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Errors
{
  double Sum = 0, Max = 0;
  long long Count = 0;
  void Add(double approx, double exact)
  {
    if (exact > 0 && std::isfinite(exact))
    {
      const double e = std::abs(approx - exact) / exact;
      Sum += e;
      Max = std::max(Max, e);
      ++Count;
    }
  }
  double Mean() const { return Count ? Sum / Count : 0.0; }
};

template <typename Mode>
void RunHeat(const char* label, CgalMesh& cm, const std::vector<CgalMesh::Vertex_index>& vi,
  const std::vector<int>& sources, const std::vector<std::vector<double>>& ref, double svgSolve,
  double svgMean)
{
  const double t0 = Now();
  CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3<CgalMesh, Mode> heat(cm);
  auto distance = cm.add_property_map<CgalMesh::Vertex_index, double>("v:heat", 0.0).first;
  // The first solve includes the factorization.
  heat.add_source(vi[sources[0]]);
  heat.estimate_geodesic_distances(distance);
  const double setup = Now() - t0;
  Errors err;
  double solve = 0;
  for (std::size_t i = 0; i < sources.size(); ++i)
  {
    heat.clear_sources();
    heat.add_source(vi[sources[i]]);
    const double t1 = Now();
    heat.estimate_geodesic_distances(distance);
    solve += Now() - t1;
    for (std::size_t v = 0; v < vi.size(); ++v)
      err.Add(distance[vi[v]], ref[i][v]);
  }
  solve /= sources.size();
  std::printf("  CGAL heat method (%s): setup %.3f s, solve %.2f ms, mean error %.2e, max %.2e | "
              "error ratio heat/SVG %.1f, time ratio heat/SVG %.2f\n",
    label, setup, 1e3 * solve, err.Mean(), err.Max, err.Mean() / svgMean, solve / svgSolve);
  cm.remove_property_map(distance);
}
} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  int numSources = 5, k = 50;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--sources" && i + 1 < argc)
      numSources = std::max(1, std::atoi(argv[++i]));
    else if (a == "--k" && i + 1 < argc)
      k = std::atoi(argv[++i]);
    else if (a == "--help" || a == "-h")
    {
      std::printf("usage: %s mesh [...] [--sources N] [--k K]\n", argv[0]);
      return 0;
    }
    else
      files.push_back(a);
  }
  for (const std::string& path : files)
  {
    gs::TriangleSoup soup;
    std::string error;
    if (!gs::ReadMesh(path, soup, error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      continue;
    }
    const gs::MeshBuildResult r = gs::TriangleMeshBuilder::Build(soup.Points, soup.Triangles);
    if (!r.Ok)
    {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), r.Error.c_str());
      continue;
    }
    const gs::TriangleMesh& m = r.Mesh;
    const int nv = m.NumberOfVertices();
    std::vector<int> sources;
    for (int s = 0; s < numSources; ++s)
      sources.push_back(static_cast<int>((static_cast<long long>(s) * 7919 + 13) % nv));
    gs::ExactGeodesicSolver exact(m);
    std::vector<std::vector<double>> ref;
    for (int s : sources)
    {
      exact.Solve(s);
      ref.push_back(exact.Distances());
    }
    gs::SaddleVertexGraph graph;
    gs::SaddleVertexGraphOptions opt;
    opt.K = k;
    if (!graph.Build(m, opt, nullptr, error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      continue;
    }
    gs::SVGGeodesicSolver svg(m, graph);
    Errors svgErr;
    double svgSolve = 0;
    for (std::size_t i = 0; i < sources.size(); ++i)
    {
      const double t0 = Now();
      svg.Solve({ gs::SurfacePoint::AtVertex(sources[i]) });
      svgSolve += Now() - t0;
      for (int v = 0; v < nv; ++v)
        svgErr.Add(svg.Distance(v), ref[i][v]);
    }
    svgSolve /= sources.size();
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("%s (%d vertices, %zu sources):\n  SVG K=%d: build %.2f s, solve %.2f ms, mean error "
                "%.2e, max %.2e\n",
      name.c_str(), nv, sources.size(), graph.GetK(), graph.BuildSeconds(), 1e3 * svgSolve,
      svgErr.Mean(), svgErr.Max);

    CgalMesh cm;
    std::vector<CgalMesh::Vertex_index> vi(nv);
    for (int v = 0; v < nv; ++v)
    {
      const gs::Vec3& p = m.Position(v);
      vi[v] = cm.add_vertex(Kernel::Point_3(p.x, p.y, p.z));
    }
    for (int f = 0; f < m.NumberOfFaces(); ++f)
    {
      const auto& t = m.Face(f);
      cm.add_face(vi[t[0]], vi[t[1]], vi[t[2]]);
    }
    RunHeat<CGAL::Heat_method_3::Direct>("direct", cm, vi, sources, ref, svgSolve, svgErr.Mean());
    RunHeat<CGAL::Heat_method_3::Intrinsic_Delaunay>(
      "intrinsic Delaunay", cm, vi, sources, ref, svgSolve, svgErr.Mean());
    std::fflush(stdout);
  }
  return 0;
}
