// Saddle vertex graph figures (issue: near-exact geodesics in milliseconds): build time, size,
// accuracy against the exact solver for K = 50, 100, 200, and single-source speed of the
// label-correcting and Dijkstra graph solvers against the exact solver, in the same run.
//
//   SVGBenchmark mesh.off|mesh.ply [...] [--k 50,100,200] [--dgg 1e-2,1e-3] [--sources N]
//                [--threads T] [--subdivide S (midpoint subdivisions of each mesh first)]
//                [--dgg-reached 1e-1 (discrete geodesic graphs whose stencils hold the reached
//                vertices too, SaddleVertexGraphOptions::ReachedStencil; labelled r1e-01)]
//   (--k "": no saddle vertex graph. The refined solve is also timed on T threads (2 by default)
//   against one; GS_PARALLEL_MINIMUM=N sets SVGSolveOptions::ParallelRefinementMinimum there.)
#include "BenchmarkSupport.h"
#include "ExactGeodesic.h"
#include "MeshGenerators.h"
#include "MeshIO.h"
#include "SVGGeodesicSolver.h"
#include "SaddleVertexGraph.h"
#include "TriangleMesh.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <cstdlib>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

using namespace gs;
using gs_bench::Now;

namespace
{
// A "Vm...:" line of /proc/self/status in bytes (0 when unavailable).
double StatusBytes(const char* key)
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.rfind(key, 0) == 0)
    {
      return 1024.0 * std::atof(line.c_str() + std::strlen(key));
    }
  }
  return 0.0;
}
} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  std::vector<int> ks = { 50, 100, 200 };
  std::vector<double> accuracies; // discrete geodesic graphs
  std::vector<bool> reachedStencils; // per accuracy: ReachedStencil
  int numSources = 5, threads = 0, subdivisions = 0;
  double maxError = 0.0; // > 0: exit 1 when the refined mean error exceeds it (a test)
  bool failed = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--k" && i + 1 < argc)
    {
      ks.clear();
      std::stringstream ss(argv[++i]);
      std::string item;
      while (std::getline(ss, item, ','))
        ks.push_back(std::atoi(item.c_str()));
    }
    else if ((a == "--dgg" || a == "--dgg-reached") && i + 1 < argc)
    {
      std::stringstream ss(argv[++i]);
      std::string item;
      while (std::getline(ss, item, ','))
      {
        accuracies.push_back(std::atof(item.c_str()));
        reachedStencils.push_back(a == "--dgg-reached");
      }
    }
    else if (a == "--sources" && i + 1 < argc)
      numSources = std::max(1, std::atoi(argv[++i]));
    else if (a == "--subdivide" && i + 1 < argc)
      subdivisions = std::max(0, std::atoi(argv[++i]));
    else if (a == "--threads" && i + 1 < argc)
      threads = std::atoi(argv[++i]);
    else if (a == "--max-error" && i + 1 < argc)
      maxError = std::atof(argv[++i]);
    else if (a == "--help" || a == "-h")
    {
      std::printf("usage: %s mesh [...] [--k 50,100,200] [--dgg 1e-2,1e-3] [--dgg-reached 1e-1] [--sources N] "
                  "[--threads T] [--subdivide S] "
                  "[--max-error E (exit 1 when the mean error exceeds E)]\n",
        argv[0]);
      return 0;
    }
    else
      files.push_back(a);
  }
  if (files.empty())
  {
    std::fprintf(stderr, "no mesh given (try --help)\n");
    return 2;
  }
  std::printf("%-24s %7s %6s %8s %9s %10s %10s %10s %10s %10s %10s %10s %8s %8s %8s %10s %10s "
              "%8s %8s %8s\n",
    "mesh", "verts", "K", "edges/v", "build_s", "us/v/core", "graph_err", "graph_max", "svg_err",
    "svg_max", "pt_err", "exact_s", "lc_ms", "dij_ms", "svg_ms", "exact/svg", "dij/lc", "kept_B/v",
    "peak_B/v", "est_B/v");
  for (const std::string& path : files)
  {
    TriangleSoup soup;
    std::string error;
    if (!ReadMesh(path, soup, error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      continue;
    }
    for (int level = 0; level < subdivisions; ++level)
      soup = SubdivideAtMidpoints(soup);
    Result<MeshBuild> r = TriangleMeshBuilder::Build(soup.Points, soup.Triangles);
    if (!r.Ok())
    {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), r.Message().c_str());
      continue;
    }
    const TriangleMesh& m = r->Mesh;
    const int nv = m.NumberOfVertices();
    std::vector<int> sources;
    for (int k = 0; k < numSources; ++k)
      sources.push_back(static_cast<int>((static_cast<long long>(k) * 7919 + 13) % nv));
    // Exact reference (and its time), once per mesh.
    ExactGeodesicSolver exact(m);
    std::vector<std::vector<double>> ref;
    double exactTime = 0;
    for (int s : sources)
    {
      const double t0 = Now();
      static_cast<void>(exact.Solve(s)); // sources are vertices of the mesh: accepted
      exactTime += Now() - t0;
      ref.push_back(exact.Distances());
    }
    exactTime /= numSources;
    // Face-point sources and their exact fields.
    std::mt19937 rng(3);
    std::uniform_int_distribution<int> face(0, m.NumberOfFaces() - 1);
    std::vector<SurfacePoint> points;
    std::vector<std::vector<double>> pointRef;
    for (int k = 0; k < 3; ++k)
    {
      points.push_back(SurfacePoint::InFace(face(rng), 0.2, 0.5, 0.3));
      static_cast<void>(exact.Solve({ points.back() })); // a point of a face: accepted
      pointRef.push_back(exact.Distances());
    }
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::vector<SaddleVertexGraphOptions> configurations;
    for (int k : ks)
    {
      configurations.emplace_back();
      configurations.back().K = k;
    }
    for (std::size_t a = 0; a < accuracies.size(); ++a)
    {
      configurations.emplace_back();
      configurations.back().Construction = GraphConstruction::DiscreteGeodesic;
      configurations.back().Accuracy = accuracies[a];
      configurations.back().ReachedStencil = reachedStencils[a];
    }
    for (SaddleVertexGraphOptions opt : configurations)
    {
      const bool dgg = opt.Construction == GraphConstruction::DiscreteGeodesic;
      SaddleVertexGraph g;
      opt.NumberOfThreads = threads;
      // Peak memory of the build: the process's peak resident size is reset first (Linux).
      std::ofstream("/proc/self/clear_refs") << "5";
      const double rssBefore = StatusBytes("VmRSS:");
      if (const Status built = g.Build(m, opt, nullptr); !built.Ok())
      {
        std::fprintf(stderr, "%s: %s\n", name.c_str(), built.Message().c_str());
        continue;
      }
      const double peakPerVertex = (StatusBytes("VmHWM:") - rssBefore) / nv;
      const double keptPerVertex = static_cast<double>(g.MemoryBytes()) / nv;
      const double estimatePerVertex = SaddleVertexGraph::EstimatedBuildBytes(nv, opt) / nv;
#ifdef _OPENMP
      const int cores = threads > 0 ? threads : omp_get_max_threads();
#else
      const int cores = 1;
#endif
      SVGGeodesicSolver svg(m, g);
      GraphDistanceSolver graph(g);
      double meanErr = 0, maxErr = 0, lc = 0, dij = 0;
      long long count = 0;
      for (int i = 0; i < numSources; ++i)
      {
        // (The graph solver works on graph nodes: the mesh vertices in the graph's order.)
        const std::vector<std::pair<int, double>> seed = { { g.Node(sources[i]), 0.0 } };
        // Repeat the short solves to get above the timer's resolution.
        const int reps = 5;
        double t0 = Now();
        for (int rep = 0; rep < reps; ++rep)
          graph.Solve(seed, GraphAlgorithm::LabelCorrecting);
        lc += (Now() - t0) / reps;
        t0 = Now();
        for (int rep = 0; rep < reps; ++rep)
          graph.Solve(seed, GraphAlgorithm::Dijkstra);
        dij += (Now() - t0) / reps;
        for (int v = 0; v < nv; ++v)
        {
          if (ref[i][v] > 0 && std::isfinite(ref[i][v]))
          {
            const double e = std::abs(graph.Distance(g.Node(v)) - ref[i][v]) / ref[i][v];
            meanErr += e;
            maxErr = std::max(maxErr, e);
            ++count;
          }
        }
      }
      // The full solver: graph plus geodesic-unfolding refinement, from the same vertices.
      double refinedErr = 0, refinedMax = 0, refined = 0;
      long long refinedCount = 0;
      for (int i = 0; i < numSources; ++i)
      {
        // Timed as the graph solves above (the same repetitions, same warm caches).
        const int reps = 5;
        const double t0 = Now();
        for (int rep = 0; rep < reps; ++rep)
          static_cast<void>(svg.Solve({ SurfacePoint::AtVertex(sources[i]) })); // accepted
        refined += (Now() - t0) / reps;
        for (int v = 0; v < nv; ++v)
        {
          if (ref[i][v] > 0 && std::isfinite(ref[i][v]))
          {
            const double e = std::abs(svg.Distance(v) - ref[i][v]) / ref[i][v];
            refinedErr += e;
            refinedMax = std::max(refinedMax, e);
            ++refinedCount;
          }
        }
      }
      refined /= numSources;
      // The refinement on several threads (SVGSolveOptions::NumberOfThreads, same distances to
      // the bit), alternating with the one-thread solve in the same run.
      double parallelSeconds = 0.0, serialSeconds = 0.0;
      bool same = true;
      const int solveThreads = threads > 0 ? threads : 2;
      if (solveThreads > 1)
      {
        SVGSolveOptions parallel;
        parallel.NumberOfThreads = solveThreads;
        if (const char* minimum = std::getenv("GS_PARALLEL_MINIMUM"))
          parallel.ParallelRefinementMinimum = std::atoll(minimum);
        std::vector<double> one(nv);
        for (int i = 0; i < numSources; ++i)
        {
          for (int rep = 0; rep < 5; ++rep)
          {
            double t0 = Now();
            static_cast<void>(svg.Solve({ SurfacePoint::AtVertex(sources[i]) }));
            serialSeconds += Now() - t0;
            for (int v = 0; v < nv; ++v)
              one[v] = svg.Distance(v);
            t0 = Now();
            static_cast<void>(svg.Solve({ SurfacePoint::AtVertex(sources[i]) }, parallel));
            parallelSeconds += Now() - t0;
            for (int v = 0; v < nv; ++v)
            {
              const double d = svg.Distance(v);
              same = same && std::memcmp(&one[v], &d, sizeof(double)) == 0;
            }
          }
        }
      }
      if (maxError > 0.0 && !(refinedErr / refinedCount <= maxError))
      {
        failed = true;
      }
      double pointErr = 0;
      long long pointCount = 0;
      for (std::size_t i = 0; i < points.size(); ++i)
      {
        static_cast<void>(svg.Solve({ points[i] })); // accepted by the exact solver above
        for (int v = 0; v < nv; ++v)
        {
          if (pointRef[i][v] > 0 && std::isfinite(pointRef[i][v]))
          {
            pointErr += std::abs(svg.Distance(v) - pointRef[i][v]) / pointRef[i][v];
            ++pointCount;
          }
        }
      }
      lc /= numSources;
      dij /= numSources;
      char label[32];
      if (dgg)
        std::snprintf(label, sizeof(label), "%s%.0e", opt.ReachedStencil ? "r" : "e", opt.Accuracy);
      else
        std::snprintf(label, sizeof(label), "%d", g.GetK());
      std::printf("%-24s %7d %6s %8.1f %9.2f %10.1f %10.2e %10.2e %10.2e %10.2e %10.2e %10.4f %8.2f %8.2f %8.2f %10.1f %10.2f %8.0f %8.0f %8.0f\n",
        name.c_str(), nv, label, g.MeanDegree(), g.BuildSeconds(),
        1e6 * g.BuildSeconds() * cores / nv, meanErr / count, maxErr, refinedErr / refinedCount,
        refinedMax, pointErr / pointCount, exactTime, 1e3 * lc, 1e3 * dij, 1e3 * refined,
        exactTime / refined, dij / lc, keptPerVertex, peakPerVertex, estimatePerVertex);
      if (solveThreads > 1)
        std::printf("  refined solve on %d threads: %.2f ms against %.2f ms on one (alternating, %d "
                    "solves each): %.2fx; same distances to the bit: %s\n",
          solveThreads, 1e3 * parallelSeconds / (5 * numSources), 1e3 * serialSeconds / (5 * numSources),
          5 * numSources, serialSeconds / parallelSeconds, same ? "yes" : "NO");
      std::fflush(stdout);
    }
  }
  std::printf("edges/v: adjacency entries per vertex; us/v/core: build time per vertex per core; "
              "graph_err/max: mean/max relative error of graph distances (vertex sources) against "
              "the exact solver; svg_err/max: the same with unfolding refinement (the filter's "
              "result); pt_err: mean error from face-point sources; exact_s: exact solve; "
              "lc/dij_ms: label-correcting / Dijkstra solve on the graph; svg_ms: full solve with "
              "refinement; kept_B/v: graph bytes per vertex; peak_B/v: peak resident memory added by "
              "the build per vertex (VmHWM, reset before); est_B/v: the build's estimate, checked "
              "against the available memory before allocating.\n");
  return failed ? 1 : 0;
}
