// The unfolding refinement of PieceDistanceSolver: SVGGeodesicSolver::Refine's sweep on a
// surface partitioned over processes, with the same kernel (StencilUnfolding.h) and so the same
// bits. The serial sweep refines vertices in order of their sort keys, each reading the refined
// distances of its stencil neighbours of smaller keys and the graph distances of the others:
// that is a dependency graph without cycles, which the processes work through by rounds. Each
// process refines every owned vertex whose smaller-key neighbours are refined, sends the refined
// distances other processes' stencils read, and receives theirs; a global sum of the vertices
// left ends the rounds (each round refines at least the smallest key left anywhere).
#include "GraphPieces.h"

#include "StencilUnfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();
} // namespace

// The sweep's state: graph and refined distances of the owned vertices and of the other
// processes' vertices the stencils read (remote slots), and who waits for whom.
struct PieceDistanceSolver::Sweep
{
  const PieceGraph& Graph;
  std::vector<double> GraphDist, Refined;   // owned (Refined: NaN until refined)
  std::vector<double> RemoteGraph, RemoteRefined; // remote slots
  std::vector<int> PredIndex;               // the predecessor's place in the stencil (-1: none)
  double FloorFraction = 0.0;

  // StencilUnfolding's view of the per-vertex state (distances only: no angles).
  double GraphDistance(int x) const { return GraphDist[static_cast<std::size_t>(x)]; }
  int Predecessor(int) const { return -1; }
  int PredecessorStencilIndex(int x) const { return PredIndex[static_cast<std::size_t>(x)]; }
  bool Interior(int x) const { return Graph.IsInterior(x); }
  double Angle(int) const { return std::numeric_limits<double>::quiet_NaN(); }
  double AnglePeriod() const { return 0.0; }
  double Floor() const { return FloorFraction; }

  double GraphOf(int code) const
  {
    return code >= 0 ? GraphDist[static_cast<std::size_t>(code)]
                     : RemoteGraph[static_cast<std::size_t>(-1 - code)];
  }
  double RefinedOf(int code) const
  {
    return code >= 0 ? Refined[static_cast<std::size_t>(code)]
                     : RemoteRefined[static_cast<std::size_t>(-1 - code)];
  }
};

// The sweep's steps.
struct PieceDistanceSolver::SweepRounds
{
  SweepRounds(Sweep& sweep, PieceCommunicator& comm, const std::vector<std::int64_t>& pred)
    : S(sweep)
    , Comm(comm)
    , Pred(pred)
  {
  }
  Sweep& S;
  PieceCommunicator& Comm;
  const std::vector<std::int64_t>& Pred;
  std::vector<std::pair<int, int>> Subscribers; // (owned vertex, rank reading it), sorted
  std::vector<std::uint32_t> Key;
  std::vector<unsigned char> Exact;
  std::vector<int> Waiting, Ready;
  std::vector<std::int64_t> DependentOffsets; // by neighbour (owned, then remote slots)
  std::vector<int> Dependents;
  std::int64_t Left = 0;

  // The graph distances of the remote vertices the stencils read, from their owners, who note
  // who reads which of their vertices (the subscribers of its refined distance).
  void ReadRemoteGraphDistances()
  {
    const PieceGraph& graph = S.Graph;
    const std::size_t n = S.GraphDist.size(), remotes = S.RemoteGraph.size();
    const std::size_t size = static_cast<std::size_t>(Comm.Size());
    std::vector<unsigned char> read(remotes, 0);
    for (std::size_t x = 0; x < n; ++x)
    {
      for (std::int64_t e = graph.StencilBegin(static_cast<int>(x));
           e < graph.StencilEnd(static_cast<int>(x)); ++e)
      {
        if (graph.StencilTarget(e) < 0)
        {
          read[static_cast<std::size_t>(-1 - graph.StencilTarget(e))] = 1;
        }
      }
    }
    std::vector<std::vector<std::int64_t>> asks(size);
    std::vector<std::vector<std::size_t>> slots(size);
    for (std::size_t r = 0; r < remotes; ++r)
    {
      if (read[r])
      {
        const std::size_t owner = static_cast<std::size_t>(graph.RemoteOwner(static_cast<int>(r)));
        asks[owner].push_back(graph.RemoteId(static_cast<int>(r)));
        slots[owner].push_back(r);
      }
    }
    const std::vector<std::vector<double>> answers =
      AskProcesses(Comm, asks, [this, &graph](int q, std::int64_t id) {
        const int i = graph.OwnedIndex(id);
        if (i >= 0)
        {
          Subscribers.push_back({ i, q });
        }
        return i >= 0 ? S.GraphDist[static_cast<std::size_t>(i)] : Inf;
      });
    std::sort(Subscribers.begin(), Subscribers.end());
    for (std::size_t q = 0; q < size; ++q)
    {
      for (std::size_t k = 0; k < slots[q].size() && k < answers[q].size(); ++k)
      {
        S.RemoteGraph[slots[q][k]] = answers[q][k];
      }
    }
  }

  // Each reached vertex waits for its stencil neighbours of smaller keys (its dependencies,
  // counted, then listed by neighbour: owned numbers, then remote slots after the owned); the
  // predecessors' places in the stencils.
  void FindDependencies(const std::vector<int>& seeds)
  {
    const PieceGraph& graph = S.Graph;
    const std::size_t n = S.GraphDist.size();
    Key.resize(n);
    Exact.assign(n, 0);
    Waiting.assign(n, 0);
    for (std::size_t x = 0; x < n; ++x)
    {
      Key[x] = unfolding::SortKey(S.GraphDist[x]);
    }
    for (const int i : seeds)
    {
      Exact[static_cast<std::size_t>(i)] = 1;
    }
    DependentOffsets.assign(n + S.RemoteGraph.size() + 1, 0);
    auto forEachDependency = [&](const auto& visit) {
      for (std::size_t x = 0; x < n; ++x)
      {
        if (Exact[x] || !(S.GraphDist[x] < Inf))
        {
          continue;
        }
        const int xi = static_cast<int>(x);
        for (std::int64_t e = graph.StencilBegin(xi); e < graph.StencilEnd(xi); ++e)
        {
          const int code = graph.StencilTarget(e);
          if (unfolding::SortKey(S.GraphOf(code)) < Key[x])
          {
            visit(code >= 0 ? static_cast<std::size_t>(code) : n + static_cast<std::size_t>(-1 - code), xi);
          }
        }
      }
    };
    forEachDependency([this](std::size_t neighbour, int x) {
      ++DependentOffsets[neighbour + 1];
      ++Waiting[static_cast<std::size_t>(x)];
    });
    for (std::size_t k = 0; k + 1 < DependentOffsets.size(); ++k)
    {
      DependentOffsets[k + 1] += DependentOffsets[k];
    }
    Dependents.resize(static_cast<std::size_t>(DependentOffsets.back()));
    {
      std::vector<std::int64_t> fill(DependentOffsets.begin(), DependentOffsets.end() - 1);
      forEachDependency([&](std::size_t neighbour, int x) {
        Dependents[static_cast<std::size_t>(fill[neighbour]++)] = x;
      });
    }
    for (std::size_t x = 0; x < n; ++x)
    {
      if (!(S.GraphDist[x] < Inf))
      {
        S.Refined[x] = S.GraphDist[x];
        continue;
      }
      ++Left;
      const int xi = static_cast<int>(x);
      for (std::int64_t e = graph.StencilBegin(xi); e < graph.StencilEnd(xi) && Pred[x] >= 0; ++e)
      {
        const int code = graph.StencilTarget(e);
        if ((code >= 0 ? graph.OwnedId(code) : graph.RemoteId(-1 - code)) == Pred[x])
        {
          S.PredIndex[x] = static_cast<int>(e - graph.StencilBegin(xi));
          break;
        }
      }
      if (Waiting[x] == 0)
      {
        Ready.push_back(xi);
      }
    }
  }

  // The vertices waiting for `neighbour` (an owned number, or the owned count + a remote slot)
  // wait for one less; those that wait no more are ready.
  void Release(std::size_t neighbour)
  {
    for (std::int64_t k = DependentOffsets[neighbour]; k < DependentOffsets[neighbour + 1]; ++k)
    {
      const int x = Dependents[static_cast<std::size_t>(k)];
      if (--Waiting[static_cast<std::size_t>(x)] == 0)
      {
        Ready.push_back(x);
      }
    }
  }

  // Rounds until every reached vertex is refined; returns how many.
  int Run(double limit)
  {
    const PieceGraph& graph = S.Graph;
    const std::size_t n = S.GraphDist.size();
    const std::size_t size = static_cast<std::size_t>(Comm.Size());
    const StencilUnfolding<PieceGraph, Sweep> kernel(graph, S);
    std::uint32_t keyX = 0;
    // Refined distances of smaller keys, graph distances of the others (as the serial sweep).
    auto distanceOf = [this, &keyX](int code) {
      const double d = S.GraphOf(code);
      return unfolding::SortKey(d) >= keyX ? d : S.RefinedOf(code);
    };
    for (int rounds = 1;; ++rounds)
    {
      std::vector<ByteBuffer> outgoing(size), incoming;
      while (!Ready.empty())
      {
        const int x = Ready.back();
        Ready.pop_back();
        const std::size_t xs = static_cast<std::size_t>(x);
        keyX = Key[xs];
        double best = Inf, angle = 0.0, value = S.GraphDist[xs];
        if (!Exact[xs] && kernel.RefineVertex(x, true, false, distanceOf, best, angle) &&
          best < value && best <= limit)
        {
          value = best;
        }
        S.Refined[xs] = value;
        --Left;
        Release(xs);
        auto it = std::lower_bound(Subscribers.begin(), Subscribers.end(), std::make_pair(x, -1));
        for (; it != Subscribers.end() && it->first == x; ++it)
        {
          ByteWriter w(outgoing[static_cast<std::size_t>(it->second)]);
          w.Put(graph.OwnedId(x));
          w.Put(value);
        }
      }
      // (The vertices left everywhere come with the messages: the rounds end when none is.)
      const std::int64_t everywhere = ExchangeCounting(Comm, outgoing, incoming, Left);
      ReadIdValuePairs(Comm, incoming, [&](std::int64_t id, double value) {
        const int code = graph.Encode(id);
        const int slot = -1 - code;
        if (code < 0 && slot < graph.NumberOfRemote() && graph.RemoteId(slot) == id)
        {
          S.RemoteRefined[static_cast<std::size_t>(slot)] = value;
          Release(n + static_cast<std::size_t>(slot));
        }
      });
      if (everywhere == 0)
      {
        return rounds;
      }
    }
  }
};

void PieceDistanceSolver::Refine(
  const std::vector<int>& seeds, double limit, PieceCommunicator& comm)
{
  const std::size_t n = static_cast<std::size_t>(Graph.NumberOfOwned());
  const std::size_t remotes = static_cast<std::size_t>(Graph.NumberOfRemote());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Sweep sweep{ Graph, Dist, std::vector<double>(n, nan), std::vector<double>(remotes, Inf),
    std::vector<double>(remotes, nan), std::vector<int>(n, -1),
    Graph.GetConstruction() == GraphConstruction::DiscreteGeodesic
      ? 1.0 / (1.0 + Graph.GetAccuracy())
      : 0.0 };
  SweepRounds rounds(sweep, comm, Pred);
  rounds.ReadRemoteGraphDistances();
  rounds.FindDependencies(seeds);
  RefinementRounds = rounds.Run(limit);
  Dist.swap(sweep.Refined);
}

} // namespace gs
