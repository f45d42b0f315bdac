#include "DistributorProbes.h"

#include "ShapeDistributorImpl.h"

namespace gs
{

double ShapeDistributorInspector::ProbeFitFraction(
  ShapeDistributor& d, int probes, std::uint64_t seed)
{
  ShapeDistributor::Impl& I = *d.Internal;
  if (probes <= 0 || I.Sampling.AllCdf.empty())
  {
    return 0.0;
  }
  const int threads = ThreadCount(I.Options.NumberOfThreads);
  I.EnsureEngines(threads);
  struct Scratch
  {
    std::vector<int> Conflicts;
    long long Fits = 0;
  };
  std::vector<Scratch> perThread(threads);
  ParallelFor(probes, threads, 64, [&](int i, int thread) {
    Scratch& s = perThread[thread];
    distribution::Random rng(seed, 3, 0, static_cast<std::uint64_t>(i));
    ShapeDistributor::Impl::Record r;
    r.Key = ~std::uint64_t(0); // (judged by every accepted shape)
    const int cls = I.Sampling.RandomClass(rng);
    const SurfacePoint centre = I.Sampling.RandomPoint(rng, false);
    if (!I.MakeShape(centre, cls, rng, r.Shape, nullptr, &s.Conflicts, r.Key) ||
      I.CheapConflict(r, s.Conflicts))
    {
      return;
    }
    I.ComputeCharts(r, I.Engine(thread));
    if (!I.FullConflict(r, s.Conflicts) && !I.DrawnConflict(r, s.Conflicts))
    {
      ++s.Fits;
    }
  });
  long long fits = 0;
  for (const Scratch& s : perThread)
  {
    fits += s.Fits;
  }
  return static_cast<double>(fits) / probes;
}

} // namespace gs

namespace gs_test
{

double ProbeFitFraction(gs::ShapeDistributor& d, int probes, std::uint64_t seed)
{
  return gs::ShapeDistributorInspector::ProbeFitFraction(d, probes, seed);
}

} // namespace gs_test
