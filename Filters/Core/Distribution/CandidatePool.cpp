// Place-keyed candidates (CandidateOrder::PlaceKeyed): a candidate pool that is a function of
// (Seed, face, index) and of the face's own density, decided greedily in priority order.
//
// Level l of the pool is a Poisson process over the faces of intensity 2^l per class-weighted
// circumscribed disc at the local density (face weight area / f^2); its candidates' keys sort
// after every key of level l - 1. A fresh run decides the levels in order, each in key order
// (RunPool): the result is sequential greedy dart throwing in key order. Level l is drawn only on the faces where a shape may still fit when it
// starts (the dead-face masks: a candidate there would certainly be rejected), so the doubling
// intensities are spent on the gaps left, as the rounds' failure count is.
#include "ShapeDistributorImpl.h"

#include <chrono>
#include <cmath>

namespace gs
{
using namespace distribution;

namespace
{
constexpr int PoolKeyBits = 56; // below the level

/// Poisson(mean) by inversion, in pieces of mean at most 200 (exp(-mean) stays normal).
int PoissonCount(Random& rng, double mean)
{
  int count = 0;
  while (mean > 0.0)
  {
    const double m = std::min(mean, 200.0);
    mean -= m;
    double p = std::exp(-m), sum = p;
    const double u = rng.Uniform();
    const int cap = static_cast<int>(m + 40.0 * std::sqrt(m) + 40.0);
    int k = 0;
    while (u > sum && k < cap)
    {
      ++k;
      p *= m / k;
      sum += p;
    }
    count += k;
  }
  return count;
}
} // namespace

void ShapeDistributor::Impl::PreparePool()
{
  double weights = 0.0, discs = 0.0;
  for (int c = 0; c < NumberOfClasses; ++c)
  {
    const double w = Sampling.ClassCdf[c] - (c > 0 ? Sampling.ClassCdf[c - 1] : 0.0);
    const double r = Tables.Classes[c].Radius * Options.ShapeSize;
    weights += w;
    discs += w * Pi * r * r;
  }
  Pool.Footprint = weights > 0.0 && discs > 0.0 ? discs / weights : 1.0;
  // (PoolReach's terms per class, in units of ShapeSize times the density factor.)
  Pool.ClassOffset.assign(NumberOfClasses, 0.0);
  Pool.ClassChart.assign(NumberOfClasses, 0.0);
  for (int c = 0; c < NumberOfClasses; ++c)
  {
    const SafeDistanceClass& k = Tables.Classes[c];
    double part = CircleMode || k.Parts.empty() ? k.Radius : 0.0;
    for (int p : k.Parts)
    {
      part = std::max(part, CircleMode ? k.Radius : Tables.Parts[p].Radius);
    }
    Pool.ClassOffset[c] = k.Parts.size() > 1 ? std::sqrt(2.0) * k.Radius : 0.0;
    Pool.ClassChart[c] = part + Measures.RMax;
  }
}

double ShapeDistributor::Impl::PoolMean(int level, int f) const
{
  return std::ldexp(Sampling.FaceWeight[f] / Pool.Footprint, level);
}

Random ShapeDistributor::Impl::DrawPoolCandidate(int level, int f, int index, PoolCandidate& p) const
{
  Random rng(Options.Seed, 5, static_cast<std::uint64_t>(level),
    (static_cast<std::uint64_t>(f) << 32) | static_cast<std::uint32_t>(index));
  p.Key = (static_cast<std::uint64_t>(level + 1) << PoolKeyBits) |
    (rng.State >> (64 - PoolKeyBits));
  p.Level = level;
  p.Face = f;
  p.Index = index;
  p.Class = Sampling.RandomClass(rng);
  double a = rng.Uniform(), b = rng.Uniform();
  if (a + b > 1.0)
  {
    a = 1.0 - a;
    b = 1.0 - b;
  }
  p.A = a;
  p.B = b;
  return rng; // (what MakeShape draws next)
}

void ShapeDistributor::Impl::PoolCandidates(int level, int f, std::vector<PoolCandidate>& out) const
{
  if (!(Sampling.FaceWeight[f] > 0.0))
  {
    return;
  }
  Random counter(Options.Seed, 6, static_cast<std::uint64_t>(level), static_cast<std::uint64_t>(f));
  const int n = PoissonCount(counter, PoolMean(level, f));
  PoolCandidate p;
  for (int k = 0; k < n; ++k)
  {
    DrawPoolCandidate(level, f, k, p);
    out.push_back(p);
  }
}

bool ShapeDistributor::Impl::PoolLess(const PoolCandidate& a, const PoolCandidate& b)
{
  if (a.Key != b.Key)
  {
    return a.Key < b.Key;
  }
  return a.Face != b.Face ? a.Face < b.Face : a.Index < b.Index;
}

void ShapeDistributor::Impl::MakePoolRecord(
  const PoolCandidate& p, bool masks, Record& r, std::vector<int>& scratch) const
{
  r = Record();
  r.Key = p.Key;
  PoolCandidate again;
  Random rng = DrawPoolCandidate(p.Level, p.Face, p.Index, again);
  const SurfacePoint centre = SurfacePoint::InFace(p.Face, 1.0 - p.A - p.B, p.A, p.B);
  // As Generate: a class that certainly cannot fit in this face, or (long classes) at this
  // centre, needs no shape.
  const bool covered = (masks && (Sampling.DeadFace(p.Face) || Sampling.DeadForClass(p.Class, p.Face))) ||
    CentreCovered(centre, p.Class, DensityAt(centre), p.Key, scratch);
  r.Valid = !covered && MakeShape(centre, p.Class, rng, r.Shape, nullptr, &scratch, p.Key);
  r.Reason = r.Valid ? Record::Rejection::None
    : covered        ? Record::Rejection::Tables
                     : Record::Rejection::WithoutShape;
}

std::vector<ShapeDistributor::Impl::PoolCandidate> ShapeDistributor::Impl::LivePoolLevel(
  int level, int threads) const
{
  const int nf = Mesh.NumberOfFaces();
  constexpr int FacesPerChunk = 2048;
  const int chunks = (nf + FacesPerChunk - 1) / FacesPerChunk;
  std::vector<std::vector<PoolCandidate>> perChunk(chunks);
  ParallelFor(chunks, threads, 1, [&](int c, int) {
    std::vector<PoolCandidate>& out = perChunk[c];
    const int end = std::min(nf, (c + 1) * FacesPerChunk);
    for (int f = c * FacesPerChunk; f < end; ++f)
    {
      if (Sampling.DeadFace(f))
      {
        continue;
      }
      const std::size_t first = out.size();
      PoolCandidates(level, f, out);
      std::size_t kept = first;
      for (std::size_t k = first; k < out.size(); ++k)
      {
        if (!Sampling.DeadForClass(out[k].Class, f))
        {
          out[kept++] = out[k];
        }
      }
      out.resize(kept);
    }
  });
  std::vector<PoolCandidate> all;
  for (const auto& part : perChunk)
  {
    all.insert(all.end(), part.begin(), part.end());
  }
  std::sort(all.begin(), all.end(), PoolLess);
  return all;
}

void ShapeDistributor::Impl::PrepareAlone(Record& r, int thread, DecisionScratch& s) const
{
  // As Decide and DrawnConflict would, in their order (the same results: each is a function
  // of the record alone).
  if (!r.Shape.Curve.empty() && Unfaithful(r))
  {
    r.Rejected = true;
    r.Reason = Record::Rejection::Faithful;
    return;
  }
  const auto chartStart = std::chrono::steady_clock::now();
  ComputeCharts(r, *PerThread.Engines[thread]);
  s.ChartSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - chartStart).count();
  ++s.Charts;
  if (CircleMode || !Options.DrawnCheck || FullConflict(r, s.Conflicts))
  {
    return;
  }
  DrawOutline(r);
  if (r.Shape.Curve.empty() && !r.Charts.empty() && !r.Charts[0].Entries.empty() && PrepareExactMap(r))
  {
    Unfaithful(r); // (its verdict kept: the drawn check reads it last, as it would test it)
  }
}

bool ShapeDistributor::Impl::DecidePoolSurvivors(
  std::vector<Record>& survivors, int threads, ShapeDistributionStatistics& stats, bool& full)
{
  std::vector<DecisionScratch> perThread(threads);
  ParallelFor(static_cast<int>(survivors.size()), threads, 1, [&](int i, int thread) {
    if (!Poll())
    {
      PrepareAlone(survivors[i], thread, perThread[thread]);
    }
  });
  if (Poll())
  {
    return false;
  }
  DecisionScratch& scratch = perThread[0];
  for (Record& r : survivors)
  {
    if (full || (!r.Rejected && !Decide(r, 0, true, false, scratch)))
    {
      CountRejection(r, stats);
      continue;
    }
    if (!r.Rejected)
    {
      Commit(std::move(r));
      full = Options.MaximumShapes > 0 && static_cast<int>(Accepted.Records.size()) >= Options.MaximumShapes;
      continue;
    }
    CountRejection(r, stats);
  }
  for (const DecisionScratch& t : perThread)
  {
    stats.Charts += t.Charts;
    stats.ChartCpuSeconds += t.ChartSeconds;
  }
  survivors.clear();
  return true;
}

bool ShapeDistributor::Impl::RunPool(
  int threads, const std::function<bool(double)>& progress, ShapeDistributionStatistics& stats)
{
  // Strictly in key order: each level's candidates in chunks, checked in parallel against the
  // shapes accepted so far (all of smaller key: a rejection then is final); the survivors get
  // what needs the record alone (charts, outline, exact map, faithfulness) in parallel, a few
  // per thread at a time, and are decided one by one in key order against every shape of
  // smaller key. No neighbourhood bound is assumed between candidates decided in parallel.
  Progress.Polling.reset(new PhasePoll(progress));
  Progress.Reported = 0.0;
  const int levels = Options.PoolLevels;
  const int survivorsPerStep = 4 * threads;
  bool full = false;
  std::vector<Record> survivors;
  for (int level = 0; level < levels && !full; ++level)
  {
    auto clock = std::chrono::steady_clock::now();
    auto lap = [&clock](double& into) {
      const auto now = std::chrono::steady_clock::now();
      into += std::chrono::duration<double>(now - clock).count();
      clock = now;
    };
    const std::vector<PoolCandidate> pool = LivePoolLevel(level, threads);
    lap(stats.GenerateSeconds);
    const int n = static_cast<int>(pool.size());
    constexpr int Chunk = 256;
    for (int start = 0; start < n && !full; start += Chunk)
    {
      const int size = std::min(n - start, Chunk);
      std::vector<Record> chunk(size);
      ParallelForEachThread<std::vector<int>>(size, threads, 16, [&](int i, std::vector<int>& scratch) {
        Record& r = chunk[i];
        if (Poll())
        {
          return;
        }
        MakePoolRecord(pool[start + i], true, r, scratch);
        r.Rejected = !r.Valid || CheapConflict(r, scratch);
        if (r.Valid && r.Rejected)
        {
          r.Reason = Record::Rejection::Tables;
        }
      });
      lap(stats.GenerateSeconds);
      if (Poll())
      {
        return false;
      }
      stats.Candidates += size;
      for (Record& r : chunk)
      {
        if (r.Rejected)
        {
          CountRejection(r, stats);
          continue;
        }
        survivors.push_back(std::move(r));
        if (static_cast<int>(survivors.size()) >= survivorsPerStep &&
          !DecidePoolSurvivors(survivors, threads, stats, full))
        {
          return false;
        }
      }
      if ((start / Chunk) % 16 == 15 && !DecidePoolSurvivors(survivors, threads, stats, full))
      {
        return false; // (the rest of a long level: candidates checked against fresher shapes)
      }
      lap(stats.CheckSeconds);
      ++stats.Rounds;
      double fraction = (level + static_cast<double>(start + size) / n) / levels;
      if (Options.MaximumShapes > 0)
      {
        fraction = std::max(fraction, static_cast<double>(Accepted.Records.size()) / Options.MaximumShapes);
      }
      Progress.Reported = std::max(Progress.Reported, std::min(0.99, fraction));
      if (!Progress.Polling->Report(Progress.Reported))
      {
        return false;
      }
    }
    if (!DecidePoolSurvivors(survivors, threads, stats, full))
    {
      return false;
    }
  }
  stats.Maximal = !full; // (every level decided: maximal for the pool)
  stats.Redecided = stats.Candidates;
  SortAcceptedByKey();
  return true;
}

void ShapeDistributor::Impl::SortAcceptedByKey(const std::vector<char>* removed)
{
  Accepted.SortByKey(removed);
  Sampling.ForgetKillLog(); // (Uncommit takes back the last commit; the order of commits is gone.)
}

} // namespace gs
