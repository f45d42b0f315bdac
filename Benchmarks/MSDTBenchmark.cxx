// Minimum safe distance tables: speed, conservativeness and tightness on real silhouettes.
//
//   MSDTBenchmark [--probes N] [--samples S] [--rows R] image.png [image.png ...]
//
// For each image: the silhouette is re-rasterized to 512 x 512 (its bounding box scaled to fit),
// the ka = kr = 64 table is timed (best of 3, all OpenMP threads), N random probes (default
// 10^6; alpha_A, alpha_B anywhere in their bins, d uniform in [table value, r_A + r_B]) are
// checked with the exact polygon overlap test of Testing/Core/ShapeOverlapOracle.h, and the mean
// table value is compared with the paper's non-conservative (bin-centre) table. Long shapes are
// split (MaximumAspectRatio 2) and probed part against part, every ordered pair of parts. Then
// the tables of the first four images as one 4-class set are timed.
#include "SafeDistanceTable.h"
#include "ShapeOverlapOracle.h"
#include "Silhouette.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace
{
using Clock = std::chrono::steady_clock;
constexpr double Pi = 3.14159265358979323846;

double Seconds(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The silhouette of `file` re-rasterized into a size x size mask (bounding box fitted, margin 1).
bool Load512(const std::string& file, int size, gs::SilhouetteMask& mask, std::string& error)
{
  const gs::Result<gs::SilhouetteImage> read = gs::ReadSilhouetteImage(file);
  if (!read.Ok())
  {
    error = read.Message();
    return false;
  }
  const gs::Shape2D shape = gs::ShapeFromMask(read->Mask);
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (const auto& ring : shape.Rings)
    for (const gs::Vec2& p : ring)
    {
      x0 = std::min(x0, p.x);
      y0 = std::min(y0, p.y);
      x1 = std::max(x1, p.x);
      y1 = std::max(y1, p.y);
    }
  const double pixel = std::max(x1 - x0, y1 - y0) / (size - 2);
  const gs::Vec2 origin{ 0.5 * (x0 + x1) - 0.5 * size * pixel, 0.5 * (y0 + y1) - 0.5 * size * pixel };
  mask = gs::RasterizeShape(shape, size, size, origin, pixel);
  std::printf("%s: %dx%d image, %zu pixels inside, re-rasterized to %dx%d (%zu inside)\n",
    file.c_str(), read->Mask.Width, read->Mask.Height, read->Mask.Count(), size, size, mask.Count());
  return true;
}

double Mean(const std::vector<double>& v)
{
  double s = 0;
  for (double x : v)
    s += x;
  return s / v.size();
}
} // namespace

int main(int argc, char* argv[])
{
  long long probes = 1000000;
  int rotationSamples = 0, rows = 1024;
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--probes") == 0 && i + 1 < argc)
      probes = std::atoll(argv[++i]);
    else if (std::strcmp(argv[i], "--samples") == 0 && i + 1 < argc)
      rotationSamples = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--rows") == 0 && i + 1 < argc)
      rows = std::atoi(argv[++i]);
    else
      files.push_back(argv[i]);
  }
  if (files.empty())
  {
    std::printf("usage: MSDTBenchmark [--probes N] image.png [...] (no image given: nothing to do)\n");
    return 0;
  }
  int threads = 1;
#ifdef _OPENMP
  threads = omp_get_max_threads();
#endif
  std::printf("MSDT benchmark: ka = kr = 64, %d OpenMP threads\n", threads);
  gs::SafeDistanceOptions options; // ka = kr = 64, conservative
  options.RotationSamples = rotationSamples;
  options.Rows = rows;
  gs::SafeDistanceOptions sampled = options;
  sampled.Conservative = false;

  std::vector<gs::SafeDistanceInput> classes;
  int failures = 0;
  for (const std::string& file : files)
  {
    gs::SilhouetteMask mask;
    std::string error;
    if (!Load512(file, 512, mask, error))
    {
      std::printf("%s: %s\n", file.c_str(), error.c_str());
      ++failures;
      continue;
    }
    gs::SafeDistanceInput input{ file, gs::ShapeFromMask(mask) };
    classes.push_back(input);

    // Speed (whole pipeline from the mask: contours, circle, profiles, table).
    double best = 1e300;
    gs::Result<gs::SafeDistanceTables> result = gs::Status::Error("not computed");
    for (int run = 0; run < 3; ++run)
    {
      const auto t0 = Clock::now();
      gs::Shape2D shape = gs::ShapeFromMask(mask);
      result = gs::ComputeSafeDistanceTables({ { file, std::move(shape) } }, options);
      best = std::min(best, Seconds(t0));
    }
    if (!result.Ok())
    {
      std::printf("  error: %s\n", result.Message().c_str());
      ++failures;
      continue;
    }
    const gs::SafeDistanceTables& T = *result;
    std::printf("  %zu boundary edges, %d part(s), aspect %.2f, rotation samples %d\n",
      input.Shape.NumberOfEdges(), T.NumberOfParts(), T.Classes[0].AspectRatio, T.RotationSamples);
    std::printf("  table time (512x512, ka=kr=64): %.3f s\n", best);

    // Tightness against the paper's sampled-angle table.
    const gs::Result<gs::SafeDistanceTables> plain = gs::ComputeSafeDistanceTables({ input }, sampled);
    const double ratio = Mean(T.Values) / Mean(plain->Values);
    std::printf("  tightness: mean conservative %.4f / mean sampled-angle %.4f = %.4f (+%.2f%%)\n",
      Mean(T.Values), Mean(plain->Values), ratio, 100.0 * (ratio - 1.0));

    // Conservativeness: random probes over every ordered pair of parts. Each part's region is
    // rebuilt by the oracle's own clipping of the class outline to the part's slab
    // (PartOfRegion), so split parts of non-convex shapes are probed as they are.
    std::vector<gs_test::OverlapOracle> oracles;
    for (const gs::SafeDistancePart& part : T.Parts)
    {
      const gs::Vec2 axis = part.Axis;
      gs_test::RegionBoundary region =
        gs_test::PartOfRegion(T.Classes[0].Outline.Rings, axis, part.From, part.To);
      for (auto& segment : region.Segments)
      {
        segment.A = segment.A - part.Centre;
        segment.B = segment.B - part.Centre;
      }
      for (auto& seed : region.Seeds)
        seed = seed - part.Centre;
      oracles.emplace_back(region, part.Radius);
      if (oracles.back().GetReach() > part.Radius * (1.0 + 1e-9))
      {
        std::printf("  part %d: boundary reaches %.6f beyond its radius %.6f\n", part.Index,
          oracles.back().GetReach(), part.Radius);
        ++failures;
      }
    }
    const int P = T.NumberOfParts();
    const double w = T.BinWidth();
    long long overlaps = 0, tested = 0;
    const auto t0 = Clock::now();
#pragma omp parallel reduction(+ : overlaps, tested)
    {
      int thread = 0;
#ifdef _OPENMP
      thread = omp_get_thread_num();
#endif
      std::mt19937_64 random(1234567u + 7919u * thread);
      std::uniform_real_distribution<double> unit(0.0, 1.0);
#pragma omp for schedule(static)
      for (long long k = 0; k < probes; ++k)
      {
        const int a = static_cast<int>(unit(random) * P) % P;
        const int b = static_cast<int>(unit(random) * P) % P;
        const int i = static_cast<int>(unit(random) * T.AngleBins) % T.AngleBins;
        const int j = static_cast<int>(unit(random) * T.AngleBins) % T.AngleBins;
        const double aA = (i + unit(random) - 0.5) * w;
        const double aB = (j + unit(random) - 0.5) * w;
        const double d0 = T.Value(a, b, i, j);
        const double dmax = T.Parts[a].Radius + T.Parts[b].Radius;
        // Half the probes right at the table value (the hardest), half anywhere above it.
        const double d = (k % 2 == 0) ? d0 : d0 + unit(random) * (dmax - d0);
        ++tested;
        if (oracles[a].Overlaps(aA, oracles[b], aB, d))
          ++overlaps;
      }
    }
    std::printf("  conservativeness: %lld probes over %d part pair(s), %lld overlaps (%.2f s)\n",
      tested, P * P, overlaps, Seconds(t0));
    if (overlaps != 0)
      ++failures;
    // Sanity of the oracle: just below the sampled-angle value at the bin centre they overlap.
    long long below = 0, belowTested = 0;
    for (int a = 0; a < P; ++a)
      for (int b = 0; b < P; ++b)
        for (int i = 0; i < T.AngleBins; i += 3)
          for (int j = 0; j < T.AngleBins; j += 3)
          {
            const double d = plain->Value(a, b, i, j) - 1.5 * T.Step(a, b);
            if (d <= 0)
              continue;
            ++belowTested;
            below += oracles[a].Overlaps(i * w, oracles[b], j * w, d);
          }
    std::printf("  oracle sanity: %lld of %lld bin-centre probes 1.5 steps below the sampled table overlap\n",
      below, belowTested);
  }

  if (classes.size() >= 4)
  {
    classes.resize(4);
    double best = 1e300;
    gs::Result<gs::SafeDistanceTables> result = gs::Status::Error("not computed");
    for (int run = 0; run < 3; ++run)
    {
      const auto t0 = Clock::now();
      result = gs::ComputeSafeDistanceTables(classes, options);
      best = std::min(best, Seconds(t0));
    }
    std::printf("4 classes (%d parts, %d tables, 512x512 each, ka=kr=64): %.3f s\n",
      result->NumberOfParts(), result->NumberOfPairs(), best);
  }
  return failures == 0 ? 0 : 1;
}
