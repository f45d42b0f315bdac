// Conflict-free, anisotropic, multi-class distribution of 2D shapes on a triangle mesh (Wang et
// al. 2016, Section 4 and Algorithm 3).
//
// SHAPES. Classes and their parts come from minimum safe distance tables (SafeDistanceTable.h,
// normalized units: class 0 has circumradius 1). A shape of class k placed at a surface point
// with density factor f has circumradius ShapeSize * f * Classes[k].Radius. A short class (one
// part) is centred on its sample and its +x axis is turned to the direction field. A long class
// (split into parts) lies along a streamline of the field traced through the sample: its major
// axis follows the curve, and every class-frame point (a along the major axis, b across it) is
// drawn at arc length a from the sample along the curve, then b across it along the geodesic
// leaving the curve perpendicularly (the curve's polar coordinates): long shapes bend with the
// field. Each part sits at its own centre, with its own axis.
//
// CONFLICTS. Two parts conflict when the geodesic distance d of their centres is below the safe
// distance of the table for the angles between each part's axis and the geodesic joining the
// centres, times the larger of the two density factors (exact for equal factors; the
// Circumcircle mode uses the sum of the class circumradii instead of the tables). Distances and
// angles come from geodesic polar coordinates (the log map) about every part centre, computed
// once per candidate that survives the cheap checks: exact in the centre's K-disk and
// near-exact beyond (saddle vertex graph), or exact everywhere without a graph. A pair is
// evaluated in the chart of the shape with the larger density factor (ties: the older shape),
// whose radius, (r_part + r_max) * ShapeSize * f + the longest edge, holds every centre it
// could conflict with; the other centre's position is interpolated in its face from the chart
// coordinates of the face's corners (exact on developable surfaces), and the arrival direction
// there is the chart's radial direction pulled back into that face. Where the chart is
// distorted (Gaussian curvature at the scale of the shapes, see DistortionLimit) the pair is
// judged by circumcircles instead: the tables assume rigid planar copies.
//
// ALGORITHM. Rounds of candidates (dart throwing: faces drawn with probability area / f^2, a
// uniform point in the face, a class by ClassWeights) with priorities = their order in the
// round. A candidate is accepted iff it conflicts with no accepted shape and no accepted
// higher-priority candidate of its round: the result equals sequential dart throwing in
// priority order, whatever the number of threads (candidates and their charts are computed in
// parallel, the final acceptance pass walks the conflict lists in order). Candidates come from
// a counter-based random generator keyed by (Seed, round, index).
// Greedy mode grows fronts: every newly accepted shape proposes GreedyDirections candidates
// around itself at the table's safe distance for each direction (gap filling, tight packing);
// when no front is left, random candidates seed new fronts.
// Termination: MaximumShapes reached, or MaximalFailures consecutive candidates (in priority
// order) rejected: a shape then fits in only about 1 / MaximalFailures of random probes
// (the tests' and benchmarks' ProbeFitFraction measures it).
//
// ONE SHAPE MODEL. A placed shape is its map class point -> surface point (Map): a short
// shape's exponential map about its centre, a long shape's curve map above. Everything drawn or
// checked comes from that map: the outline (Outline: the class outline pushed forward), the
// decal (Decal: the map's inverse, the centre's polar chart or for a long shape the map sampled
// on a CurveGrid and inverted there, split where it is not affine over a face), the drawn check
// and VerifyOverlaps (each outline read through the neighbour's inverse). The tables judge
// rigid planar copies of the parts; the drawn check makes them hold where the map bends.
#pragma once

#include "SafeDistanceTable.h"
#include "ShapeDecal.h"
#include "ShapeMap.h"
#include "ShapeOutline.h"
#include "Status.h"
#include "SurfaceCurve.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"
#include "Vector.h"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace gs
{

class SaddleVertexGraph;

enum class DistributionMode
{
  Random = 0,
  Greedy = 1,
  CircumcirclePoissonDisk = 2
};

/// How the Random and CircumcirclePoissonDisk modes draw their candidates.
enum class CandidateOrder
{
  /// Rounds of candidates drawn from the faces still alive, priorities in draw order; the run
  /// ends after MaximalFailures consecutive failures.
  Rounds = 0,
  /// Every candidate, and its priority, is a function of (Seed, face, index): a Poisson process
  /// of intensity 1 / f^2 per area in PoolLevels levels of doubling intensity (a level's
  /// candidates below the previous level's in priority), decided greedily in priority order.
  /// The result depends on each place's own density only, so a run after an edit of the
  /// density (the same mesh, graph, tables, directions and other options) re-decides only the
  /// candidates the edit reaches through the conflict chain, and equals a fresh run bit for bit.
  PlaceKeyed = 1
};

/// The number of OpenMP threads that a NumberOfThreads of `requested` means: `requested` when
/// > 0, otherwise OpenMP's default (1 without OpenMP). Results do not depend on it. (The filter
/// caps what users ask at MaximumThreadCount(): more threads than processors only cost memory,
/// each holding its own chart engine; tests may ask more to exercise the thread split.)
int ThreadCount(int requested);
/// The processors OpenMP may use (1 without OpenMP).
int MaximumThreadCount();

struct ShapeDistributionOptions
{
  double ShapeSize = 1.0;           ///< circumradius of class 0 at density 1 (world units)
  std::vector<double> ClassWeights; ///< relative frequencies (empty: all equal)
  DistributionMode Mode = DistributionMode::Random;
  std::uint64_t Seed = 0;
  int MaximumShapes = 0;    ///< 0: until maximal
  int NumberOfThreads = 0;  ///< 0: all
  int Symmetry = 1;         ///< N of the direction field (1, 2, 4): streamlines of long shapes
  int MaximalFailures = 0;  ///< consecutive failures that end the run; 0: 10000
  int GreedyDirections = 16;
  double SafetyMargin = 0.0; ///< relative enlargement of every safe distance
  /// Curved regions: where the polar chart of one shape stretches the other's centre triangle
  /// by more than this (relative edge length change, about |K| d^2 / 6 for Gaussian curvature K
  /// at distance d), the rigid planar placement the tables assume no longer holds, and the pair
  /// is judged by its circumcircles (d >= r_A + r_B: rigorous on any surface). 0: always.
  double DistortionLimit = 0.01;
  /// Holonomy margin: a shape drawn by its own exponential map turns, in its neighbour's chart,
  /// by up to the absolute discrete curvature (angle defects) it encloses with the neighbour;
  /// the safe distance grows by that angle times the shape's radius (estimated from the density
  /// of |angle defect| around the neighbour's centre), times this factor. 1: conflict-free on
  /// noisy meshes too (at the cost of density there); 0: the tables alone.
  double HolonomyMargin = 1.0;
  /// Keep every shape's circle on the surface: a candidate is rejected when a boundary vertex
  /// lies within its (part) circumradius plus half the longest edge. false: shapes near the
  /// boundary may hang over it (their outlines stop there).
  bool KeepInside = false;
  /// After the tables accept a shape, its outline as drawn is checked against its accepted
  /// neighbours' (a point of one inside the other by more than 0.125% of the smaller
  /// circumradius, read through the inverse of the other's drawing map: a short shape's exact
  /// log map, computed once per candidate as VerifyOverlaps computes it, a long shape's
  /// CurveGrid): the tables assume rigid planar copies, which a long shape bending with its
  /// curve, or a chart that is no isometry across a neighbour, are not. false: the tables alone.
  bool DrawnCheck = true;
  /// With DrawnCheck: a shape is placed only where its map is one-to-one over its silhouette, so
  /// that its decal draws the outline it is checked with: every point of its drawn outline, read
  /// back through the inverse of its map (a short shape's exact log map, a long shape's
  /// CurveGrid), must give the class point it was drawn from, within FaithfulTolerance of the
  /// class circumradius (0 < tolerance <= 1). It is not where a long shape's curve turns more
  /// tightly than its width (the perpendicular geodesics cross: the map folds), or a short
  /// shape's straightest geodesics pass saddle vertices or reach around a thin part (its log
  /// map, the shortest paths, is no longer their inverse). Tested after the tables accept the
  /// shape (a long shape before its charts, a short one after its neighbours' drawn checks).
  /// false: such shapes are placed, their decals drawing what the inverse map gives
  /// (refined_elephant subdivided once, ShapeSize 1% of the diagonal: 5% of the long shapes).
  bool FaithfulCheck = true;
  double FaithfulTolerance = 0.05;
  /// Long candidates: the streamline behind the centre is traced in stages, up to each part
  /// behind the centre (nearest first), and the candidate is given up as soon as its parts
  /// traced so far conflict (as the cheap checks would find), before the rest of the streamline
  /// behind and the streamline ahead are traced. The same placements either way, bit for bit;
  /// false only to compare the two (tests, DistributionBenchmark).
  bool EarlyRejection = true;
  /// See CandidateOrder (Greedy mode always uses rounds).
  CandidateOrder Order = CandidateOrder::Rounds;
  /// PlaceKeyed: the levels of the candidate pool; level l holds 2^l candidates per class
  /// circumscribed disc (at the local density), its candidates drawn only on faces where a
  /// shape may still fit when the level starts.
  int PoolLevels = 8;
  /// PlaceKeyed: a run after a change of the density only re-decides what the change reaches
  /// (the previous run's state); false: a fresh run (the same result; for comparisons). Either
  /// way the shapes a run shares with the previous one keep their decals.
  bool ReuseLastRun = true;
  /// PlaceKeyed: an edit whose changed faces hold more than this share of the pool's candidates
  /// (their face weights, before or after, over all) runs fresh, in parallel: sooner than
  /// re-deciding most of the surface one candidate at a time, the same shapes.
  double MaximumEditShare = 0.1;
};

/// One part of a placed shape (a short shape has one).
struct PlacedPart
{
  int Part = 0;        ///< index into SafeDistanceTables::Parts (the class circle in Circumcircle mode)
  SurfacePoint Centre; ///< a face point
  Vec3 Position;
  Vec3 Axis;           ///< unit tangent in Centre's face: the part's (class) +x axis
};

struct PlacedShape
{
  int ClassId = 0;
  double Scale = 1.0;  ///< density factor f at the centre
  SurfacePoint Centre; ///< the sample (face point)
  Vec3 Position;
  Vec3 Direction; ///< unit tangent: the class +x axis at the centre
  Vec3 Normal;    ///< face normal at the centre
  std::vector<PlacedPart> Parts;
  /// Long shapes: the streamline carrying the major axis (pieces in order) and the arc length
  /// of the centre along it. Empty for short shapes.
  std::vector<CurvePiece> Curve;
  double CurveCentre = 0.0;
};

struct ShapeDistributionStatistics
{
  long long Candidates = 0;       ///< candidates drawn
  long long Charts = 0;           ///< polar charts computed (candidates past the cheap checks)
  int Rounds = 0;
  long long ConsecutiveFailures = 0; ///< at termination
  bool Maximal = false;          ///< ended by the failure count (not MaximumShapes)
  double Seconds = 0.0;
  /// Wall-clock seconds by phase: drawing candidates (positions, streamlines, parts), checks
  /// against placed shapes (with the charts of the survivors), checks within rounds.
  double GenerateSeconds = 0.0, CheckSeconds = 0.0, RoundSeconds = 0.0;
  double ChartCpuSeconds = 0.0; ///< summed over threads: computing polar charts
  double PrepareSeconds = 0.0;  ///< checks, sampling weights, per-thread geodesic engines
  /// Candidates by what rejected them (with the shapes placed, and those taken back past the
  /// end of the last round, they make up Candidates): no shape could be laid at the centre
  /// drawn (a long shape's streamline or a part leaving the surface, KeepInside); the safe
  /// distance tables (against placed shapes, masked faces or a higher-priority candidate);
  /// FaithfulCheck (the shape's map not one-to-one over its silhouette); the drawn check (the
  /// outlines as drawn overlap). The same for any thread count.
  long long RejectedWithoutShape = 0, RejectedByTables = 0, RejectedByFaithfulCheck = 0,
            RejectedByDrawnCheck = 0;
  /// PlaceKeyed: candidates whose fate was decided in this run (all, for a fresh run; those an
  /// edit reached, for an incremental one), and whether the run reused the previous run.
  long long Redecided = 0;
  bool Incremental = false;
  double EditShare = 0.0; ///< the share of the pool's candidates in the changed faces (see MaximumEditShare)
};

/// What a Run placed.
struct ShapeDistribution
{
  std::vector<PlacedShape> Shapes;
  ShapeDistributionStatistics Statistics;
};

class ShapeDistributor
{
public:
  /// The mesh (and the graph, optional: without it the charts use the exact solver) must outlive
  /// the distributor. A graph built for another mesh (another number of vertices) makes Run
  /// fail.
  explicit ShapeDistributor(const TriangleMesh& mesh, const SaddleVertexGraph* graph = nullptr);
  ~ShapeDistributor();

  /// The order of magnitude of the number of shapes a run places (dart throwing covers about
  /// half the surface with the shapes' circles): the sum over the faces carrying shapes of
  /// area / (pi (ShapeSize f r)^2) / 2, r the classes' mean circumradius, f the smallest
  /// density factor of the face's corners. Cheap; for warnings before long runs.
  /// An error naming the first option of `options` out of its range, with its value
  /// (MaximumShapes, MaximalFailures, NumberOfThreads, GreedyDirections, SafetyMargin,
  /// DistortionLimit, HolonomyMargin, FaithfulTolerance); Run checks them too.
  static Status CheckOptionRanges(const ShapeDistributionOptions& options);
  static double ExpectedCount(const TriangleMesh& mesh, const SafeDistanceTables& tables,
    const std::vector<double>& vertexDensity, double shapeSize);

  /// `faceDirections`: one tangent vector per face (zero or non-finite: no direction there, the
  /// shape gets a random orientation). `vertexDensity`: empty (f = 1) or one factor per vertex;
  /// faces touching a vertex whose factor is not a positive finite number get no shape.
  /// `progress` (optional) receives values in [0, 1]; returning false aborts (the result is then
  /// IsAborted()). Fails, saying why, on a graph of another mesh and on inconsistent tables,
  /// options, directions or densities: every option is checked here, callers need not.
  Result<ShapeDistribution> Run(const SafeDistanceTables& tables,
    const std::vector<Vec3>& faceDirections, const std::vector<double>& vertexDensity,
    const ShapeDistributionOptions& options, const std::function<bool(double)>& progress = nullptr);

  /// After Run: the surface point of class-frame point p (normalized units) of placed shape s,
  /// through the polar coordinates of its centre (short shapes) or of its curve (long shapes).
  SurfacePoint MapToSurface(int shape, const Vec2& p) const;
  /// The same map, telling whether the point was reached or the map stopped at the mesh
  /// boundary (MappedPoint::End is then where it stopped).
  MappedPoint Map(int shape, const Vec2& p) const;
  /// After Run: shape s's outline as drawn on the surface (ShapeOutline.h): its class outline
  /// sampled at most `spacing` apart (world units, > 0), cut where it leaves the surface (short
  /// shapes: closed along the mesh boundary; long shapes: open pieces). Thread-safe.
  std::vector<OutlinePiece> Outline(int shape, double spacing) const;
  /// After Run: the faces covered by shape s with texture coordinates: the faces whose texture
  /// triangle meets the class square (so that a shape smaller than a face is drawn too), split
  /// where the shape's map departs from the affine texture map by more than `tolerance` times
  /// the circumradius (long shapes, whose map along the curve is read on its grid; a short
  /// shape's map, its geodesic polar chart, is affine on each face wherever the surface unfolds
  /// around its centre; 0: no splitting); pieces where the map folds or jumps are dropped. May
  /// be called from the threads of an OpenMP loop with at most the run's NumberOfThreads
  /// threads (long shapes use the calling thread's geodesic engine).
  ShapeDecal Decal(int shape, double tolerance = DefaultDecalTolerance) const;
  static constexpr double DefaultDecalTolerance = 0.01;

  const std::vector<PlacedShape>& Shapes() const;
  /// The tables and options of the last Run.
  const SafeDistanceTables& Tables() const;
  const TriangleMesh& Mesh() const;
  const ShapeDistributionOptions& Options() const;
  /// After Run: the class-frame point (normalized units) of surface point x as seen by short
  /// shape s, as the drawn check read it: x's coordinates in the log map of s's centre (the
  /// inverse of MapToSurface), the exact one the drawn check kept (with DrawnCheck), otherwise
  /// the placement's polar chart, interpolated in x's face. False for long shapes and points
  /// beyond the map (farther from the centre than the shape's circle).
  bool ClassPoint(int shape, const SurfacePoint& x, Vec2& p) const;
  /// The spacing between outline points the drawn check uses (half a mean edge): Outline at
  /// this spacing returns the outline the check drew.
  double OutlineSpacing() const;
  /// A long shape's drawing map and its inverse near it (Index()ed; the one the drawn check
  /// built, or a new one); null for a short shape.
  std::shared_ptr<const CurveGrid> Frame(int shape) const;

private:
  struct Impl;
  std::unique_ptr<Impl> Internal;
  // The test seam (Testing/Support/DistributorProbes.cpp): measurements of a run's internals
  // that tests and benchmarks make, not part of the API.
  friend struct ShapeDistributorInspector;
};

} // namespace gs
