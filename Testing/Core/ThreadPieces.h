// A surface partitioned over "processes" that are threads of one test: a PieceCommunicator whose
// collectives meet at a barrier, and the pieces of a whole mesh by a face partition, with the
// whole mesh's vertex and face numbers as global ids (the serial run the pieces must match).
#pragma once

#include "PieceCommunicator.h"
#include "SurfacePiece.h"
#include "TriangleMesh.h"

#include <algorithm>
#include <condition_variable>
#include <functional>
#include <limits>
#include <mutex>
#include <thread>
#include <vector>

namespace gs_test
{

// What the threads of one partitioned run share.
class ThreadHub
{
public:
  explicit ThreadHub(int processes)
    : Size(processes)
    , Mail(static_cast<std::size_t>(processes),
        std::vector<gs::ByteBuffer>(static_cast<std::size_t>(processes)))
    , Values(static_cast<std::size_t>(processes), 0.0)
  {
  }

  // Runs body(rank, communicator) on Size threads and waits for them.
  void Run(const std::function<void(int, gs::PieceCommunicator&)>& body);

  void Barrier()
  {
    std::unique_lock<std::mutex> lock(Mutex);
    const long generation = Generation;
    if (++Arrived == Size)
    {
      Arrived = 0;
      ++Generation;
      Wake.notify_all();
      return;
    }
    Wake.wait(lock, [&] { return Generation != generation; });
  }

  const int Size;
  std::vector<std::vector<gs::ByteBuffer>> Mail; // Mail[from][to]
  std::vector<double> Values;

private:
  std::mutex Mutex;
  std::condition_variable Wake;
  int Arrived = 0;
  long Generation = 0;
};

class ThreadCommunicator : public gs::PieceCommunicator
{
public:
  ThreadCommunicator(ThreadHub& hub, int rank)
    : Hub(hub)
    , MyRank(rank)
  {
  }
  int Rank() const override { return MyRank; }
  int Size() const override { return Hub.Size; }
  void Exchange(const std::vector<gs::ByteBuffer>& outgoing,
    std::vector<gs::ByteBuffer>& incoming) override
  {
    Hub.Mail[static_cast<std::size_t>(MyRank)] = outgoing;
    Hub.Mail[static_cast<std::size_t>(MyRank)].resize(static_cast<std::size_t>(Hub.Size));
    Hub.Barrier();
    incoming.assign(static_cast<std::size_t>(Hub.Size), {});
    for (int q = 0; q < Hub.Size; ++q)
    {
      incoming[static_cast<std::size_t>(q)] =
        Hub.Mail[static_cast<std::size_t>(q)][static_cast<std::size_t>(MyRank)];
    }
    Hub.Barrier();
  }
  std::int64_t Sum(std::int64_t value) override
  {
    return static_cast<std::int64_t>(Reduce(static_cast<double>(value), 0));
  }
  double Min(double value) override { return Reduce(value, 1); }
  double Max(double value) override { return Reduce(value, 2); }

private:
  double Reduce(double value, int kind)
  {
    Hub.Values[static_cast<std::size_t>(MyRank)] = value;
    Hub.Barrier();
    double r = Hub.Values[0];
    for (int q = 1; q < Hub.Size; ++q)
    {
      const double x = Hub.Values[static_cast<std::size_t>(q)];
      r = kind == 0 ? r + x : kind == 1 ? std::min(r, x) : std::max(r, x);
    }
    Hub.Barrier();
    return r;
  }

  ThreadHub& Hub;
  const int MyRank;
};

inline void ThreadHub::Run(const std::function<void(int, gs::PieceCommunicator&)>& body)
{
  std::vector<std::thread> threads;
  for (int r = 0; r < Size; ++r)
  {
    threads.emplace_back([this, r, &body] {
      ThreadCommunicator comm(*this, r);
      body(r, comm);
    });
  }
  for (std::thread& t : threads)
  {
    t.join();
  }
}

// The faces of `mesh` whose part is `rank`, with the mesh's own vertex and face numbers as ids.
inline gs::PieceTriangles PieceOf(
  const gs::TriangleMesh& mesh, const std::vector<int>& partOfFace, int rank)
{
  gs::PieceTriangles piece;
  std::vector<int> point(static_cast<std::size_t>(mesh.NumberOfVertices()), -1);
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    if (partOfFace[static_cast<std::size_t>(f)] != rank)
    {
      continue;
    }
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k)
    {
      const int v = mesh.Face(f)[static_cast<std::size_t>(k)];
      if (point[static_cast<std::size_t>(v)] < 0)
      {
        point[static_cast<std::size_t>(v)] = static_cast<int>(piece.Points.size());
        piece.Points.push_back(mesh.Position(v));
        piece.PointIds.push_back(v);
      }
      t[static_cast<std::size_t>(k)] = point[static_cast<std::size_t>(v)];
    }
    piece.Triangles.push_back(t);
    piece.TriangleIds.push_back(f);
  }
  return piece;
}

// A partition of the faces into `parts` slabs along the direction (dx, dy, dz) of their
// centroids (equal face counts), then each slab's faces dealt in runs of `run` faces of the
// face order to the next part (run 0: none), which leaves pieces with holes and islands.
inline std::vector<int> PartitionFaces(
  const gs::TriangleMesh& mesh, int parts, const gs::Vec3& direction, int run = 0)
{
  const int nf = mesh.NumberOfFaces();
  std::vector<std::pair<double, int>> keys;
  for (int f = 0; f < nf; ++f)
  {
    const auto& t = mesh.Face(f);
    const gs::Vec3 c = (mesh.Position(t[0]) + mesh.Position(t[1]) + mesh.Position(t[2])) / 3.0;
    keys.push_back({ gs::Dot(c, direction), f });
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> part(static_cast<std::size_t>(nf), 0);
  for (int i = 0; i < nf; ++i)
  {
    int p = static_cast<int>(static_cast<long long>(i) * parts / nf);
    const int f = keys[static_cast<std::size_t>(i)].second;
    if (run > 0 && (f / run) % 7 == 3)
    {
      p = (p + 1) % parts;
    }
    part[static_cast<std::size_t>(f)] = p;
  }
  return part;
}

} // namespace gs_test
