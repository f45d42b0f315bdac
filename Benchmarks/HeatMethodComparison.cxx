// Our saddle vertex graph and discrete geodesic graphs against CGAL's heat method (Crane et al. 2013; CGAL::Heat_method_3,
// prefactored once, then solved from each new source), both measured against the exact solver
// in the same run, on the same welded mesh and sources.
//
//   HeatMethodComparison mesh.off|mesh.ply [...] [--sources N] [--k K] [--dgg A,B,...] [--rounds R]
//   [--dgg-reached A,... (discrete geodesic graphs whose stencils hold the reached vertices too)]
//   [--heat-only (no graphs: the heat method against the exact solver alone)]
#include "BenchmarkSupport.h"
#include "ExactGeodesic.h"
#include "MeshIO.h"
#include "SVGGeodesicSolver.h"
#include "SaddleVertexGraph.h"
#include "TriangleMesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Heat_method_3/Surface_mesh_geodesic_distances_3.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using gs_bench::Median;
using gs_bench::Now;

namespace
{
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

// One solver under comparison: Solve(i) computes the field from sources[i] into Distance(v).
struct Method
{
  std::string Label;
  std::function<void(std::size_t)> Solve;
  std::function<double(int)> Distance;
  double Setup = 0.0;
  Errors Err;
  std::vector<double> Times;
};

template <typename Mode>
struct Heat
{
  CGAL::Heat_method_3::Surface_mesh_geodesic_distances_3<CgalMesh, Mode> Solver;
  CgalMesh::Property_map<CgalMesh::Vertex_index, double> Distance;
  Heat(CgalMesh& cm, const std::string& name)
    : Solver(cm)
  {
    Distance = cm.add_property_map<CgalMesh::Vertex_index, double>(name, 0.0).first;
  }
};

template <typename Mode>
Method MakeHeat(const char* label, const char* name, CgalMesh& cm,
  const std::vector<CgalMesh::Vertex_index>& vi, const std::vector<int>& sources)
{
  Method m;
  m.Label = std::string("CGAL heat method (") + label + ")";
  const double t0 = Now();
  auto heat = std::make_shared<Heat<Mode>>(cm, name);
  // The first solve includes the factorization.
  heat->Solver.add_source(vi[sources[0]]);
  heat->Solver.estimate_geodesic_distances(heat->Distance);
  m.Setup = Now() - t0;
  m.Solve = [heat, &vi, &sources](std::size_t i) {
    heat->Solver.clear_sources();
    heat->Solver.add_source(vi[sources[i]]);
    heat->Solver.estimate_geodesic_distances(heat->Distance);
  };
  m.Distance = [heat, &vi](int v) { return heat->Distance[vi[v]]; };
  return m;
}
} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  int numSources = 5, k = 50, rounds = 5;
  std::vector<double> accuracies = { 1e-2, 1e-3 };
  std::vector<bool> reachedStencils = { false, false }; // per accuracy: ReachedStencil
  bool listed = false; // (--dgg or --dgg-reached given: they replace the default accuracies)
  bool heatOnly = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--sources" && i + 1 < argc)
      numSources = std::max(1, std::atoi(argv[++i]));
    else if (a == "--k" && i + 1 < argc)
      k = std::atoi(argv[++i]);
    else if ((a == "--dgg" || a == "--dgg-reached") && i + 1 < argc)
    {
      if (!listed)
      {
        accuracies.clear();
        reachedStencils.clear();
        listed = true;
      }
      for (const char* p = argv[++i]; *p;)
      {
        char* end = nullptr;
        accuracies.push_back(std::strtod(p, &end));
        reachedStencils.push_back(a == "--dgg-reached");
        p = *end == ',' ? end + 1 : end;
        if (end == p && *p)
          break;
      }
    }
    else if (a == "--heat-only")
      heatOnly = true;
    else if (a == "--rounds" && i + 1 < argc)
      rounds = std::max(1, std::atoi(argv[++i]));
    else if (a == "--help" || a == "-h")
    {
      std::printf(
        "usage: %s mesh [...] [--sources N] [--k K] [--dgg 1e-2,1e-3] [--dgg-reached 1e-1] [--rounds R] "
        "[--heat-only]\n", argv[0]);
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
    const gs::Result<gs::MeshBuild> r = gs::TriangleMeshBuilder::Build(soup.Points, soup.Triangles);
    if (!r.Ok())
    {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), r.Message().c_str());
      continue;
    }
    const gs::TriangleMesh& m = r->Mesh;
    const int nv = m.NumberOfVertices();
    std::vector<int> sources;
    for (int s = 0; s < numSources; ++s)
      sources.push_back(static_cast<int>((static_cast<long long>(s) * 7919 + 13) % nv));
    gs::ExactGeodesicSolver exact(m);
    std::vector<std::vector<double>> ref;
    for (int s : sources)
    {
      static_cast<void>(exact.Solve(s)); // sources are vertices of the mesh: accepted
      ref.push_back(exact.Distances());
    }
    // The graphs: SVG with K, then a discrete geodesic graph per accuracy.
    std::vector<gs::SaddleVertexGraphOptions> configurations(heatOnly ? 0 : 1);
    if (!heatOnly)
      configurations[0].K = k;
    for (std::size_t a = 0; a < (heatOnly ? 0 : accuracies.size()); ++a)
    {
      configurations.emplace_back();
      configurations.back().Construction = gs::GraphConstruction::DiscreteGeodesic;
      configurations.back().Accuracy = accuracies[a];
      configurations.back().ReachedStencil = reachedStencils[a];
    }
    std::vector<std::unique_ptr<gs::SaddleVertexGraph>> graphs;
    std::vector<std::unique_ptr<gs::SVGGeodesicSolver>> solvers;
    for (const auto& opt : configurations)
    {
      graphs.push_back(std::make_unique<gs::SaddleVertexGraph>());
      if (const gs::Status built = graphs.back()->Build(m, opt, nullptr); !built.Ok())
      {
        std::fprintf(stderr, "%s\n", built.Message().c_str());
        graphs.pop_back();
        continue;
      }
      solvers.push_back(std::make_unique<gs::SVGGeodesicSolver>(m, *graphs.back()));
    }
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
    std::vector<Method> methods;
    for (std::size_t g = 0; g < graphs.size(); ++g)
    {
      const gs::SaddleVertexGraph& graph = *graphs[g];
      gs::SVGGeodesicSolver& solver = *solvers[g];
      Method ours;
      char label[64];
      if (graph.GetConstruction() == gs::GraphConstruction::DiscreteGeodesic)
        std::snprintf(label, sizeof(label), "DGG accuracy %.0e%s (%.1f links/v)", graph.GetAccuracy(),
          graph.GetReachedStencil() ? ", reached stencils" : "", graph.MeanDegree());
      else
        std::snprintf(label, sizeof(label), "SVG K=%d (%.1f links/v)", graph.GetK(), graph.MeanDegree());
      ours.Label = label;
      ours.Setup = graph.BuildSeconds();
      ours.Solve = [&solver, &sources](std::size_t i) {
        static_cast<void>(solver.Solve({ gs::SurfacePoint::AtVertex(sources[i]) })); // accepted
      };
      ours.Distance = [&solver](int v) { return solver.Distance(v); };
      methods.push_back(std::move(ours));
    }
    const std::size_t heatIndex = methods.size();
    methods.push_back(MakeHeat<CGAL::Heat_method_3::Direct>("direct", "v:heat", cm, vi, sources));
    methods.push_back(MakeHeat<CGAL::Heat_method_3::Intrinsic_Delaunay>(
      "intrinsic Delaunay", "v:heat_idt", cm, vi, sources));
    // Timing: every method solves every source once untimed (warm caches, errors), then
    // `rounds` timed rounds alternate between the methods source by source, so that a change of
    // load on the machine falls on all of them; each method's figure is its median solve.
    for (std::size_t i = 0; i < sources.size(); ++i)
    {
      for (Method& me : methods)
      {
        me.Solve(i);
        for (int v = 0; v < nv; ++v)
          me.Err.Add(me.Distance(v), ref[i][v]);
      }
    }
    for (int round = 0; round < rounds; ++round)
    {
      for (std::size_t i = 0; i < sources.size(); ++i)
      {
        for (Method& me : methods)
        {
          const double t0 = Now();
          me.Solve(i);
          me.Times.push_back(Now() - t0);
        }
      }
    }
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("%s (%d vertices, %zu sources, %d timed rounds):\n", name.c_str(), nv,
      sources.size(), rounds);
    // Ratios against the heat method (direct), measured in this run.
    const double heatSolve = Median(methods[heatIndex].Times);
    const double heatMean = methods[heatIndex].Err.Mean();
    for (const Method& me : methods)
    {
      const double solve = Median(me.Times);
      std::printf("  %s: setup %.3f s, solve %.2f ms (median; min %.2f), mean error %.2e, max %.2e",
        me.Label.c_str(), me.Setup, 1e3 * solve,
        1e3 * *std::min_element(me.Times.begin(), me.Times.end()), me.Err.Mean(), me.Err.Max);
      if (&me != &methods[heatIndex])
        std::printf(" | heat (direct) / this: error %.1f, solve time %.2f", heatMean / me.Err.Mean(),
          heatSolve / solve);
      std::printf("\n");
    }
    std::fflush(stdout);
  }
  return 0;
}
