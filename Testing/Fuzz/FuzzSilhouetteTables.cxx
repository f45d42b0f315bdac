// libFuzzer harness: random pixels through silhouettes and minimum safe distance tables.
// Bytes -> a small image (width, height up to 24, 1 to 4 channels, optional alpha) ->
// MakeSilhouette (must reject empty / full images with a message) -> ShapeFromMask ->
// ComputeSafeDistanceTables with few bins, two classes (the shape and itself turned into a
// polygon class), parts split for long shapes.
#include "SafeDistanceTable.h"
#include "Silhouette.h"

#include <cstddef>
#include <cstdint>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size < 4)
  {
    return 0;
  }
  const int width = 1 + data[0] % 24, height = 1 + data[1] % 24;
  const int channels = 1 + data[2] % 4;
  const int alpha = channels == 2 || channels == 4 ? channels - 1 : -1;
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * channels, 1.0f);
  for (std::size_t i = 0; i < pixels.size() && 3 + i < size; ++i)
  {
    pixels[i] = data[3 + i] / 255.0f;
  }
  const gs::Result<gs::SilhouetteImage> read =
    gs::MakeSilhouette(pixels.data(), width, height, channels, alpha);
  if (!read.Ok())
  {
    return 0;
  }
  const gs::Shape2D shape = gs::ShapeFromMask(read->Mask);
  gs::SafeDistanceOptions options;
  options.AngleBins = 4 + data[2] % 5;
  options.DistanceSteps = 8;
  options.Rows = 64;
  options.MaximumAspectRatio = 1.5 + (data[1] % 4);
  std::vector<gs::SafeDistanceInput> classes{ { "a", shape } };
  if (data[0] % 2)
  {
    classes.push_back({ "b", gs::ShapeFromPolygons(shape.Rings) });
  }
  const gs::Result<gs::SafeDistanceTables> r = gs::ComputeSafeDistanceTables(classes, options);
  if (r.Ok())
  {
    for (double v : r->Values)
    {
      if (!(v >= 0.0) || v > 1e9)
      {
        __builtin_trap(); // tables hold finite non-negative distances
      }
    }
  }
  return 0;
}
