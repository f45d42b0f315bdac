// Measurements of a Shape Distributor run that tests and benchmarks make through the
// distributor's test seam (ShapeDistributorInspector, a friend): not part of the core's API.
#pragma once

#include "ShapeDistributor.h"

#include <cstdint>

namespace gs
{
struct ShapeDistributorInspector
{
  /// The distributor's private state, for the unit tests of its owners (they include
  /// ShapeDistributorImpl.h).
  using Impl = ShapeDistributor::Impl;
  static double ProbeFitFraction(ShapeDistributor& d, int probes, std::uint64_t seed);
};
} // namespace gs

namespace gs_test
{
/// After Run: the fraction of `probes` random candidates (drawn like the run's, with
/// field-aligned orientation, from `seed`) that would fit among the placed shapes: how close to
/// maximal the run is (MaximalFailures).
double ProbeFitFraction(gs::ShapeDistributor& d, int probes, std::uint64_t seed);
} // namespace gs_test
