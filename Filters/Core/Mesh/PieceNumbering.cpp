#include "PieceNumbering.h"

#include "PositionKey.h"

#include <algorithm>
#include <limits>
#include <string>
#include <unordered_map>

namespace gs
{

namespace
{
// What a process offers for a position: where its triangles first use it, and the gathered
// index of the point they use there.
struct Offer
{
  int Rank;
  std::int64_t FirstUse;
  std::int64_t Index;
  bool Beats(const Offer& o) const
  {
    return Rank < o.Rank || (Rank == o.Rank && FirstUse < o.FirstUse);
  }
};

// Every process's counts of points and triangles: the exclusive prefix sums at this rank, and
// the total of points.
void Offsets(std::int64_t points, std::int64_t triangles, PieceCommunicator& comm,
  std::int64_t& firstPoint, std::int64_t& firstTriangle, std::int64_t& totalPoints)
{
  std::vector<ByteBuffer> out(static_cast<std::size_t>(comm.Size())), in;
  for (ByteBuffer& b : out)
  {
    ByteWriter w(b);
    w.Put(points);
    w.Put(triangles);
  }
  comm.Exchange(out, in);
  firstPoint = firstTriangle = totalPoints = 0;
  for (int q = 0; q < comm.Size(); ++q)
  {
    std::int64_t p = points, t = triangles;
    if (q != comm.Rank())
    {
      ByteReader r(in[static_cast<std::size_t>(q)]);
      r.Get(p);
      r.Get(t);
    }
    if (q < comm.Rank())
    {
      firstPoint += p;
      firstTriangle += t;
    }
    totalPoints += p;
  }
}
} // namespace

Status NumberAsGathered(const std::vector<Vec3>& points,
  const std::vector<std::array<int, 3>>& triangles, PieceCommunicator& comm,
  GatheredNumbering& numbering)
{
  numbering = GatheredNumbering();
  const std::size_t np = points.size();
  std::string problem;
  for (std::size_t t = 0; t < triangles.size() && problem.empty(); ++t)
  {
    for (const int k : triangles[t])
    {
      if (k < 0 || static_cast<std::size_t>(k) >= np)
      {
        problem = "triangle " + std::to_string(t) + " of process " +
          std::to_string(comm.Rank()) + " uses a point that is not in its piece";
        break;
      }
    }
  }
  std::string first;
  if (FirstMessage(comm, problem, first) >= 0)
  {
    return Status::Error(first);
  }
  std::int64_t firstTriangle = 0;
  Offsets(static_cast<std::int64_t>(np), static_cast<std::int64_t>(triangles.size()), comm,
    numbering.FirstPoint, firstTriangle, numbering.TotalPoints);
  numbering.TriangleIds.resize(triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    numbering.TriangleIds[t] = firstTriangle + static_cast<std::int64_t>(t);
  }

  // This process's distinct positions, in the order its triangles first use them, each with the
  // point used there (its own welding).
  std::unordered_map<PositionKey, int, PositionKey::Hasher> groupOf;
  std::vector<int> group(np, -1);
  std::vector<Offer> offers;
  std::vector<PositionKey> keys;
  for (std::size_t t = 0; t < triangles.size(); ++t)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int p = triangles[t][static_cast<std::size_t>(k)];
      if (group[static_cast<std::size_t>(p)] >= 0)
      {
        continue;
      }
      const PositionKey key = PositionKey::Of(points[static_cast<std::size_t>(p)]);
      const auto [it, added] = groupOf.emplace(key, static_cast<int>(offers.size()));
      if (added)
      {
        offers.push_back({ comm.Rank(), static_cast<std::int64_t>(3 * t) + k,
          numbering.FirstPoint + p });
        keys.push_back(key);
      }
      group[static_cast<std::size_t>(p)] = it->second;
    }
  }

  // Each position to the process its hash names; the answer is the winner's gathered index.
  const std::size_t size = static_cast<std::size_t>(comm.Size());
  std::vector<ByteBuffer> asks(size), asked, answers(size), answered;
  std::vector<std::vector<int>> sentTo(size);
  for (std::size_t g = 0; g < offers.size(); ++g)
  {
    const std::size_t to = keys[g].Hash() % size;
    ByteWriter w(asks[to]);
    w.Put(keys[g]);
    w.Put(offers[g].FirstUse);
    w.Put(offers[g].Index);
    sentTo[to].push_back(static_cast<int>(g));
  }
  comm.Exchange(asks, asked);
  asked[static_cast<std::size_t>(comm.Rank())] = asks[static_cast<std::size_t>(comm.Rank())];
  std::unordered_map<PositionKey, Offer, PositionKey::Hasher> best;
  for (int pass = 0; pass < 2; ++pass)
  {
    for (std::size_t q = 0; q < size; ++q)
    {
      ByteReader r(asked[q]);
      ByteWriter w(answers[q]);
      PositionKey key{};
      Offer offer{ static_cast<int>(q), 0, 0 };
      while (r.Get(key) && r.Get(offer.FirstUse) && r.Get(offer.Index))
      {
        if (pass == 0)
        {
          const auto [it, added] = best.emplace(key, offer);
          if (!added && offer.Beats(it->second))
          {
            it->second = offer;
          }
        }
        else
        {
          w.Put(best.at(key).Index);
        }
      }
    }
  }
  comm.Exchange(answers, answered);
  answered[static_cast<std::size_t>(comm.Rank())] = answers[static_cast<std::size_t>(comm.Rank())];
  std::vector<std::int64_t> winner(offers.size(), -1);
  for (std::size_t q = 0; q < size; ++q)
  {
    ByteReader r(answered[q]);
    for (const int g : sentTo[q])
    {
      r.Get(winner[static_cast<std::size_t>(g)]);
    }
  }
  numbering.PointIds.assign(np, -1);
  for (std::size_t p = 0; p < np; ++p)
  {
    if (group[p] >= 0)
    {
      numbering.PointIds[p] = winner[static_cast<std::size_t>(group[p])];
    }
  }
  return Status();
}

std::int64_t GatheredPointId(const std::vector<std::int64_t>& pointIds, std::int64_t firstPoint,
  std::int64_t index, PieceCommunicator& comm)
{
  const std::int64_t local = index - firstPoint;
  const bool mine = local >= 0 && local < static_cast<std::int64_t>(pointIds.size());
  const double id = mine ? static_cast<double>(pointIds[static_cast<std::size_t>(local)]) : -1.0;
  return static_cast<std::int64_t>(comm.Max(id));
}

} // namespace gs
