// Shape distribution benchmark: the figures of the ShapeDistributor issue, in one run.
//
//  1. Density against the circumcircle baseline (the paper's Fig. 9): a planar square, one
//     shape class, field-aligned (constant field) and unoriented (no field), 20 seeds, Random /
//     Greedy / Circumcircle Poisson disk: mean counts and ratios. Every layout is checked by the
//     independent planar overlap test.
//     1b. Issue 17's square: the pentagram on a square 40 circumradii wide, 8 seeds: per seed and
//     mean, Greedy against the circumcircles and against the densest lattice's count for the area
//     (--square W: that section alone, W circumradii wide).
//  2. Maximality: random probes that would still fit after a run.
//  3. Density fidelity: a density ramp on the square; count x f^2 per unit area in strips.
//  4. Real mesh (refined_elephant, subdivided once: ~355K faces): saddle vertex graph build,
//     4 classes with 1 and 2 threads (identical results; --speed-rounds R alternating runs of
//     each, median times, default 3), counts at two resolutions of the same surface, overlaps
//     by the chart-based surface test.
//
// Usage: DistributionBenchmark <refined_elephant.off> [shape images dir] [--quick]
//   or: DistributionBenchmark <mesh.off> --scale --image a.png [--image b.png ...] [--cache graph.svg]
//       [--size 0.01] [--greedy] [--speed-rounds R] [--graph-accuracy A (the charts' discrete geodesic
//       graph, default 0.1 as the filter's; 0: the saddle vertex graph of K = 50)] [--check (exit 2 when
//       VerifyOverlaps reports a pair, two decals share more than 1% of a shape's lattice points,
//       short decals leave over 0.2% of their outline points undrawn, or a decal leaves 8 or more
//       consecutive points of its outline undrawn)]
//       (see AtScale; environment: GS_DEBUG_ORACLE prints, for such decal pairs, the shared points as
//       each shape's map reads them; GS_DISTORTION_LIMIT
//       sets DistortionLimit, GS_DRAWN_CHECK=0 turns the drawn check off, GS_DEBUG_DEPTH prints, for each overlapping pair, how far the long
//       shape's drawn map departs from its rigid parts)
//   [--square W [--seeds N] (section 1b alone, a square W circumradii wide, N seeds; environment:
//   GS_SQUARE_CELLS sets its mesh's cells per side, default edges of 0.2; GS_SQUARE_JITTER moves
//   its interior vertices by up to that fraction of a cell, GS_SQUARE_FLIP=1 splits each cell
//   along a random diagonal: an irregular triangulation (the count of triangles turned over is
//   printed); GS_SQUARE_GRAPH=A: charts on the discrete geodesic graph of accuracy A;
//   GS_SQUARE_REASONS=1: each run's rejections by check; GS_DISTORTION_LIMIT sets DistortionLimit)]
//   or: DistributionBenchmark Data/bumpy_sphere.ply --under-load --image Data/shapes/star.png [--image ...]
//       [--speed-rounds R] (the demo's distribution on 1 and 2 threads, alone and with one
//       competing CPU-bound process: see UnderLoad)
//   [--mesh-only (section 4 only)] [--speed-only (its speed figures only)] [--speed-rounds R]
//   (images: star.png, eagle.png, fish.png, bird.png from ../shared/data/meshes/shapes2d or
//   openclipart; polygons are used when missing).
#include "DistributorProbes.h"
#include "../Testing/Core/DistributionChecks.h"
#include "BenchmarkSupport.h"

#include "Hash.h"
#include "MeshGenerators.h"
#include "GeodesicShooting.h"
#include "MeshIO.h"
#include "OverlapCheck.h"
#include "SaddleVertexGraph.h"
#include "SafeDistanceTable.h"
#include "ShapeDistributor.h"
#include "ShapeDrawing.h"
#include "Silhouette.h"
#include "TriangleMesh.h"
#include "UnitSilhouettes.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <set>
#include <thread>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>
#include <unordered_map>
#include <unordered_set>
#include <string>
#include <vector>

using namespace gs;
using gs_bench::Median;
using gs_bench::Now;

namespace
{
constexpr double Pi = 3.14159265358979323846;
long long TotalShapes = 0, TotalOverlaps = 0, TotalPairs = 0;
bool CheckScale = false;   // --check: the at-scale run fails on a fault found below
// Pairs VerifyOverlaps reports, decal pairs sharing over 1%, runs whose short decals leave over
// 0.2% of their outline points undrawn, and runs with decals leaving strips of their outline
// undrawn (per kind).
long long ScaleFaults = 0;
// The decal oracle (issue 21): what the decals draw, compared on a fixed lattice of points of
// every mesh face (28 barycentric points): a lattice point drawn inside the silhouette (the
// texture coordinate, linear in the decal triangle holding it, as a renderer draws it) by two
// shapes is drawn twice. Independent of the tables, the charts and the drawn check.
struct DecalOracleResult
{
  long long SharingPairs = 0; // pairs with a lattice point drawn by both
  long long PairsOverOnePercent = 0; // sharing more than 1% of the smaller shape's drawn points
  double Worst = 0.0; // the largest shared fraction
  std::vector<std::pair<std::pair<int, int>, double>> Over; // the pairs over 1%, with their fractions
  std::uint64_t DrawnHash = 0; // what the decals draw: the lattice points inside, with their class points
};

// Decals against outlines: each shape's drawn outline points read in its own decal (texture
// coordinates as rendered), the class point's distance to the silhouette's boundary over the
// circumradius; per kind (short, long): mean, the share over 5%, and points outside the decal.
void DecalsAgainstOutlines(const SafeDistanceTables& t, const std::vector<PlacedShape>& shapes,
  const std::vector<ShapeDecal>& decals, const std::vector<std::vector<OutlinePiece>>& outlines)
{
  for (const bool longShapes : { false, true })
  {
    double sum = 0.0;
    long long points = 0, uncovered = 0, far = 0, farFromOwn = 0;
    long long kindShapes = 0, unfaithful = 0; // shapes with a point outside or 5% off its own
    // Shapes with a strip of their outline undrawn: StripPoints or more consecutive points of a
    // piece outside the decal (isolated points are the finest pieces dropped at a fold).
    constexpr int StripPoints = 8;
    long long stripShapes = 0;
    int longestStrip = 0;
    std::size_t longestStripShape = 0;
    for (std::size_t s = 0; s < shapes.size(); ++s)
    {
      if (shapes[s].Curve.empty() == longShapes)
        continue;
      ++kindShapes;
      const long long before = uncovered + farFromOwn;
      const SafeDistanceClass& c = t.Classes[shapes[s].ClassId];
      int longestRun = 0;
      for (const OutlinePiece& piece : outlines[s])
      {
        int run = 0;
        for (std::size_t i = 0; i < piece.Points.size(); ++i)
        {
          const SurfacePoint& p = piece.Points[i];
          ++points;
          Vec2 uv{ 0.0, 0.0 };
          if (!decals[s].TextureCoordinate(p, uv))
          {
            ++uncovered;
            longestRun = std::max(longestRun, ++run);
            if (getenv("GS_DEBUG_FAITH") && i < piece.ClassPoints.size())
              std::printf("      shape %zu class %d uncovered at class point (%.3f, %.3f) r %.3f face %d bary %.3f %.3f %.3f\n", s, shapes[s].ClassId,
                piece.ClassPoints[i].x / c.Radius, piece.ClassPoints[i].y / c.Radius, c.Radius, p.Face, p.Bary[0], p.Bary[1], p.Bary[2]);
            continue;
          }
          run = 0;
          const Vec2 q = gs_test::ClassPointOfTexture(uv, c.Radius);
          double best = 1e300;
          for (const auto& ring : c.Outline.Rings)
            for (std::size_t k = 0; k < ring.size(); ++k)
            {
              const Vec2 a = ring[k], ab = ring[(k + 1) % ring.size()] - a;
              const double l2 = Dot(ab, ab);
              const double u = l2 > 0.0 ? std::min(1.0, std::max(0.0, Dot(q - a, ab) / l2)) : 0.0;
              best = std::min(best, Norm(a + ab * u - q));
            }
          const double e = best / c.Radius;
          sum += e;
          far += e > 0.05 ? 1 : 0;
          // (Where a short shape's outline runs along the mesh boundary, its points are inside
          // the silhouette, at the class points the map stopped at: ClassPoints.)
          if (i < piece.ClassPoints.size())
          {
            farFromOwn += Norm(piece.ClassPoints[i] - q) > 0.05 * c.Radius ? 1 : 0;
            if (getenv("GS_DEBUG_FAITH") && Norm(piece.ClassPoints[i] - q) > 0.05 * c.Radius)
              std::printf("      shape %zu class %d far at class point (%.3f, %.3f) decal (%.3f, %.3f)\n", s, shapes[s].ClassId,
                piece.ClassPoints[i].x / c.Radius, piece.ClassPoints[i].y / c.Radius, q.x / c.Radius, q.y / c.Radius);
          }
        }
      }
      unfaithful += uncovered + farFromOwn > before ? 1 : 0;
      stripShapes += longestRun >= StripPoints ? 1 : 0;
      if (longestRun > longestStrip)
      {
        longestStrip = longestRun;
        longestStripShape = s;
      }
      if (getenv("GS_DEBUG_FAITH") && uncovered + farFromOwn > before)
        std::printf("      shape %zu class %d: %zu decal triangles, centre face %d (vertex %d), bary %.3f %.3f %.3f\n", s,
          shapes[s].ClassId, decals[s].Faces.size(), shapes[s].Centre.Face, shapes[s].Centre.Vertex,
          shapes[s].Centre.Bary[0], shapes[s].Centre.Bary[1], shapes[s].Centre.Bary[2]);
    }
    const long long covered = points - uncovered;
    // (A short decal is the exact log map of its centre, which the outline's points read back
    // to their class points: one that leaves them undrawn drops the wrong pieces.)
    if (!longShapes && uncovered > 0.002 * static_cast<double>(points))
    {
      std::printf("    short decals leave %lld of %lld outline points undrawn (over 0.2%%)\n", uncovered, points);
      ++ScaleFaults;
    }
    // (Long decals: a fold that the shape's own outline reads back through (FaithfulCheck) but
    // its decal does not draw left strips of up to 8 points before the check read the outline
    // as the decal does, from the grid node nearest each point.)
    if (stripShapes > 0)
    {
      std::printf("    %lld %s shapes leave a strip of %d or more outline points undrawn (the longest: %d points, "
                  "shape %zu)\n", stripShapes, longShapes ? "long" : "short", StripPoints, longestStrip, longestStripShape);
      ++ScaleFaults;
    }
    std::printf("    decals against outlines, %s shapes: %lld outline points, %lld outside the decal; class point off "
                "the silhouette: mean %.2e of the radius, %.3f%% over 5%%; off the outline's own class point: %.3f%% over "
                "5%%; %lld of %lld shapes with such a point\n", longShapes ? "long" : "short", points, uncovered,
      covered > 0 ? sum / covered : 0.0, covered > 0 ? 100.0 * far / covered : 0.0,
      covered > 0 ? 100.0 * farFromOwn / covered : 0.0, unfaithful, kindShapes);
  }
}

DecalOracleResult DecalOracle(const SafeDistanceTables& t, const std::vector<PlacedShape>& shapes,
  const std::vector<ShapeDecal>& decals)
{
  std::unordered_map<std::uint64_t, int> owner;
  std::map<std::pair<int, int>, long long> shared;
  std::vector<long long> drawn(shapes.size(), 0);
  Hasher drawnHash; // (the same for decals that differ only in triangles drawing nothing)
  for (std::size_t s = 0; s < shapes.size(); ++s)
  {
    const SafeDistanceClass& c = t.Classes[shapes[s].ClassId];
    const ClassRegion region(c.Outline.Rings, c.Radius, 0.0);
    std::unordered_set<std::uint64_t> mine;
    const ShapeDecal& decal = decals[s];
    gs_test::ForEachDrawnLatticePoint(decal, c, region,
      [&](std::size_t k, int index, const std::array<double, 3>&, const Vec2& uv, const Vec2&) {
        if (mine.insert(static_cast<std::uint64_t>(decal.Faces[k]) * 64 + index).second)
        {
          drawnHash.AddValue(decal.Faces[k]);
          drawnHash.AddValue(index);
          drawnHash.AddValue(uv);
        }
      });
    drawn[s] = static_cast<long long>(mine.size());
    for (std::uint64_t key : mine)
    {
      const auto it = owner.find(key);
      if (it == owner.end())
        owner.emplace(key, static_cast<int>(s));
      else
        ++shared[{ it->second, static_cast<int>(s) }];
    }
  }
  DecalOracleResult r;
  r.DrawnHash = drawnHash.H;
  for (const auto& e : shared)
  {
    const long long smaller = std::max(1LL, std::min(drawn[e.first.first], drawn[e.first.second]));
    const double fraction = static_cast<double>(e.second) / smaller;
    ++r.SharingPairs;
    r.PairsOverOnePercent += fraction > 0.01 ? 1 : 0;
    if (fraction > 0.01)
      r.Over.push_back({ e.first, fraction });
    r.Worst = std::max(r.Worst, fraction);
  }
  return r;
}

std::string SvgPrefix; // --svg: seed-0 layouts of the square as SVG files

void WriteSvg(const std::string& file, const SafeDistanceTables& t, const std::vector<PlacedShape>& shapes, double size,
  double side = 10.0)
{
  FILE* f = std::fopen(file.c_str(), "w");
  if (!f)
    return;
  std::fprintf(f, "<svg xmlns='http://www.w3.org/2000/svg' viewBox='%g %g %g %g' width='800' height='800'>\n",
    -0.05 * side, -0.05 * side, 1.1 * side, 1.1 * side);
  std::fprintf(f, "<rect x='0' y='0' width='%g' height='%g' fill='none' stroke='gray' stroke-width='0.02'/>\n", side, side);
  for (const PlacedShape& s : shapes)
  {
    const double a = std::atan2(s.Direction.y, s.Direction.x), k = size * s.Scale;
    for (const auto& ring : t.Classes[s.ClassId].Outline.Rings)
    {
      std::fprintf(f, "<polygon fill='steelblue' stroke='black' stroke-width='0.01' points='");
      for (const Vec2& p : ring)
      {
        const double x = s.Position.x + k * (std::cos(a) * p.x - std::sin(a) * p.y);
        const double y = s.Position.y + k * (std::sin(a) * p.x + std::cos(a) * p.y);
        std::fprintf(f, "%.4f,%.4f ", x, side - y);
      }
      std::fprintf(f, "'/>\n");
    }
  }
  std::fprintf(f, "</svg>\n");
  std::fclose(f);
  // The same as a legacy VTK polydata (ParaView opens it).
  FILE* g = std::fopen((file + ".vtk").c_str(), "w");
  if (!g)
    return;
  std::vector<std::vector<Vec2>> polys;
  for (const PlacedShape& s : shapes)
  {
    const double a = std::atan2(s.Direction.y, s.Direction.x), k = size * s.Scale;
    for (const auto& ring : t.Classes[s.ClassId].Outline.Rings)
    {
      std::vector<Vec2> poly;
      for (const Vec2& p : ring)
        poly.push_back(Vec2{ s.Position.x + k * (std::cos(a) * p.x - std::sin(a) * p.y),
          s.Position.y + k * (std::sin(a) * p.x + std::cos(a) * p.y) });
      polys.push_back(poly);
    }
  }
  std::size_t points = 0;
  for (const auto& q : polys)
    points += q.size();
  std::fprintf(g, "# vtk DataFile Version 3.0\nlayout\nASCII\nDATASET POLYDATA\nPOINTS %zu double\n", points);
  for (const auto& q : polys)
    for (const Vec2& p : q)
      std::fprintf(g, "%.6f %.6f 0\n", p.x, p.y);
  std::fprintf(g, "POLYGONS %zu %zu\n", polys.size(), polys.size() + points);
  std::size_t id = 0;
  for (const auto& q : polys)
  {
    std::fprintf(g, "%zu", q.size());
    for (std::size_t k = 0; k < q.size(); ++k)
      std::fprintf(g, " %zu", id++);
    std::fprintf(g, "\n");
  }
  std::fclose(g);
}

// The regular {5/2} star's outline: inner radius / outer radius = 0.382.
std::vector<Vec2> Pentagram()
{
  return MakeStarPolygon(5, 1.0, std::cos(2 * Pi / 5) / std::cos(Pi / 5));
}

// Scaled to circumradius 1, so that every class has the same size.
bool ShapeFromImage(const std::string& file, Shape2D& shape)
{
  Result<Shape2D> r = UnitShapeFromImage(file);
  if (!r.Ok())
  {
    return false;
  }
  shape = *r;
  return true;
}

// One class per image file (scaled to circumradius 1); false, naming the file, when one cannot
// be read.
bool ImageClasses(const std::vector<std::string>& images, std::vector<SafeDistanceInput>& classes)
{
  for (const std::string& file : images)
  {
    Shape2D shape;
    if (!ShapeFromImage(file, shape))
    {
      std::fprintf(stderr, "cannot read %s\n", file.c_str());
      return false;
    }
    classes.push_back({ file, shape });
  }
  return true;
}

// The mesh file's triangles; false, with the reader's message, when it cannot be read.
bool ReadMeshOrSay(const std::string& path, TriangleSoup& soup)
{
  std::string error;
  if (!ReadMesh(path, soup, error))
  {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), error.c_str());
    return false;
  }
  return true;
}

// The charts' graph as the filter builds it: the discrete geodesic graph of `accuracy` (the
// filter's default 0.1); accuracy 0: the saddle vertex graph of K = 50.
SaddleVertexGraphOptions ChartGraphOptions(double accuracy)
{
  SaddleVertexGraphOptions go;
  go.K = 50;
  if (accuracy > 0.0)
  {
    go.Construction = GraphConstruction::DiscreteGeodesic;
    go.Accuracy = accuracy;
  }
  return go;
}

SafeDistanceTables Tables(const std::vector<SafeDistanceInput>& in)
{
  SafeDistanceOptions o;
  o.AngleBins = 64;
  o.DistanceSteps = 64;
  Result<SafeDistanceTables> r = ComputeSafeDistanceTables(in, o);
  if (!r.Ok())
  {
    std::fprintf(stderr, "tables: %s\n", r.Message().c_str());
    std::exit(1);
  }
  return *r;
}


TriangleMesh Build(const TriangleSoup& s)
{
  Result<MeshBuild> r = TriangleMeshBuilder::Build(s.Points, s.Triangles);
  if (!r.Ok())
  {
    std::fprintf(stderr, "mesh: %s\n", r.Message().c_str());
    std::exit(1);
  }
  return std::move(r->Mesh);
}

const char* ModeName(DistributionMode m)
{
  return m == DistributionMode::Random ? "Random" : m == DistributionMode::Greedy ? "Greedy" : "Circumcircle";
}

// Section 1 for one shape class.
void Figure9(const std::string& name, const SafeDistanceInput& shape, int seeds)
{
  const TriangleMesh plane = Build(MakePlanarGrid(50, 50, 10.0, 10.0));
  const SafeDistanceTables t = Tables({ shape });
  if (t.NumberOfParts() == 1)
  {
    // What geometry allows dart throwing (random sequential addition): it jams at a number
    // density of about c / (excluded area), with c = 2.19 for disks and 2.25 for aligned squares
    // (jamming coverages 0.547 and 0.562), so Random / circumcircle is about the ratio of the
    // excluded areas. Two copies turned alike exclude the region within D(beta) of each other,
    // D(beta) = the table's distance for the line at angle beta (seen from either copy), and
    // circumcircles the disk of radius 2r.
    const double r = t.Parts[0].Radius;
    const int n = 4096;
    double area = 0.0;
    for (int k = 0; k < n; ++k)
    {
      const double beta = 2.0 * M_PI * (k + 0.5) / n;
      const double d = std::max(t.Lookup(0, 0, -beta, -beta), t.Lookup(0, 0, -beta - M_PI, -beta - M_PI));
      area += 0.5 * d * d * (2.0 * M_PI / n);
    }
    std::printf("  %-10s aligned: excluded area %.2f r^2 (circumcircles %.2f r^2): dart throwing jams "
                "near %.2fx the circumcircle count\n",
      name.c_str(), area / (r * r), 4.0 * M_PI, 4.0 * M_PI * r * r / area);
  }
  for (bool aligned : { true, false })
  {
    std::vector<Vec3> dirs(plane.NumberOfFaces(), aligned ? Vec3{ 1, 0, 0 } : Vec3{ 0, 0, 0 });
    std::map<DistributionMode, double> mean;
    for (DistributionMode mode :
      { DistributionMode::CircumcirclePoissonDisk, DistributionMode::Random, DistributionMode::Greedy })
    {
      double sum = 0.0;
      for (int seed = 0; seed < seeds; ++seed)
      {
        ShapeDistributor d(plane);
        ShapeDistributionOptions o;
        o.ShapeSize = 0.5;
        o.Mode = mode;
        o.Seed = static_cast<std::uint64_t>(seed);
        const Result<ShapeDistribution> r = d.Run(t, dirs, {}, o);
        int pairs = 0;
        const int overlaps = gs_test::CountPlanarOverlaps(plane, t, r->Shapes, o.ShapeSize, &pairs);
        TotalShapes += static_cast<long long>(r->Shapes.size());
        TotalOverlaps += overlaps;
        TotalPairs += pairs;
        sum += static_cast<double>(r->Shapes.size());
        if (seed == 0 && aligned)
        {
          if (!SvgPrefix.empty())
            WriteSvg(SvgPrefix + "_" + name + "_" + ModeName(mode) + ".svg", t, r->Shapes, o.ShapeSize);
          std::printf("    %-12s seed 0: %zu shapes, %lld candidates, %.3f s; probes that fit: %.4f%% of 1e5\n",
            ModeName(mode), r->Shapes.size(), r->Statistics.Candidates, r->Statistics.Seconds,
            100.0 * gs_test::ProbeFitFraction(d, 100000, 12345));
        }
      }
      mean[mode] = sum / seeds;
    }
    const double c = mean[DistributionMode::CircumcirclePoissonDisk];
    std::printf("  %-10s %-9s | circumcircle %6.1f | random %6.1f (%.2fx) | greedy %6.1f (%.2fx)\n",
      name.c_str(), aligned ? "aligned" : "unoriented", c, mean[DistributionMode::Random],
      mean[DistributionMode::Random] / c, mean[DistributionMode::Greedy],
      mean[DistributionMode::Greedy] / c);
  }
}

void DensityFidelity(const SafeDistanceInput& shape, int seeds)
{
  // f = 0.5 + 0.5 x / 10 on the square [0, 10]^2: strips of width 2.
  const TriangleMesh plane = Build(MakePlanarGrid(100, 100, 10.0, 10.0));
  const SafeDistanceTables t = Tables({ shape });
  std::vector<double> f(plane.NumberOfVertices());
  for (int v = 0; v < plane.NumberOfVertices(); ++v)
    f[v] = 0.5 + 0.05 * plane.Position(v).x;
  std::vector<Vec3> dirs(plane.NumberOfFaces(), Vec3{ 1, 0, 0 });
  double strips[5] = { 0, 0, 0, 0, 0 };
  for (int seed = 0; seed < seeds; ++seed)
  {
    ShapeDistributor d(plane);
    ShapeDistributionOptions o;
    o.ShapeSize = 0.3;
    o.Seed = static_cast<std::uint64_t>(seed);
    const Result<ShapeDistribution> r = d.Run(t, dirs, f, o);
    TotalShapes += static_cast<long long>(r->Shapes.size());
    int pairs = 0;
    TotalOverlaps += gs_test::CountPlanarOverlaps(plane, t, r->Shapes, o.ShapeSize, &pairs);
    TotalPairs += pairs;
    for (const PlacedShape& s : r->Shapes)
    {
      const int k = static_cast<int>(s.Position.x / 2.0);
      // Stay one shape away from the square's sides (boundary effects).
      if (k >= 0 && k < 5 && s.Position.y > 1.0 && s.Position.y < 9.0)
        strips[k] += s.Scale * s.Scale; // count x f^2: constant if the count follows 1 / f^2
    }
  }
  double mean = 0.0;
  for (double s : strips)
    mean += s / 5.0;
  double worst = 0.0;
  std::printf("  count x f^2 per strip (f from 0.5 to 1):");
  for (double s : strips)
  {
    std::printf(" %.3f", s / mean);
    worst = std::max(worst, std::abs(s / mean - 1.0));
  }
  std::printf("  -> largest deviation %.1f%% (bar: 10%%)\n", 100.0 * worst);
}

// The densest lattice of copies turned alike that the tables admit (the cell area, normalized
// units): the same definition as the distributor's Greedy lattices (GreedyProposals.cpp), searched
// here independently: a lattice {i u + j v} is admissible when every vector w is at least D(angle
// of w) long, D(beta) = the table's distance of the pair for the line at beta seen from either
// copy; the basis vectors on D's boundary, smallest cell first.
double DensestLatticeCell(const SafeDistanceTables& t)
{
  auto D = [&](double beta) {
    double d = 0.0;
    for (const double b : { beta - 2e-3, beta, beta + 2e-3 })
      d = std::max({ d, t.Lookup(0, 0, -b, -b), t.Lookup(0, 0, -b - Pi, -b - Pi) });
    return d;
  };
  const double cap = 2.0 * t.Parts[0].Radius;
  auto admissible = [&](const Vec2& u, const Vec2& v) {
    for (int i = -6; i <= 6; ++i)
      for (int j = 0; j <= 6; ++j)
      {
        if (j == 0 && i <= 0)
          continue;
        const Vec2 w = u * i + v * j;
        const double len = Norm(w);
        if (len < cap && len < D(std::atan2(w.y, w.x)) * (1.0 - 1e-12))
          return false;
      }
    return true;
  };
  const int n = 512;
  std::vector<Vec2> boundary(n);
  for (int k = 0; k < n; ++k)
  {
    const double beta = Pi * (k + 0.5) / n;
    boundary[k] = Vec2{ std::cos(beta), std::sin(beta) } * (D(beta) * (1.0 + 1e-9));
  }
  double best = 1e300;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (const double sign : { 1.0, -1.0 })
      {
        const Vec2 u = boundary[a], v = boundary[b] * sign;
        const double area = Cross(u, v);
        if (area > 1e-12 * cap * cap && area < best && admissible(u, v))
          best = area;
      }
  return best;
}

// Many shapes on a large square (all modes, pentagram, aligned): overlap checks at scale.
void LargeSquare(const SafeDistanceInput& shape, int seeds)
{
  const TriangleMesh plane = Build(MakePlanarGrid(150, 150, 50.0, 50.0));
  const SafeDistanceTables t = Tables({ shape });
  const double lattice = 2500.0 / (DensestLatticeCell(t) * 0.25);
  std::printf("  the densest lattice of the tables: %.1f shapes for the area\n", lattice);
  std::vector<Vec3> dirs(plane.NumberOfFaces(), Vec3{ 1, 0, 0 });
  for (DistributionMode mode :
    { DistributionMode::CircumcirclePoissonDisk, DistributionMode::Random, DistributionMode::Greedy })
  {
    double sum = 0.0, seconds = 0.0;
    int overlaps = 0, pairs = 0;
    for (int seed = 0; seed < seeds; ++seed)
    {
      ShapeDistributor d(plane);
      ShapeDistributionOptions o;
      o.ShapeSize = 0.5;
      o.Mode = mode;
      o.Seed = static_cast<std::uint64_t>(1000 + seed);
      const Result<ShapeDistribution> r = d.Run(t, dirs, {}, o);
      int p = 0;
      overlaps += gs_test::CountPlanarOverlaps(plane, t, r->Shapes, o.ShapeSize, &p);
      pairs += p;
      sum += static_cast<double>(r->Shapes.size());
      seconds += r->Statistics.Seconds;
    }
    TotalShapes += static_cast<long long>(sum);
    TotalOverlaps += overlaps;
    TotalPairs += pairs;
    std::printf("  %-12s %8.1f shapes per run (%.1f%% of the lattice's), %.2f s per run, %d overlaps in %d close pairs\n",
      ModeName(mode), sum / seeds, 100.0 * sum / seeds / lattice, seconds / seeds, overlaps, pairs);
  }
}

// Issue 17, part 4: the pentagram on a square `width` circumradii wide (shape radius 0.5, mesh
// edges 0.2 as in section 1), field-aligned: Greedy against the circumcircles' count and the
// densest lattice's count for the square's area, per seed; Random against the dart-throwing
// estimate of section 1.
void IssueSquare(const SafeDistanceInput& shape, double width, int seeds)
{
  const double side = 0.5 * width;
  int cells = static_cast<int>(std::lround(side / 0.2));
  if (const char* c = std::getenv("GS_SQUARE_CELLS"))
    cells = std::max(1, std::atoi(c)); // (other mesh resolutions: cells per side)
  // GS_SQUARE_JITTER, GS_SQUARE_FLIP: an irregular triangulation (MakeIrregularPlanarGrid).
  const char* jitter = std::getenv("GS_SQUARE_JITTER");
  const TriangleSoup grid = jitter
    ? MakeIrregularPlanarGrid(cells, side, std::atof(jitter), std::getenv("GS_SQUARE_FLIP") != nullptr, 5)
    : MakePlanarGrid(cells, cells, side, side);
  const TriangleMesh plane = Build(grid);
  int inverted = 0;
  for (int f = 0; f < plane.NumberOfFaces(); ++f)
    inverted += plane.FaceNormal(f).z < 0.0;
  if (inverted > 0)
    std::printf("  %d inverted triangles\n", inverted);
  const SafeDistanceTables t = Tables({ shape });
  const double r = t.Parts[0].Radius, size = 0.5;
  const double cell = DensestLatticeCell(t);
  const double lattice = side * side / (cell * size * size);
  std::printf("  %g x %g square (%g circumradii), %d x %d cells: densest lattice of the tables %.3f r^2 -> %.1f "
              "shapes for the area\n", side, side, width, cells, cells, cell / (r * r), lattice);
  std::vector<Vec3> dirs(plane.NumberOfFaces(), Vec3{ 1, 0, 0 });
  std::map<DistributionMode, double> mean;
  // GS_SQUARE_GRAPH=A: the charts on the discrete geodesic graph of accuracy A, as the filter's
  // default (0.1) computes them; unset: exact charts.
  SaddleVertexGraph graph;
  const char* graphAccuracy = std::getenv("GS_SQUARE_GRAPH");
  if (graphAccuracy && !graph.Build(plane, ChartGraphOptions(std::atof(graphAccuracy)), nullptr).Ok())
    graphAccuracy = nullptr;
  for (DistributionMode mode :
    { DistributionMode::CircumcirclePoissonDisk, DistributionMode::Random, DistributionMode::Greedy })
  {
    double sum = 0.0;
    std::printf("    %-12s", ModeName(mode));
    for (int seed = 0; seed < seeds; ++seed)
    {
      ShapeDistributor d(plane, graphAccuracy ? &graph : nullptr);
      ShapeDistributionOptions o;
      o.ShapeSize = size;
      o.Mode = mode;
      o.Seed = static_cast<std::uint64_t>(seed);
      if (const char* limit = std::getenv("GS_DISTORTION_LIMIT"))
        o.DistortionLimit = std::atof(limit);
      const Result<ShapeDistribution> res = d.Run(t, dirs, {}, o);
      int pairs = 0;
      const int overlaps = gs_test::CountPlanarOverlaps(plane, t, res->Shapes, o.ShapeSize, &pairs);
      TotalShapes += static_cast<long long>(res->Shapes.size());
      TotalOverlaps += overlaps;
      TotalPairs += pairs;
      sum += static_cast<double>(res->Shapes.size());
      std::printf(" %zu%s", res->Shapes.size(), overlaps ? "(OVERLAPS)" : "");
      if (std::getenv("GS_SQUARE_REASONS"))
        std::printf(" [candidates %lld: tables %lld, faithful %lld, drawn %lld, no shape %lld]",
          res->Statistics.Candidates, res->Statistics.RejectedByTables, res->Statistics.RejectedByFaithfulCheck,
          res->Statistics.RejectedByDrawnCheck, res->Statistics.RejectedWithoutShape);
      if (seed == 0 && !SvgPrefix.empty())
        WriteSvg(SvgPrefix + "_square" + std::to_string(static_cast<int>(width)) + "_" + ModeName(mode) + ".svg",
          t, res->Shapes, o.ShapeSize, side);
    }
    mean[mode] = sum / seeds;
    std::printf("  (seeds 0-%d): mean %.1f\n", seeds - 1, mean[mode]);
  }
  const double c = mean[DistributionMode::CircumcirclePoissonDisk];
  std::printf("  circumcircle %.1f | random %.1f (%.2fx) | greedy %.1f (%.2fx; %.1f%% of the lattice's %.1f)\n", c,
    mean[DistributionMode::Random], mean[DistributionMode::Random] / c, mean[DistributionMode::Greedy],
    mean[DistributionMode::Greedy] / c, 100.0 * mean[DistributionMode::Greedy] / lattice, lattice);
}

// A generated bumpy sphere (saddles everywhere): several classes, surface overlap test.
void BumpySphere(const std::vector<SafeDistanceInput>& classes, int seeds)
{
  TriangleSoup soup = MakeIcosphere(1.0, 6);
  for (Vec3& p : soup.Points)
  {
    // Smooth bumps: positive and negative curvature (saddles) at the scale of a few shapes.
    p = p * (1.0 + 0.12 * std::sin(4.0 * p.x) * std::sin(4.0 * p.y) * std::sin(4.0 * p.z));
  }
  const TriangleMesh sphere = Build(soup);
  SaddleVertexGraph graph;
  SaddleVertexGraphOptions go;
  if (const Status built = graph.Build(sphere, go, nullptr); !built.Ok())
  {
    std::fprintf(stderr, "graph: %s\n", built.Message().c_str());
    return;
  }
  const SafeDistanceTables t = Tables(classes);
  std::vector<Vec3> dirs(sphere.NumberOfFaces());
  for (int f = 0; f < sphere.NumberOfFaces(); ++f)
  {
    const auto& c = sphere.Face(f);
    dirs[f] = Cross(Vec3{ 0.2, 0.1, 1.0 }, sphere.Position(c[0]) + sphere.Position(c[1]) + sphere.Position(c[2]));
  }
  long long shapes = 0, pairs = 0;
  int overlaps = 0;
  double seconds = 0.0;
  for (int seed = 0; seed < seeds; ++seed)
  {
    ShapeDistributor d(sphere, getenv("GS_EXACT") ? nullptr : &graph);
    ShapeDistributionOptions o;
    o.ShapeSize = 0.08;
    o.Mode = seed % 2 ? DistributionMode::Greedy : DistributionMode::Random;
    if (getenv("GS_MARGIN"))
      o.SafetyMargin = atof(getenv("GS_MARGIN"));
    if (getenv("GS_HOLONOMY"))
      o.HolonomyMargin = atof(getenv("GS_HOLONOMY"));
    if (getenv("GS_DISTORTION"))
      o.DistortionLimit = atof(getenv("GS_DISTORTION"));
    o.Seed = static_cast<std::uint64_t>(seed);
    const Result<ShapeDistribution> r = d.Run(t, dirs, {}, o);
    long long p = 0;
    overlaps += gs_test::CountSurfaceOverlaps(sphere, t, d, o.ShapeSize, 0.02, &p);
    pairs += p;
    shapes += static_cast<long long>(r->Shapes.size());
    seconds += r->Statistics.Seconds;
    if (getenv("GS_VERBOSE"))
      std::printf("    seed %d: %zu shapes, %lld candidates, %lld charts, %.2f s (generate %.2f, checks %.2f, set-up %.2f)\n", seed, r->Shapes.size(), r->Statistics.Candidates, r->Statistics.Charts, r->Statistics.Seconds, r->Statistics.GenerateSeconds, r->Statistics.CheckSeconds, r->Statistics.PrepareSeconds);
  }
  TotalShapes += shapes;
  TotalOverlaps += overlaps;
  TotalPairs += pairs;
  std::printf("  %d vertices, %zu classes, %d runs (Random and Greedy): %.1f shapes and %.2f s per run; surface overlap test: %d overlaps in %lld close pairs\n",
    sphere.NumberOfVertices(), classes.size(), seeds, static_cast<double>(shapes) / seeds, seconds / seeds,
    overlaps, pairs);
}

} // namespace

// --scale: the Shape Distributor at scale as the filter runs it (issue 17): a mesh subdivided once,
// the given shape images (each scaled to circumradius 1), ShapeSize `size` times the bounding-box
// diagonal, a constant direction; the graph from `cache` (built and saved when missing);
// `runs` re-runs with new seeds alternating 1 and 2 threads; per phase: distribution (set-up,
// candidates, checks and charts, rounds), decals, outlines and the overlap check (VerifyOverlaps).
int AtScale(const std::string& meshPath, const std::vector<std::string>& images, const std::string& cache,
  int runs, double size, DistributionMode mode, double graphAccuracy)
{
  TriangleSoup soup;
  if (!ReadMeshOrSay(meshPath, soup))
  {
    return 1;
  }
  const TriangleSoup subdivided = SubdivideAtMidpoints(soup);
  const double tb0 = Now();
  const TriangleMesh mesh = Build(subdivided);
  std::printf("  mesh build: %.3f s\n", Now() - tb0);
  std::vector<SafeDistanceInput> classes;
  if (!ImageClasses(images, classes))
  {
    return 1;
  }
  const SafeDistanceTables t = Tables(classes);
  int longClasses = 0;
  for (const SafeDistanceClass& c : t.Classes)
    longClasses += c.Parts.size() > 1 ? 1 : 0;
  std::printf("At scale: %s subdivided once: %d vertices, %d faces; %zu classes (%d long), ShapeSize %.3g of "
              "the diagonal, %s\n", meshPath.c_str(), mesh.NumberOfVertices(), mesh.NumberOfFaces(),
    classes.size(), longClasses, size, ModeName(mode));
  const std::uint64_t meshHash = SaddleVertexGraph::HashMesh(mesh);
  // The charts' graph: as the filter's default, the discrete geodesic graph of accuracy 0.1
  // (--graph-accuracy 0: the saddle vertex graph of K = 50).
  SaddleVertexGraph graph;
  const SaddleVertexGraphOptions go = ChartGraphOptions(graphAccuracy);
  if (cache.empty() || !graph.Load(cache, meshHash, go).Ok())
  {
    const double t0 = Now();
    if (const Status built = graph.Build(mesh, go, nullptr); !built.Ok())
    {
      std::fprintf(stderr, "graph: %s\n", built.Message().c_str());
      return 1;
    }
    if (graphAccuracy > 0.0)
      std::printf("  graph build (discrete geodesic graph, accuracy %g, 2 threads): %.2f s\n", graphAccuracy, Now() - t0);
    else
      std::printf("  graph build (saddle vertex graph, K = 50, 2 threads): %.2f s\n", Now() - t0);
    if (const Status saved = cache.empty() ? Status() : graph.Save(cache, meshHash); !saved.Ok())
      std::fprintf(stderr, "graph cache: %s\n", saved.Message().c_str());
  }
  const std::vector<Vec3> directions(mesh.NumberOfFaces(), Vec3{ 0.3, 1.0, 0.2 });
  ShapeDistributor d(mesh, &graph);
  std::map<int, std::vector<double>> phase[8];
  std::map<int, std::vector<std::size_t>> counts;
  const char* names[8] = { "set-up", "candidates", "checks and charts", "rounds", "decals", "outlines",
    "overlap check", "all" };
  for (int run = 0; run <= runs; ++run)
  {
    for (int threads : { 1, 2 })
    {
      ShapeDistributionOptions o;
      o.ShapeSize = size * mesh.BoundingBoxDiagonal();
      o.Seed = static_cast<std::uint64_t>(10 + run);
      o.NumberOfThreads = threads;
      o.Mode = mode;
      if (const char* drawn = std::getenv("GS_DRAWN_CHECK"))
        o.DrawnCheck = std::atoi(drawn) != 0;
      if (const char* faithful = std::getenv("GS_FAITHFUL"))
        o.FaithfulCheck = std::atoi(faithful) != 0;
      if (const char* tol = std::getenv("GS_FAITHFUL_TOLERANCE"))
        o.FaithfulTolerance = std::atof(tol);
      if (const char* early = std::getenv("GS_EARLY_REJECTION"))
        o.EarlyRejection = std::atoi(early) != 0; // (0: whole long shapes built, the same placements)
      if (const char* failures = std::getenv("GS_MAXIMAL_FAILURES"))
        o.MaximalFailures = std::atoi(failures); // (the speed / maximality trade-off)
      if (const char* limit = std::getenv("GS_DISTORTION_LIMIT"))
        o.DistortionLimit = std::atof(limit); // (0: every close pair judged by circumcircles)
      const double t0 = Now();
      const Result<ShapeDistribution> r = d.Run(t, directions, {}, o);
      const double t1 = Now();
      const int n = static_cast<int>(r->Shapes.size());
      Hasher placements; // (for refactors: the same placements bit for bit)
      for (const PlacedShape& shape : r->Shapes)
      {
        placements.AddValue(shape.Position);
        placements.AddValue(shape.Direction);
        placements.AddValue(shape.ClassId);
      }
      std::printf("    placements hash %016llx\n", static_cast<unsigned long long>(placements.H));
      std::vector<double> decalSeconds;
      const std::vector<ShapeDecal> decals =
        DrawDecals(d, ShapeDistributor::DefaultDecalTolerance, threads, &decalSeconds);
      double longSeconds = 0.0;
      for (int s = 0; s < n; ++s)
        if (!r->Shapes[s].Curve.empty())
          longSeconds += decalSeconds[s];
      const double t2 = Now();
      if (threads == 1)
      {
        std::printf("    decals: %.3f s CPU for long shapes, %.3f s for short ones\n", longSeconds, t2 - t1 - longSeconds);
        // The cost of splitting faces where the map is not affine (DecalTolerance): the same
        // decals with whole faces only, in the same run.
        long long pieces = 0, wholeFaces = 0;
        Hasher decalHash; // (for refactors: the same decals bit for bit)
        for (const ShapeDecal& decal : decals)
        {
          pieces += static_cast<long long>(decal.Faces.size());
          decalHash.AddVector(decal.Faces);
          decalHash.AddVector(decal.Corners);
          decalHash.AddVector(decal.TextureCoordinates);
        }
        std::printf("    decals hash %016llx\n", static_cast<unsigned long long>(decalHash.H));
        const double w0 = Now();
        for (int s = 0; s < n; ++s)
          wholeFaces += static_cast<long long>(d.Decal(s, 0.0).Faces.size());
        const double w1 = Now();
        std::printf("    decal triangles: %lld split at tolerance %.3g (%.3f s), %lld whole faces only (%.3f s): %.2fx triangles, %.2fx time\n",
          pieces, ShapeDistributor::DefaultDecalTolerance, t2 - t1, wholeFaces, w1 - w0,
          wholeFaces > 0 ? static_cast<double>(pieces) / wholeFaces : 0.0, (w1 - w0) > 0 ? (t2 - t1) / (w1 - w0) : 0.0);
      }
      const std::vector<std::vector<OutlinePiece>> outlines = DrawOutlines(d, threads);
      const double t3 = Now();
      OverlapCheckOptions co;
      co.NumberOfThreads = threads;
      const Result<OverlapCheckResult> checked = CheckOverlaps(d, outlines, co);
      if (!checked.Ok())
      {
        std::fprintf(stderr, "overlap check: %s\n", checked.Message().c_str());
        return 1;
      }
      const OverlapCheckResult& check = *checked;
      ScaleFaults += static_cast<long long>(check.Pairs.size());
      const double t4 = Now();
      if (threads == 2)
      {
        // The same check through the placement's own charts (on the geodesic graph).
        OverlapCheckOptions xo = co;
        xo.ExactCharts = false;
        const double x0 = Now();
        const Result<OverlapCheckResult> chartChecked = CheckOverlaps(d, outlines, xo);
        if (chartChecked.Ok())
        {
          std::printf("    overlap check through the placement's charts: %zu pairs, %lld examined, %.3f s (%.2fx the exact check)\n",
            chartChecked->Pairs.size(), chartChecked->PairsExamined, Now() - x0, (Now() - x0) / std::max(1e-9, t4 - t3));
          for (std::size_t k = 0; k < chartChecked->Pairs.size() && k < 6; ++k)
            std::printf("      pair %d (class %d) and %d (class %d)\n", chartChecked->Pairs[k].first,
              r->Shapes[chartChecked->Pairs[k].first].ClassId, chartChecked->Pairs[k].second,
              r->Shapes[chartChecked->Pairs[k].second].ClassId);
        }
      }
      if (threads == 1 && std::getenv("GS_PROBES"))
        std::printf("    probes that still fit: %.4f%% of 100000\n", 100.0 * gs_test::ProbeFitFraction(d, 100000, 777));
      if (threads == 1)
      {
        const DecalOracleResult oracle = DecalOracle(t, r->Shapes, decals);
        DecalsAgainstOutlines(t, r->Shapes, decals, outlines);
        std::printf("    decal oracle: %lld pairs draw a common lattice point, %lld of them more than 1%% of the "
                    "smaller shape's (worst %.2f%%)\n", oracle.SharingPairs, oracle.PairsOverOnePercent,
          100.0 * oracle.Worst);
        std::printf("    decals drawn hash %016llx (lattice points inside the silhouette)\n",
          static_cast<unsigned long long>(oracle.DrawnHash));
        if (std::getenv("GS_DEBUG_ORACLE"))
          for (const auto& pair : oracle.Over)
          {
            std::map<std::uint64_t, std::pair<Vec2, SurfacePoint>> pts[2];
            const int ids[2] = { pair.first.first, pair.first.second };
            for (int w = 0; w < 2; ++w)
            {
              const SafeDistanceClass& c = t.Classes[r->Shapes[ids[w]].ClassId];
              const ClassRegion region(c.Outline.Rings, c.Radius, 0.0);
              const ShapeDecal& decal = decals[ids[w]];
              gs_test::ForEachDrawnLatticePoint(decal, c, region,
                [&](std::size_t k, int index, const std::array<double, 3>& bary, const Vec2&, const Vec2& q) {
                  pts[w][static_cast<std::uint64_t>(decal.Faces[k]) * 64 + index] =
                    std::make_pair(q, SurfacePoint{ -1, decal.Faces[k], bary });
                });
            }
            for (int w = 0; w < 2; ++w)
            {
              const PlacedShape& S = r->Shapes[ids[w]];
              std::printf("      shape %d class %d at (%.4f %.4f %.4f), radius %.4f, %zu parts, curve %zu\n", ids[w],
                S.ClassId, S.Position.x, S.Position.y, S.Position.z,
                t.Classes[S.ClassId].Radius * o.ShapeSize * S.Scale, S.Parts.size(), S.Curve.size());
            }
            for (const auto& e : pts[0])
            {
              const auto it = pts[1].find(e.first);
              if (it == pts[1].end())
                continue;
              const SurfacePoint& x = e.second.second;
              const Vec3 X = mesh.Interpolate(x.Face, x.Bary);
              Vec2 c0{ NAN, NAN }, c1{ NAN, NAN };
              auto classPoint = [&](int id, Vec2& c) {
                if (r->Shapes[id].Curve.empty())
                  return d.ClassPoint(id, x, c);
                const auto grid = d.Frame(id);
                int hint = -1;
                const bool ok = grid->ClassPoint(x, c, &hint);
                for (int k = 0; k < static_cast<int>(grid->Nodes.size()); ++k)
                  if (grid->Nodes[k].Valid) { hint = k; break; }
                Vec2 e; double dist = -1; int nn = -1;
                grid->Locate(X, hint, e, &dist, &nn);
                const MappedPoint m = d.Map(id, e);
                std::printf("        grid %dx%d step %.4f: located (%.3f %.3f) at %.4f from the grid (node %d at %.4f); map of the decal point %s, %.4f from X\n",
                  grid->Columns, grid->Rows, grid->Step, e.x, e.y, dist, nn, Norm(grid->Nodes[nn].Position - X),
                  m.Reached ? "reached" : "stopped", Norm(mesh.Position(m.End) - X));
                return ok;
              };
              const bool ok0 = classPoint(ids[0], c0), ok1 = classPoint(ids[1], c1);
              std::printf("      face %d (%.4f %.4f %.4f): decal %d (%.3f %.3f) chart %d (%.3f %.3f) | decal %d (%.3f %.3f) chart %d (%.3f %.3f); |X-c| %.4f %.4f\n",
                x.Face, X.x, X.y, X.z, ids[0], e.second.first.x, e.second.first.y, ok0, c0.x, c0.y, ids[1],
                it->second.first.x, it->second.first.y, ok1, c1.x, c1.y, Norm(X - r->Shapes[ids[0]].Position),
                Norm(X - r->Shapes[ids[1]].Position));
            }
          }
        ScaleFaults += oracle.PairsOverOnePercent;
        for (const auto& pair : oracle.Over)
          std::printf("      decals of %d (class %d%s) and %d (class %d%s) share %.2f%%\n", pair.first.first,
            r->Shapes[pair.first.first].ClassId, r->Shapes[pair.first.first].Curve.empty() ? "" : ", long",
            pair.first.second, r->Shapes[pair.first.second].ClassId,
            r->Shapes[pair.first.second].Curve.empty() ? "" : ", long", 100.0 * pair.second);
      }
      const ShapeDistributionStatistics& st = r->Statistics;
      const double values[8] = { st.PrepareSeconds, st.GenerateSeconds, st.CheckSeconds, st.RoundSeconds,
        t2 - t1, t3 - t2, t4 - t3, t3 - t0 };
      std::printf("  seed %d, %d thread(s): %d shapes, %lld candidates, %lld charts; distribution %.2f s, "
                  "with decals and outlines %.2f s (%.0f shapes/s); overlap check %.3f s (%zu pairs, %lld "
                  "examined)%s\n", 10 + run, threads, n, st.Candidates, st.Charts, t1 - t0,
        t3 - t0, n / (t3 - t0), t4 - t3, check.Pairs.size(), check.PairsExamined,
        run == 0 ? " (warm-up)" : "");
      for (std::size_t k = 0; k < check.Pairs.size() && k < 4 && threads == 1; ++k)
      {
        const PlacedShape &a = r->Shapes[check.Pairs[k].first], &b = r->Shapes[check.Pairs[k].second];
        // Depth: the deepest point of the long (or second) outline inside the short shape.
        const int sa = a.Curve.empty() ? check.Pairs[k].first : check.Pairs[k].second;
        const int sb = sa == check.Pairs[k].first ? check.Pairs[k].second : check.Pairs[k].first;
        double depth = 0.0;
        const auto& rings = t.Classes[r->Shapes[sa].ClassId].Outline.Rings;
        ClassRegion region(rings, t.Classes[r->Shapes[sa].ClassId].Radius, 0.0);
        for (const OutlinePiece& piece : outlines[sb])
          for (const SurfacePoint& q : piece.Points)
          {
            Vec2 p;
            if (!d.ClassPoint(sa, q, p) || !region.Inside(p))
              continue;
            double best = 1e300;
            for (const auto& ring : rings)
              for (std::size_t i = 0; i < ring.size(); ++i)
              {
                const Vec2 u = ring[i], ab = ring[(i + 1) % ring.size()] - u;
                const double l2 = Dot(ab, ab);
                const double tt = l2 > 0.0 ? std::min(1.0, std::max(0.0, Dot(p - u, ab) / l2)) : 0.0;
                best = std::min(best, Norm(u + ab * tt - p));
              }
            if (best > depth)
            {
              depth = best;
              if (std::getenv("GS_DEBUG_DEPTH"))
              {
                const Vec3 X = mesh.Interpolate(q.Face, q.Bary);
                std::printf("      deepest so far %.3f at class point of %d (%.3f %.3f); parts of %d:", best, sa, p.x, p.y, sb);
                for (const PlacedPart& part : r->Shapes[sb].Parts)
                  std::printf(" [part %d r %.3f: %.4f from the point, %.4f from %d's centre]", part.Part,
                    t.Parts[part.Part].Radius * o.ShapeSize * r->Shapes[sb].Scale, Norm(part.Position - X),
                    Norm(part.Position - r->Shapes[sa].Position), sa);
                std::printf("\n");
              }
            }
          }
        {
          // Independent of both maps: the two drawn outlines projected on the tangent plane at the
          // first shape's centre, their common area over the smaller one's.
          const PlacedShape& A = r->Shapes[check.Pairs[k].first];
          const Vec3 n = A.Normal, e1 = Unit(A.Direction), e2 = Cross(n, e1);
          auto project = [&](int s) {
            std::vector<std::vector<Vec2>> rings;
            for (const OutlinePiece& piece : outlines[s])
            {
              std::vector<Vec2> ring;
              for (const SurfacePoint& q : piece.Points)
              {
                const Vec3 x = mesh.Interpolate(q.Face, q.Bary) - A.Position;
                ring.push_back(Vec2{ Dot(x, e1), Dot(x, e2) });
              }
              rings.push_back(ring);
            }
            return rings;
          };
          const auto ra = project(check.Pairs[k].first), rb = project(check.Pairs[k].second);
          const double common = gs_test::CommonArea(ra, rb, 400);
          const double areaA = gs_test::CommonArea(ra, ra, 400), areaB = gs_test::CommonArea(rb, rb, 400);
          std::printf("    projected on the tangent plane: common area %.2f%% of the smaller shape\n",
            100.0 * common / std::min(areaA, areaB));
        }
        if (std::getenv("GS_DEBUG_DEPTH"))
        {
          // The long shape's drawn map against each rigid part, at its outline points in the part's circle.
          const int L = r->Shapes[check.Pairs[k].first].Curve.empty() ? check.Pairs[k].second : check.Pairs[k].first;
          const PlacedShape& ls = r->Shapes[L];
          const double unit = o.ShapeSize * ls.Scale;
          for (const PlacedPart& part : ls.Parts)
          {
            const Vec2 pc = t.Parts[part.Part].Centre;
            const double R = t.Parts[part.Part].Radius;
            const double ref = TangentAngle(mesh, part.Centre, part.Axis);
            double worst = 0.0;
            int count = 0;
            for (const auto& ring : t.Classes[ls.ClassId].Outline.Rings)
              for (const Vec2& p : ring)
              {
                const Vec2 q = p - pc;
                if (Norm(q) > R)
                  continue;
                const MappedPoint drawn = d.Map(L, p);
                const GeodesicShot rigid = ShootGeodesic(mesh, part.Centre, ref + std::atan2(q.y, q.x), Norm(q) * unit);
                worst = std::max(worst, Norm(mesh.Interpolate(drawn.End.Face, drawn.End.Bary) - mesh.Interpolate(rigid.End.Face, rigid.End.Bary)));
                ++count;
              }
            std::printf("      part %d of %d: drawn vs rigid at %d outline points: max %.5f (%.1f%% of the part radius)\n", part.Part, L, count, worst, 100.0 * worst / (R * unit));
            // In the short shape's chart: the part's rigid copy (placed as the conflict test places
            // it) against the drawn long shape, and whether the rigid copy overlaps the short one.
            const int S = L == check.Pairs[k].first ? check.Pairs[k].second : check.Pairs[k].first;
            const double sunit = o.ShapeSize * r->Shapes[S].Scale;
            Vec2 qc;
            if (!d.ClassPoint(S, part.Centre, qc))
              continue;
            const GeodesicShot step = ShootGeodesic(mesh, part.Centre, ref, 0.05 * R * unit);
            Vec2 qa;
            if (!d.ClassPoint(S, step.End, qa))
              continue;
            const double axis = std::atan2(qa.y - qc.y, qa.x - qc.x);
            const ClassRegion region(t.Classes[r->Shapes[S].ClassId].Outline.Rings, t.Classes[r->Shapes[S].ClassId].Radius, 0.0);
            double gap = 0.0;
            int rigidInside = 0, drawnInside = 0;
            for (const auto& ring : t.Classes[ls.ClassId].Outline.Rings)
              for (const Vec2& p : ring)
              {
                const Vec2 q = p - pc;
                if (Norm(q) > R)
                  continue;
                const Vec2 rigid = qc + Vec2{ std::cos(axis) * q.x - std::sin(axis) * q.y, std::sin(axis) * q.x + std::cos(axis) * q.y } * (unit / sunit);
                Vec2 drawn;
                if (!d.ClassPoint(S, d.Map(L, p).End, drawn))
                  continue;
                gap = std::max(gap, Norm(rigid - drawn));
                rigidInside += region.Inside(rigid) ? 1 : 0;
                drawnInside += region.Inside(drawn) ? 1 : 0;
              }
            const double phi = std::atan2(qc.y, qc.x);
            std::printf("        in %d's chart: centre (%.4f %.4f), d %.4f, axis %.3f, alphaA %.3f alphaB %.3f, table %.4f; rigid vs drawn max %.4f; points inside: rigid %d, drawn %d\n",
              S, qc.x, qc.y, Norm(qc), axis, -phi, axis - phi,
              t.Lookup(t.Classes[r->Shapes[S].ClassId].Parts[0], part.Part, -phi, axis - phi), gap, rigidInside, drawnInside);
          }
        }
        std::printf("    overlap: shapes %d (class %d%s) and %d (class %d%s), centres %.4f apart (radius %.4f): "
                    "the outline of %d reaches %.2f%% of the radius into %d\n",
          check.Pairs[k].first, a.ClassId, a.Curve.empty() ? "" : ", long", check.Pairs[k].second, b.ClassId,
          b.Curve.empty() ? "" : ", long", Norm(a.Position - b.Position), o.ShapeSize, sb,
          100.0 * depth / t.Classes[r->Shapes[sa].ClassId].Radius, sa);
      }
      if (run == 0)
        continue; // the first run of each thread count: per-thread engines, lattices
      for (int k = 0; k < 8; ++k)
        phase[k][threads].push_back(values[k]);
      counts[threads].push_back(r->Shapes.size());
    }
  }
  for (int threads : { 1, 2 })
  {
    std::printf("  median of %d, %d thread(s):", runs, threads);
    for (int k = 0; k < 8; ++k)
      std::printf(" %s %.3f s%s", names[k], Median(phase[k][threads]), k < 7 ? "," : "\n");
  }
  const double one = Median(phase[7][1]), two = Median(phase[7][2]);
  std::printf("  2 threads: %.2fx one; overlap check / distribution with outputs: %.1f%%; same shapes for 1 "
              "and 2 threads: %s\n", one / two, 100.0 * Median(phase[6][2]) / two,
    counts[1] == counts[2] ? "yes" : "NO");
  if (CheckScale && ScaleFaults > 0)
    std::printf("FAILED: %lld faults (VerifyOverlaps pairs, decal pairs sharing over 1%%, short decals leaving "
                "outline points undrawn, decals leaving strips of their outline undrawn)\n", ScaleFaults);
  return counts[1] == counts[2] && !(CheckScale && ScaleFaults > 0) ? 0 : 2;
}

// --under-load: the demo's distribution (the bundled bumpy sphere, its four classes, Greedy, decals
// and outlines as the filter draws them) on 1 and 2 threads, each with and without one CPU-bound
// competing process (a forked child spinning), alternating; medians of R rounds. What a ParaView
// user sees when anything else runs: 2 threads should be no slower than 1.
int UnderLoad(const std::string& meshPath, const std::vector<std::string>& images, int rounds)
{
  TriangleSoup soup;
  if (!ReadMeshOrSay(meshPath, soup))
  {
    return 1;
  }
  const TriangleMesh mesh = Build(soup);
  std::vector<SafeDistanceInput> classes;
  if (!ImageClasses(images, classes))
  {
    return 1;
  }
  const SafeDistanceTables t = Tables(classes);
  SaddleVertexGraph graph;
  if (const Status built = graph.Build(mesh, ChartGraphOptions(0.1), nullptr); !built.Ok())
  {
    std::fprintf(stderr, "graph: %s\n", built.Message().c_str());
    return 1;
  }
  const Vec3 lo = mesh.BoundingBoxMin(), hi = mesh.BoundingBoxMax();
  const double halfExtent = 0.5 * std::max({ hi.x - lo.x, hi.y - lo.y, hi.z - lo.z });
  const std::vector<Vec3> directions(mesh.NumberOfFaces(), Vec3{ 0.3, 1.0, 0.2 });
  ShapeDistributor d(mesh, &graph);
  std::printf("Under load: %s, %d faces, %zu classes, Greedy, ShapeSize 0.09 of the half extent; %d rounds\n",
    meshPath.c_str(), mesh.NumberOfFaces(), classes.size(), rounds);
  std::map<std::pair<int, bool>, std::vector<double>> seconds;
  std::map<std::pair<int, bool>, std::set<std::size_t>> counts;
  for (int round = 0; round < rounds; ++round)
  {
    for (bool compete : { false, true })
    {
      for (int threads : { 1, 2 })
      {
        pid_t child = -1;
        if (compete)
        {
          child = fork();
          if (child == 0)
          {
            for (volatile unsigned long long spin = 0;; spin = spin + 1)
            {
            }
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(50)); // (the child runs)
        }
        ShapeDistributionOptions o;
        o.ShapeSize = 0.09 * halfExtent;
        o.Seed = static_cast<std::uint64_t>(10 + round);
        o.NumberOfThreads = threads;
        o.Mode = DistributionMode::Greedy;
        const double t0 = Now();
        const Result<ShapeDistribution> r = d.Run(t, directions, {}, o);
        const std::vector<ShapeDecal> decals =
          DrawDecals(d, ShapeDistributor::DefaultDecalTolerance, threads, nullptr);
        const std::vector<std::vector<OutlinePiece>> outlines = DrawOutlines(d, threads);
        const double elapsed = Now() - t0;
        if (child > 0)
        {
          kill(child, SIGKILL);
          waitpid(child, nullptr, 0);
        }
        if (!r.Ok())
        {
          std::fprintf(stderr, "distribution: %s\n", r.Message().c_str());
          return 1;
        }
        seconds[{ threads, compete }].push_back(elapsed);
        counts[{ threads, compete }].insert(r->Shapes.size());
        std::printf("  seed %d, %d thread%s, %s: %.3f s, %zu shapes\n", 10 + round, threads,
          threads > 1 ? "s" : "", compete ? "one competing process" : "alone", elapsed, r->Shapes.size());
      }
    }
  }
  for (bool compete : { false, true })
  {
    const double one = Median(seconds[{ 1, compete }]), two = Median(seconds[{ 2, compete }]);
    std::printf("%s: median 1 thread %.3f s, 2 threads %.3f s: 2 threads take %.2fx the time of 1\n",
      compete ? "one competing process" : "alone", one, two, two / one);
  }
  return 0;
}

int main(int argc, char* argv[])
{
  bool quick = false, meshOnly = false, exactCharts = false, speedOnly = false;
  double squareOnly = 0.0; // --square W: the issue's square only, W circumradii wide
  int squareSeeds = 0;      // --seeds N: its seeds (default 8, --quick 3)
  int speedRounds = 3;
  double margin = -1.0, distortion = -1.0;
  std::vector<std::string> args, scaleImages;
  std::string scaleCache;
  double scaleSize = 0.01, scaleAccuracy = 0.1;
  bool scale = false, underLoad = false;
  DistributionMode scaleMode = DistributionMode::Random;
  for (int i = 1; i < argc; ++i)
  {
    if (std::strcmp(argv[i], "--scale") == 0)
      scale = true;
    else if (std::strcmp(argv[i], "--under-load") == 0)
      underLoad = true;
    else if (std::strcmp(argv[i], "--cache") == 0 && i + 1 < argc)
      scaleCache = argv[++i];
    else if (std::strcmp(argv[i], "--size") == 0 && i + 1 < argc)
      scaleSize = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--graph-accuracy") == 0 && i + 1 < argc)
      scaleAccuracy = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--check") == 0)
      CheckScale = true;
    else if (std::strcmp(argv[i], "--greedy") == 0)
      scaleMode = DistributionMode::Greedy;
    else if (std::strcmp(argv[i], "--image") == 0 && i + 1 < argc)
      scaleImages.push_back(argv[++i]);
    else if (std::strcmp(argv[i], "--square") == 0 && i + 1 < argc)
      squareOnly = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--seeds") == 0 && i + 1 < argc)
      squareSeeds = std::max(1, std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else if (std::strcmp(argv[i], "--svg") == 0 && i + 1 < argc)
      SvgPrefix = argv[++i];
    else if (std::strcmp(argv[i], "--speed-only") == 0)
      speedOnly = true;
    else if (std::strcmp(argv[i], "--exact-charts") == 0)
      exactCharts = true;
    else if (std::strcmp(argv[i], "--mesh-only") == 0)
      meshOnly = true;
    else if (std::strcmp(argv[i], "--distortion") == 0 && i + 1 < argc)
      distortion = std::atof(argv[++i]);
    else if (std::strcmp(argv[i], "--speed-rounds") == 0 && i + 1 < argc)
      speedRounds = std::max(1, std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--margin") == 0 && i + 1 < argc)
      margin = std::atof(argv[++i]);
    else
      args.push_back(argv[i]);
  }
  if (underLoad && !args.empty())
    return UnderLoad(args[0], scaleImages, speedRounds);
  if (scale && !args.empty())
    return AtScale(args[0], scaleImages, scaleCache, speedRounds, scaleSize, scaleMode, scaleAccuracy);
  const std::string images = args.size() > 1 ? args[1] : "";
  std::vector<SafeDistanceInput> classes;
  classes.push_back({ "pentagram", ShapeFromPolygons({ Pentagram() }) });
  for (const char* name : { "star", "eagle", "fish", "bird" })
  {
    Shape2D s;
    if (!images.empty() && ShapeFromImage(images + "/" + name + ".png", s))
      classes.push_back({ name, s });
    else
      std::printf("(no %s image in '%s')\n", name, images.c_str());
  }
  const int seeds = quick ? 3 : 20;
  if (squareOnly > 0.0)
  {
    const int n = squareSeeds > 0 ? squareSeeds : quick ? 3 : 8;
    std::printf("1b. The pentagram on a square %g circumradii wide, aligned, %d seeds\n", squareOnly, n);
    IssueSquare(classes[0], squareOnly, n);
    std::printf("Total: %lld shapes placed, %lld close pairs checked, %lld overlaps\n", TotalShapes, TotalPairs,
      TotalOverlaps);
    return TotalOverlaps == 0 ? 0 : 2;
  }

  if (!meshOnly)
  {
  std::printf("1. Density against circumcircle Poisson disk, 10 x 10 square, shape radius 0.5, %d seeds\n", seeds);
  for (const SafeDistanceInput& c : classes)
  {
    if (c.Name == "pentagram" || c.Name == "star" || c.Name == "eagle")
      Figure9(c.Name, c, seeds);
  }
  std::printf("1b. Issue 17's square: the pentagram on a square 40 circumradii wide, aligned, %d seeds\n", quick ? 3 : 8);
  IssueSquare(classes[0], 40.0, quick ? 3 : 8);
  std::printf("2. Density fidelity (pentagram, %d seeds)\n", quick ? 2 : 8);
  DensityFidelity(classes[0], quick ? 2 : 8);
  std::printf("3. Large square 50 x 50, pentagram radius 0.5, aligned, %d seeds per mode\n", quick ? 1 : 7);
  LargeSquare(classes[0], quick ? 1 : 7);
  std::printf("4. Bumpy sphere (r = 1 + 0.12 sin 4x sin 4y sin 4z, 40962 vertices), shape radius 0.08\n");
  BumpySphere(std::vector<SafeDistanceInput>(classes.begin(), classes.begin() + std::min<std::size_t>(4, classes.size())), quick ? 2 : 10);
  }

  if (!args.empty())
  {
    TriangleSoup soup;
    if (!ReadMeshOrSay(args[0], soup))
    {
      return 1;
    }
    const TriangleMesh coarse = Build(soup);
    const TriangleMesh fine = Build(SubdivideAtMidpoints(soup));
    std::vector<SafeDistanceInput> four(classes.begin(), classes.begin() + std::min<std::size_t>(4, classes.size()));
    const SafeDistanceTables t = Tables(four);
    std::printf("5. %s subdivided once: %d vertices, %d faces; %zu classes\n", args[0].c_str(),
      fine.NumberOfVertices(), fine.NumberOfFaces(), four.size());
    double shapeSize = 0.012 * fine.BoundingBoxDiagonal();
    std::map<const TriangleMesh*, std::unique_ptr<SaddleVertexGraph>> graphs;
    for (const TriangleMesh* m : { &coarse, &fine })
    {
      if (speedOnly && m == &coarse)
        continue;
      const double t0 = Now();
      graphs[m].reset(new SaddleVertexGraph());
      SaddleVertexGraphOptions go;
      go.K = 50;
      if (const Status built = graphs[m]->Build(*m, go, nullptr); !built.Ok())
      {
        std::fprintf(stderr, "graph: %s\n", built.Message().c_str());
        return 1;
      }
      std::printf("  graph build (K = 50, 2 threads), %d faces: %.2f s\n", m->NumberOfFaces(), Now() - t0);
    }
    auto directionsOf = [](const TriangleMesh& m) {
      // A smooth field: the projection of a fixed axis (singular where the axis is normal).
      std::vector<Vec3> d(m.NumberOfFaces());
      for (int f = 0; f < m.NumberOfFaces(); ++f)
        d[f] = Vec3{ 0.3, 1.0, 0.2 };
      return d;
    };
    // Cold: a new distributor (per-mesh set-up: per-thread geodesic engines, field frames).
    {
      ShapeDistributor cold(fine, exactCharts ? nullptr : graphs[&fine].get());
      ShapeDistributionOptions o;
      o.ShapeSize = shapeSize;
      o.Seed = 1;
      const double t0 = Now();
      const Result<ShapeDistribution> r = cold.Run(t, directionsOf(fine), {}, o);
      std::printf("  cold run (new distributor, 2 threads): %zu shapes in %.2f s (set-up %.2f s)\n",
        r->Shapes.size(), Now() - t0, r->Statistics.PrepareSeconds);
    }
    // Warm, as the filter re-runs while the mesh is unchanged: the same distributor.
    ShapeDistributor d(fine, exactCharts ? nullptr : graphs[&fine].get());
    {
      ShapeDistributionOptions o;
      o.ShapeSize = shapeSize;
      o.MaximumShapes = 1;
      static_cast<void>(d.Run(t, directionsOf(fine), {}, o)); // warm-up: lattices, engines
    }
    // Speed: rounds alternating 1 and 2 threads (so that load changes on the machine fall on
    // both), median times; the checks below use the last run of each.
    ShapeDistribution results[3];
    std::vector<double> times[3];
    for (int round = 0; round < speedRounds; ++round)
    {
      for (int threads : { 1, 2 })
      {
        ShapeDistributionOptions o;
        o.ShapeSize = shapeSize;
        o.Seed = 1;
        o.NumberOfThreads = threads;
        if (margin >= 0.0)
          o.SafetyMargin = margin;
        if (distortion >= 0.0)
          o.DistortionLimit = distortion;
        const double t0 = Now();
        results[threads] = std::move(*d.Run(t, directionsOf(fine), {}, o));
        times[threads].push_back(Now() - t0);
        const ShapeDistribution& r = results[threads];
        std::printf("  %d thread(s): %zu shapes, %lld candidates, %lld charts, %.2f s (candidates %.2f, "
                    "checks and charts %.2f (charts %.2f s CPU), rounds %.2f, set-up %.2f)\n", threads,
          r.Shapes.size(), r.Statistics.Candidates, r.Statistics.Charts, times[threads].back(),
          r.Statistics.GenerateSeconds, r.Statistics.CheckSeconds, r.Statistics.ChartCpuSeconds,
          r.Statistics.RoundSeconds, r.Statistics.PrepareSeconds);
      }
    }
    const double t1s = Median(times[1]), t2s = Median(times[2]);
    const std::vector<PlacedShape>& reference = results[1].Shapes;
    const ShapeDistribution& r = results[2];
    bool same = r.Shapes.size() == reference.size();
    for (std::size_t i = 0; same && i < reference.size(); ++i)
      same = r.Shapes[i].Position.x == reference[i].Position.x && r.Shapes[i].ClassId == reference[i].ClassId;
    std::printf("  median of %d: 1 thread %.2f s, 2 threads %.2f s: speed-up %.2fx; identical result: %s\n",
      speedRounds, t1s, t2s, t1s / t2s, same ? "yes" : "NO");
    if (speedOnly)
      return same ? 0 : 2;
    {
      long long pairs = 0;
      const double t1 = Now();
      const int overlaps = gs_test::CountSurfaceOverlaps(fine, t, d, shapeSize, 0.02, &pairs);
      std::printf("  surface overlap test (exact polar chart of one shape, the other's outline drawn on the surface): %d overlaps in %lld close pairs (%.1f s)\n",
        overlaps, pairs, Now() - t1);
      TotalShapes += static_cast<long long>(r.Shapes.size());
      TotalOverlaps += overlaps;
      TotalPairs += pairs;
      std::printf("  probes that fit: %.4f%% of %d\n", 100.0 * gs_test::ProbeFitFraction(d, quick ? 10000 : 100000, 777), quick ? 10000 : 100000);
    }
    // Resolution insensitivity: the same surface (midpoint subdivision keeps it exactly).
    double counts[2] = { 0, 0 };
    const int resolutionSeeds = quick ? 1 : 3;
    for (int which = 0; which < 2; ++which)
    {
      const TriangleMesh& m = which == 0 ? coarse : fine;
      for (int seed = 0; seed < resolutionSeeds; ++seed)
      {
        ShapeDistributor d(m, graphs[&m].get());
        ShapeDistributionOptions o;
        o.ShapeSize = shapeSize;
        o.Seed = static_cast<std::uint64_t>(100 + seed);
        counts[which] += static_cast<double>(d.Run(t, directionsOf(m), {}, o)->Shapes.size()) / resolutionSeeds;
      }
    }
    std::printf("  resolution: %.1f shapes on %d faces, %.1f on %d faces: %.1f%% apart (bar: 5%%)\n",
      counts[0], coarse.NumberOfFaces(), counts[1], fine.NumberOfFaces(),
      100.0 * std::abs(counts[1] - counts[0]) / counts[1]);
  }
  std::printf("Total: %lld shapes placed, %lld close pairs checked, %lld overlaps\n", TotalShapes,
    TotalPairs, TotalOverlaps);
  return TotalOverlaps == 0 ? 0 : 2;
}
