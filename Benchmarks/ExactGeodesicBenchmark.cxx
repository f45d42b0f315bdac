// Speed of the exact geodesic solver on real meshes: seconds per single-source, all-destination
// solve (one thread), against edge-graph Dijkstra measured in the same run as the baseline.
//
//   ExactGeodesicBenchmark mesh.off [mesh2.ply ...] [--sources N] [--subdivide S] [--first-source F]
//
// Every solve is also checked: each vertex the edge graph reaches (the source's connected part)
// must get a finite exact distance, never above the edge-graph distance (the length of a path on
// the surface) by more than rounding. The program exits 1 when a check fails.
#include "ExactGeodesic.h"
#include "ExactInParts.h"
#include "MeshGenerators.h"
#include "MeshIO.h"
#include "TriangleMesh.h"
#include "VirtualSourceGeodesic.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <queue>
#include <string>
#include <vector>

using namespace gs;

namespace
{
double Seconds(const std::function<void()>& f)
{
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Baseline: Dijkstra on the edge graph (a binary heap), the classic fast approximation.
double GraphDijkstra(const TriangleMesh& m, int source, std::vector<double>& d)
{
  d.assign(m.NumberOfVertices(), INFINITY);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  d[source] = 0;
  q.push({ 0, source });
  while (!q.empty())
  {
    auto [dv, v] = q.top();
    q.pop();
    if (dv > d[v])
      continue;
    const int start = m.VertexHalfedge(v);
    int h = start;
    do
    {
      for (int e : { h, TriangleMesh::Prev(h) })
      {
        const int w = e == h ? m.Destination(h) : m.Origin(e);
        const double nd = dv + m.EdgeLength(e);
        if (nd < d[w])
        {
          d[w] = nd;
          q.push({ nd, w });
        }
      }
      h = m.RotateCCW(h);
    } while (h >= 0 && h != start);
  }
  return 0;
}
} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  int numSources = 5, subdivisions = 0, firstSource = 0, parts = 0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--sources" && i + 1 < argc)
    {
      numSources = std::max(1, std::atoi(argv[++i]));
    }
    else if (a == "--subdivide" && i + 1 < argc)
    {
      subdivisions = std::max(0, std::atoi(argv[++i]));
    }
    else if (a == "--parts" && i + 1 < argc)
    {
      parts = std::max(0, std::atoi(argv[++i]));
    }
    else if (a == "--first-source" && i + 1 < argc)
    {
      firstSource = std::max(0, std::atoi(argv[++i]));
    }
    else if (a == "--help" || a == "-h")
    {
      std::printf("usage: %s mesh.off|mesh.ply [...] [--sources N] [--subdivide S (midpoint "
                  "subdivisions first)] [--first-source F (skip the first F sources)] [--parts P (also the "
                  "exact solver in P parts on threads: time and difference)]\n",
        argv[0]);
      return 0;
    }
    else
    {
      files.push_back(a);
    }
  }
  if (files.empty())
  {
    std::fprintf(stderr, "no mesh given (try --help)\n");
    return 2;
  }
  std::printf("%-28s %8s %8s %8s %12s %12s %8s %12s %10s %10s %10s %10s %8s\n", "mesh", "vertices",
    "faces", "saddles", "exact_s", "dijkstra_s", "ratio", "windows", "max_err_dij", "vsp_s",
    "vsp_mean", "vsp_max", "vsp_Mv/s");
  int failures = 0;
  for (const std::string& path : files)
  {
    TriangleSoup soup;
    std::string error;
    if (!ReadMesh(path, soup, error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      ++failures;
      continue;
    }
    for (int level = 0; level < subdivisions; ++level)
      soup = SubdivideAtMidpoints(soup);
    Result<MeshBuild> r = TriangleMeshBuilder::Build(soup.Points, soup.Triangles);
    if (!r.Ok())
    {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), r.Message().c_str());
      ++failures;
      continue;
    }
    const TriangleMesh& m = r->Mesh;
    int saddles = 0;
    for (int v = 0; v < m.NumberOfVertices(); ++v)
      saddles += m.IsSaddleVertex(v);
    ExactGeodesicSolver solver(m);
    std::unique_ptr<ExactSolverInParts> inParts;
    VirtualSourceSolver virtualSources(m);
    double exact = 0, dijkstra = 0, windows = 0, relGap = 0, vsp = 0, vspSum = 0, vspSigned = 0, vspMax = 0;
    double vspAngles = 0;
    std::vector<double> angleErrors; // degrees
    long long vspCount = 0, vspUnreached = 0;
    std::vector<double> graph;
    const double rounding = 1e-9 * m.BoundingBoxDiagonal();
    for (int k = firstSource; k < firstSource + numSources; ++k)
    {
      const int source = static_cast<int>((static_cast<long long>(k) * 7919 + 13) % m.NumberOfVertices());
      const double exactTime = Seconds([&] { static_cast<void>(solver.Solve(source)); }); // a vertex: accepted
      exact += exactTime;
      windows += static_cast<double>(solver.Statistics().WindowsPropagated);
      if (parts > 0)
      {
        // The solver in parts on threads, against the serial one just run.
        if (!inParts)
          inParts = std::make_unique<ExactSolverInParts>(m, parts);
        const double t = Seconds([&] { static_cast<void>(inParts->Solve(std::vector<int>{ source })); });
        double largest = 0, worst = 0;
        for (int v = 0; v < m.NumberOfVertices(); ++v)
        {
          const double d = solver.Distance(v);
          if (std::isfinite(d))
          {
            largest = std::max(largest, d);
            worst = std::max(worst, std::abs(inParts->Distance(v) - d));
          }
          else if (std::isfinite(inParts->Distance(v)))
            worst = std::numeric_limits<double>::infinity();
        }
        std::printf("  source %d: exact %.3f s, in %d parts %.3f s (%.2fx), %d rounds, windows %lld "
                    "against %lld; largest difference %.2e of the largest distance\n",
          source, exactTime, parts, t, exactTime / t, inParts->Rounds(),
          static_cast<long long>(inParts->WindowsPropagated()),
          static_cast<long long>(solver.Statistics().WindowsPropagated), worst / largest);
      }
      dijkstra += Seconds([&] { GraphDijkstra(m, source, graph); });
      vsp += Seconds([&] { static_cast<void>(virtualSources.Solve({ SurfacePoint::AtVertex(source) })); });
      int notFinite = 0, aboveGraph = 0;
      for (int v = 0; v < m.NumberOfVertices(); ++v)
      {
        const double d = solver.Distance(v);
        if (d > 0 && std::isfinite(d))
        {
          relGap = std::max(relGap, (graph[v] - d) / d);
          const double e = std::abs(virtualSources.Distance(v) - d) / d;
          vspSum += e;
          vspSigned += (virtualSources.Distance(v) - d) / d;
          vspMax = std::max(vspMax, e);
          ++vspCount;
        }
        if (std::isfinite(graph[v]) && !std::isfinite(virtualSources.Distance(v)) && vspUnreached++ < 3)
          std::printf("  source %d: vertex %d unreached by virtual sources\n", source, v);
        if (std::isfinite(graph[v]) && !std::isfinite(d))
        {
          if (notFinite++ < 5)
            std::printf("  source %d: vertex %d has distance %g (edge graph %g)\n", source, v, d,
              graph[v]);
        }
        else if (d > graph[v] + rounding)
        {
          if (aboveGraph++ < 5)
            std::printf("  source %d: vertex %d exact %.17g above the edge graph's %.17g\n",
              source, v, d, graph[v]);
        }
      }
      VirtualSourceOptions withAngles;
      withAngles.Angles = true;
      vspAngles += Seconds([&] { static_cast<void>(virtualSources.Solve({ SurfacePoint::AtVertex(source) }, withAngles)); });
      for (int v = 0; v < m.NumberOfVertices(); ++v)
      {
        if (v != source && std::isfinite(solver.Distance(v)))
        {
          const double a = virtualSources.DepartureAngle(v) - solver.DepartureAngle(v);
          angleErrors.push_back(std::abs(std::remainder(a, 2.0 * M_PI)) * 180.0 / M_PI);
        }
      }
      if (notFinite + aboveGraph > 0)
      {
        std::printf("  source %d: %d reachable vertices not finite, %d above the edge graph\n",
          source, notFinite, aboveGraph);
        ++failures;
      }
    }
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("%-28s %8d %8d %8d %12.4f %12.4f %8.1f %12.0f %10.4f %10.4f %10.2e %10.2e %8.2f\n",
      name.c_str(), m.NumberOfVertices(), m.NumberOfFaces(), saddles, exact / numSources,
      dijkstra / numSources, exact / dijkstra, windows / numSources, relGap, vsp / numSources,
      vspSum / std::max(1LL, vspCount), vspMax, 1e-6 * m.NumberOfVertices() * numSources / vsp);
    std::printf("signed mean %.3e\n", vspSigned / std::max(1LL, vspCount));
    if (!angleErrors.empty())
    {
      // Departure angles (virtual sources against exact): mean, median and 95th percentile.
      double sum = 0;
      for (double e : angleErrors)
        sum += e;
      const auto at = [&](double q) {
        std::vector<double> sorted = angleErrors;
        const std::size_t i = static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1));
        std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(i), sorted.end());
        return sorted[i];
      };
      std::printf("vsp departure angles: %.2fx the solve's time; difference from exact: mean %.3f deg, "
                  "median %.3f, 95th percentile %.3f\n",
        vspAngles / vsp, sum / static_cast<double>(angleErrors.size()), at(0.5), at(0.95));
    }
  }
  std::printf("exact_s: seconds per single-source exact solve (one thread); dijkstra_s: edge-graph "
              "Dijkstra, same sources; ratio = exact/dijkstra; max_err_dij: largest relative excess "
              "of the edge-graph distance over the exact one.\n");
  return failures == 0 ? 0 : 1;
}
