// Direction fields: first solve (with factorization) against re-solve (factorization kept) on
// real meshes, for both modes, with Poincare-Hopf checked on every result.
//
//   DirectionFieldBenchmark mesh.off [mesh.off ...]
//
// Smoothest (Knoppel et al. 2013), N = 4, with a stroke of constrained faces: first solve, then
// re-solve with the stroke's directions turned (same faces). Prescribed singularities (trivial
// connections), N = 4, |chi| * 4 singularities of index -1/4 (or 8 of +1/4 on a sphere): first
// solve, then re-solve with the singularities moved to other vertices.
#include "DirectionField.h"
#include "MeshIO.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;
double Seconds(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::vector<gs::VertexSingularity> Spread(const gs::TriangleMesh& m, int offset)
{
  const int chi = m.EulerCharacteristic();
  const int count = chi > 0 ? 4 * chi : -4 * chi;
  const double index = chi > 0 ? 0.25 : -0.25;
  std::vector<gs::VertexSingularity> s;
  for (int k = 0; k < count; ++k)
  {
    s.push_back({ static_cast<int>((static_cast<long long>(2 * k + 1) * m.NumberOfVertices() / (2 * count) + offset) %
                    m.NumberOfVertices()),
      index });
  }
  return s;
}
} // namespace

int main(int argc, char* argv[])
{
  std::printf("%-22s %7s %5s | %-16s | %-34s | %-34s\n", "mesh", "faces", "chi",
    "smoothest (free)", "smoothest N=4 + stroke: first / re", "prescribed N=4: first / re-solve");
  int bad = 0;
  for (int i = 1; i < argc; ++i)
  {
    gs::TriangleSoup soup;
    std::string error;
    if (!gs::ReadMesh(argv[i], soup, error))
    {
      std::fprintf(stderr, "%s: %s\n", argv[i], error.c_str());
      return 1;
    }
    auto built = gs::TriangleMeshBuilder::Build(soup.Points, soup.Triangles);
    if (!built.Ok())
    {
      std::fprintf(stderr, "%s: %s\n", argv[i], built.Message().c_str());
      return 1;
    }
    const gs::TriangleMesh& mesh = built->Mesh;
    const int chi = mesh.EulerCharacteristic();
    // A stroke: 40 faces walked across edges from face 0.
    std::vector<gs::FaceDirectionConstraint> stroke;
    {
      int f = 0, from = -1;
      for (int k = 0; k < 40; ++k)
      {
        const gs::Vec3 e = mesh.Position(mesh.Face(f)[1]) - mesh.Position(mesh.Face(f)[0]);
        stroke.push_back({ f, e });
        int next = -1;
        for (int c = 0; c < 3 && next < 0; ++c)
        {
          const int t = mesh.Twin(3 * f + (c + k) % 3);
          if (t >= 0 && t / 3 != from)
          {
            next = t / 3;
          }
        }
        if (next < 0)
        {
          break;
        }
        from = f;
        f = next;
      }
    }
    std::vector<gs::FaceDirectionConstraint> turned = stroke;
    for (auto& c : turned)
    {
      c.Direction = gs::Cross(mesh.FaceNormal(c.Face), c.Direction) + c.Direction * 0.3;
    }
    std::vector<double> angles;
    double smoothFirst = 0, smoothRe = 0, presFirst = 0, presRe = 0, free = 0;
    {
      // No constraint: the smallest eigenvector (factorization + Rayleigh-Ritz iterations).
      gs::DirectionFieldSolver solver(mesh);
      auto t0 = Clock::now();
      const bool ok = solver.SolveSmoothest(4, 0.0, {}, angles).Ok();
      free = Seconds(t0);
      bad += !ok || std::abs(solver.IndexSum(4, angles) - chi) > 1e-6;
    }
    {
      gs::DirectionFieldSolver solver(mesh);
      auto t0 = Clock::now();
      bool ok = solver.SolveSmoothest(4, 0.0, stroke, angles).Ok();
      smoothFirst = Seconds(t0);
      bad += !ok || std::abs(solver.IndexSum(4, angles) - chi) > 1e-6;
      t0 = Clock::now();
      ok = solver.SolveSmoothest(4, 0.0, turned, angles).Ok();
      smoothRe = Seconds(t0);
      bad += !ok || std::abs(solver.IndexSum(4, angles) - chi) > 1e-6;
    }
    {
      gs::DirectionFieldSolver solver(mesh);
      auto t0 = Clock::now();
      const gs::Status first = solver.SolvePrescribed(4, Spread(mesh, 0), {}, angles);
      presFirst = Seconds(t0);
      bad += !first.Ok() || std::abs(solver.IndexSum(4, angles) - chi) > 1e-6;
      if (!first.Ok())
      {
        std::fprintf(stderr, "%s\n", first.Message().c_str());
      }
      t0 = Clock::now();
      const bool ok = solver.SolvePrescribed(4, Spread(mesh, 17), {}, angles).Ok();
      presRe = Seconds(t0);
      bad += !ok || std::abs(solver.IndexSum(4, angles) - chi) > 1e-6;
    }
    std::string name = argv[i];
    name = name.substr(name.find_last_of('/') + 1);
    std::printf("%-22s %7d %5d | %14.3f s | %7.3f s / %7.4f s = %6.1fx  | %7.3f s / %7.4f s = %6.1fx\n",
      name.c_str(), mesh.NumberOfFaces(), chi, free, smoothFirst, smoothRe, smoothFirst / smoothRe,
      presFirst, presRe, presFirst / presRe);
  }
  if (bad)
  {
    std::fprintf(stderr, "%d solve(s) failed or broke Poincare-Hopf\n", bad);
    return 1;
  }
  return 0;
}
