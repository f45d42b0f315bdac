// Shapes for the minimum safe distance tables: binary silhouettes read from images, closed
// polygons, and their boundaries as closed rings (pure C++, no VTK; image reading uses
// OpenImageIO).
//
// Coordinates are shape-local with y up. For a pixel mask, pixel (x, y) is the unit square
// [x, x+1] x [y, y+1] and row y = 0 is the BOTTOM row of the image (the file's last row).
#pragma once

#include "Status.h"
#include "Vector.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gs
{

/// A binary pixel grid, row-major, row 0 at the bottom (y up).
struct SilhouetteMask
{
  int Width = 0;
  int Height = 0;
  std::vector<std::uint8_t> Inside; // Width * Height, 1 = inside the shape

  bool At(int x, int y) const
  {
    return x >= 0 && y >= 0 && x < Width && y < Height &&
      Inside[static_cast<std::size_t>(y) * Width + x] != 0;
  }
  std::size_t Count() const;
};

/// How pixels become inside/outside. Values are in [0, 1] (normalized pixel values).
struct SilhouetteThresholds
{
  /// Images with an alpha channel: inside where alpha >= AlphaThreshold.
  double AlphaThreshold = 0.5;
  /// Images without alpha: inside where the luminance (Rec. 709 weights; the value itself for
  /// one-channel images) is below LuminanceThreshold (dark shape on a light background).
  double LuminanceThreshold = 0.5;
};

/// A thresholded image (ReadSilhouetteImage, MakeSilhouette).
struct SilhouetteImage
{
  SilhouetteMask Mask;
  bool FromAlpha = false; // the alpha channel was used (else the luminance)
  // Images larger than MaximumSilhouetteImageSide on a side are reduced while reading by this
  // integer factor (each output pixel the mean of a factor x factor block); 1 otherwise.
  int ReductionFactor = 1;
  int ImageWidth = 0, ImageHeight = 0; // the file's size
};

/// Longest side, in pixels, of the images thresholded at full size: larger ones (up to any size
/// OpenImageIO reads) are box-reduced while reading, a strip of rows at a time, so that a
/// 16K x 16K image needs about 100 MB instead of 4 GB. The silhouette's outline is traced at
/// this resolution, finer than the tables (AngleBins) and textures (TextureSize) use.
constexpr int MaximumSilhouetteImageSide = 4096;

/// Reads an image with OpenImageIO (PNG, JPEG, TIFF, EXR, ... whatever it reads) and thresholds
/// it. Fails (with a message) on unreadable or empty images, and on images whose silhouette is
/// empty (all transparent / all light) or fills the whole image (all opaque / all dark).
Result<SilhouetteImage> ReadSilhouetteImage(
  const std::string& fileName, const SilhouetteThresholds& thresholds = {});

/// Thresholds pixels given top row first (as in image files), `channels` floats per pixel in
/// [0, 1]; `alphaChannel` is the index of the alpha channel or -1. Same checks as above.
Result<SilhouetteImage> MakeSilhouette(const float* pixels, int width, int height, int channels,
  int alphaChannel, const SilhouetteThresholds& thresholds = {});

/// Writes a mask as an 8-bit PNG (or any format OpenImageIO writes, chosen by extension): RGBA
/// black with alpha 255 inside, 0 outside when `withAlpha`, else one channel, 0 inside and 255
/// outside. Used by tests and tools.
Status WriteSilhouetteImage(
  const SilhouetteMask& mask, const std::string& fileName, bool withAlpha);

/// A 2D region bounded by closed rings (even-odd rule). Each ring lists its vertices once (the
/// closing edge from the last vertex back to the first is implied). Rings are oriented with the
/// inside on the left (outer rings counter-clockwise, holes clockwise).
struct Shape2D
{
  std::vector<std::vector<Vec2>> Rings;

  std::size_t NumberOfEdges() const;
  /// Signed area (positive for correctly oriented rings; for rings that cross each other or
  /// themselves, not the even-odd area: see FilledArea).
  double Area() const;
  /// The area enclosed under the even-odd rule, whatever the rings' orientation, crossings or
  /// repetitions (two identical rings enclose nothing).
  double FilledArea() const;
  /// Exact integrals over the even-odd region of 1, x, y, x^2, y^2 and xy, in coordinates
  /// relative to `ref` (horizontal slabs between vertices and edge crossings; O(E^2) at worst).
  std::array<double, 6> EvenOddIntegrals(const Vec2& ref) const;
  /// Even-odd point-in-region test (points on the boundary may go either way).
  bool Contains(const Vec2& p) const;
};

/// The pixel-boundary contours of a mask: exact boundaries of the union of inside pixels,
/// with collinear runs of pixel edges merged. Pixels touching only at a corner are joined.
Shape2D ShapeFromMask(const SilhouetteMask& mask);

/// A region from arbitrary closed polygons (even-odd rule, any orientation, crossings allowed):
/// drops repeated consecutive vertices and rings with fewer than 3 distinct vertices, then
/// orients each ring by its nesting depth (even depth counter-clockwise, odd depth clockwise;
/// a ring whose signed area is 0, such as a symmetric bow-tie, as given).
Shape2D ShapeFromPolygons(const std::vector<std::vector<Vec2>>& polygons);

/// Rasterizes a region into a mask: a pixel is inside when its centre is. `origin` is the
/// shape-local position of pixel (0, 0)'s lower-left corner, `pixelSize` the pixel's side.
SilhouetteMask RasterizeShape(const Shape2D& shape, int width, int height, const Vec2& origin,
  double pixelSize);

} // namespace gs
