// Independent check of the exact geodesic solver against CGAL's Surface_mesh_shortest_path
// (Xin-Wang style exact window propagation, in double precision), on the same welded mesh and
// the same source vertices. Prints the largest relative difference and both solvers' times.
//
//   CgalComparison mesh.off|mesh.ply [--sources N] [--tolerance T]
// Exit status 1 when the largest relative difference exceeds the tolerance (default 1e-6), so
// that the comparison can run as a test.
#include "ExactGeodesic.h"
#include "MeshGenerators.h"
#include "MeshIO.h"
#include "TriangleMesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_shortest_path.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Traits = CGAL::Surface_mesh_shortest_path_traits<Kernel, CgalMesh>;
using CgalShortestPath = CGAL::Surface_mesh_shortest_path<Traits>;

int main(int argc, char** argv)
{
  std::string path;
  int numSources = 3;
  double tolerance = 1e-6;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--sources" && i + 1 < argc)
      numSources = std::max(1, std::atoi(argv[++i]));
    else if (a == "--tolerance" && i + 1 < argc)
      tolerance = std::atof(argv[++i]);
    else if (a == "--help" || a == "-h")
    {
      std::printf("usage: %s mesh.off|mesh.ply|bumpy [--sources N] [--tolerance T]\n", argv[0]);
      return 0;
    }
    else
      path = a;
  }
  gs::TriangleSoup soup;
  std::string error;
  if (path == "bumpy")
  {
    // A generated non-developable sphere with saddles everywhere (no data file needed).
    soup = gs::MakeIcosphere(1.0, 3);
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(0.85, 1.15);
    for (gs::Vec3& p : soup.Points)
      p = p * u(rng);
  }
  else if (path.empty() || !gs::ReadMesh(path, soup, error))
  {
    std::fprintf(stderr, "%s\n", path.empty() ? "no mesh given (try --help)" : error.c_str());
    return 2;
  }
  const gs::Result<gs::MeshBuild> r = gs::TriangleMeshBuilder::Build(soup.Points, soup.Triangles);
  if (!r.Ok())
  {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), r.Message().c_str());
    return 2;
  }
  const gs::TriangleMesh& m = r->Mesh;

  CgalMesh cm;
  std::vector<CgalMesh::Vertex_index> vi(m.NumberOfVertices());
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    const gs::Vec3& p = m.Position(v);
    vi[v] = cm.add_vertex(Kernel::Point_3(p.x, p.y, p.z));
  }
  for (int f = 0; f < m.NumberOfFaces(); ++f)
  {
    const auto& t = m.Face(f);
    if (cm.add_face(vi[t[0]], vi[t[1]], vi[t[2]]) == CgalMesh::null_face())
    {
      std::fprintf(stderr, "CGAL rejected face %d\n", f);
      return 2;
    }
  }

  gs::ExactGeodesicSolver solver(m);
  double ours = 0, theirs = 0, worst = 0;
  for (int k = 0; k < numSources; ++k)
  {
    const int source = static_cast<int>((static_cast<long long>(k) * 7919 + 13) % m.NumberOfVertices());
    auto t0 = std::chrono::steady_clock::now();
    static_cast<void>(solver.Solve(source)); // a vertex of the mesh: accepted
    auto t1 = std::chrono::steady_clock::now();
    CgalShortestPath sp(cm);
    sp.add_source_point(vi[source]);
    sp.build_sequence_tree();
    std::vector<double> ref(m.NumberOfVertices());
    for (int v = 0; v < m.NumberOfVertices(); ++v)
      ref[v] = sp.shortest_distance_to_source_points(vi[v]).first;
    auto t2 = std::chrono::steady_clock::now();
    ours += std::chrono::duration<double>(t1 - t0).count();
    theirs += std::chrono::duration<double>(t2 - t1).count();
    for (int v = 0; v < m.NumberOfVertices(); ++v)
    {
      if (v == source)
        continue;
      const double d = solver.Distance(v);
      const bool cgalReached = std::isfinite(ref[v]) && ref[v] >= 0;
      if (!cgalReached || !std::isfinite(d))
      {
        // Another connected component: both must call it unreachable.
        if (cgalReached != std::isfinite(d))
          worst = INFINITY;
        continue;
      }
      const double rel = std::abs(d - ref[v]) / std::max(ref[v], 1e-300);
      if (!(rel <= worst))
      {
        worst = rel;
        if (!std::isfinite(rel))
          worst = INFINITY;
      }
    }
  }
  std::printf("%s: %d vertices, %d sources: max relative difference %.3g; seconds per solve: "
              "GeodesicShapes %.4f, CGAL %.4f (ratio CGAL/ours %.1f)\n",
    path.c_str(), m.NumberOfVertices(), numSources, worst, ours / numSources, theirs / numSources,
    theirs / ours);
  return worst <= tolerance ? 0 : 1;
}
