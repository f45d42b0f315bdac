// Writes the small analytic meshes bundled in Data/ (ASCII PLY). Run from the build tree:
//   ./build/bin/GeodesicShapesGenerateData Data
// The outputs are committed; rerun only when the generators or the sizes change.
#include "MeshGenerators.h"
#include "MeshIO.h"

#include <cmath>
#include <iostream>
#include <string>

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
  return status;
}
