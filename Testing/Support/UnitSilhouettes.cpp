#include "UnitSilhouettes.h"

#include "SafeDistanceTable.h"

#include <vector>

namespace gs
{

Result<Shape2D> UnitShapeFromImage(const std::string& file)
{
  Result<SilhouetteImage> image = ReadSilhouetteImage(file);
  if (!image.Ok())
  {
    return Status::Error(image.Message());
  }
  Shape2D shape = ShapeFromMask(image->Mask);
  std::vector<Vec2> all;
  for (const auto& ring : shape.Rings)
  {
    all.insert(all.end(), ring.begin(), ring.end());
  }
  const Circle c = SmallestEnclosingCircle(all);
  for (auto& ring : shape.Rings)
  {
    for (Vec2& p : ring)
    {
      p = (p - c.Centre) * (1.0 / c.Radius);
    }
  }
  return shape;
}

} // namespace gs
