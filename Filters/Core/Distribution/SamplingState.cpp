#include "SamplingState.h"

#include <algorithm>

namespace gs
{
namespace distribution
{

void SamplingState::Reset(int faces, int classes)
{
  Dead.assign(faces, 0);
  DeadFor.assign(static_cast<std::size_t>(classes) * faces, 0);
  Killed.clear();
  KilledBy.clear();
}

void SamplingState::BuildCdf()
{
  const int nf = NumberOfFaces();
  FaceCdf.assign(nf, 0.0);
  double total = 0.0;
  for (int f = 0; f < nf; ++f)
  {
    total += Dead[f] ? 0.0 : FaceWeight[f];
    FaceCdf[f] = total;
  }
  DeadSinceCdf = 0;
}

SurfacePoint SamplingState::RandomPoint(Random& rng, bool live) const
{
  const std::vector<double>& cdf = live ? FaceCdf : AllCdf;
  const double u = rng.Uniform() * cdf.back();
  int f = static_cast<int>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
  f = std::min(f, static_cast<int>(cdf.size()) - 1);
  while (f > 0 && cdf[f] == cdf[f - 1])
  {
    --f; // never a zero-weight face
  }
  double a = rng.Uniform(), b = rng.Uniform();
  if (a + b > 1.0)
  {
    a = 1.0 - a;
    b = 1.0 - b;
  }
  return SurfacePoint::InFace(f, 1.0 - a - b, a, b);
}

int SamplingState::RandomClass(Random& rng) const
{
  const double u = rng.Uniform() * ClassCdf.back();
  int k = static_cast<int>(std::upper_bound(ClassCdf.begin(), ClassCdf.end(), u) - ClassCdf.begin());
  k = std::min(k, static_cast<int>(ClassCdf.size()) - 1);
  while (k > 0 && ClassCdf[k] == ClassCdf[k - 1])
  {
    --k;
  }
  return k;
}

void SamplingState::Kill(const std::vector<std::pair<int, int>>& kills)
{
  const std::size_t nf = Dead.size();
  const int nc = static_cast<int>(ClassCdf.size());
  for (const auto& cf : kills)
  {
    const int c = cf.first, f = cf.second;
    char& dead = DeadFor[static_cast<std::size_t>(c) * nf + f];
    if (dead)
    {
      continue;
    }
    dead = 1;
    Killed.emplace_back(c, f);
    bool all = true;
    for (int o = 0; o < nc && all; ++o)
    {
      all = !(ClassCdf[o] > (o > 0 ? ClassCdf[o - 1] : 0.0)) || DeadFor[static_cast<std::size_t>(o) * nf + f];
    }
    if (all && !Dead[f])
    {
      Dead[f] = 1;
      Killed.emplace_back(-1, f);
      ++DeadSinceCdf;
    }
  }
}

void SamplingState::ReviveLast()
{
  const std::size_t nf = Dead.size();
  for (std::size_t k = KilledBy.back(); k < Killed.size(); ++k)
  {
    if (Killed[k].first < 0)
    {
      Dead[Killed[k].second] = 0;
    }
    else
    {
      DeadFor[static_cast<std::size_t>(Killed[k].first) * nf + Killed[k].second] = 0;
    }
  }
  Killed.resize(KilledBy.back());
  KilledBy.pop_back();
  DeadSinceCdf += 1;
}

} // namespace distribution
} // namespace gs
