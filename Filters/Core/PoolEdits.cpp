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
  return LastPool.Valid && LastPool.Fingerprint == fingerprint &&
    LastPool.Density.size() == vertexDensity.size() && !vertexDensity.empty();
}

double ShapeDistributor::Impl::PoolReach(int cls, double scale) const
{
  const double drawn = Tables.Classes[cls].Parts.size() > 1 ? std::sqrt(2.0) : 1.0;
  return PoolNeighbourSlack * drawn * Tables.Classes[cls].Radius * Options.ShapeSize * scale *
    (1.0 + Options.SafetyMargin);
}

bool ShapeDistributor::Impl::KilledBefore(int cls, int f, std::uint64_t key) const
{
  // (A killed face's corners are in the killer's chart, so in CoverIndex.)
  const std::pair<int, int> cf(cls, f);
  for (int v : Mesh.Face(f))
  {
    for (int id : CoverIndex[v])
    {
      const Record& X = Accepted[id];
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
  Record r = std::move(Accepted[id]);
  Accepted[id] = Record();
  auto drop = [id](std::vector<int>& ids) {
    ids.erase(std::remove(ids.begin(), ids.end(), id), ids.end());
  };
  for (int v : ChartVertices(r))
  {
    drop(CoverIndex[v]);
  }
  for (int v : CentreCorners(r))
  {
    drop(CentreIndex[v]);
  }
  return r;
}

namespace
{
struct Reached
{
  std::uint64_t Key;
  int Level, Face, Index;
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
} // namespace

bool ShapeDistributor::Impl::RunPoolIncremental(const std::vector<double>& oldDensity,
  const std::function<bool(double)>& progress, ShapeDistributionStatistics& stats)
{
  Polling.reset(new PhasePoll(progress));
  Reported = 0.0;
  const auto start = std::chrono::steady_clock::now();
  const int nf = Mesh.NumberOfFaces();
  // The faces whose density changed: their candidates are new.
  std::vector<char> changedVertex(Mesh.NumberOfVertices(), 0);
  for (int v = 0; v < Mesh.NumberOfVertices(); ++v)
  {
    changedVertex[v] = SameBits(oldDensity[v], Density[v]) ? 0 : 1;
  }
  std::vector<char> changed(nf, 0);
  std::vector<int> changedFaces;
  for (int f = 0; f < nf; ++f)
  {
    for (int v : Mesh.Face(f))
    {
      changed[f] = changed[f] || changedVertex[v];
    }
    if (changed[f])
    {
      changedFaces.push_back(f);
    }
  }
  // The faces by cells of space (their centroids), for the reach of a shape.
  double maxScale = MaxFaceDensity;
  for (const Record& r : Accepted)
  {
    maxScale = std::max(maxScale, r.Shape.Scale);
  }
  int widest = 0;
  for (int c = 0; c < NumberOfClasses; ++c)
  {
    widest = Tables.Classes[c].Radius > Tables.Classes[widest].Radius ? c : widest;
  }
  const double maxReach = PoolReach(widest, maxScale);
  const double cell = std::max(2.0 * maxReach, MaxEdge);
  using Cell = std::array<long long, 3>;
  auto cellOf = [cell](const Vec3& x) {
    return Cell{ static_cast<long long>(std::floor(x.x / cell)),
      static_cast<long long>(std::floor(x.y / cell)), static_cast<long long>(std::floor(x.z / cell)) };
  };
  std::vector<std::pair<Cell, int>> grid(nf);
  for (int f = 0; f < nf; ++f)
  {
    const auto& v = Mesh.Face(f);
    grid[f] = { cellOf((Mesh.Position(v[0]) + Mesh.Position(v[1]) + Mesh.Position(v[2])) / 3.0), f };
  }
  std::sort(grid.begin(), grid.end());
  // Every level's candidates of a face, with their positions and reaches (drawn once).
  struct Drawn
  {
    PoolCandidate P;
    Vec3 X;
    double Reach;
  };
  std::unordered_map<int, std::vector<Drawn>> drawnFaces;
  auto candidatesOf = [&](int f) -> const std::vector<Drawn>& {
    auto it = drawnFaces.find(f);
    if (it != drawnFaces.end())
    {
      return it->second;
    }
    std::vector<PoolCandidate> pool;
    for (int level = 0; level < Options.PoolLevels; ++level)
    {
      PoolCandidates(level, f, pool);
    }
    std::vector<Drawn> out;
    out.reserve(pool.size());
    for (const PoolCandidate& p : pool)
    {
      const SurfacePoint centre = SurfacePoint::InFace(f, 1.0 - p.A - p.B, p.A, p.B);
      out.push_back({ p, Mesh.Interpolate(f, centre.Bary), PoolReach(p.Class, DensityAt(centre)) });
    }
    return drawnFaces.emplace(f, std::move(out)).first->second;
  };
  std::priority_queue<Reached, std::vector<Reached>, LaterFirst> heap;
  std::unordered_set<std::uint64_t> decided;
  // The accepted shapes by key, and by the face of their sample.
  std::unordered_map<std::uint64_t, int> acceptedByKey;
  std::unordered_map<int, std::vector<std::uint64_t>> acceptedInFace;
  auto forget = [&](const Record& r) {
    acceptedByKey.erase(r.Key);
    std::vector<std::uint64_t>& keys = acceptedInFace[r.Shape.Centre.Face];
    keys.erase(std::remove(keys.begin(), keys.end(), r.Key), keys.end());
  };
  // The faces within `range` of x (their centroids' cells).
  auto facesNear = [&](const Vec3& x, double range, const std::function<void(int)>& visit) {
    const Cell c = cellOf(x);
    const long long span = static_cast<long long>(std::ceil((range + MaxEdge) / cell));
    for (long long dx = -span; dx <= span; ++dx)
      for (long long dy = -span; dy <= span; ++dy)
        for (long long dz = -span; dz <= span; ++dz)
        {
          const Cell q{ c[0] + dx, c[1] + dy, c[2] + dz };
          for (auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(q, -1));
               it != grid.end() && it->first == q; ++it)
          {
            visit(it->second);
          }
        }
  };
  // A changed face's candidates are reached through a mark at each level's start (as a fresh
  // run draws a level on the faces alive when it starts): the kills final then decide which
  // are drawn. A shape at x (reach: its own, key: its key) left: the larger-key candidates
  // within reach that were rejected may fit now (those accepted stay so); faces where a final
  // shape (of smaller key) kills a class hold no candidate of that class that could.
  std::vector<char> alive(NumberOfClasses);
  // Marks of (face, level): the shapes that left within reach of the face (x, reach), or
  // none for a changed face (all its candidates).
  struct Source
  {
    Vec3 X;
    double Reach;
  };
  struct Mark
  {
    bool All = false;
    std::vector<Source> Sources;
  };
  std::unordered_map<std::uint64_t, Mark> marks;
  auto mark = [&](int f, int level, const Source* source) {
    const std::uint64_t id = static_cast<std::uint64_t>(f) * 64 + static_cast<std::uint64_t>(level);
    auto inserted = marks.emplace(id, Mark());
    if (inserted.second)
    {
      heap.push({ static_cast<std::uint64_t>(level + 1) << 56, level, f, -1 });
    }
    Mark& m = inserted.first->second;
    m.All = m.All || !source;
    if (source && !m.All)
    {
      m.Sources.push_back(*source);
    }
  };
  // Face f's candidates of `level` after `key` whose class no final shape kills there and,
  // unless `all`, within reach of a source.
  auto push = [&](int f, int level, std::uint64_t key, bool all, const std::vector<Source>& sources) {
    bool any = false;
    for (int c = 0; c < NumberOfClasses; ++c)
    {
      alive[c] = !KilledBefore(c, f, key);
      any = any || alive[c];
    }
    if (!any)
    {
      return;
    }
    for (const Drawn& d : candidatesOf(f))
    {
      if (d.P.Level != level || d.P.Key <= key || !alive[d.P.Class] || acceptedByKey.count(d.P.Key) ||
        decided.count(d.P.Key))
      {
        continue;
      }
      bool near = all;
      for (std::size_t k = 0; k < sources.size() && !near; ++k)
      {
        near = Norm(d.X - sources[k].X) <= sources[k].Reach + d.Reach;
      }
      if (near)
      {
        heap.push({ d.P.Key, d.P.Level, d.P.Face, d.P.Index });
      }
    }
  };
  auto reachRejected = [&](const Vec3& x, double reachOf, std::uint64_t key) {
    const int level = static_cast<int>(key >> 56) - 1;
    const Source source{ x, reachOf };
    const std::vector<Source> one{ source };
    facesNear(x, reachOf + maxReach, [&](int f) {
      push(f, level, key, false, one);
      for (int later = level + 1; later < Options.PoolLevels; ++later)
      {
        mark(f, later, &source);
      }
    });
  };
  // A shape at x came: the larger-key accepted shapes within reach may not fit any more (those
  // rejected stay so).
  auto reachAccepted = [&](const Vec3& x, double reachOf, std::uint64_t key) {
    facesNear(x, reachOf + maxReach, [&](int f) {
      auto it = acceptedInFace.find(f);
      if (it == acceptedInFace.end())
      {
        return;
      }
      for (std::uint64_t k : it->second)
      {
        const Record& X = Accepted[acceptedByKey.at(k)];
        if (k > key && Norm(X.Shape.Position - x) <= reachOf + PoolReach(X.Shape.ClassId, X.Shape.Scale))
        {
          heap.push({ k, -1, f, 0 });
        }
      }
    });
  };
  std::vector<char> removed(Accepted.size(), 0);
  for (int id = 0; id < static_cast<int>(Accepted.size()); ++id)
  {
    const Record& r = Accepted[id];
    if (!changed[r.Shape.Centre.Face])
    {
      acceptedByKey.emplace(r.Key, id);
      acceptedInFace[r.Shape.Centre.Face].push_back(r.Key);
    }
  }
  // Those of the changed faces leave (their candidates are new).
  for (int id = 0; id < static_cast<int>(Accepted.size()); ++id)
  {
    if (changed[Accepted[id].Shape.Centre.Face])
    {
      const Record r = RemoveAccepted(id);
      removed[id] = 1;
      reachRejected(r.Shape.Position, PoolReach(r.Shape.ClassId, r.Shape.Scale), r.Key);
    }
  }
  for (int f : changedFaces)
  {
    for (int level = 0; level < Options.PoolLevels; ++level)
    {
      mark(f, level, nullptr);
    }
  }
  // Key order: each candidate sees the final fates of every smaller key.
  KillOnCommit = false;
  DecisionScratch scratch;
  long long polled = 0;
  while (!heap.empty())
  {
    const Reached next = heap.top();
    heap.pop();
    if (next.Index < 0)
    {
      // (A level's start: the kills final now decide.)
      const Mark& m = marks.at(static_cast<std::uint64_t>(next.Face) * 64 + static_cast<std::uint64_t>(next.Level));
      push(next.Face, next.Level, next.Key - 1, m.All, m.Sources);
      continue;
    }
    if (!decided.insert(next.Key).second)
    {
      continue;
    }
    if ((++polled & 63) == 0 && Poll())
    {
      KillOnCommit = true;
      return false;
    }
    Record r;
    const auto was = acceptedByKey.find(next.Key);
    const bool wasAccepted = was != acceptedByKey.end();
    bool killed = false;
    if (wasAccepted)
    {
      const int id = was->second;
      r = RemoveAccepted(id);
      removed[id] = 1;
      forget(r);
      r.Reason = Record::Rejection::None;
      r.Rejected = false;
      killed = KilledBefore(r.Shape.ClassId, r.Shape.Centre.Face, r.Key);
    }
    else
    {
      PoolCandidate p;
      DrawPoolCandidate(next.Level, next.Face, next.Index, p);
      killed = KilledBefore(p.Class, p.Face, p.Key);
      if (!killed)
      {
        MakePoolRecord(p, false, r, scratch.Conflicts);
      }
    }
    const bool fits = !killed && r.Valid && Decide(r, 0, true, false, scratch);
    if (fits == wasAccepted && !fits)
    {
      continue; // (rejected as before)
    }
    const Vec3 x = r.Shape.Position;
    const double reachOf = PoolReach(r.Shape.ClassId, r.Shape.Scale);
    const std::uint64_t key = next.Key;
    if (fits)
    {
      acceptedByKey.emplace(key, static_cast<int>(Accepted.size()));
      acceptedInFace[r.Shape.Centre.Face].push_back(key);
      removed.push_back(0);
      Commit(std::move(r));
    }
    if (fits && !wasAccepted)
    {
      reachAccepted(x, reachOf, key);
    }
    else if (!fits && wasAccepted)
    {
      reachRejected(x, reachOf, key);
    }
  }
  KillOnCommit = true;
  // The accepted shapes without the empty slots, in key order.
  std::vector<int> newId(Accepted.size(), -1);
  std::vector<Record> kept;
  for (std::size_t id = 0; id < Accepted.size(); ++id)
  {
    if (!removed[id])
    {
      newId[id] = static_cast<int>(kept.size());
      kept.push_back(std::move(Accepted[id]));
    }
  }
  Accepted.swap(kept);
  for (auto* index : { &CoverIndex, &CentreIndex })
  {
    for (std::vector<int>& ids : *index)
    {
      for (int& id : ids)
      {
        id = newId[id];
      }
    }
  }
  SortAcceptedByKey();
  stats.Incremental = true;
  stats.Maximal = true;
  stats.Redecided = static_cast<long long>(decided.size());
  stats.Candidates = stats.Redecided;
  stats.Charts = scratch.Charts;
  stats.ChartCpuSeconds = scratch.ChartSeconds;
  stats.CheckSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return true;
}

} // namespace gs
