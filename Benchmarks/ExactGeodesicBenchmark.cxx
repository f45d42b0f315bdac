// Speed of the exact geodesic solver on real meshes: seconds per single-source, all-destination
// solve (one thread), against edge-graph Dijkstra measured in the same run as the baseline.
//
//   ExactGeodesicBenchmark mesh.off [mesh2.ply ...] [--sources N]
#include "ExactGeodesic.h"
#include "MeshIO.h"
#include "TriangleMesh.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
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
  int numSources = 5;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--sources" && i + 1 < argc)
    {
      numSources = std::max(1, std::atoi(argv[++i]));
    }
    else if (a == "--help" || a == "-h")
    {
      std::printf("usage: %s mesh.off|mesh.ply [...] [--sources N]\n", argv[0]);
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
  std::printf("%-28s %8s %8s %8s %12s %12s %8s %12s %10s\n", "mesh", "vertices", "faces", "saddles",
    "exact_s", "dijkstra_s", "ratio", "windows", "max_err_dij");
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
    double exact = 0, dijkstra = 0, windows = 0, relGap = 0;
    std::vector<double> graph;
    for (int k = 0; k < numSources; ++k)
    {
      const int source = static_cast<int>((static_cast<long long>(k) * 7919 + 13) % m.NumberOfVertices());
      exact += Seconds([&] { static_cast<void>(solver.Solve(source)); }); // a vertex: accepted
      windows += static_cast<double>(solver.Statistics().WindowsPropagated);
      dijkstra += Seconds([&] { GraphDijkstra(m, source, graph); });
      for (int v = 0; v < m.NumberOfVertices(); ++v)
      {
        const double d = solver.Distance(v);
        if (d > 0 && std::isfinite(d))
          relGap = std::max(relGap, (graph[v] - d) / d);
      }
    }
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("%-28s %8d %8d %8d %12.4f %12.4f %8.1f %12.0f %10.4f\n", name.c_str(),
      m.NumberOfVertices(), m.NumberOfFaces(), saddles, exact / numSources, dijkstra / numSources,
      exact / dijkstra, windows / numSources, relGap);
  }
  std::printf("exact_s: seconds per single-source exact solve (one thread); dijkstra_s: edge-graph "
              "Dijkstra, same sources; ratio = exact/dijkstra; max_err_dij: largest relative excess "
              "of the edge-graph distance over the exact one.\n");
  return failures == 0 ? 0 : 1;
}
