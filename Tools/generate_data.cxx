// Writes the small analytic meshes bundled in Data/ (ASCII PLY), the bumpy sphere of the main
// job, and the four shape silhouettes of Data/shapes/ (RGBA PNG, drawn here as polygons and
// rasterized: a pentagram, a gull, a leaf and a fish). Run from the build tree:
//   ./build/bin/GeodesicShapesGenerateData Data
// The outputs are committed; rerun only when the generators or the sizes change.
#include "MeshGenerators.h"
#include "MeshIO.h"
#include "Silhouette.h"

#include <cmath>
#include <iostream>
#include <string>

namespace
{
// Smooth bumps on a unit icosphere (level 4): regions of positive and negative curvature.
gs::TriangleSoup BumpySphere()
{
  gs::TriangleSoup s = gs::MakeIcosphere(1.0, 4);
  for (gs::Vec3& p : s.Points)
  {
    p = p * (1.0 + 0.12 * std::sin(3.0 * p.x) * std::sin(3.0 * p.y) * std::sin(3.0 * p.z));
  }
  return s;
}

// A gull in flight, wings spread along x.
std::vector<gs::Vec2> Gull()
{
  return { { -1.0, 0.05 }, { -0.75, 0.3 }, { -0.45, 0.38 }, { -0.18, 0.18 }, { 0.0, 0.26 },
    { 0.18, 0.18 }, { 0.45, 0.38 }, { 0.75, 0.3 }, { 1.0, 0.05 }, { 0.7, 0.14 }, { 0.4, 0.12 },
    { 0.15, -0.02 }, { 0.06, -0.3 }, { -0.06, -0.3 }, { -0.15, -0.02 }, { -0.4, 0.12 },
    { -0.7, 0.14 } };
}

// A pointed leaf along x (long: MSDT Source splits it into parts).
std::vector<gs::Vec2> Leaf()
{
  std::vector<gs::Vec2> ring;
  for (int k = 0; k <= 24; ++k)
  {
    const double x = -1.0 + 2.0 * k / 24;
    ring.emplace_back(x, 0.32 * (1.0 - x * x) * (1.0 + 0.3 * x));
  }
  for (int k = 23; k >= 1; --k)
  {
    const double x = -1.0 + 2.0 * k / 24;
    ring.emplace_back(x, -0.32 * (1.0 - x * x) * (1.0 + 0.3 * x));
  }
  return ring;
}

// A fish swimming towards -x: an elliptic body and a forked tail.
std::vector<gs::Vec2> Fish()
{
  const double pi = std::acos(-1.0);
  std::vector<gs::Vec2> ring;
  for (int k = 0; k <= 32; ++k)
  {
    const double a = 0.12 * pi + (2.0 * pi - 0.24 * pi) * k / 32;
    ring.emplace_back(-0.2 + 0.62 * std::cos(a), 0.36 * std::sin(a));
  }
  for (const gs::Vec2& p : std::vector<gs::Vec2>{ { 0.55, -0.08 }, { 0.98, -0.38 }, { 0.82, 0.0 },
         { 0.98, 0.38 }, { 0.55, 0.08 } })
  {
    ring.push_back(p);
  }
  return ring;
}

int WriteShapes(const std::string& dir)
{
  const struct
  {
    const char* Name;
    std::vector<gs::Vec2> Ring;
  } shapes[] = { { "star.png", gs::MakeStarPolygon(5, 1.0, 0.382) }, { "gull.png", Gull() }, { "leaf.png", Leaf() },
    { "fish.png", Fish() } };
  int status = 0;
  for (const auto& shape : shapes)
  {
    const int size = 128;
    const gs::SilhouetteMask mask = gs::RasterizeShape(
      gs::ShapeFromPolygons({ shape.Ring }), size, size, gs::Vec2{ -1.05, -1.05 }, 2.1 / size);
    const std::string path = dir + "/shapes/" + shape.Name;
    if (const gs::Status written = gs::WriteSilhouetteImage(mask, path, true); !written.Ok())
    {
      std::cerr << path << ": " << written.Message() << "\n";
      status = 1;
      continue;
    }
    std::cout << path << ": " << mask.Count() << " pixels inside\n";
  }
  return status;
}
} // namespace

int main(int argc, char* argv[])
{
  const std::string dir = argc > 1 ? argv[1] : "Data";
  const double pi = std::acos(-1.0);
  struct Item
  {
    const char* Name;
    gs::TriangleSoup Soup;
  };
  const Item items[] = {
    { "planar_grid.ply", gs::MakePlanarGrid(20, 20, 1.0, 1.0) },
    { "lshape.ply", gs::MakeLShape(16) },
    { "cone.ply", gs::MakeCone(pi / 6.0, 1.0, 16, 48) },
    { "cylinder.ply", gs::MakeCylinder(0.5, 2.0, 48, 24) },
    { "sphere.ply", gs::MakeIcosphere(1.0, 3) },
    { "torus.ply", gs::MakeTorus(1.0, 0.4, 72, 32) },
    { "bumpy_sphere.ply", BumpySphere() },
  };
  int status = 0;
  for (const Item& item : items)
  {
    std::string error;
    const std::string path = dir + "/" + item.Name;
    if (!gs::WritePLY(path, item.Soup, error))
    {
      std::cerr << path << ": " << error << "\n";
      status = 1;
      continue;
    }
    std::cout << path << ": " << item.Soup.Points.size() << " points, "
              << item.Soup.Triangles.size() << " triangles\n";
  }
  return WriteShapes(dir) | status;
}
