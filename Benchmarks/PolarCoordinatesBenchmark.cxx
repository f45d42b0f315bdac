// Geodesic polar coordinates: time to parameterize a patch of a given number of vertices about a
// point (the figure: a 10K-vertex patch), and the inverse-map round trip error.
//
//   PolarCoordinatesBenchmark mesh.off|mesh.ply [...] [--patch 10000] [--sources 5]
#include "GeodesicPolarCoordinates.h"
#include "SaddleVertexGraph.h"
#include "MeshIO.h"
#include "TriangleMesh.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

using namespace gs;

int main(int argc, char** argv)
{
  std::vector<std::string> files;
  int patch = 10000, numSources = 5;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--patch" && i + 1 < argc)
      patch = std::max(10, std::atoi(argv[++i]));
    else if (a == "--sources" && i + 1 < argc)
      numSources = std::max(1, std::atoi(argv[++i]));
    else if (a == "--help" || a == "-h")
    {
      std::printf("usage: %s mesh [...] [--patch N] [--sources S]\n", argv[0]);
      return 0;
    }
    else
      files.push_back(a);
  }
  std::printf("%-24s %8s %8s %10s %10s %10s %10s %11s %11s %14s\n", "mesh", "verts", "patch",
    "radius", "exact_ms", "svg_ms", "build_s", "rho_err", "theta_med", "roundtrip/edge");
  for (const std::string& path : files)
  {
    TriangleSoup soup;
    std::string error;
    if (!ReadMesh(path, soup, error))
    {
      std::fprintf(stderr, "%s\n", error.c_str());
      continue;
    }
    const Result<MeshBuild> r = TriangleMeshBuilder::Build(soup.Points, soup.Triangles);
    if (!r.Ok())
    {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), r.Message().c_str());
      continue;
    }
    const TriangleMesh& m = r->Mesh;
    const int nv = m.NumberOfVertices();
    SaddleVertexGraph graph;
    if (const Status built = graph.Build(m, SaddleVertexGraphOptions(), nullptr); !built.Ok())
    {
      std::fprintf(stderr, "%s: %s\n", path.c_str(), built.Message().c_str());
      continue;
    }
    GeodesicPolarCoordinates pc(m), fast(m, &graph);
    double seconds = 0, fastSeconds = 0, radiusSum = 0, worst = 0, rhoErr = 0;
    std::vector<double> thetaErr;
    long long inside = 0;
    auto compute = [](GeodesicPolarCoordinates& polar, int s, double radius) {
      if (const Status solved = polar.Compute(SurfacePoint::AtVertex(s), radius); !solved.Ok())
      {
        std::fprintf(stderr, "source %d: %s\n", s, solved.Message().c_str());
      }
    };
    for (int k = 0; k < numSources; ++k)
    {
      const int s = static_cast<int>((static_cast<long long>(k) * 7919 + 13) % nv);
      // The radius holding `patch` vertices.
      compute(pc, s, INFINITY);
      const std::vector<int>& all = pc.Inside();
      const int count = std::min<int>(patch, static_cast<int>(all.size()));
      const double radius = pc.Rho(all[count - 1]) * (1 + 1e-12);
      auto t0 = std::chrono::steady_clock::now();
      compute(pc, s, radius);
      seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      t0 = std::chrono::steady_clock::now();
      compute(fast, s, radius);
      fastSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      radiusSum += radius;
      inside += static_cast<long long>(pc.Inside().size());
      double rhoSum = 0;
      for (int v : pc.Inside())
      {
        if (v == s || !std::isfinite(fast.Rho(v)))
          continue;
        rhoSum += std::abs(fast.Rho(v) - pc.Rho(v)) / pc.Rho(v);
        double d = std::fmod(std::abs(fast.Theta(v) - pc.Theta(v)), 2 * 3.14159265358979323846);
        thetaErr.push_back(std::min(d, 2 * 3.14159265358979323846 - d) * 180 / 3.14159265358979323846);
      }
      rhoErr += rhoSum / std::max<std::size_t>(1, pc.Inside().size());
      // Inverse map of a sample of vertices.
      for (std::size_t i = 0; i < pc.Inside().size(); i += 97)
      {
        const int v = pc.Inside()[i];
        if (v == s)
          continue;
        const Result<SurfacePoint> q = pc.ToSurface(pc.Rho(v), pc.Theta(v));
        worst = std::max(worst, q.Ok() ? Norm(m.Interpolate(q->Face, q->Bary) - m.Position(v))
                                       : std::numeric_limits<double>::infinity());
      }
    }
    std::nth_element(thetaErr.begin(), thetaErr.begin() + thetaErr.size() / 2, thetaErr.end());
    const std::string name = path.substr(path.find_last_of('/') + 1);
    std::printf("%-24s %8d %8lld %10.4f %10.2f %10.2f %10.2f %11.2e %11.3f %14.2e\n", name.c_str(),
      nv, inside / numSources, radiusSum / numSources, 1e3 * seconds / numSources,
      1e3 * fastSeconds / numSources, graph.BuildSeconds(), rhoErr / numSources,
      thetaErr.empty() ? 0.0 : thetaErr[thetaErr.size() / 2], worst / m.MeanEdgeLength());
  }
  std::printf("exact_ms / svg_ms: polar coordinates of a patch of that many vertices about a vertex "
              "with the exact engine / the saddle vertex graph engine (K=50, graph built once: "
              "build_s); rho_err: mean relative difference of the SVG engine's rho; theta_med: "
              "median difference of its theta, degrees; roundtrip/edge: largest distance between "
              "a vertex and the inverse map of its exact coordinates, in mean edge lengths "
              "(vertices behind saddles, where the log map folds, included).\n");
  return 0;
}
