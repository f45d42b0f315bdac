// Algorithm 3: rounds of candidates with priorities (their order in the round); a candidate is
// accepted iff it conflicts with no accepted shape and no accepted higher-priority candidate of
// its round, decided in parallel waves: the result is sequential dart throwing in priority
// order, whatever the number of threads.
#include "ShapeDistributorImpl.h"

#include <array>
#include <chrono>
#include <cmath>

namespace gs
{
using namespace distribution;

bool ShapeDistributor::Impl::RunRounds(
  int threads, const std::function<bool(double)>& progress, ShapeDistributionStatistics& stats)
{
  Progress.Polling.reset(new PhasePoll(progress));
  Progress.Reported = 0.0;
  RunState run;
  run.FailuresToStop = Options.MaximalFailures > 0 ? Options.MaximalFailures : 10000;
  const bool greedyMode = Options.Mode == DistributionMode::Greedy;
  for (int round = 0; !run.Stop; ++round)
  {
    const bool greedy = greedyMode && !run.Front.empty();
    const bool seeding = greedyMode && !greedy && run.SeedsGrow;
    auto clock = std::chrono::steady_clock::now();
    auto lap = [&clock](double& into) {
      const auto now = std::chrono::steady_clock::now();
      into += std::chrono::duration<double>(now - clock).count();
      clock = now;
    };
    std::vector<Record> batch;
    if (greedy)
    {
      DrawGreedyBatch(run.Front, round, threads, batch);
    }
    else if (!DrawRandomBatch(round, seeding, run, batch))
    {
      stats.Maximal = true; // no face left where a shape could fit
      break;
    }
    lap(stats.GenerateSeconds);
    if (Poll() || !DecideRound(batch, greedy, seeding, threads, run, stats))
    {
      return false;
    }
    clock = std::chrono::steady_clock::now();
    const int roundStart = static_cast<int>(Accepted.Records.size()) - run.AcceptedInRound;
    std::vector<int> nextFront;
    for (int id = roundStart; id < static_cast<int>(Accepted.Records.size()); ++id)
    {
      nextFront.push_back(id);
    }
    if (greedyMode)
    {
      // A seed whose front cannot grow at all: the gaps left hold single shapes, which plain
      // dart throwing fills (one seed per round would cost a whole round per gap).
      if (greedy)
      {
        run.GrownSinceSeed += static_cast<long long>(nextFront.size());
      }
      else if (seeding)
      {
        if (run.Seeds > 0 && run.GrownSinceSeed == 0)
        {
          run.SeedsGrow = false;
        }
        ++run.Seeds;
        run.GrownSinceSeed = 0;
      }
      run.Front.swap(nextFront);
    }
    lap(stats.RoundSeconds);
    stats.Rounds = round + 1;
    double fraction = static_cast<double>(run.Consecutive) / static_cast<double>(run.FailuresToStop);
    if (Options.MaximumShapes > 0)
    {
      fraction = std::max(fraction, static_cast<double>(Accepted.Records.size()) / Options.MaximumShapes);
    }
    run.Reported = std::max(run.Reported, std::min(0.99, fraction));
    Progress.Reported = run.Reported;
    if (!Progress.Polling->Report(run.Reported))
    {
      return false;
    }
  }
  stats.ConsecutiveFailures = run.Consecutive;
  return true;
}

bool ShapeDistributor::Impl::DecideRound(std::vector<Record>& batch, bool greedy, bool seeding,
  int threads, RunState& run, ShapeDistributionStatistics& stats)
{
  auto clock = std::chrono::steady_clock::now();
  auto lap = [&clock](double& into) {
    const auto now = std::chrono::steady_clock::now();
    into += std::chrono::duration<double>(now - clock).count();
    clock = now;
  };
  const int n = static_cast<int>(batch.size());
  stats.Candidates += n;
  long long charts = 0;
  double chartSeconds = 0.0;
  // (a) Cheap checks against the shapes of previous rounds (no chart needed).
  CheapChecks(batch, threads);
  // (b) Survivors that may conflict with each other.
  std::vector<int> survivors;
  for (int i = 0; i < n; ++i)
  {
    if (!batch[i].Rejected)
    {
      survivors.push_back(i);
    }
  }
  const std::vector<std::vector<int>> above = HigherPriorityNeighbours(batch, survivors, threads);
  if (Poll())
  {
    return false;
  }
  // (c) Waves: a survivor is decided once all its higher-priority neighbours are; it is then
  // checked against every accepted shape (those of this round included) and, if free, gets
  // its charts and is accepted. Candidates of one wave are never neighbours, so this is
  // sequential dart throwing in priority order, with charts only for accepted shapes (and
  // the rare ones a smaller neighbour rejects).
  const int roundStart = static_cast<int>(Accepted.Records.size());
  std::vector<char> state(n, 2); // 0 undecided, 1 accepted, 2 rejected
  for (int i : survivors)
  {
    state[i] = 0;
  }
  std::vector<int> acceptedAs(n, -1); // id in Accepted
  if (seeding)
  {
    PlantSeed(batch, survivors, state, acceptedAs, charts);
  }
  else
  {
    DecideInWaves(batch, survivors, above, state, acceptedAs, threads, run, charts, chartSeconds);
  }
  stats.Charts += charts;
  stats.ChartCpuSeconds += chartSeconds;
  lap(stats.CheckSeconds);
  if (Poll())
  {
    return false; // (the round's decisions were cut short: nothing of it is kept)
  }
  for (int i = 0; i < n; ++i)
  {
    if (state[i] != 1)
    {
      CountRejection(batch[i], stats);
    }
  }
  run.FaithfulFirst = stats.RejectedByFaithfulCheck > run.ChartedThenTables;
  // (d) Priority order: consecutive failures and MaximumShapes may end the run inside the
  // round; shapes after that point are taken back.
  const int cut = CutRound(state, roundStart, greedy, seeding, run, stats);
  TakeBack(roundStart, cut, state, acceptedAs);
  run.AcceptedInRound = static_cast<int>(Accepted.Records.size()) - roundStart;
  lap(stats.RoundSeconds);
  return true;
}

void ShapeDistributor::Impl::CountRejection(const Record& r, ShapeDistributionStatistics& stats)
{
  switch (r.Reason)
  {
    case Record::Rejection::WithoutShape:
      ++stats.RejectedWithoutShape;
      break;
    case Record::Rejection::Tables:
      ++stats.RejectedByTables;
      break;
    case Record::Rejection::Faithful:
      ++stats.RejectedByFaithfulCheck;
      break;
    case Record::Rejection::Drawn:
      ++stats.RejectedByDrawnCheck;
      break;
    case Record::Rejection::None:
    default:
      break;
  }
}

void ShapeDistributor::Impl::DrawGreedyBatch(
  const std::vector<int>& front, int round, int threads, std::vector<Record>& batch) const
{
  // Proposals of every front shape, nearest to the first shape first.
  std::vector<std::vector<Proposal>> proposals(front.size());
  ParallelFor(static_cast<int>(front.size()), threads, 4, [&](int k, int) {
    if (!Poll())
    {
      proposals[k] = Propose(front[k], round, k);
    }
  });
  std::vector<Proposal> all;
  for (const auto& p : proposals)
  {
    all.insert(all.end(), p.begin(), p.end());
  }
  std::stable_sort(all.begin(), all.end(),
    [](const Proposal& a, const Proposal& b) { return a.Key < b.Key; });
  const int n = static_cast<int>(all.size());
  batch.resize(n);
  // (scratch: MakeShape's precheck of long shapes: the same decisions)
  ParallelForEachThread<std::vector<int>>(n, threads, 16, [&](int i, std::vector<int>& scratch) {
    Random rng(Options.Seed, 4, static_cast<std::uint64_t>(round), static_cast<std::uint64_t>(i));
    batch[i].Valid = !Poll() &&
      MakeShape(all[i].Centre, all[i].Class, rng, batch[i].Shape, &all[i].Prefer, &scratch);
    batch[i].Reason = batch[i].Valid ? Record::Rejection::None : Record::Rejection::WithoutShape;
  });
}

bool ShapeDistributor::Impl::DrawRandomBatch(
  int round, bool seeding, RunState& run, std::vector<Record>& batch)
{
  if (Sampling.KilledSinceCdf() > 0)
  {
    Sampling.BuildCdf();
  }
  if (!Sampling.AnyLiveFace())
  {
    return false;
  }
  // Up to 4096: little work past the last failure. Greedy seeds one shape per round.
  const int n = seeding ? (run.RandomRounds == 0 ? 1 : 256) : 256 << std::min(run.RandomRounds, 4);
  ++run.RandomRounds;
  batch.resize(n);
  Generate(batch, round);
  return true;
}

void ShapeDistributor::Impl::CheapChecks(std::vector<Record>& batch, int threads)
{
  const int n = static_cast<int>(batch.size());
  ParallelForEachThread<std::vector<int>>(n, threads, 64, [&](int i, std::vector<int>& scratch) {
    Record& r = batch[i];
    if (Poll())
    {
      r.Rejected = true;
      return;
    }
    r.Rejected = !r.Valid || CheapConflict(r, scratch);
    if (r.Valid && r.Rejected)
    {
      r.Reason = Record::Rejection::Tables;
    }
  });
}

std::vector<std::vector<int>> ShapeDistributor::Impl::HigherPriorityNeighbours(
  const std::vector<Record>& batch, const std::vector<int>& survivors, int threads) const
{
  // Parts closer in space than the sum of their circumradii (the geodesic distance is never
  // shorter), found on a grid of cells as large as the largest such sum.
  std::vector<std::vector<int>> above(batch.size());
  const double cell =
    2.0 * Measures.RMax * Options.ShapeSize * Sampling.MaxFaceDensity * (1.0 + Options.SafetyMargin);
  auto key = [cell](const Vec3& x) {
    return std::array<long long, 3>{ static_cast<long long>(std::floor(x.x / cell)),
      static_cast<long long>(std::floor(x.y / cell)), static_cast<long long>(std::floor(x.z / cell)) };
  };
  std::vector<std::pair<std::array<long long, 3>, int>> grid; // (cell, candidate)
  for (int i : survivors)
  {
    for (const PlacedPart& p : batch[i].Shape.Parts)
    {
      grid.emplace_back(key(p.Position), i);
    }
  }
  std::sort(grid.begin(), grid.end());
  grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
  ParallelFor(static_cast<int>(survivors.size()), threads, 64, [&](int k, int) {
    const int i = survivors[k];
    const Record& r = batch[i];
    std::vector<int>& list = above[i];
    for (const PlacedPart& p : r.Shape.Parts)
    {
      const std::array<long long, 3> c = key(p.Position);
      for (long long dx = -1; dx <= 1; ++dx)
        for (long long dy = -1; dy <= 1; ++dy)
          for (long long dz = -1; dz <= 1; ++dz)
          {
            const std::array<long long, 3> q{ c[0] + dx, c[1] + dy, c[2] + dz };
            auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(q, -1));
            for (; it != grid.end() && it->first == q && it->second < i; ++it)
            {
              const Record& o = batch[it->second];
              const double unit = Options.ShapeSize * std::max(r.Shape.Scale, o.Shape.Scale) *
                (1.0 + Options.SafetyMargin);
              for (const PlacedPart& op : o.Shape.Parts)
              {
                if (Norm(op.Position - p.Position) <=
                  (PartRadius(p.Part) + PartRadius(op.Part)) * unit * (1.0 + 1e-9))
                {
                  list.push_back(it->second);
                  break;
                }
              }
            }
          }
    }
    SortUnique(list);
  });
  return above;
}

void ShapeDistributor::Impl::PlantSeed(std::vector<Record>& batch, const std::vector<int>& survivors,
  std::vector<char>& state, std::vector<int>& acceptedAs, long long& charts)
{
  // Greedy seeds one shape per random round: the first survivor that fits, in order (decided
  // as every candidate is, Decide).
  DecisionScratch scratch;
  for (int i : survivors)
  {
    Record& r = batch[i];
    if (Poll())
    {
      break;
    }
    if (!Decide(r, 0, false, false, scratch))
    {
      state[i] = 2;
      continue;
    }
    state[i] = 1;
    acceptedAs[i] = static_cast<int>(Accepted.Records.size());
    Commit(std::move(r));
    break;
  }
  charts += scratch.Charts;
  for (int i : survivors)
  {
    state[i] = state[i] == 0 ? 2 : state[i]; // after the seed: beyond the cut below
  }
}

bool ShapeDistributor::Impl::Decide(
  Record& r, int thread, bool recheck, bool faithfulFirst, DecisionScratch& s)
{
  r.Rejected = true;
  if (recheck && CheapConflict(r, s.Conflicts))
  {
    r.Reason = Record::Rejection::Tables;
    return false;
  }
  // (A long shape: always before its charts; a short one where that saves charts.)
  if ((!r.Shape.Curve.empty() || faithfulFirst) && Unfaithful(r))
  {
    r.Reason = Record::Rejection::Faithful;
    return false;
  }
  if (r.Charts.empty())
  {
    const auto chartStart = std::chrono::steady_clock::now();
    ComputeCharts(r, *PerThread.Engines[thread]);
    s.ChartSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - chartStart).count();
    ++s.Charts;
  }
  if (r.FaithfulChecked && r.Shape.Curve.empty() && (r.Charts.empty() || r.Charts[0].Entries.empty()))
  {
    // (Checked before its charts: read through charts that came out empty, the check
    // would have failed, as it does when it runs after them.)
    r.Reason = Record::Rejection::Faithful;
    r.Charts.clear();
    return false;
  }
  if (FullConflict(r, s.Conflicts))
  {
    r.Reason = Record::Rejection::Tables;
    ++s.TablesAfterCharts;
  }
  if (r.Reason == Record::Rejection::Tables || DrawnConflict(r, s.Conflicts))
  {
    r.Charts.clear();
    return false;
  }
  r.Rejected = false;
  PrepareCommit(r, PerThread.Marks[thread], s.Marked);
  return true;
}

void ShapeDistributor::Impl::DecideInWaves(std::vector<Record>& batch, const std::vector<int>& survivors,
  const std::vector<std::vector<int>>& above, std::vector<char>& state, std::vector<int>& acceptedAs,
  int threads, RunState& run, long long& chartCount, double& chartCpuSeconds)
{
  long long charts = 0;
  double chartSeconds = 0.0;
  std::vector<int> undecided = survivors, ready, waiting;
  while (!undecided.empty() && !Poll())
  {
    ready.clear();
    waiting.clear();
    for (int i : undecided)
    {
      bool free = true;
      for (int j : above[i])
      {
        free = free && state[j] != 0;
      }
      (free ? ready : waiting).push_back(i);
    }
    const int nr = static_cast<int>(ready.size());
    // Chunks down to one candidate: a chart costs about 0.6 ms, and waves are often short (a
    // chunk of 4 left one thread idle for up to 3 charts).
    std::vector<DecisionScratch> perThread(threads);
    ParallelFor(nr, threads, 1, [&](int k, int thread) {
      Record& r = batch[ready[k]];
      if (Poll())
      {
        r.Rejected = true;
        return;
      }
      bool recheck = false;
      for (int j : above[ready[k]])
      {
        recheck = recheck || state[j] == 1;
      }
      Decide(r, thread, recheck, run.FaithfulFirst, perThread[thread]);
    });
    for (const DecisionScratch& s : perThread)
    {
      charts += s.Charts;
      chartSeconds += s.ChartSeconds;
      run.ChartedThenTables += s.TablesAfterCharts;
    }
    for (int i : ready) // priority order
    {
      if (batch[i].Rejected)
      {
        state[i] = 2;
        continue;
      }
      state[i] = 1;
      acceptedAs[i] = static_cast<int>(Accepted.Records.size());
      Commit(std::move(batch[i]));
    }
    undecided.swap(waiting);
  }
  chartCount += charts;
  chartCpuSeconds += chartSeconds;
}

int ShapeDistributor::Impl::CutRound(const std::vector<char>& state, int roundStart, bool greedy,
  bool seeding, RunState& run, ShapeDistributionStatistics& stats) const
{
  const int n = static_cast<int>(state.size());
  int cut = n;
  int total = roundStart;
  for (int i = 0; i < n; ++i)
  {
    if (state[i] != 1)
    {
      ++run.Consecutive;
      if (run.Consecutive >= run.FailuresToStop && !greedy)
      {
        run.Stop = true;
        stats.Maximal = true;
        cut = i + 1;
        break;
      }
      continue;
    }
    run.Consecutive = 0;
    ++total;
    if (Options.MaximumShapes > 0 && total >= Options.MaximumShapes)
    {
      run.Stop = true;
      cut = i + 1;
      break;
    }
    if (seeding)
    {
      cut = i + 1; // Greedy: one random seed, then its front grows
      break;
    }
  }
  return cut;
}

void ShapeDistributor::Impl::TakeBack(
  int roundStart, int cut, const std::vector<char>& state, const std::vector<int>& acceptedAs)
{
  const int n = static_cast<int>(state.size());
  bool takeBack = false;
  for (int i = cut; i < n; ++i)
  {
    takeBack = takeBack || state[i] == 1;
  }
  if (!takeBack)
  {
    return;
  }
  std::vector<std::pair<int, Record>> kept; // (priority, record)
  while (static_cast<int>(Accepted.Records.size()) > roundStart)
  {
    const int id = static_cast<int>(Accepted.Records.size()) - 1;
    int i = 0;
    while (acceptedAs[i] != id)
    {
      ++i;
    }
    Record r = Uncommit();
    if (i < cut)
    {
      kept.emplace_back(i, std::move(r));
    }
  }
  std::sort(kept.begin(), kept.end(),
    [](const std::pair<int, Record>& a, const std::pair<int, Record>& b) { return a.first < b.first; });
  for (auto& k : kept)
  {
    Commit(std::move(k.second));
  }
}

} // namespace gs
