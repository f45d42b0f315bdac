#include "ThreadCommunicator.h"

#include <algorithm>
#include <exception>
#include <stdexcept>
#include <thread>

namespace gs
{

ThreadHub::ThreadHub(int ranks)
  : Ranks(std::max(ranks, 1))
  , Mail(static_cast<std::size_t>(Ranks), std::vector<ByteBuffer>(static_cast<std::size_t>(Ranks)))
  , Values(static_cast<std::size_t>(Ranks), 0.0)
{
}

namespace
{
// What a rank's collective throws once another rank failed.
struct HubBroken : std::runtime_error
{
  HubBroken()
    : std::runtime_error("another rank of the computation failed")
  {
  }
};
} // namespace

void ThreadHub::CheckBroken() const
{
  if (Broken)
  {
    throw HubBroken();
  }
}

void ThreadHub::Barrier()
{
  std::unique_lock<std::mutex> lock(Mutex);
  CheckBroken();
  const long generation = Generation;
  if (++Arrived == Ranks)
  {
    Arrived = 0;
    ++Generation;
    Wake.notify_all();
    return;
  }
  Wake.wait(lock, [&] { return Generation != generation || Broken; });
  if (Generation == generation)
  {
    CheckBroken();
  }
}

void ThreadHub::Run(const std::function<void(int, PieceCommunicator&)>& body)
{
  {
    std::lock_guard<std::mutex> lock(Mutex);
    Broken = false;
    Arrived = 0;
  }
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(Ranks));
  auto runRank = [&](int rank) {
    try
    {
      ThreadCommunicator comm(*this, rank);
      body(rank, comm);
    }
    catch (const HubBroken&)
    {
      // (Another rank's failure, reported by that rank.)
    }
    catch (...)
    {
      errors[static_cast<std::size_t>(rank)] = std::current_exception();
      std::lock_guard<std::mutex> lock(Mutex);
      Broken = true;
      Wake.notify_all();
    }
  };
  std::vector<std::thread> threads;
  std::exception_ptr notStarted;
  try
  {
    threads.reserve(static_cast<std::size_t>(Ranks - 1));
    for (int rank = 1; rank < Ranks; ++rank)
    {
      threads.emplace_back(runRank, rank);
    }
  }
  catch (...)
  {
    // A thread that could not start: the started ones must not wait for it.
    notStarted = std::current_exception();
    std::lock_guard<std::mutex> lock(Mutex);
    Broken = true;
    Wake.notify_all();
  }
  if (!notStarted)
  {
    runRank(0);
  }
  for (std::thread& t : threads)
  {
    t.join();
  }
  if (notStarted)
  {
    std::rethrow_exception(notStarted);
  }
  for (const std::exception_ptr& e : errors)
  {
    if (e)
    {
      std::rethrow_exception(e);
    }
  }
}

void ThreadCommunicator::Exchange(
  const std::vector<ByteBuffer>& outgoing, std::vector<ByteBuffer>& incoming)
{
  const std::size_t me = static_cast<std::size_t>(MyRank), n = static_cast<std::size_t>(Hub.Ranks);
  Hub.Mail[me] = outgoing;
  Hub.Mail[me].resize(n);
  Hub.Barrier();
  incoming.assign(n, {});
  for (std::size_t q = 0; q < n; ++q)
  {
    incoming[q] = Hub.Mail[q][me];
  }
  Hub.Barrier(); // nobody writes its mail again before everyone has read it
}

std::int64_t ThreadCommunicator::Sum(std::int64_t value)
{
  return static_cast<std::int64_t>(Reduce(static_cast<double>(value), Kind::Sum));
}

double ThreadCommunicator::Reduce(double value, Kind kind)
{
  Hub.Values[static_cast<std::size_t>(MyRank)] = value;
  Hub.Barrier();
  double r = Hub.Values[0];
  for (int q = 1; q < Hub.Ranks; ++q)
  {
    const double x = Hub.Values[static_cast<std::size_t>(q)];
    r = kind == Kind::Sum ? r + x : kind == Kind::Min ? std::min(r, x) : std::max(r, x);
  }
  Hub.Barrier();
  return r;
}

} // namespace gs
