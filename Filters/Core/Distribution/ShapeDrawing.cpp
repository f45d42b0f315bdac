#include "ShapeDrawing.h"

#include "ParallelFor.h"
#include "PhasePoll.h"

#include <chrono>

namespace gs
{


std::vector<ShapeDecal> DrawDecals(const ShapeDistributor& distributor, double tolerance,
  int numberOfThreads, std::vector<double>* seconds, const std::function<bool(double)>& progress)
{
  const int ns = static_cast<int>(distributor.Shapes().size());
  std::vector<ShapeDecal> decals(ns);
  if (seconds)
  {
    seconds->assign(ns, 0.0);
  }
  const int threads = ThreadCount(numberOfThreads);
  PhasePoll poll(progress, ns);
  ParallelFor(ns, threads, 4, [&](int s, int) {
    if (poll.Skip(s))
    {
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    decals[s] = distributor.Decal(s, tolerance);
    if (seconds)
    {
      (*seconds)[s] =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  });
  return decals;
}

std::vector<std::vector<OutlinePiece>> DrawOutlines(
  const ShapeDistributor& distributor, int numberOfThreads, const std::function<bool(double)>& progress)
{
  const int ns = static_cast<int>(distributor.Shapes().size());
  std::vector<std::vector<OutlinePiece>> outlines(ns);
  const double spacing = distributor.OutlineSpacing();
  const int threads = ThreadCount(numberOfThreads);
  PhasePoll poll(progress, ns);
  ParallelFor(ns, threads, 4, [&](int s, int) {
    if (!poll.Skip(s))
    {
      outlines[s] = distributor.Outline(s, spacing);
    }
  });
  return outlines;
}

} // namespace gs
