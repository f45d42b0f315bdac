// "Processes" that are threads of one process: a PieceCommunicator whose collectives meet at a
// barrier, so that a computation written for a surface partitioned over MPI processes (the
// solves on pieces: ExactPieces.h, GraphPieces.h) runs on the cores of one machine, and the
// tests run it without MPI. Every collective is deterministic: what a rank receives depends on
// what the ranks sent, never on which thread came first.
#pragma once

#include "PieceCommunicator.h"

#include <condition_variable>
#include <functional>
#include <mutex>
#include <vector>

namespace gs
{

/// What the threads of one partitioned run share.
class ThreadHub
{
public:
  explicit ThreadHub(int ranks);

  /// Runs body(rank, communicator) for every rank, rank 0 on the calling thread (so that a
  /// progress report from rank 0 comes from the caller's thread) and the others on threads of
  /// their own, and waits for them all. An exception from a rank (out of memory) breaks the
  /// hub: the other ranks' collectives throw instead of waiting for it, and once all ended the
  /// first rank's exception is rethrown to the caller.
  void Run(const std::function<void(int rank, PieceCommunicator& comm)>& body);

  int Size() const { return Ranks; }

private:
  friend class ThreadCommunicator;
  void Barrier();

  // Throws when a rank failed (Broken): no collective waits for a rank that will not come.
  void CheckBroken() const;

  const int Ranks;
  bool Broken = false; // (guarded by Mutex)
  std::vector<std::vector<ByteBuffer>> Mail; // Mail[from][to]
  std::vector<double> Values;                // one per rank, for the reductions
  std::mutex Mutex;
  std::condition_variable Wake;
  int Arrived = 0;
  long Generation = 0;
};

/// Rank `rank` of a ThreadHub.
class ThreadCommunicator : public PieceCommunicator
{
public:
  ThreadCommunicator(ThreadHub& hub, int rank)
    : Hub(hub)
    , MyRank(rank)
  {
  }
  int Rank() const override { return MyRank; }
  int Size() const override { return Hub.Ranks; }
  void Exchange(const std::vector<ByteBuffer>& outgoing, std::vector<ByteBuffer>& incoming) override;
  std::int64_t Sum(std::int64_t value) override;
  double Min(double value) override { return Reduce(value, Kind::Min); }
  double Max(double value) override { return Reduce(value, Kind::Max); }

private:
  enum class Kind
  {
    Sum,
    Min,
    Max
  };
  // Every rank's value combined in rank order (the same result, to the bit, on every rank).
  double Reduce(double value, Kind kind);

  ThreadHub& Hub;
  const int MyRank;
};

} // namespace gs
