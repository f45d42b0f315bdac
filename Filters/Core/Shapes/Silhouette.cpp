#include "Silhouette.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

namespace gs
{

std::size_t SilhouetteMask::Count() const
{
  return static_cast<std::size_t>(std::count(this->Inside.begin(), this->Inside.end(), 1));
}

//------------------------------------------------------------------------------
Result<SilhouetteImage> MakeSilhouette(const float* pixels, int width, int height, int channels,
  int alphaChannel, const SilhouetteThresholds& thresholds)
{
  if (width <= 0 || height <= 0 || channels <= 0 || !pixels)
  {
    return Status::Error("empty image");
  }
  SilhouetteImage result;
  result.FromAlpha = alphaChannel >= 0 && alphaChannel < channels;
  SilhouetteMask& mask = result.Mask;
  mask.Width = width;
  mask.Height = height;
  mask.Inside.assign(static_cast<std::size_t>(width) * height, 0);
  const int colours = result.FromAlpha ? std::min(alphaChannel, 3) : std::min(channels, 3);
  for (int row = 0; row < height; ++row)
  {
    const int y = height - 1 - row; // files store the top row first; y is up
    for (int x = 0; x < width; ++x)
    {
      const float* p = pixels + (static_cast<std::size_t>(row) * width + x) * channels;
      bool inside;
      if (result.FromAlpha)
      {
        inside = p[alphaChannel] >= thresholds.AlphaThreshold;
      }
      else
      {
        // Rec. 709 luminance of RGB; a grey image is its own luminance.
        const double lum =
          colours >= 3 ? 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2] : p[0];
        inside = lum < thresholds.LuminanceThreshold;
      }
      mask.Inside[static_cast<std::size_t>(y) * width + x] = inside ? 1 : 0;
    }
  }
  const std::size_t count = mask.Count();
  if (count == 0)
  {
    return Status::Error(result.FromAlpha
        ? "no pixel has alpha >= AlphaThreshold (all transparent): empty silhouette"
        : "no pixel has luminance < LuminanceThreshold (all light): empty silhouette");
  }
  if (count == mask.Inside.size())
  {
    return Status::Error(result.FromAlpha
        ? "every pixel has alpha >= AlphaThreshold (all opaque): the silhouette is the whole image"
        : "every pixel has luminance < LuminanceThreshold (all dark): the silhouette is the whole "
          "image");
  }
  return result;
}

//------------------------------------------------------------------------------
Result<SilhouetteImage> ReadSilhouetteImage(
  const std::string& fileName, const SilhouetteThresholds& thresholds)
{
  auto input = OIIO::ImageInput::open(fileName);
  if (!input)
  {
    return Status::Error("cannot read image '" + fileName + "': " + OIIO::geterror());
  }
  const OIIO::ImageSpec spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
  {
    return Status::Error("image '" + fileName + "' is empty");
  }
  // Read a strip of `factor` rows at a time; large images are box-reduced by that integer
  // factor on the way (factor 1: the rows as they are).
  const int longest = std::max(spec.width, spec.height);
  const int factor = (longest + MaximumSilhouetteImageSide - 1) / MaximumSilhouetteImageSide;
  const int width = (spec.width + factor - 1) / factor;
  const int height = (spec.height + factor - 1) / factor;
  const int channels = spec.nchannels;
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * channels, 0.0f);
  std::vector<float> strip(static_cast<std::size_t>(spec.width) * factor * channels);
  for (int row = 0; row < height; ++row)
  {
    const int y0 = spec.y + row * factor;
    const int y1 = std::min(y0 + factor, spec.y + spec.height);
    if (!input->read_scanlines(0, 0, y0, y1, 0, 0, channels, OIIO::TypeDesc::FLOAT, strip.data()))
    {
      return Status::Error("cannot read the pixels of '" + fileName + "': " + input->geterror());
    }
    const int rows = y1 - y0;
    float* out = &pixels[static_cast<std::size_t>(row) * width * channels];
    for (int r = 0; r < rows; ++r)
    {
      const float* in = &strip[static_cast<std::size_t>(r) * spec.width * channels];
      for (int x = 0; x < spec.width; ++x)
      {
        float* o = out + static_cast<std::size_t>(x / factor) * channels;
        for (int c = 0; c < channels; ++c)
        {
          o[c] += in[static_cast<std::size_t>(x) * channels + c];
        }
      }
    }
    if (factor > 1)
    {
      for (int x = 0; x < width; ++x)
      {
        const int columns = std::min(factor, spec.width - x * factor);
        const float scale = 1.0f / static_cast<float>(rows * columns);
        for (int c = 0; c < channels; ++c)
        {
          out[static_cast<std::size_t>(x) * channels + c] *= scale;
        }
      }
    }
  }
  input->close();
  Result<SilhouetteImage> result =
    MakeSilhouette(pixels.data(), width, height, channels, spec.alpha_channel, thresholds);
  if (!result.Ok())
  {
    return Status::Error("image '" + fileName + "': " + result.Message());
  }
  result->ReductionFactor = factor;
  result->ImageWidth = spec.width;
  result->ImageHeight = spec.height;
  return result;
}

//------------------------------------------------------------------------------
Status WriteSilhouetteImage(const SilhouetteMask& mask, const std::string& fileName, bool withAlpha)
{
  if (mask.Width <= 0 || mask.Height <= 0)
  {
    return Status::Error("empty mask");
  }
  auto output = OIIO::ImageOutput::create(fileName);
  if (!output)
  {
    return Status::Error("cannot create '" + fileName + "': " + OIIO::geterror());
  }
  const int channels = withAlpha ? 4 : 1;
  OIIO::ImageSpec spec(mask.Width, mask.Height, channels, OIIO::TypeDesc::UINT8);
  if (withAlpha)
  {
    spec.alpha_channel = 3;
  }
  std::vector<unsigned char> pixels(static_cast<std::size_t>(mask.Width) * mask.Height * channels);
  for (int row = 0; row < mask.Height; ++row)
  {
    const int y = mask.Height - 1 - row;
    for (int x = 0; x < mask.Width; ++x)
    {
      unsigned char* p = &pixels[(static_cast<std::size_t>(row) * mask.Width + x) * channels];
      const bool in = mask.At(x, y);
      if (withAlpha)
      {
        p[0] = p[1] = p[2] = 0;
        p[3] = in ? 255 : 0;
      }
      else
      {
        p[0] = in ? 0 : 255;
      }
    }
  }
  if (!output->open(fileName, spec) ||
    !output->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !output->close())
  {
    return Status::Error("cannot write '" + fileName + "': " + output->geterror());
  }
  return Status();
}

//------------------------------------------------------------------------------
std::size_t Shape2D::NumberOfEdges() const
{
  std::size_t n = 0;
  for (const auto& ring : this->Rings)
  {
    n += ring.size();
  }
  return n;
}

double Shape2D::Area() const
{
  double twice = 0.0;
  for (const auto& ring : this->Rings)
  {
    for (std::size_t k = 0; k < ring.size(); ++k)
    {
      twice += Cross(ring[k], ring[(k + 1) % ring.size()]);
    }
  }
  return 0.5 * twice;
}

std::array<double, 6> Shape2D::EvenOddIntegrals(const Vec2& ref) const
{
  // Horizontal slabs between consecutive event heights (every vertex, every crossing of two
  // edges): inside a slab no two edges cross, so the edges spanning it keep their order and
  // the even-odd region is the union of the spans between crossings 0-1, 2-3, ... Across a span
  // at height y the integrands (xr - xl, (xr^2 - xl^2) / 2, y (xr - xl), (xr^3 - xl^3) / 3,
  // y^2 (xr - xl), y (xr^2 - xl^2) / 2) are cubic in y (xl, xr are linear): Simpson's rule
  // over the slab is exact.
  struct Edge
  {
    Vec2 A, B; // A.y < B.y
  };
  std::vector<Edge> edges;
  std::vector<double> events;
  for (const auto& ring : this->Rings)
  {
    for (std::size_t k = 0, n = ring.size(); k < n; ++k)
    {
      Vec2 a = ring[k] - ref, b = ring[(k + 1) % n] - ref;
      events.push_back(a.y);
      if (a.y == b.y)
      {
        continue; // (no crossing with a horizontal line inside a slab)
      }
      if (a.y > b.y)
      {
        std::swap(a, b);
      }
      edges.push_back({ a, b });
    }
  }
  // Crossings of two edges: only pairs overlapping in height (edges sorted by their low end).
  std::sort(edges.begin(), edges.end(), [](const Edge& e, const Edge& f) { return e.A.y < f.A.y; });
  for (std::size_t i = 0; i < edges.size(); ++i)
  {
    const Edge& e = edges[i];
    for (std::size_t j = i + 1; j < edges.size() && edges[j].A.y < e.B.y; ++j)
    {
      const Edge& f = edges[j];
      const Vec2 d = e.B - e.A, g = f.B - f.A, w = f.A - e.A;
      const double den = Cross(d, g);
      if (den == 0.0)
      {
        continue;
      }
      const double t = Cross(w, g) / den, u = Cross(w, d) / den;
      if (t > 0.0 && t < 1.0 && u > 0.0 && u < 1.0)
      {
        events.push_back(e.A.y + t * d.y);
      }
    }
  }
  std::sort(events.begin(), events.end());
  events.erase(std::unique(events.begin(), events.end()), events.end());
  std::array<double, 6> sum{};
  std::vector<std::pair<double, const Edge*>> spanning;
  auto xAt = [](const Edge& e, double y) {
    return e.A.x + (y - e.A.y) * (e.B.x - e.A.x) / (e.B.y - e.A.y);
  };
  for (std::size_t k = 0; k + 1 < events.size(); ++k)
  {
    const double y0 = events[k], y1 = events[k + 1], ym = 0.5 * (y0 + y1), h = y1 - y0;
    spanning.clear();
    for (const Edge& e : edges)
    {
      if (e.A.y <= y0 && e.B.y >= y1)
      {
        spanning.emplace_back(xAt(e, ym), &e);
      }
      else if (e.A.y >= y1)
      {
        break; // (sorted by their low end)
      }
    }
    std::sort(spanning.begin(), spanning.end(),
      [](const std::pair<double, const Edge*>& a, const std::pair<double, const Edge*>& b) {
        return a.first < b.first;
      });
    for (std::size_t m = 0; m + 1 < spanning.size(); m += 2)
    {
      const Edge& l = *spanning[m].second;
      const Edge& r = *spanning[m + 1].second;
      const double ys[3] = { y0, ym, y1 }, weights[3] = { h / 6.0, 4.0 * h / 6.0, h / 6.0 };
      for (int q = 0; q < 3; ++q)
      {
        const double y = ys[q], xl = xAt(l, y), xr = xAt(r, y), len = xr - xl;
        const double x2 = 0.5 * (xr * xr - xl * xl);
        const double f[6] = { len, x2, y * len, (xr * xr * xr - xl * xl * xl) / 3.0, y * y * len,
          y * x2 };
        for (int c = 0; c < 6; ++c)
        {
          sum[c] += weights[q] * f[c];
        }
      }
    }
  }
  return sum;
}

double Shape2D::FilledArea() const
{
  // (About a vertex of the shape: coordinates relative to it keep the integrals' rounding at
  // the shape's own scale.)
  for (const auto& ring : this->Rings)
  {
    if (!ring.empty())
    {
      return EvenOddIntegrals(ring[0])[0];
    }
  }
  return 0.0;
}

namespace
{
bool RingContains(const std::vector<Vec2>& ring, const Vec2& p)
{
  bool inside = false;
  for (std::size_t k = 0, n = ring.size(); k < n; ++k)
  {
    const Vec2& a = ring[k];
    const Vec2& b = ring[(k + 1) % n];
    if ((a.y > p.y) != (b.y > p.y))
    {
      const double x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
      if (x > p.x)
      {
        inside = !inside;
      }
    }
  }
  return inside;
}
} // namespace

bool Shape2D::Contains(const Vec2& p) const
{
  bool inside = false;
  for (const auto& ring : this->Rings)
  {
    inside ^= RingContains(ring, p);
  }
  return inside;
}

//------------------------------------------------------------------------------
Shape2D ShapeFromMask(const SilhouetteMask& mask)
{
  // Directed pixel-boundary edges with the inside on the left; vertex (x, y) has id
  // y * (W + 1) + x. Directions: 0 = +x, 1 = +y, 2 = -x, 3 = -y.
  const int W = mask.Width, H = mask.Height;
  const auto vid = [W](int x, int y) { return static_cast<std::size_t>(y) * (W + 1) + x; };
  struct Edge
  {
    std::size_t From, To;
    int Dir;
  };
  std::vector<Edge> edges;
  std::vector<int> out0(static_cast<std::size_t>(W + 1) * (H + 1), -1);
  std::vector<int> out1(out0.size(), -1);
  auto add = [&](int x0, int y0, int x1, int y1, int dir) {
    const Edge e{ vid(x0, y0), vid(x1, y1), dir };
    const int id = static_cast<int>(edges.size());
    edges.push_back(e);
    (out0[e.From] < 0 ? out0[e.From] : out1[e.From]) = id;
  };
  for (int y = 0; y < H; ++y)
  {
    for (int x = 0; x < W; ++x)
    {
      if (!mask.At(x, y))
      {
        continue;
      }
      if (!mask.At(x, y - 1))
        add(x, y, x + 1, y, 0);
      if (!mask.At(x + 1, y))
        add(x + 1, y, x + 1, y + 1, 1);
      if (!mask.At(x, y + 1))
        add(x + 1, y + 1, x, y + 1, 2);
      if (!mask.At(x - 1, y))
        add(x, y + 1, x, y, 3);
    }
  }
  Shape2D shape;
  std::vector<char> used(edges.size(), 0);
  std::vector<int> loop;
  for (std::size_t start = 0; start < edges.size(); ++start)
  {
    if (used[start])
    {
      continue;
    }
    loop.clear();
    int cur = static_cast<int>(start);
    while (cur >= 0 && !used[cur])
    {
      used[cur] = 1;
      loop.push_back(cur);
      const std::size_t v = edges[cur].To;
      int a = out0[v], b = out1[v];
      if (a >= 0 && used[a])
        a = -1;
      if (b >= 0 && used[b])
        b = -1;
      if (a >= 0 && b >= 0)
      {
        // Two ways on at a corner shared by diagonal pixels: turn right (joins them).
        const int right = (edges[cur].Dir + 3) % 4;
        cur = edges[a].Dir == right ? a : b;
      }
      else
      {
        cur = a >= 0 ? a : b;
      }
    }
    // Keep only the corners (where the direction changes).
    std::vector<Vec2> ring;
    const std::size_t n = loop.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      const Edge& e = edges[loop[k]];
      if (e.Dir != edges[loop[(k + n - 1) % n]].Dir)
      {
        ring.emplace_back(
          static_cast<double>(e.From % (W + 1)), static_cast<double>(e.From / (W + 1)));
      }
    }
    if (ring.size() >= 3)
    {
      shape.Rings.push_back(std::move(ring));
    }
  }
  return shape;
}

//------------------------------------------------------------------------------
Shape2D ShapeFromPolygons(const std::vector<std::vector<Vec2>>& polygons)
{
  Shape2D shape;
  for (const auto& polygon : polygons)
  {
    std::vector<Vec2> ring;
    for (const Vec2& p : polygon)
    {
      if (ring.empty() || p.x != ring.back().x || p.y != ring.back().y)
      {
        ring.push_back(p);
      }
    }
    while (ring.size() > 1 && ring.front().x == ring.back().x && ring.front().y == ring.back().y)
    {
      ring.pop_back();
    }
    // (Every ring of 3 or more distinct vertices, whatever its signed area: a symmetric bow-tie
    // has none but encloses two triangles under the even-odd rule.)
    if (ring.size() >= 3)
    {
      shape.Rings.push_back(std::move(ring));
    }
  }
  // Orientation from the nesting depth: outer rings counter-clockwise, holes clockwise.
  const std::size_t n = shape.Rings.size();
  std::vector<int> depth(n, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t j = 0; j < n; ++j)
    {
      if (i != j && RingContains(shape.Rings[j], shape.Rings[i][0]))
      {
        ++depth[i];
      }
    }
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    auto& ring = shape.Rings[i];
    double twice = 0.0;
    for (std::size_t k = 0; k < ring.size(); ++k)
    {
      twice += Cross(ring[k], ring[(k + 1) % ring.size()]);
    }
    // (A self-intersecting ring has no orientation that puts its inside on the left: left as
    // given when its signed area is 0; the even-odd rule decides what it encloses.)
    if (twice != 0.0 && (twice > 0.0) != (depth[i] % 2 == 0))
    {
      std::reverse(ring.begin(), ring.end());
    }
  }
  return shape;
}

//------------------------------------------------------------------------------
SilhouetteMask RasterizeShape(
  const Shape2D& shape, int width, int height, const Vec2& origin, double pixelSize)
{
  SilhouetteMask mask;
  mask.Width = std::max(width, 0);
  mask.Height = std::max(height, 0);
  mask.Inside.assign(static_cast<std::size_t>(mask.Width) * mask.Height, 0);
  std::vector<double> crossings;
  for (int y = 0; y < mask.Height; ++y)
  {
    const double py = origin.y + (y + 0.5) * pixelSize;
    crossings.clear();
    for (const auto& ring : shape.Rings)
    {
      for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      {
        const Vec2& a = ring[k];
        const Vec2& b = ring[(k + 1) % n];
        if ((a.y > py) != (b.y > py))
        {
          crossings.push_back(a.x + (py - a.y) / (b.y - a.y) * (b.x - a.x));
        }
      }
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
    {
      // Pixels whose centre lies in [crossings[k], crossings[k+1]).
      const double x0 = (crossings[k] - origin.x) / pixelSize - 0.5;
      const double x1 = (crossings[k + 1] - origin.x) / pixelSize - 0.5;
      const int first = std::max(0, static_cast<int>(std::ceil(x0)));
      const int last = std::min(mask.Width - 1, static_cast<int>(std::ceil(x1)) - 1);
      for (int x = first; x <= last; ++x)
      {
        mask.Inside[static_cast<std::size_t>(y) * mask.Width + x] = 1;
      }
    }
  }
  return mask;
}

} // namespace gs
