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

ShapeDistributionResult ShapeDistributor::Run(const SafeDistanceTables& tables,
  const std::vector<Vec3>& faceDirections, const std::vector<double>& vertexDensity,
  const ShapeDistributionOptions& options, const std::function<bool(double)>& progress)
{
  const auto start = std::chrono::steady_clock::now();
  ShapeDistributionResult result;
  Impl& I = *P;
  result.Error = I.Prepare(tables, faceDirections, vertexDensity, options);
  if (!result.Error.empty())
  {
    I.Accepted.clear();
    I.Placed.clear();
    return result;
  }
  const ShapeDistributionOptions& O = I.O;
  const int threads = ThreadCount(O.NumberOfThreads);
  I.EnsureEngines(threads);
  result.Statistics.PrepareSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long long failuresToStop = O.MaximalFailures > 0 ? O.MaximalFailures : 10000;
  const bool greedyMode = O.Mode == DistributionMode::Greedy;
  std::vector<int> front;
  bool seedsGrow = true;          // Greedy: random rounds plant one seed each
  long long seeds = 0, grownSinceSeed = 0;
  long long consecutive = 0;
  int randomRounds = 0;
  bool stop = false;
  double reported = 0.0;
  ShapeDistributionStatistics& stats = result.Statistics;
  for (int round = 0; !stop; ++round)
  {
    const bool greedy = greedyMode && !front.empty();
    const bool seeding = greedyMode && !greedy && seedsGrow;
    auto clock = std::chrono::steady_clock::now();
    auto lap = [&clock](double& into) {
      const auto now = std::chrono::steady_clock::now();
      into += std::chrono::duration<double>(now - clock).count();
      clock = now;
    };
    std::vector<Impl::Record> batch;
    int n;
    if (greedy)
    {
      // Proposals of every front shape, nearest to the first shape first.
      std::vector<std::vector<Impl::Proposal>> proposals(front.size());
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
      for (int k = 0; k < static_cast<int>(front.size()); ++k)
      {
        proposals[k] = I.Propose(front[k], round, k);
      }
      std::vector<Impl::Proposal> all;
      for (const auto& p : proposals)
      {
        all.insert(all.end(), p.begin(), p.end());
      }
      std::stable_sort(all.begin(), all.end(),
        [](const Impl::Proposal& a, const Impl::Proposal& b) { return a.Key < b.Key; });
      n = static_cast<int>(all.size());
      batch.resize(n);
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
      for (int i = 0; i < n; ++i)
      {
        Random rng(O.Seed, 4, static_cast<std::uint64_t>(round), static_cast<std::uint64_t>(i));
        batch[i].Valid = I.MakeShape(all[i].Centre, all[i].Class, rng, batch[i].S, &all[i].Prefer);
      }
    }
    else
    {
      if (I.DeadSinceCdf > 0)
      {
        I.BuildCdf();
      }
      if (!I.AnyLiveFace())
      {
        stats.Maximal = true; // no face left where a shape could fit
        break;
      }
      // Up to 4096: little work past the last failure. Greedy seeds one shape per round.
      n = seeding ? (randomRounds == 0 ? 1 : 256) : 256 << std::min(randomRounds, 4);
      ++randomRounds;
      batch.resize(n);
      I.Generate(batch, round);
    }
    lap(stats.GenerateSeconds);
    stats.Candidates += n;
    long long charts = 0;
    double chartSeconds = 0.0;
    // (a) Cheap checks against the shapes of previous rounds (no chart needed).
#pragma omp parallel num_threads(threads)
    {
      std::vector<int> scratch;
#pragma omp for schedule(dynamic, 64)
      for (int i = 0; i < n; ++i)
      {
        Impl::Record& r = batch[i];
        r.Rejected = !r.Valid || I.CheapConflict(r, scratch);
      }
    }
    // (b) Survivors that may conflict with each other: parts closer in space than the sum of
    // their circumradii (the geodesic distance is never shorter). Each keeps its
    // higher-priority neighbours.
    std::vector<int> survivors;
    for (int i = 0; i < n; ++i)
    {
      if (!batch[i].Rejected)
      {
        survivors.push_back(i);
      }
    }
    std::vector<std::vector<int>> above(n);
    {
      const double cell = 2.0 * I.RMax * O.ShapeSize * I.MaxFaceDensity * (1.0 + O.SafetyMargin);
      auto key = [cell](const Vec3& x) {
        return std::array<long long, 3>{ static_cast<long long>(std::floor(x.x / cell)),
          static_cast<long long>(std::floor(x.y / cell)), static_cast<long long>(std::floor(x.z / cell)) };
      };
      std::vector<std::pair<std::array<long long, 3>, int>> grid; // (cell, candidate)
      for (int i : survivors)
      {
        for (const PlacedPart& p : batch[i].S.Parts)
        {
          grid.emplace_back(key(p.Position), i);
        }
      }
      std::sort(grid.begin(), grid.end());
      grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
      for (std::size_t k = 0; k < survivors.size(); ++k)
      {
        const int i = survivors[k];
        const Impl::Record& r = batch[i];
        std::vector<int>& list = above[i];
        for (const PlacedPart& p : r.S.Parts)
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
                  const Impl::Record& o = batch[it->second];
                  const double unit = O.ShapeSize * std::max(r.S.Scale, o.S.Scale) * (1.0 + O.SafetyMargin);
                  for (const PlacedPart& op : o.S.Parts)
                  {
                    if (Norm(op.Position - p.Position) <=
                      (I.PartRadius(p.Part) + I.PartRadius(op.Part)) * unit * (1.0 + 1e-9))
                    {
                      list.push_back(it->second);
                      break;
                    }
                  }
                }
              }
        }
        SortUnique(list);
      }
    }
    // (c) Waves: a survivor is decided once all its higher-priority neighbours are; it is then
    // checked against every accepted shape (those of this round included) and, if free, gets
    // its charts and is accepted. Candidates of one wave are never neighbours, so this is
    // sequential dart throwing in priority order, with charts only for accepted shapes (and
    // the rare ones a smaller neighbour rejects).
    const int roundStart = static_cast<int>(I.Accepted.size());
    std::vector<char> state(n, 2); // 0 undecided, 1 accepted, 2 rejected
    for (int i : survivors)
    {
      state[i] = 0;
    }
    std::vector<int> acceptedAs(n, -1); // id in I.Accepted
    std::vector<int> undecided = survivors, ready, waiting;
    if (seeding)
    {
      // Greedy seeds one shape per random round: the first survivor that fits, in order.
      std::vector<int> scratch;
      for (int i : survivors)
      {
        Impl::Record& r = batch[i];
        I.ComputeCharts(r, I.Engine0());
        ++charts;
        if (I.FullConflict(r, scratch) || I.DrawnConflict(r, scratch))
        {
          state[i] = 2;
          continue;
        }
        state[i] = 1;
        acceptedAs[i] = static_cast<int>(I.Accepted.size());
        I.Commit(std::move(r));
        break;
      }
      for (int i : survivors)
      {
        state[i] = state[i] == 0 ? 2 : state[i]; // after the seed: beyond the cut below
      }
      undecided.clear();
    }
    while (!undecided.empty())
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
#pragma omp parallel num_threads(threads) reduction(+ : charts, chartSeconds)
      {
        std::vector<int> scratch, marked;
        // One candidate at a time: a chart costs about 0.6 ms, and waves are often short (a
        // chunk of 4 left one thread idle for up to 3 charts).
#pragma omp for schedule(dynamic, 1)
        for (int k = 0; k < nr; ++k)
        {
          Impl::Record& r = batch[ready[k]];
          bool recheck = false;
          for (int j : above[ready[k]])
          {
            recheck = recheck || state[j] == 1;
          }
          if (recheck && I.CheapConflict(r, scratch))
          {
            r.Rejected = true;
            continue;
          }
          const auto chartStart = std::chrono::steady_clock::now();
          I.ComputeCharts(r, I.Engine());
          chartSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - chartStart).count();
          ++charts;
          if (I.FullConflict(r, scratch) || I.DrawnConflict(r, scratch))
          {
            r.Rejected = true;
            r.Charts.clear();
            continue;
          }
          I.PrepareCommit(r, I.Marks[ThreadId()], marked);
        }
      }
      for (int i : ready) // priority order
      {
        if (batch[i].Rejected)
        {
          state[i] = 2;
          continue;
        }
        state[i] = 1;
        acceptedAs[i] = static_cast<int>(I.Accepted.size());
        I.Commit(std::move(batch[i]));
      }
      undecided.swap(waiting);
    }
    stats.Charts += charts;
    stats.ChartCpuSeconds += chartSeconds;
    lap(stats.CheckSeconds);
    // (d) Priority order: consecutive failures and MaximumShapes may end the run inside the
    // round; shapes after that point are taken back.
    int cut = n;
    int total = roundStart;
    for (int i = 0; i < n; ++i)
    {
      if (state[i] != 1)
      {
        ++consecutive;
        if (consecutive >= failuresToStop && !greedy)
        {
          stop = true;
          stats.Maximal = true;
          cut = i + 1;
          break;
        }
        continue;
      }
      consecutive = 0;
      ++total;
      if (O.MaximumShapes > 0 && total >= O.MaximumShapes)
      {
        stop = true;
        cut = i + 1;
        break;
      }
      if (seeding)
      {
        cut = i + 1; // Greedy: one random seed, then its front grows
        break;
      }
    }
    bool takeBack = false;
    for (int i = cut; i < n; ++i)
    {
      takeBack = takeBack || state[i] == 1;
    }
    std::vector<int> nextFront;
    if (takeBack)
    {
      std::vector<std::pair<int, Impl::Record>> kept; // (priority, record)
      while (static_cast<int>(I.Accepted.size()) > roundStart)
      {
        const int id = static_cast<int>(I.Accepted.size()) - 1;
        int i = 0;
        while (acceptedAs[i] != id)
        {
          ++i;
        }
        Impl::Record r = I.Uncommit();
        if (i < cut)
        {
          kept.emplace_back(i, std::move(r));
        }
      }
      std::sort(kept.begin(), kept.end(),
        [](const std::pair<int, Impl::Record>& a, const std::pair<int, Impl::Record>& b) { return a.first < b.first; });
      for (auto& k : kept)
      {
        I.Commit(std::move(k.second));
      }
    }
    for (int id = roundStart; id < static_cast<int>(I.Accepted.size()); ++id)
    {
      nextFront.push_back(id);
    }
    if (greedyMode)
    {
      // A seed whose front cannot grow at all: the gaps left hold single shapes, which plain
      // dart throwing fills (one seed per round would cost a whole round per gap).
      if (greedy)
      {
        grownSinceSeed += static_cast<long long>(nextFront.size());
      }
      else if (seeding)
      {
        if (seeds > 0 && grownSinceSeed == 0)
        {
          seedsGrow = false;
        }
        ++seeds;
        grownSinceSeed = 0;
      }
      front.swap(nextFront);
    }
    lap(stats.RoundSeconds);
    stats.Rounds = round + 1;
    double fraction = static_cast<double>(consecutive) / static_cast<double>(failuresToStop);
    if (O.MaximumShapes > 0)
    {
      fraction = std::max(fraction, static_cast<double>(I.Accepted.size()) / O.MaximumShapes);
    }
    reported = std::max(reported, std::min(0.99, fraction));
    if (progress && !progress(reported))
    {
      result.Error = "aborted";
      I.Accepted.clear();
      I.Placed.clear();
      return result;
    }
  }
  stats.ConsecutiveFailures = consecutive;
  stats.Seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.Shapes = I.Placed;
  result.Ok = true;
  if (progress)
  {
    progress(1.0);
  }
  return result;
}

} // namespace gs
