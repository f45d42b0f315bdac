// The Shape Distributor's private state and the concepts it is made of (not installed; included
// only by the distributor's own files and its tests' seam). ShapeDistributor.h describes the
// model. The state has owners, each a member group below (at most 20 members in all):
//   SamplingState.h/.cpp   Sampling: class and face distributions, dead faces, the kill log
//   AcceptedShapes.cpp     Accepted: the accepted shapes and their vertex indexes (add, take
//                          back, remove, reorder by key)
// and each concept lives in a file named after it:
//   CandidateSampling.cpp  dart throwing: the weights and masks prepared, a candidate's geometry
//                          (direction, streamline, parts), the faces a shape kills
//   ShapeCharts.cpp        the polar charts of a shape's parts; commit and take back (the
//                          accepted shapes and the sampling state together); the pool of exact
//                          chart engines
//   ConflictRules.cpp      Algorithm 2: two shapes' parts judged in a polar chart by the safe
//                          distance tables; the cheap centre check, the boundary and the drawn
//                          check
//   PriorityRounds.cpp     Algorithm 3: rounds of candidates accepted in priority order, in
//                          parallel waves (Decide: the one order of the checks)
//   CandidatePool.cpp      place-keyed candidates (CandidateOrder::PlaceKeyed), decided in
//                          key order
//   PoolEdits.cpp          a place-keyed run after a density edit: what the edit reaches
//                          decided again, the rest kept
//   GreedyProposals.cpp    Greedy mode: candidates around accepted shapes, densest lattices
//   ShapeMap.cpp           the shape model: class point -> surface point (exponential map,
//                          curve map), outlines, CurveGrid
//   ShapeDecal.cpp         a shape's decal (the inverse map on the faces it covers)
//   ShapeDistributor.cpp   the public class: Run, the queries after it
// Determinism: every random number comes from Random keyed by (Seed, kind, round, index); the
// parallel loops write per-candidate results only, and shared state changes in priority order.
#pragma once

#include "DirectionField.h"
#include "DistributionRandom.h"
#include "GeodesicPolarCoordinates.h"
#include "OverlapCheck.h"
#include "ParallelFor.h"
#include "PhasePoll.h"
#include "SamplingState.h"
#include "ShapeDistributor.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <map>
#include <unordered_map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace gs
{
namespace distribution
{
constexpr double Pi = 3.14159265358979323846;
constexpr double TwoPi = 2.0 * Pi;

struct ChartEntry
{
  int Vertex;
  float X, Y;
};

/// Log-map coordinates of the vertices about one part centre (x axis: the part's axis), sorted
/// by vertex.
struct Chart
{
  std::vector<ChartEntry> Entries;
  /// Sum of |angle defect| of the chart's vertices over the chart's area: the density of
  /// absolute discrete Gaussian curvature around the centre.
  float Roughness = 0.0f;
  const ChartEntry* Find(int v) const
  {
    auto it = std::lower_bound(Entries.begin(), Entries.end(), v,
      [](const ChartEntry& e, int value) { return e.Vertex < value; });
    return it != Entries.end() && it->Vertex == v ? &*it : nullptr;
  }
};

/// Marks on the mesh's vertices that Begin clears at once (a new stamp per use): for loops over
/// a shape's region that visit each vertex once, one per thread.
struct VertexStamps
{
  std::vector<unsigned> Stamp;
  unsigned Current = 0;
  void Begin(std::size_t vertices)
  {
    if (Stamp.size() != vertices || Current == ~0u)
    {
      Stamp.assign(vertices, 0u);
      Current = 0;
    }
    ++Current;
  }
  bool Marked(int v) const { return Stamp[v] == Current; }
  /// Marks v; false when it was marked already.
  bool Mark(int v)
  {
    if (Stamp[v] == Current)
    {
      return false;
    }
    Stamp[v] = Current;
    return true;
  }
};

inline void SortUnique(std::vector<int>& v)
{
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}
/// Whether face f's chart triangle (corners c, in units of `unit` world units) can be its image
/// under the log map: no edge longer than MaxChartStretch times the face's longest edge. A face
/// across the chart's cut locus (its corners reached around a hole, a thin part or a ridge from
/// two sides) spans the chart and holds no point of it: interpolated there, a far point lands
/// near the centre. (ShapeDistributor::Impl::ChartPoint and the short decals.)
constexpr double MaxChartStretch = 3.0;
bool ChartFaceHolds(const TriangleMesh& mesh, int f, const Vec2 (&c)[3], double unit);

} // namespace distribution

struct ShapeDistributor::Impl
{
  using Random = distribution::Random;
  using Chart = distribution::Chart;
  using ChartEntry = distribution::ChartEntry;

  const TriangleMesh& Mesh;
  const SaddleVertexGraph* Graph;

  Impl(const TriangleMesh& mesh, const SaddleVertexGraph* graph)
    : Mesh(mesh)
    , Graph(graph)
  {
  }

  /// A candidate or an accepted shape: its placement and the charts of its parts.
  struct Record
  {
    PlacedShape Shape;
    std::vector<Chart> Charts; // one per part (empty before the chart step)
    // The priority (CandidateOrder::PlaceKeyed; 0 in rounds): smaller is decided first. Every
    // check judges a candidate against the accepted shapes of smaller or equal key only, which
    // in a fresh run are all of them; a run re-deciding part of a previous one sees the
    // accepted shapes of lower priority too, and must not be judged by them.
    std::uint64_t Key = 0;
    bool Valid = false;
    bool Rejected = false;
    // What rejected it (ShapeDistributionStatistics' counts).
    enum class Rejection : unsigned char
    {
      None,
      WithoutShape,
      Tables,
      Faithful,
      Drawn
    };
    Rejection Reason = Rejection::None;
    // Prepared in parallel for the commit (see PrepareCommit).
    bool Prepared = false;
    std::vector<int> Cover, Centres;
    // (class, face); kept, sorted, by a place-keyed run's accepted shapes (KilledBefore)
    std::vector<std::pair<int, int>> Kills;
    // The outline as drawn (Outline, OutlineSpacing), once the tables accept the shape.
    std::vector<OutlinePiece> Drawn;
    bool HasDrawn = false;
    bool FaithfulChecked = false; // (Unfaithful: tested once; its verdict)
    bool FaithfulVerdict = false; // unfaithful
    // A short shape under the drawn check: the exact log map of its centre (PrepareExactMap),
    // through which the drawn check and FaithfulCheck read it.
    std::shared_ptr<const LogMapSnapshot> Exact;
    // Long shapes: the inverse of the drawing map (for the drawn check against long neighbours).
    std::shared_ptr<const CurveGrid> Frame;
    // Place-keyed runs: the decal drawn (ShapeDistributor::Decal) at DecalTolerance, kept.
    mutable std::shared_ptr<const ShapeDecal> Decal;
    mutable double DecalTolerance = 0.0;
  };

  // ---- The run's inputs (Prepare) --------------------------------------------------------
  SafeDistanceTables Tables;
  ShapeDistributionOptions Options;
  bool CircleMode = false;
  std::vector<Vec3> FaceDirection; // unit, in the face plane; zero: none
  std::vector<double> Density;     // per vertex (empty: 1)
  int NumberOfClasses = 0;

  /// Checks the inputs and sets up every concept's state for a run.
  Status Prepare(const SafeDistanceTables& tables, const std::vector<Vec3>& faceDirections,
    const std::vector<double>& vertexDensity, const ShapeDistributionOptions& options);
  /// The consistency of the mesh, graph, tables and options (Prepare's first step).
  Status CheckTablesAndOptions() const;

  double PartRadius(int part) const
  {
    return CircleMode ? Tables.Classes[part].Radius : Tables.Parts[part].Radius;
  }

  // ---- Candidate sampling (CandidateSampling.cpp) ---------------------------------------
  distribution::SamplingState Sampling;
  /// An error when the largest class at the largest density factor has a circumscribed disc
  /// holding more area than the largest connected part of the surface (PrepareFaceWeights).
  Status CheckShapeSizeAgainstSurface() const;
  /// How many shapes a run may place (an upper estimate: ExpectedCount's disc packing, times
  /// 3 for the tables' closer packing).
  double EstimatedShapes() const;
  /// An error when EstimatedShapes' memory exceeds 80% of the available memory (unless
  /// MaximumShapes bounds it).
  Status CheckMemory() const;
  static constexpr double ShortShapeBytes = 40e3;
  static constexpr double LongShapeBytes = 160e3;
  /// What tracing long classes needs (PrepareLongClasses).
  struct LongClasses
  {
    std::vector<double> ClassExtentMin, ClassExtentMax; // outline extent along the major axis
    // A long class's parts behind its centre, nearest first.
    std::vector<std::vector<int>> BehindParts;
    std::unique_ptr<DirectionFieldSolver> Field; // streamlines
    std::vector<double> FieldAngles;
  } Long;

  /// ClassWeights as a distribution.
  Status PrepareClassWeights();
  /// The face directions projected to the faces' planes.
  Status PrepareDirections(const std::vector<Vec3>& faceDirections);
  /// The density, the face weights area / f^2 and the masks (nothing dead).
  Status PrepareFaceWeights(const std::vector<double>& vertexDensity);
  /// KillRadius and KillReach: per (part, class), the smallest safe distance of the part against
  /// any part of the class (2% less, for the charts' approximations); per class, its reach.
  void PrepareDeadFaces();
  /// Long classes: their extent along the major axis, and the field's angles for streamlines.
  void PrepareLongClasses();

  double DensityAt(const SurfacePoint& p) const
  {
    if (Density.empty())
    {
      return 1.0;
    }
    const auto& f = Mesh.Face(p.Face);
    return p.Bary[0] * Density[f[0]] + p.Bary[1] * Density[f[1]] + p.Bary[2] * Density[f[2]];
  }
  /// Fills a round's batch of random candidates (parallel; kind 1 of Random).
  void Generate(std::vector<Record>& batch, int round) const;
  /// Builds a candidate's geometry at `centre` (a face point) for class `cls`: the direction,
  /// the curve of a long class and the parts. False when it does not fit (curve too short).
  /// `prefer` (optional): of the field's N directions in the face, take the one closest to it
  /// (greedy fronts keep neighbours turned alike in cross fields); otherwise the face's own.
  /// `precheck` (optional, scratch for CheapConflict; with Options.EarlyRejection): a long
  /// class's streamline behind the centre is traced in stages, up to each part behind the
  /// centre (BehindParts, nearest first), and the parts placed so far are checked as
  /// CheapConflict checks them; on a conflict the candidate is given up (false) before the rest
  /// of the streamline is traced. The same decision as building the whole shape and checking
  /// it: those parts are computed bit for bit as the whole shape computes them (the staged
  /// streamline has the same pieces, and parts are placed walking the streamline from the
  /// centre, PointOnCurve over its pieces), and a conflict of some parts is a conflict of the
  /// shape.
  /// `key`: the candidate's Record::Key (the precheck's judges).
  bool MakeShape(const SurfacePoint& centre, int cls, Random& rng, PlacedShape& s,
    const Vec3* prefer = nullptr, std::vector<int>* precheck = nullptr, std::uint64_t key = 0) const;
  /// The direction a candidate in face f turns to: the field's (of its N, the closest to
  /// `prefer` when given), or a direction spun by `spin` turns where the field vanishes.
  Vec3 ShapeFieldDirection(int f, const Vec3& normal, double spin, const Vec3* prefer) const;
  /// A long class's curve and parts (MakeShape): s holds the class, centre, scale and normal;
  /// sets its direction, curve and (unless CircleMode) parts; false when it does not fit.
  bool MakeLongShape(const Vec3& dir, PlacedShape& s, std::vector<int>* precheck,
    std::uint64_t key) const;
  /// MakeShape's staged precheck: traces `tracer` (behind the centre) up to each part of
  /// BehindParts in turn and checks the parts placed so far; false on a conflict.
  bool BehindPartsFit(DirectionFieldSolver::StreamlineTracer& tracer, const PlacedShape& s,
    double scale, double phiM, std::vector<int>& precheck, std::uint64_t key) const;
  /// A part's distance from the shape's centre along its curve, at `scale`.
  double PartDistanceAlongCurve(int cls, int part, double scale) const;
  /// Places `part` of class cls on the streamline `line` (behind: the curve runs the other way).
  bool PlacePartOnCurve(const Streamline& line, bool behind, int cls, int part, double scale,
    double phiM, PlacedPart& p) const;
  /// Places part `part` (MakeShape, and its precheck on the curve behind the centre): from the
  /// curve point (face, x) with the curve's unit tangent there, `across` off the curve, its axis
  /// turned by -phiM from the curve's direction; false when it leaves the surface.
  bool PlacePart(int face, const Vec3& x, const Vec3& tangent, int part, double across,
    double phiM, PlacedPart& p) const;
  /// Faces where no candidate can fit any more: every candidate centred in them conflicts with
  /// part k of the new shape, because its distance from that part's centre is below the smallest
  /// safe distance against any part of any class, less the class's reach (its part centres'
  /// offsets from its sample). Sampling skips them: the run is the same dart throwing, without
  /// the candidates that would certainly fail.
  /// The (class, face) pairs the shape kills (see above), whatever is dead already. `mark` is a
  /// per-vertex scratch array of zeros (left as found).
  void CollectKills(const Record& r, std::vector<char>& mark, std::vector<int>& marked,
    std::vector<std::pair<int, int>>& kills) const;
  /// Marks the faces a committed shape kills (recorded in Killed for Uncommit).
  void KillFaces(const Record& r);

  // ---- Shape charts and the accepted shapes (ShapeCharts.cpp) ---------------------------
  /// The accepted shapes and the indexes the conflict checks look them up by.
  struct AcceptedShapes
  {
    std::vector<Record> Records;
    std::vector<PlacedShape> Placed; // Records' shapes
    std::vector<std::vector<int>> CoverIndex;  // vertex -> accepted shapes whose chart holds it
    std::vector<std::vector<int>> CentreIndex; // vertex -> accepted shapes with a part centre in a face of it

    /// No shape, empty indexes over `vertices` vertices.
    void Reset(int vertices);
    /// Appends r, indexed at its chart vertices `cover` and centre corners `centres`; its id.
    int Add(Record&& r, const std::vector<int>& cover, const std::vector<int>& centres);
    /// Takes the last shape out (its index entries at `cover` and `centres`, the ones Add made).
    Record TakeLast(const std::vector<int>& cover, const std::vector<int>& centres);
    /// Takes shape `id` out of the indexes (its slot left empty, ids unchanged) and returns it.
    Record Remove(int id, const std::vector<int>& cover, const std::vector<int>& centres);
    /// Records (and Placed, and the indexes' ids) in key order, without the slots `removed`
    /// marks (optional).
    void SortByKey(const std::vector<char>* removed);
  } Accepted;
  /// What the charts' radii and roughness need (PrepareChartMeasures).
  struct ChartMeasures
  {
    double RMax = 0.0; // largest part radius (class radius in Circumcircle mode), normalized
    double MaxEdge = 0.0;
    double ChartMargin = 0.0; // beyond the largest safe distance: two mean edge lengths
    std::vector<double> Defect; // per vertex: |2 pi - angle sum| (interior vertices)
  } Measures;
  /// Per thread of the parallel loops: a geodesic engine and scratch marks.
  struct ThreadScratch
  {
    std::vector<std::unique_ptr<GeodesicPolarCoordinates>> Engines;
    std::vector<std::vector<char>> Marks; // per vertex, all 0 between uses
    std::vector<int> Marked;              // the calling thread's marked vertices
  } PerThread;

  /// MaxEdge, ChartMargin, Defect and RMax: what the charts' radii and roughness need.
  void PrepareChartMeasures();
  /// A part's chart radius: (r_part + r_max) * ShapeSize * f (with the safety margin) + the
  /// chart margin, enough to hold every centre the part could conflict with.
  double ChartRadius(const PlacedShape& s, const PlacedPart& p) const
  {
    return (PartRadius(p.Part) + Measures.RMax) * Options.ShapeSize * s.Scale *
      (1.0 + Options.SafetyMargin) +
      Measures.ChartMargin;
  }
  /// The charts of the record's parts (log map about each part centre, x axis the part's axis).
  void ComputeCharts(Record& r, GeodesicPolarCoordinates& engine) const;
  /// Chart vertices of a record (all parts), sorted, unique.
  static std::vector<int> ChartVertices(const Record& r);
  /// The corners of the faces holding the record's part centres, sorted, unique.
  std::vector<int> CentreCorners(const Record& r) const;
  /// A surface point in a chart (divided by `unit`): a vertex's entry, or a face point's corners
  /// interpolated; false when a corner is not in the chart or the face does not hold in it
  /// (ChartFaceHolds).
  bool ChartPoint(const Chart& chart, const SurfacePoint& x, double unit, Vec2& p) const;
  /// A short shape's class point of x (the exact log map of its centre when the drawn check
  /// computed it, Record::Exact; otherwise its centre's chart); false for long shapes.
  bool ClassPointOf(const Record& r, const SurfacePoint& x, Vec2& p) const;
  /// The commit's own work that needs no shared state, done in parallel before it.
  void PrepareCommit(Record& r, std::vector<char>& mark, std::vector<int>& marked) const;
  /// Accepts a shape: indexes its chart vertices and centre corners, kills faces.
  void Commit(Record&& r);
  /// Takes back the last committed shape (index entries, killed faces) and returns it.
  Record Uncommit();
  /// Per-thread geodesic engines and scratch marks for `threads` threads.
  void EnsureEngines(int threads);
  // The engine of a ParallelFor thread (0: the calling thread's, also outside parallel loops).
  GeodesicPolarCoordinates& Engine(int thread) { return *PerThread.Engines[thread]; }

  // ---- The conflict test, Algorithm 2 (ConflictRules.cpp) ------------------------------
  // Per class: its silhouette for point queries, and the clearance of its centre (the distance
  // from the class origin, the point a candidate is centred at, to the outline; -1 when the
  // origin is outside the silhouette). See CentreCovered.
  struct ClassSilhouettes
  {
    std::vector<ClassRegion> Regions;
    std::vector<double> Clearance;
    double MaxClearance = 0.0; // the regions' reach for Within

    /// Regions, Clearance and MaxClearance of `classes` (their outlines, in class units).
    void Prepare(const std::vector<SafeDistanceClass>& classes);
  } Silhouettes;

  /// Silhouettes of the tables' classes (ClassSilhouettes::Prepare).
  void PrepareClassRegions() { Silhouettes.Prepare(Tables.Classes); }
  /// The tables' safe distance of parts a and b at angles alphaA, alphaB (normalized); the sum
  /// of the class radii in Circumcircle mode.
  double SafeDistance(int a, int b, double alphaA, double alphaB) const
  {
    if (CircleMode)
    {
      return Tables.Classes[a].Radius + Tables.Classes[b].Radius;
    }
    return Tables.Lookup(a, b, alphaA, alphaB);
  }
  /// Does shape Y conflict with shape X, judged in X's charts?
  bool ConflictInCharts(const Record& X, const Record& Y) const;
  /// Checks against accepted shapes whose charts judge the pair (f_X >= f_C: the older decides
  /// ties). Needs no chart of the candidate.
  bool CheapConflict(const Record& c, std::vector<int>& scratch) const;
  /// KeepInside: a boundary vertex within a part's circle (plus half the longest edge).
  bool TouchesBoundary(const Record& c) const;
  /// Checks against accepted shapes with a smaller density factor, in the candidate's charts
  /// (and KeepInside).
  bool FullConflict(const Record& c, std::vector<int>& scratch) const;
  /// A candidate of class `cls` centred at `centre` (density factor `scale`) certainly overlaps
  /// an accepted shape: its centre, inside its own silhouette with clearance rho (see
  /// Clearance), lies within 0.9 rho of an accepted part's silhouette, read in that part's chart
  /// within the part's circle (a 2% margin for the chart). The full check would reject it too
  /// (the tables keep silhouettes apart); this one needs no curve, so long candidates skip
  /// tracing their streamlines where the surface is taken.
  bool CentreCovered(const SurfacePoint& centre, int cls, double scale, std::uint64_t key,
    std::vector<int>& scratch) const;
  /// The drawn check, after the tables accepted the candidate (its charts computed): its outline
  /// as drawn (kept in the record) against every accepted neighbour's, as VerifyOverlaps judges
  /// them: a conflict when one reaches into the other's silhouette deeper than a quarter of
  /// VerifyOverlaps' tolerance (0.125% of the smaller circumradius), each outline read through
  /// the inverse of the other's drawing map (a short shape's exact log map, Record::Exact; a
  /// long shape's CurveGrid), both ways, as VerifyOverlaps reads them: at a pointed outline the two depths differ (test
  /// OverlapCheck.DrawnCheckReadsShortOutlinesInLongFrames). The tables assume rigid planar
  /// copies; this catches where the drawn shapes are not (a long shape's part bending with its
  /// curve, a chart that is no isometry across the neighbour's circle).
  bool DrawnConflict(Record& c, std::vector<int>& scratch) const;
  /// Whether c's drawn outline does not read back through the inverse of its own map to the
  /// class points it was drawn from (Options.FaithfulCheck): its map is not one-to-one over its
  /// silhouette. Draws the outline (and a long shape's grid) if not done yet; tested once, the
  /// verdict kept (a test in parallel ahead of the decision, read where the decision reads it). A
  /// short shape is read through the exact log map of its centre, as its decal is drawn.
  bool Unfaithful(Record& c) const;
  /// Unfaithful's test itself (the outline drawn).
  bool FaithfulnessFails(Record& c, bool isShort) const;
  /// The outline as drawn, and a long shape's CurveGrid, kept in the record.
  void DrawOutline(Record& c) const;
  /// A short shape's exact log map (Record::Exact), out to a longest edge of the mesh beyond its
  /// circle (as VerifyOverlaps computes it), computed once; false when it cannot be computed.
  bool PrepareExactMap(Record& c) const;

  // ---- Priority rounds, Algorithm 3 (PriorityRounds.cpp) -------------------------------
  /// Where a run stands between rounds.
  struct RunState
  {
    long long FailuresToStop = 10000;
    std::vector<int> Front;   // Greedy: the shapes accepted in the last round
    bool SeedsGrow = true;    // Greedy: random rounds plant one seed each
    long long Seeds = 0, GrownSinceSeed = 0;
    long long Consecutive = 0; // consecutive failures in priority order
    int RandomRounds = 0;
    bool Stop = false;
    double Reported = 0.0; // progress
    // Short candidates checked for faithfulness before their charts: where FaithfulCheck has
    // rejected more candidates than the tables rejected after a chart (a rough surface, shapes
    // a few triangles wide), a chart would mostly be computed for a candidate the check then
    // rejects. The decisions are the same in either order; only what is computed, and the
    // reason a candidate failing both is counted under, differ.
    bool FaithfulFirst = false;
    long long ChartedThenTables = 0; // candidates the tables rejected after their charts
    int AcceptedInRound = 0; // the shapes the last round kept (the last ones in Accepted)
  };
  /// The rounds of a prepared run, until MaximumShapes, MaximalFailures or no live face; false
  /// when aborted by `progress`.
  bool RunRounds(int threads, const std::function<bool(double)>& progress, ShapeDistributionStatistics& stats);

  // ---- Progress and abort inside a round (RunRounds) ---------------------------------------
  // A round may hold thousands of candidates, each costing up to a fraction of a second: the
  // caller's callback is polled from inside the rounds too (PhasePoll: on the calling thread,
  // at most every 0.1 s); every loop of the round stops early once it is aborted. Set for the
  // duration of a run only.
  struct RunProgress
  {
    std::unique_ptr<PhasePoll> Polling;
    double Reported = 0.0; // the fraction last reported
  } Progress;
  /// True once the run is aborted (Polling's Poll at the fraction last reported).
  bool Poll() const { return Progress.Polling && Progress.Polling->Poll(Progress.Reported); }
  /// Decides a round's candidates (their priorities: their order in the batch): (a) to (d)
  /// below, the kept shapes committed; false when aborted.
  bool DecideRound(std::vector<Record>& batch, bool greedy, bool seeding, int threads, RunState& run,
    ShapeDistributionStatistics& stats);
  /// A Greedy round's candidates: the proposals of every front shape, nearest to the first
  /// shape first (kind 4 of Random).
  void DrawGreedyBatch(const std::vector<int>& front, int round, int threads, std::vector<Record>& batch) const;
  /// A random round's candidates (1 to 4096); false when no face is left alive.
  bool DrawRandomBatch(int round, bool seeding, RunState& run, std::vector<Record>& batch);
  /// (a) Rejects the candidates that conflict with accepted shapes in those shapes' charts.
  void CheapChecks(std::vector<Record>& batch, int threads);
  /// (b) Per survivor, the higher-priority survivors it may conflict with (parts closer in
  /// space than the sum of their circumradii).
  std::vector<std::vector<int>> HigherPriorityNeighbours(
    const std::vector<Record>& batch, const std::vector<int>& survivors, int threads) const;
  /// Greedy's random rounds: the first survivor that fits is the seed; the others are rejected.
  void PlantSeed(std::vector<Record>& batch, const std::vector<int>& survivors, std::vector<char>& state,
    std::vector<int>& acceptedAs, long long& charts);
  /// Per-thread scratch and counts of Decide.
  struct DecisionScratch
  {
    std::vector<int> Conflicts, Marked;
    long long Charts = 0, TablesAfterCharts = 0;
    double ChartSeconds = 0.0;
  };
  /// Decides one candidate whose higher-priority neighbours are decided, in the order every
  /// caller uses: the cheap check again (`recheck`: when an accepted shape may have come since
  /// the last one), faithfulness (first for long shapes, or `faithfulFirst`), its charts (unless
  /// it has them), the full check, the drawn check. Accepted: true, prepared for Commit
  /// (thread: the engine and marks used). Rejected: Record::Rejected and Reason set.
  bool Decide(Record& r, int thread, bool recheck, bool faithfulFirst, DecisionScratch& s);
  /// (c) Survivors decided in waves (state: 0 undecided, 1 accepted, 2 rejected; acceptedAs:
  /// the id in Accepted).
  void DecideInWaves(std::vector<Record>& batch, const std::vector<int>& survivors,
    const std::vector<std::vector<int>>& above, std::vector<char>& state, std::vector<int>& acceptedAs,
    int threads, RunState& run, long long& charts, double& chartSeconds);
  /// (d) Where the round ends in priority order (consecutive failures, MaximumShapes, Greedy's
  /// one seed): the number of candidates kept.
  int CutRound(const std::vector<char>& state, int roundStart, bool greedy, bool seeding, RunState& run,
    ShapeDistributionStatistics& stats) const;
  /// Takes back the round's shapes after the cut, recommitting the others in priority order.
  void TakeBack(int roundStart, int cut, const std::vector<char>& state, const std::vector<int>& acceptedAs);

  // ---- Place-keyed candidates (CandidatePool.cpp) ------------------------------------------
  /// A candidate of the pool: level, face and index name it; its key, class and point in the
  /// face follow from them (DrawPoolCandidate).
  struct PoolCandidate
  {
    std::uint64_t Key = 0;
    int Level = 0, Face = 0, Index = 0, Class = 0;
    double A = 0.0, B = 0.0; // barycentric coordinates of corners 1 and 2
  };
  void PreparePool();
  /// The expected number of candidates of face f at level `level`.
  double PoolMean(int level, int f) const;
  /// Candidate `index` of face f at `level`; returns its generator, ready for MakeShape.
  Random DrawPoolCandidate(int level, int f, int index, PoolCandidate& p) const;
  /// Appends face f's candidates at `level` (a function of Seed, the face and its weight).
  void PoolCandidates(int level, int f, std::vector<PoolCandidate>& out) const;
  /// Key order (ties, never seen in practice, by face and index).
  static bool PoolLess(const PoolCandidate& a, const PoolCandidate& b);
  /// The level's candidates on faces where their class may still fit, in key order.
  std::vector<PoolCandidate> LivePoolLevel(int level, int threads) const;
  /// A pool candidate's record (its shape; invalid, with the reason, when none can be laid or,
  /// with `masks`, its face is dead for its class).
  void MakePoolRecord(const PoolCandidate& p, bool masks, Record& r, std::vector<int>& scratch) const;
  /// What a candidate's decision needs of itself alone, in Decide's order: a long shape's
  /// faithfulness (Rejected when it fails), its charts, outline and exact log map (and a short
  /// shape's faithfulness read through it, kept for the drawn check's end). The outline
  /// and exact map serve the drawn check only: not drawn when the full check already finds a
  /// conflict with the shapes accepted so far, all of smaller key in a fresh run, which then
  /// rejects it whatever is accepted next.
  void PrepareAlone(Record& r, int thread, DecisionScratch& s) const;
  /// The survivors of the cheap checks (in key order) prepared in parallel, then decided one by
  /// one; `full` once MaximumShapes are placed. False when aborted.
  bool DecidePoolSurvivors(std::vector<Record>& survivors, int threads, ShapeDistributionStatistics& stats,
    bool& full);
  static void CountRejection(const Record& r, ShapeDistributionStatistics& stats);
  /// A fresh PlaceKeyed run: the levels in order; false when aborted.
  bool RunPool(int threads, const std::function<bool(double)>& progress, ShapeDistributionStatistics& stats);
  /// Accepted (and Placed, and the indexes' ids) in key order: the order of a greedy run,
  /// whatever waves and rounds decided it in; without the slots `removed` marks (an edit's,
  /// whose ids no index holds any more).
  void SortAcceptedByKey(const std::vector<char>* removed = nullptr);

  /// What the last PlaceKeyed run was given, but the density (a hash), and its density.
  struct LastPoolRun
  {
    bool Valid = false;
    std::uint64_t Fingerprint = 0;
    std::vector<double> Density;
  };
  /// A hash of everything a PlaceKeyed run depends on but the density and the thread count.
  static std::uint64_t PoolFingerprint(const SafeDistanceTables& tables,
    const std::vector<Vec3>& faceDirections, const ShapeDistributionOptions& options);
  /// Whether this run may re-decide the last one's edits only.
  bool CanRunIncrementally(std::uint64_t fingerprint, const std::vector<double>& vertexDensity) const;
  /// The distance in space between their samples beyond which shapes of classes clsA and clsB
  /// at densities scaleA and scaleB never conflict (by any check; see PoolEdits.cpp): an edit
  /// re-decides the candidates within it of a shape whose fate changed.
  double PoolReach(int clsA, double scaleA, int clsB, double scaleB) const;
  /// An incremental PlaceKeyed run after a density edit (`oldDensity`: the last run's): the
  /// candidates of the faces whose density changed, and every lower-priority candidate within
  /// reach of a shape whose fate changed, re-decided in key order (the others keep theirs),
  /// until nothing changes: the result of a fresh run. False when aborted.
  bool RunPoolIncremental(const std::vector<double>& oldDensity, const std::function<bool(double)>& progress,
    ShapeDistributionStatistics& stats);
  /// Whether an accepted shape of smaller key than `key` kills face f for class `cls` (see
  /// CollectKills): a candidate there is certainly rejected, as a fresh run's masks skip it.
  bool KilledBefore(int cls, int f, std::uint64_t key) const;
  /// The share of the pool's weight in the faces whose density changed from `oldDensity` (the
  /// larger of their old and new weights over the whole new weight).
  double EditShare(const std::vector<double>& oldDensity) const;
  struct PoolEdit; // (PoolEdits.cpp)
  /// The decals of the last run's shapes by key, with the shapes they were drawn for.
  struct StashedDecal
  {
    PlacedShape Shape;
    std::shared_ptr<const ShapeDecal> Decal;
    double Tolerance = 0.0;
  };
  /// The place-keyed runs' state.
  struct PoolState
  {
    double Footprint = 1.0; // class-weighted mean circumscribed disc area at density 1
    // Per class, normalized: the farthest part centre from the sample (sqrt 2 class radii for
    // a long class), and the largest part radius plus RMax (its charts' reach): see PoolReach.
    std::vector<double> ClassOffset, ClassChart;
    bool Active = false;       // this run decides a pool (kills and decals kept)
    bool KillOnCommit = true;  // Commit kills faces (not in an incremental run: no masks)
    LastPoolRun Last;
    double KillsMaxFaceDensity = 0.0; // the MaxFaceDensity the kept Kills were collected at
    std::unordered_map<std::uint64_t, StashedDecal> DecalStash;
  } Pool;
  void StashDecals();
  /// The stashed decals to the accepted shapes placed the same, bit for bit; the stash cleared.
  void TakeStashedDecals();
  /// Takes an accepted shape out of the indexes (its slot left empty) and returns it.
  Record RemoveAccepted(int id);

  // ---- Greedy proposals and lattices (GreedyProposals.cpp) ------------------------------
  // Greedy: per single-part class, the densest lattice of copies turned alike that the tables
  // admit (six neighbour vectors in the shape's frame, normalized units); empty: none.
  struct ClassLattices
  {
    std::vector<std::vector<Vec2>> ByClass;
    // Lattices found in earlier runs, by a hash of what they depend on (the part's radius and
    // its own table): a re-run with the same tables (a new seed, say) skips the search (35-160
    // ms for 4 classes at 64-128 angle bins).
    std::map<std::uint64_t, std::vector<Vec2>> Cache;
  } Lattices;

  void ComputeLattices();
  /// The densest lattice for part p (see ComputeLattices); empty when the search finds none.
  std::vector<Vec2> PartLattice(int p) const;
  /// Greedy: candidate centres around accepted shape `parentId`, touching it and one of its
  /// neighbours (or, alone, in GreedyDirections directions), the new shape assumed turned like
  /// the parent. Key: distance from the first shape (fronts fill outwards).
  struct Proposal
  {
    SurfacePoint Centre;
    int Class = 0;
    double Key = 0.0;
    Vec3 Prefer; // the parent's field direction
  };
  std::vector<Proposal> Propose(int parentId, int round, int slot) const;
  /// An accepted neighbour as the parent's chart sees it: its centre and axis angle, its part
  /// and the unit of the pair.
  struct Neighbour
  {
    Vec2 Centre;
    double Axis;
    int Part;
    double Unit;
  };
  /// The single-part accepted neighbours near parent A (for a new part pc, part pa of A).
  std::vector<Neighbour> NeighboursInChart(int parentId, int pa, int pc) const;
  /// The contact curve of a parent for a new shape turned like it (GreedyProposals.cpp).
  struct Contact;
  /// Lattice neighbours of the parent that no placed neighbour rules out (betas and lengths).
  void LatticeDirections(const Contact& contact, int cls, std::vector<double>& betas,
    std::vector<double>& lengths) const;
  /// Directions on the contact curve where the new shape touches a neighbour too.
  void ContactDirections(const Contact& contact, std::vector<double>& betas) const;
  /// The proposals' centres: geodesics shot from A (reference angle a0) at angles `betas`,
  /// `lengths` long (or the contact curve's reach) and a hair more, kept where a shape of class
  /// cls may land.
  void ShootProposals(const Record& A, int cls, const Contact& contact, const std::vector<double>& betas,
    const std::vector<double>& lengths, double a0, std::vector<Proposal>& out) const;

  // ---- The shape model: map, outline, CurveGrid (ShapeMap.cpp) --------------------------
  /// Class point p (normalized) of shape s -> surface point (see ShapeDistributor::Map).
  MappedPoint MapShape(const PlacedShape& s, const Vec2& p) const;
  /// Shape s's outline as drawn (see ShapeDistributor::Outline).
  std::vector<OutlinePiece> OutlineOf(const PlacedShape& s, double spacing) const;
  /// Between outline points: half a mean edge (what the filter draws).
  double OutlineSpacing() const { return 0.5 * Mesh.MeanEdgeLength(); }
  /// Point at arc length u along curve pieces (clamped), with the unit tangent there.
  static bool PointOnCurve(const TriangleMesh& m, const std::vector<CurvePiece>& curve, double u,
    int& face, Vec3& x, Vec3& tangent);
  /// From curve point (face, x) with tangent t: `across` to the left (negative: right) along the
  /// perpendicular geodesic. Returns the end and the transported tangent.
  bool Across(int face, const Vec3& x, const Vec3& t, double across, SurfacePoint& end,
    Vec3& endTangent, bool* boundary = nullptr) const;
  /// The map of a long shape (the one its outline and its parts use): class point p -> the
  /// point at arc length CurveCentre + <p, m> scale along its curve, then <p, perp> scale across
  /// it along the perpendicular geodesic (m: the class's major axis), sampled on a grid of
  /// (along, across) nodes finer than an edge (one geodesic shot per column and side), covering
  /// the silhouette's extent and two mean edges more. CurveGrid::Locate inverts it.
  CurveGrid BuildCurveGrid(const PlacedShape& s, const SafeDistanceClass& c) const;
  /// The foot of grid column u (arc length, beyond the ends along the geodesic continuing the
  /// curve) and the curve's tangent there; false when the column has none.
  bool CurveGridFoot(const PlacedShape& s, double u, double length, SurfacePoint& foot, Vec3& tangent) const;
  /// The class points (normalized) of the vertices near a long shape: the vertices of the grid
  /// nodes' faces and their neighbours, each located from a node of that face. Appends
  /// (vertex, class point) pairs, and to `far` (optional) the vertices farther than half a grid
  /// step from the grid (their class points are the affine extension of the nearest grid
  /// triangle).
  void CurveShapeVertices(const CurveGrid& grid, std::vector<std::pair<int, Vec2>>& local,
    std::vector<int>* far = nullptr) const;
  /// A long shape's CurveGrid: the one the drawn check built (indexed), or a new one.
  std::shared_ptr<const CurveGrid> FrameOf(int shape) const;

  // ---- Decals (ShapeDecal.cpp) ----------------------------------------------------------
  /// See ShapeDistributor::Decal.
  ShapeDecal DecalOf(int shape, double tolerance) const;
  // ---- The exact engines' pool (ShapeCharts.cpp) -------------------------------------------
  // Exact geodesic polar coordinates engines for short shapes' decals and the drawn check's
  // exact log maps (PrepareExactMap): both may run on any thread, so an engine is leased from
  // the pool (Take; a new one when it is empty) and goes back to it when the lease ends.
  struct ExactEnginePool
  {
    std::mutex Mutex;
    std::vector<std::unique_ptr<GeodesicPolarCoordinates>> Free;
  };
  mutable ExactEnginePool ExactEngines;
  class ExactEngineLease
  {
  public:
    explicit ExactEngineLease(const Impl& owner)
      : Owner(owner)
    {
    }
    ExactEngineLease(const ExactEngineLease&) = delete;
    ExactEngineLease& operator=(const ExactEngineLease&) = delete;
    ~ExactEngineLease();
    GeodesicPolarCoordinates& Take();

  private:
    const Impl& Owner;
    std::unique_ptr<GeodesicPolarCoordinates> Engine;
  };
};

} // namespace gs
