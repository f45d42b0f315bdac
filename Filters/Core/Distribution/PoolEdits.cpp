// Edits of a place-keyed run (CandidateOrder::PlaceKeyed): after a change of the density only,
// re-decide what the change reaches and keep the rest, so that the result is the fresh run's.
//
// A fresh run is greedy in key order: a candidate is accepted iff no accepted candidate of
// smaller key conflicts with it. Its fate depends on its own shape and on the fates of the
// smaller-key candidates within reach only. An edit changes the candidates of the faces whose
// density changed (their number, scale and shapes); every other candidate is the same. So the
// candidates to re-decide are those of the changed faces and, transitively, the larger-key
// candidates within reach of a candidate whose fate changed; decided in key order (a heap),
// each sees final fates for every smaller key. Random-order greedy has short dependence chains
// (Blelloch, Fineman, Shun 2012), so the work is about the edited region.
#include "ShapeDistributorImpl.h"

#include "Hash.h"
#include "ParallelFor.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <queue>
#include <unordered_map>
#include <unordered_set>

namespace gs
{
using namespace distribution;

std::uint64_t ShapeDistributor::Impl::PoolFingerprint(const SafeDistanceTables& tables,
  const std::vector<Vec3>& faceDirections, const ShapeDistributionOptions& o)
{
  Hasher h;
  h.AddValue(tables.AngleBins);
  h.AddValue(tables.DistanceSteps);
  h.AddValue(tables.Conservative);
  h.AddValue(tables.Scale);
  h.AddVector(tables.Values);
  for (const SafeDistanceClass& c : tables.Classes)
  {
    h.AddValue(c.Radius);
    h.AddValue(c.MajorAxis);
    h.AddVector(c.Parts);
    h.AddValue(c.SourceCircle.Radius);
    h.AddValue(c.SourceCircle.Centre);
  }
  for (const SafeDistancePart& p : tables.Parts)
  {
    h.AddValue(p.ClassId);
    h.AddValue(p.Centre);
    h.AddValue(p.Radius);
    h.AddValue(p.Axis);
    h.AddValue(p.From);
    h.AddValue(p.To);
    h.AddVector(p.Edges);
  }
  h.AddVector(faceDirections);
  h.AddValue(o.ShapeSize);
  h.AddVector(o.ClassWeights);
  h.AddValue(o.Mode);
  h.AddValue(o.Seed);
  h.AddValue(o.MaximumShapes);
  h.AddValue(o.Symmetry);
  h.AddValue(o.GreedyDirections);
  h.AddValue(o.SafetyMargin);
  h.AddValue(o.DistortionLimit);
  h.AddValue(o.HolonomyMargin);
  h.AddValue(o.KeepInside);
  h.AddValue(o.DrawnCheck);
  h.AddValue(o.FaithfulCheck);
  h.AddValue(o.FaithfulTolerance);
  h.AddValue(o.EarlyRejection);
  h.AddValue(o.Order);
  h.AddValue(o.PoolLevels);
  return h.H;
}

bool ShapeDistributor::Impl::CanRunIncrementally(
  std::uint64_t fingerprint, const std::vector<double>& vertexDensity) const
{
  // (The caller checks MaximumShapes: it ends a run at a count, which no edit's reach bounds.)
  return Pool.Last.Valid && Pool.Last.Fingerprint == fingerprint &&
    Pool.Last.Density.size() == vertexDensity.size() && !vertexDensity.empty();
}

double ShapeDistributor::Impl::PoolReach(int clsA, double scaleA, int clsB, double scaleB) const
{
  // Two shapes conflict (a) by the tables only where a part centre of one lies in a face with a
  // corner in a chart of the other (how CheapConflict and FullConflict find them), the chart of
  // radius at most ChartRadius (ConflictInCharts cuts the tables at the sum of the part radii,
  // before the holonomy turn), so the part centres are within ChartRadius and a longest edge in
  // space; (b) by their drawn outlines only when their centres are closer than the sum of their
  // circumradii (DrawnConflict). A part centre lies within sqrt 2 class radii of its sample (a
  // long shape is drawn along paths |along| + |across|). Positions in space: the geodesic
  // distance never undercuts them.
  const double size = Options.ShapeSize * (1.0 + Options.SafetyMargin);
  const double offsetA = Pool.ClassOffset[clsA] * scaleA, offsetB = Pool.ClassOffset[clsB] * scaleB;
  const double chartA = Pool.ClassChart[clsA] * scaleA, chartB = Pool.ClassChart[clsB] * scaleB;
  const double tables = (offsetA + offsetB + std::max(chartA, chartB)) * size + Measures.ChartMargin;
  const double drawn = (Tables.Classes[clsA].Radius * scaleA + Tables.Classes[clsB].Radius * scaleB) * size;
  return std::max(tables, drawn) + Measures.MaxEdge;
}

double ShapeDistributor::Impl::EditShare(const std::vector<double>& oldDensity) const
{
  double changed = 0.0, total = 0.0;
  for (int f = 0; f < Mesh.NumberOfFaces(); ++f)
  {
    total += Sampling.FaceWeight[f];
    double fm = 0.0;
    bool same = true, ok = true;
    for (int v : Mesh.Face(f))
    {
      same = same && std::memcmp(&oldDensity[v], &Density[v], sizeof(double)) == 0;
      ok = ok && oldDensity[v] > 0.0 && std::isfinite(oldDensity[v]);
      fm += oldDensity[v] / 3.0;
    }
    if (!same)
    {
      changed += std::max(Sampling.FaceWeight[f], ok ? Mesh.FaceArea(f) / (fm * fm) : 0.0);
    }
  }
  return total > 0.0 ? changed / total : 1.0;
}

void ShapeDistributor::Impl::StashDecals()
{
  Pool.DecalStash.clear();
  for (const Record& r : Accepted.Records)
  {
    if (r.Decal)
    {
      Pool.DecalStash[r.Key] = { r.Shape, r.Decal, r.DecalTolerance };
    }
  }
}

namespace
{
bool SamePlacement(const PlacedShape& a, const PlacedShape& b)
{
  auto same = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; };
  if (a.ClassId != b.ClassId || !same(a.Scale, b.Scale) || !same(a.Position, b.Position) ||
    !same(a.Direction, b.Direction) || a.Parts.size() != b.Parts.size() ||
    a.Curve.size() != b.Curve.size() || !same(a.CurveCentre, b.CurveCentre))
  {
    return false;
  }
  for (std::size_t k = 0; k < a.Parts.size(); ++k)
  {
    if (!same(a.Parts[k].Position, b.Parts[k].Position) || !same(a.Parts[k].Axis, b.Parts[k].Axis))
    {
      return false;
    }
  }
  for (std::size_t k = 0; k < a.Curve.size(); ++k)
  {
    if (a.Curve[k].Face != b.Curve[k].Face || !same(a.Curve[k].A, b.Curve[k].A) ||
      !same(a.Curve[k].B, b.Curve[k].B))
    {
      return false;
    }
  }
  return true;
}
} // namespace

void ShapeDistributor::Impl::TakeStashedDecals()
{
  for (Record& r : Accepted.Records)
  {
    auto it = Pool.DecalStash.find(r.Key);
    if (!r.Decal && it != Pool.DecalStash.end() && SamePlacement(it->second.Shape, r.Shape))
    {
      r.Decal = it->second.Decal;
      r.DecalTolerance = it->second.Tolerance;
    }
  }
  Pool.DecalStash.clear();
}

bool ShapeDistributor::Impl::KilledBefore(int cls, int f, std::uint64_t key) const
{
  // (A killed face's corners are in the killer's chart, so in CoverIndex.)
  const std::pair<int, int> cf(cls, f);
  for (int v : Mesh.Face(f))
  {
    for (int id : Accepted.CoverIndex[v])
    {
      const Record& X = Accepted.Records[id];
      if (X.Key < key && std::binary_search(X.Kills.begin(), X.Kills.end(), cf))
      {
        return true;
      }
    }
  }
  return false;
}

ShapeDistributor::Impl::Record ShapeDistributor::Impl::RemoveAccepted(int id)
{
  const Record& r = Accepted.Records[id];
  return Accepted.Remove(id, ChartVertices(r), CentreCorners(r));
}

namespace
{
struct Reached
{
  std::uint64_t Key;
  int Level, Face, Index; // Index < 0: the mark of (Face, Level) at its level's start
};
struct LaterFirst
{
  bool operator()(const Reached& a, const Reached& b) const
  {
    if (a.Key != b.Key)
    {
      return a.Key > b.Key;
    }
    return a.Face != b.Face ? a.Face > b.Face : a.Index > b.Index;
  }
};
bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}
using Cell = std::array<long long, 3>;
// Candidates the look-ahead checks per thread at a time (RunPoolIncremental).
constexpr int LookAhead = 32;
} // namespace

/// One edit's run (RunPoolIncremental): what it has reached and decided.
struct ShapeDistributor::Impl::PoolEdit
{
  Impl& I;
  explicit PoolEdit(Impl& owner)
    : I(owner)
  {
  }

  // The faces whose density changed.
  std::vector<char> Changed;
  std::vector<int> ChangedFaces;
  // The faces by cells of space (their centroids), for the reach of a shape.
  double MaxScale = 1.0, CellSize = 1.0;
  int Widest = 0; // the class of the largest circumradius
  std::vector<std::pair<Cell, int>> Grid;
  // Every level's candidates of a face, with their positions and reaches (drawn once).
  struct Drawn
  {
    PoolCandidate P;
    Vec3 X;
    double Scale;
  };
  std::unordered_map<int, std::vector<Drawn>> DrawnFaces;
  // What is left to decide (key order), and what is decided.
  std::priority_queue<Reached, std::vector<Reached>, LaterFirst> Heap;
  std::unordered_set<std::uint64_t> Decided;
  // The accepted shapes by key, and by the face of their sample; the slots emptied.
  std::unordered_map<std::uint64_t, int> AcceptedByKey;
  std::unordered_map<int, std::vector<std::uint64_t>> AcceptedInFace;
  std::vector<char> Removed;
  // Marks of a face at the starts of later levels: the shapes that left within reach of the
  // face (x, reach), each for the levels after its own, or all of a level's candidates (a
  // changed face). One record per face: a shape reaches its faces once, not once per level.
  struct Source
  {
    Vec3 X;
    int Class;
    double Scale;
    int Level; // it marks the levels after this one
  };
  struct FaceMarks
  {
    std::uint32_t Queued = 0, All = 0; // per level: its start is in the heap; all candidates
    // The shapes that left when the edit started (by level: a level's start reads a prefix),
    // and those that left since (each marks the levels after its own).
    std::vector<Source> Early, Late;
  };
  std::unordered_map<int, FaceMarks> Marks;
  bool Started = false; // (Start done: shapes leave one by one, in key order)
  // Sources as Push reads them: a run of them, and another of which those below a level count.
  struct Sources
  {
    const Source *First, *Last, *More, *MoreLast;
    int Below;
  };
  std::vector<char> Alive;
  DecisionScratch Scratch;
  // Look-ahead: the candidates next in key order get their checks against the accepted shapes
  // (kills, the cheap check) and what needs the record alone (PrepareAlone: charts, outline,
  // exact map, faithfulness) in parallel, before their turn. A decision takes the checks' results
  // only when no shape was accepted or taken out since (State: bumped by each), and the prepared
  // record whenever it is the shape its turn makes: the decisions stay one by one in key order,
  // with the results of the serial run.
  struct Ahead
  {
    Record R;
    std::uint64_t State = 0;
    bool Killed = false, Conflict = false, Prepared = false;
  };
  std::unordered_map<std::uint64_t, Ahead> AheadOf; // (the undecided candidates it has seen)
  std::uint64_t State = 0;
  std::vector<DecisionScratch> AheadScratch;

  Cell CellOf(const Vec3& x) const
  {
    return Cell{ static_cast<long long>(std::floor(x.x / CellSize)),
      static_cast<long long>(std::floor(x.y / CellSize)),
      static_cast<long long>(std::floor(x.z / CellSize)) };
  }

  void FindChangedFaces(const std::vector<double>& oldDensity)
  {
    const TriangleMesh& mesh = I.Mesh;
    std::vector<char> changedVertex(mesh.NumberOfVertices(), 0);
    for (int v = 0; v < mesh.NumberOfVertices(); ++v)
    {
      changedVertex[v] = SameBits(oldDensity[v], I.Density[v]) ? 0 : 1;
    }
    Changed.assign(mesh.NumberOfFaces(), 0);
    for (int f = 0; f < mesh.NumberOfFaces(); ++f)
    {
      for (int v : mesh.Face(f))
      {
        Changed[f] = Changed[f] || changedVertex[v];
      }
      if (Changed[f])
      {
        ChangedFaces.push_back(f);
      }
    }
  }

  void BuildGrid()
  {
    MaxScale = I.Sampling.MaxFaceDensity;
    for (const Record& r : I.Accepted.Records)
    {
      MaxScale = std::max(MaxScale, r.Shape.Scale);
    }
    for (int c = 0; c < I.NumberOfClasses; ++c)
    {
      Widest = I.Tables.Classes[c].Radius > I.Tables.Classes[Widest].Radius ? c : Widest;
    }
    CellSize = std::max(I.PoolReach(Widest, MaxScale, Widest, MaxScale), I.Measures.MaxEdge);
    const TriangleMesh& mesh = I.Mesh;
    Grid.resize(mesh.NumberOfFaces());
    for (int f = 0; f < mesh.NumberOfFaces(); ++f)
    {
      const auto& v = mesh.Face(f);
      Grid[f] = { CellOf((mesh.Position(v[0]) + mesh.Position(v[1]) + mesh.Position(v[2])) / 3.0), f };
    }
    std::sort(Grid.begin(), Grid.end());
  }

  const std::vector<Drawn>& CandidatesOf(int f)
  {
    auto it = DrawnFaces.find(f);
    if (it != DrawnFaces.end())
    {
      return it->second;
    }
    std::vector<PoolCandidate> pool;
    for (int level = 0; level < I.Options.PoolLevels; ++level)
    {
      I.PoolCandidates(level, f, pool);
    }
    std::vector<Drawn> out;
    out.reserve(pool.size());
    for (const PoolCandidate& p : pool)
    {
      const SurfacePoint centre = SurfacePoint::InFace(f, 1.0 - p.A - p.B, p.A, p.B);
      out.push_back({ p, I.Mesh.Interpolate(f, centre.Bary), I.DensityAt(centre) });
    }
    return DrawnFaces.emplace(f, std::move(out)).first->second;
  }

  /// The faces within `range` of x (their centroids' cells, an edge more).
  template <class Visit>
  void FacesNear(const Vec3& x, double range, Visit&& visit) const
  {
    const Cell c = CellOf(x);
    const long long span = static_cast<long long>(std::ceil((range + I.Measures.MaxEdge) / CellSize));
    for (long long dx = -span; dx <= span; ++dx)
      for (long long dy = -span; dy <= span; ++dy)
        for (long long dz = -span; dz <= span; ++dz)
        {
          const Cell q{ c[0] + dx, c[1] + dy, c[2] + dz };
          for (auto it = std::lower_bound(Grid.begin(), Grid.end(), std::make_pair(q, -1));
               it != Grid.end() && it->first == q; ++it)
          {
            visit(it->second);
          }
        }
  }

  /// Marks face f at the start of every level after `after`: for `source`, or (null) for all
  /// of each level's candidates.
  void AddMarks(int f, int after, const Source* source)
  {
    FaceMarks& m = Marks[f];
    for (int level = after + 1; level < I.Options.PoolLevels; ++level)
    {
      const std::uint32_t bit = 1u << level;
      if (!(m.Queued & bit))
      {
        m.Queued |= bit;
        Heap.push({ static_cast<std::uint64_t>(level + 1) << 56, level, f, -1 });
      }
      m.All |= source ? 0u : bit;
    }
    if (source)
    {
      (Started ? m.Late : m.Early).push_back(*source);
    }
  }

  /// Face f's candidates of `level` after `key` that were not accepted, whose class no final
  /// shape (of smaller key) kills there and, unless `all`, within reach of a source.
  void Push(int f, int level, std::uint64_t key, bool all, const Sources& sources)
  {
    auto reaches = [this](const Source& o, const Drawn& d) {
      return Norm(d.X - o.X) <= I.PoolReach(o.Class, o.Scale, d.P.Class, d.Scale);
    };
    // (The cheap tests first; whether a class is killed here, once asked.)
    constexpr char Unknown = 2;
    std::fill(Alive.begin(), Alive.end(), Unknown);
    for (const Drawn& d : CandidatesOf(f))
    {
      if (d.P.Level != level || d.P.Key <= key)
      {
        continue;
      }
      bool near = all;
      for (const Source* o = sources.First; o != sources.Last && !near; ++o)
      {
        near = reaches(*o, d);
      }
      for (const Source* o = sources.More; o != sources.MoreLast && !near; ++o)
      {
        near = o->Level < sources.Below && reaches(*o, d);
      }
      if (!near || AcceptedByKey.count(d.P.Key) || Decided.count(d.P.Key))
      {
        continue;
      }
      char& alive = Alive[d.P.Class];
      if (alive == Unknown)
      {
        alive = I.KilledBefore(d.P.Class, f, key) ? 0 : 1;
      }
      if (alive)
      {
        Heap.push({ d.P.Key, d.P.Level, d.P.Face, d.P.Index });
      }
    }
  }

  /// How far a shape of class `cls` at density `scale` may conflict with any other.
  double Range(int cls, double scale) const { return I.PoolReach(cls, scale, Widest, MaxScale); }

  /// A shape of class `cls` at density `scale` at x (key: its key) left: the larger-key
  /// candidates within reach (PoolReach) that were rejected may fit now (those accepted stay
  /// so); those of its level now, those of later levels through marks at their levels' starts.
  void ReachRejected(const Vec3& x, int cls, double scale, std::uint64_t key)
  {
    const int level = static_cast<int>(key >> 56) - 1;
    const Source source{ x, cls, scale, level };
    const Sources one{ &source, &source + 1, nullptr, nullptr, 0 };
    FacesNear(x, Range(cls, scale), [&](int f) {
      Push(f, level, key, false, one);
      AddMarks(f, level, &source);
    });
  }

  /// A shape came: the larger-key accepted shapes within reach may not fit any more (those
  /// rejected stay so).
  void ReachAccepted(const Vec3& x, int cls, double scale, std::uint64_t key)
  {
    FacesNear(x, Range(cls, scale), [&](int f) {
      auto it = AcceptedInFace.find(f);
      if (it == AcceptedInFace.end())
      {
        return;
      }
      for (std::uint64_t k : it->second)
      {
        const Record& X = I.Accepted.Records[AcceptedByKey.at(k)];
        if (k > key && Norm(X.Shape.Position - x) <= I.PoolReach(cls, scale, X.Shape.ClassId, X.Shape.Scale))
        {
          Heap.push({ k, -1, f, 0 });
        }
      }
    });
  }

  /// The accepted shapes of the changed faces leave (their candidates are new); the changed
  /// faces' candidates are marked at every level.
  void Start()
  {
    Alive.resize(I.NumberOfClasses);
    Removed.assign(I.Accepted.Records.size(), 0);
    for (int id = 0; id < static_cast<int>(I.Accepted.Records.size()); ++id)
    {
      const Record& r = I.Accepted.Records[id];
      if (!Changed[r.Shape.Centre.Face])
      {
        AcceptedByKey.emplace(r.Key, id);
        AcceptedInFace[r.Shape.Centre.Face].push_back(r.Key);
      }
    }
    for (int id = 0; id < static_cast<int>(I.Accepted.Records.size()); ++id)
    {
      if (Changed[I.Accepted.Records[id].Shape.Centre.Face])
      {
        const Record r = I.RemoveAccepted(id);
        ++State;
        Removed[id] = 1;
        ReachRejected(r.Shape.Position, r.Shape.ClassId, r.Shape.Scale, r.Key);
      }
    }
    for (int f : ChangedFaces)
    {
      AddMarks(f, -1, nullptr);
    }
    for (auto& face : Marks)
    {
      std::stable_sort(face.second.Early.begin(), face.second.Early.end(),
        [](const Source& a, const Source& b) { return a.Level < b.Level; });
    }
    Started = true;
  }

  /// Takes an accepted shape out, for its decision again.
  Record TakeAccepted(int id)
  {
    Record r = I.RemoveAccepted(id);
    ++State;
    Removed[id] = 1;
    AcceptedByKey.erase(r.Key);
    std::vector<std::uint64_t>& keys = AcceptedInFace[r.Shape.Centre.Face];
    keys.erase(std::remove(keys.begin(), keys.end(), r.Key), keys.end());
    r.Reason = Record::Rejection::None;
    r.Rejected = false;
    return r;
  }

  /// Decides the next candidate (or mark) in key order, and what its change of fate reaches.
  void DecideNext()
  {
    const Reached next = Heap.top();
    Heap.pop();
    if (next.Index < 0)
    {
      // (A level's start: the kills final now decide which candidates are drawn.)
      const FaceMarks& m = Marks.at(next.Face);
      const bool all = (m.All >> next.Level) & 1u;
      const Source* early = m.Early.data();
      const Source* earlyBelow = std::partition_point(early, early + m.Early.size(),
        [&next](const Source& o) { return o.Level < next.Level; });
      const Source* late = m.Late.data();
      Push(next.Face, next.Level, next.Key - 1, all,
        Sources{ early, earlyBelow, late, late + m.Late.size(), next.Level });
      return;
    }
    if (!Decided.insert(next.Key).second)
    {
      return;
    }
    Record r;
    const auto was = AcceptedByKey.find(next.Key);
    const bool wasAccepted = was != AcceptedByKey.end();
    bool killed = false;
    if (wasAccepted)
    {
      r = TakeAccepted(was->second);
      killed = I.KilledBefore(r.Shape.ClassId, r.Shape.Centre.Face, r.Key);
    }
    bool conflict = false; // (a new candidate: the cheap check, done here or ahead)
    if (!wasAccepted)
    {
      const auto ahead = AheadOf.find(next.Key);
      bool checked = false;
      if (ahead != AheadOf.end() && ahead->second.State == State)
      {
        killed = ahead->second.Killed;
        conflict = ahead->second.Conflict;
        checked = true;
        r = std::move(ahead->second.R);
      }
      else
      {
        PoolCandidate p;
        I.DrawPoolCandidate(next.Level, next.Face, next.Index, p);
        killed = I.KilledBefore(p.Class, p.Face, p.Key);
        if (!killed)
        {
          I.MakePoolRecord(p, false, r, Scratch.Conflicts);
          if (ahead != AheadOf.end() && ahead->second.Prepared && r.Valid &&
            SamePlacement(ahead->second.R.Shape, r.Shape))
          {
            r = std::move(ahead->second.R); // (what it needs of itself alone)
          }
        }
      }
      if (ahead != AheadOf.end())
      {
        AheadOf.erase(ahead);
      }
      if (!killed && r.Valid && !checked)
      {
        conflict = I.CheapConflict(r, Scratch.Conflicts);
      }
      // (Charts made ahead count where the decision would have made them: past the cheap check.)
      Scratch.Charts += !killed && r.Valid && !conflict && !r.Charts.empty() ? 1 : 0;
    }
    // (A prepared record rejected alone is unfaithful: Decide would not test it again.)
    const bool fits = !killed && r.Valid && !conflict && !r.Rejected &&
      I.Decide(r, 0, wasAccepted, false, Scratch);
    if (!fits && !wasAccepted)
    {
      return; // (rejected as before)
    }
    const Vec3 x = r.Shape.Position;
    const int cls = r.Shape.ClassId;
    const double scale = r.Shape.Scale;
    if (fits)
    {
      AcceptedByKey.emplace(next.Key, static_cast<int>(I.Accepted.Records.size()));
      AcceptedInFace[r.Shape.Centre.Face].push_back(next.Key);
      Removed.push_back(0);
      I.Commit(std::move(r));
      ++State;
    }
    if (fits && !wasAccepted)
    {
      ReachAccepted(x, cls, scale, next.Key);
    }
    else if (!fits && wasAccepted)
    {
      ReachRejected(x, cls, scale, next.Key);
    }
  }

  /// When the next candidate in key order is one the look-ahead has not seen: the next `count`
  /// unseen candidates are checked and prepared, in parallel (the heap and the accepted shapes
  /// only read). False when aborted (nothing kept).
  bool PrepareAhead(int count, int threads)
  {
    // (Candidates only: not the marks of a level's start, nor the accepted shapes' entries.)
    auto unseen = [this](const Reached& r) {
      return r.Index >= 0 && r.Level >= 0 && !Decided.count(r.Key) && !AcceptedByKey.count(r.Key) &&
        !AheadOf.count(r.Key);
    };
    if (Heap.empty() || !unseen(Heap.top()))
    {
      return true;
    }
    // (At most a few batches' worth of entries looked at: the level starts and the entries seen
    // or decided between them are put back, not searched through to the heap's end.)
    std::vector<Reached> popped, ahead;
    while (!Heap.empty() && static_cast<int>(ahead.size()) < count &&
      static_cast<int>(popped.size()) < 8 * count)
    {
      const Reached next = Heap.top();
      Heap.pop();
      popped.push_back(next);
      if (unseen(next) && (ahead.empty() || ahead.back().Key != next.Key)) // (copies come together)
      {
        ahead.push_back(next);
      }
    }
    for (const Reached& r : popped)
    {
      Heap.push(r);
    }
    const int n = static_cast<int>(ahead.size());
    std::vector<Ahead> results(n);
    AheadScratch.resize(threads);
    ParallelFor(n, threads, 1, [&](int i, int thread) {
      if (I.Poll())
      {
        return;
      }
      Ahead& a = results[i];
      a.State = State;
      PoolCandidate p;
      I.DrawPoolCandidate(ahead[i].Level, ahead[i].Face, ahead[i].Index, p);
      DecisionScratch& s = AheadScratch[thread];
      a.Killed = I.KilledBefore(p.Class, p.Face, p.Key);
      if (a.Killed)
      {
        return;
      }
      I.MakePoolRecord(p, false, a.R, s.Conflicts);
      a.Conflict = a.R.Valid && I.CheapConflict(a.R, s.Conflicts);
      if (a.R.Valid && !a.Conflict)
      {
        I.PrepareAlone(a.R, thread, s);
        a.Prepared = true;
      }
    });
    if (I.Poll())
    {
      return false; // (some were left unchecked)
    }
    for (int i = 0; i < n; ++i)
    {
      AheadOf.emplace(ahead[i].Key, std::move(results[i]));
    }
    return true;
  }

  /// The accepted shapes without the empty slots, in key order.
  void Finish() { I.SortAcceptedByKey(&Removed); }
};

bool ShapeDistributor::Impl::RunPoolIncremental(const std::vector<double>& oldDensity,
  const std::function<bool(double)>& progress, ShapeDistributionStatistics& stats)
{
  Progress.Polling.reset(new PhasePoll(progress));
  Progress.Reported = 0.0;
  const auto start = std::chrono::steady_clock::now();
  PoolEdit edit(*this);
  edit.FindChangedFaces(oldDensity);
  edit.BuildGrid();
  edit.Start();
  // Key order: each candidate sees the final fates of every smaller key.
  Pool.KillOnCommit = false;
  const int threads = ThreadCount(Options.NumberOfThreads);
  for (long long k = 1; !edit.Heap.empty(); ++k)
  {
    if ((k & 63) == 0 && Poll())
    {
      Pool.KillOnCommit = true;
      return false;
    }
    if (threads > 1 && !edit.PrepareAhead(LookAhead * threads, threads))
    {
      Pool.KillOnCommit = true;
      return false;
    }
    edit.DecideNext();
  }
  Pool.KillOnCommit = true;
  if (Poll())
  {
    return false; // (an abort during the last decisions: their checks gave up)
  }
  edit.Finish();
  stats.Incremental = true;
  stats.Maximal = true;
  stats.Redecided = static_cast<long long>(edit.Decided.size());
  stats.Candidates = stats.Redecided;
  stats.Charts = edit.Scratch.Charts;
  stats.ChartCpuSeconds = edit.Scratch.ChartSeconds;
  for (const DecisionScratch& t : edit.AheadScratch)
  {
    stats.ChartCpuSeconds += t.ChartSeconds; // (its charts counted where decisions took them)
  }
  stats.CheckSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

} // namespace gs
