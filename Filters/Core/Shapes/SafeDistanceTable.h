// Minimum safe distance tables (MSDT) between 2D shapes: Wang et al. 2016, "Anisotropic shape
// distribution on manifold surfaces", Sec. 4.2 and Algorithm 1, made conservative over whole
// angle bins.
//
// CONVENTION. Shape A (a part, see below) has its circle centre at the origin and shape B at
// (d, 0): the line joining the centres is the +x axis, from A to B. alpha_A is the angle from
// that line to A's polar axis (A's own +x axis), counter-clockwise: A is rotated by alpha_A
// about its centre; likewise B by alpha_B about its centre. Angle bin i (0 <= i < ka) covers
// [i w - w/2, i w + w/2) with w = 2 pi / ka (bins are centred on i w; AngleBin()).
// Table(a, b)[i][j] is a distance d0 on the grid k (r_a + r_b) / kr, 0 <= k <= kr, such that
// for EVERY alpha_A in bin i, alpha_B in bin j and d >= d0 the interiors of A and B do not
// intersect (regions, not only boundaries: one shape inside the other or in its hole counts).
//
// METHOD. For a translation along x, the interiors are disjoint for every d > D with
//   D = max over y of ( rightmost x of A at height y  -  leftmost x of B at height y ),
// (both extents are reached on the boundary), so D is the exact threshold the paper's search
// over kr steps approximates. Per shape and angle bin the extents are tabulated on horizontal
// rows (upper bound of the right extent, lower bound of the left extent over each row): every
// table entry is then one pass over the rows. Conservative over whole bins: each bin is
// sampled at RotationSamples angles, and each boundary segment is dilated by the largest
// displacement a rotation of half a sub-bin can cause to it (|p - c| 2 sin(w / (4 s)) for its
// farther end point, in a square that contains that disk). D is rounded up to the step grid.
//
// UNITS. Source coordinates are pixels (images) or the polygons' own units; everything in the
// result is divided by Scale, the circumradius of the FIRST class, so that class has radius 1.
//
// LONG SHAPES. A class whose aspect ratio (extent along its major axis, from the area's second
// moments, over the extent across it) exceeds MaximumAspectRatio is cut across the major axis
// into ceil(aspect / MaximumAspectRatio) strips of equal width (Fig. 7 of the paper); each part
// has its own circle and tables. Tables exist for every ordered pair of parts (P^2 tables for
// P parts in all; m^2 when no class is split).
#pragma once

#include "Silhouette.h"
#include "Status.h"
#include "Vector.h"

#include <functional>
#include <string>
#include <vector>

namespace gs
{

struct Circle
{
  Vec2 Centre;
  double Radius = 0.0;
};

/// Smallest circle containing all points (Welzl's algorithm, iterative with a fixed-seed
/// shuffle: expected linear time, deterministic). An empty input gives radius 0 at the origin.
Circle SmallestEnclosingCircle(std::vector<Vec2> points);

struct Segment2
{
  Vec2 A, B;
};

struct SafeDistanceOptions
{
  int AngleBins = 64;     ///< ka: angle bins per shape (>= 1)
  int DistanceSteps = 64; ///< kr: distance steps between 0 and r_A + r_B (>= 1)
  /// Classes whose aspect ratio is above this are split into parts (>= 1; a huge value
  /// disables splitting).
  double MaximumAspectRatio = 2.0;
  /// Rotation samples per angle bin (conservative mode). 0 (default): ceil(8 pi kr / ka), which
  /// keeps the rotation dilation of a pair under an eighth of a distance step.
  int RotationSamples = 0;
  /// Rows of the extent profiles over [-R, R] (R: largest part radius plus the dilation).
  int Rows = 1024;
  /// false: the paper's non-conservative table, each bin evaluated only at its centre angle.
  bool Conservative = true;
};

/// One shape class as given: a name (e.g. its file) and its region in source units.
struct SafeDistanceInput
{
  std::string Name;
  Shape2D Shape;
};

struct SafeDistanceClass
{
  std::string Name;
  Circle SourceCircle; ///< smallest enclosing circle in source units
  double Radius = 0.0; ///< circumradius in normalized units
  /// Region in normalized units, origin at the circle centre, axes as in the source.
  Shape2D Outline;
  double AspectRatio = 1.0;
  Vec2 MajorAxis{ 1.0, 0.0 }; ///< unit vector (class frame)
  std::vector<int> Parts;     ///< indices into SafeDistanceTables::Parts
};

struct SafeDistancePart
{
  int ClassId = 0;
  int Index = 0;      ///< 0 .. number of parts of its class - 1, along MajorAxis
  Vec2 Centre;        ///< circle centre in the class frame (normalized units)
  double Radius = 0.; ///< circumradius (normalized units)
  /// The part is the class region where From <= Dot(p, Axis) <= To (class frame); an unsplit
  /// class has a single part with infinite bounds.
  Vec2 Axis{ 1.0, 0.0 };
  double From = -1e300, To = 1e300;
  std::vector<Segment2> Edges; ///< boundary of the part, relative to Centre (normalized units)
};

struct SafeDistanceTables
{
  int AngleBins = 0;
  int DistanceSteps = 0;
  int RotationSamples = 0; ///< per bin (1 for a non-conservative table)
  bool Conservative = true;
  double Scale = 1.0; ///< source units per normalized unit (the first class's circumradius)
  std::vector<SafeDistanceClass> Classes;
  std::vector<SafeDistancePart> Parts;
  /// Tables of ordered part pairs (a, b), pair index a * P + b; entry (i, j) of a pair at
  /// pair * ka * ka + j * ka + i (i: bin of alpha_A, j: bin of alpha_B). Normalized units.
  std::vector<double> Values;

  int NumberOfParts() const { return static_cast<int>(this->Parts.size()); }
  int NumberOfPairs() const { return this->NumberOfParts() * this->NumberOfParts(); }
  double BinWidth() const;
  /// Distance step of pair (a, b): (r_a + r_b) / kr.
  double Step(int a, int b) const;
  double Value(int a, int b, int i, int j) const
  {
    const std::size_t ka = static_cast<std::size_t>(this->AngleBins);
    return this->Values[(static_cast<std::size_t>(a) * this->Parts.size() + b) * ka * ka +
      static_cast<std::size_t>(j) * ka + i];
  }
  /// Bin of an angle (radians, any range): round(alpha / w) modulo ka.
  static int AngleBin(double alpha, int angleBins);
  /// The safe distance for parts a, b at relative angles alphaA, alphaB (radians).
  double Lookup(int a, int b, double alphaA, double alphaB) const
  {
    return this->Value(
      a, b, AngleBin(alphaA, this->AngleBins), AngleBin(alphaB, this->AngleBins));
  }
};

/// Step 1 alone: the classes (circles, normalization, aspect ratio) and parts, without table
/// values. Cheap (no rotation): a pipeline's information pass uses it to know the number of
/// parts. Only options.MaximumAspectRatio matters here.
Result<SafeDistanceTables> ComputeSafeDistanceParts(
  const std::vector<SafeDistanceInput>& shapes, const SafeDistanceOptions& options = {});

/// Largest memory the P^2 tables may take: a request beyond it is refused before allocation.
constexpr double MaximumSafeDistanceTableBytes = 2e9;

/// An error when tables of `parts` parts at `angleBins` bins would not be computed (their memory
/// above MaximumSafeDistanceTableBytes).
Status CheckSafeDistanceTableSize(int parts, int angleBins);

/// An error naming the first option out of its range (AngleBins, DistanceSteps, Rows,
/// RotationSamples, MaximumAspectRatio): what the computations below check first. Cheap, for
/// callers that want to refuse bad options before they read any shape.
Status CheckSafeDistanceOptions(const SafeDistanceOptions& options);

/// Step 2: the P^2 tables of the classes and parts made by ComputeSafeDistanceParts (its
/// MaximumAspectRatio is not looked at again). Progress and abort as below.
Result<SafeDistanceTables> ComputeSafeDistanceValues(SafeDistanceTables parts,
  const SafeDistanceOptions& options = {}, const std::function<bool(double)>& progress = nullptr);

/// Both steps: builds the classes, parts and all P^2 tables. OpenMP-parallel (profiles over angle
/// bins, tables over rows) and deterministic. `progress` (optional) is called from the calling
/// thread with values in [0, 1]; returning false aborts (the result IsAborted()).
Result<SafeDistanceTables> ComputeSafeDistanceTables(const std::vector<SafeDistanceInput>& shapes,
  const SafeDistanceOptions& options = {}, const std::function<bool(double)>& progress = nullptr);

} // namespace gs
