#include "vtkSaddleVertexGraphCache.h"

#include <vtkAlgorithm.h>
#include <vtkSetGet.h>

#include <algorithm>
#include <deque>
#include <filesystem>
#include <mutex>
#include <set>
#include <system_error>

namespace
{
using GraphPointer = std::shared_ptr<const gs::SaddleVertexGraph>;

// What tells graphs of one mesh apart: the construction and its parameter (K clamped to the
// vertex count as the core clamps it, or the accuracy and whether the stencils hold the reached
// vertices).
struct GraphKey
{
  gs::GraphConstruction Construction = gs::GraphConstruction::SaddleVertex;
  int K = 0;
  double Accuracy = 0.0;
  bool ReachedStencil = false;
  bool operator==(const GraphKey& o) const
  {
    return Construction == o.Construction && K == o.K && Accuracy == o.Accuracy &&
      ReachedStencil == o.ReachedStencil;
  }
};

struct Entry
{
  std::uint64_t Hash = 0;
  GraphKey Key;
  std::weak_ptr<const gs::SaddleVertexGraph> Graph;
  std::set<std::string> Files; // cache files known to hold this graph
};

struct Store
{
  std::mutex Mutex;
  std::vector<Entry> Entries;       // every graph alive somewhere (pruned when expired)
  std::deque<GraphPointer> Recent;  // most recently used first, at most Capacity
};

Store& TheStore()
{
  static Store store; // function-local: constructed on first use, shared by the whole process
  return store;
}

// Callers hold the store's mutex.
void Touch(Store& store, const GraphPointer& graph)
{
  auto it = std::find(store.Recent.begin(), store.Recent.end(), graph);
  if (it != store.Recent.end())
  {
    store.Recent.erase(it);
  }
  store.Recent.push_front(graph);
  while (store.Recent.size() > vtkSaddleVertexGraphCache::Capacity)
  {
    store.Recent.pop_back();
  }
}

Entry* Find(Store& store, std::uint64_t hash, const GraphKey& key)
{
  store.Entries.erase(std::remove_if(store.Entries.begin(), store.Entries.end(),
                        [](const Entry& e) { return e.Graph.expired(); }),
    store.Entries.end());
  for (Entry& e : store.Entries)
  {
    if (e.Hash == hash && e.Key == key)
    {
      return &e;
    }
  }
  return nullptr;
}

const char* GraphName(const gs::SaddleVertexGraphOptions& options)
{
  return options.Construction == gs::GraphConstruction::DiscreteGeodesic ? "Discrete geodesic graph"
                                                                         : "Saddle vertex graph";
}

bool FileExists(const std::string& path)
{
  std::error_code ec;
  return std::filesystem::exists(path, ec);
}

// Writes the graph to `fileName` unless the entry already knows the file holds it.
void SaveIfNeeded(const GraphPointer& graph, std::uint64_t hash, const GraphKey& key,
  const std::string& fileName, std::vector<std::string>& warnings)
{
  Store& store = TheStore();
  {
    std::lock_guard<std::mutex> lock(store.Mutex);
    Entry* e = Find(store, hash, key);
    if (e && e->Files.count(fileName) && FileExists(fileName))
    {
      return;
    }
  }
  const gs::Status saved = graph->Save(fileName, hash);
  if (!saved.Ok())
  {
    warnings.push_back("could not save the graph to the cache file: " + saved.Message());
    return;
  }
  std::lock_guard<std::mutex> lock(store.Mutex);
  if (Entry* e = Find(store, hash, key))
  {
    e->Files.insert(fileName);
  }
}

// Adds a new graph (or returns the one another thread added meanwhile).
GraphPointer Insert(
  const GraphPointer& graph, std::uint64_t hash, const GraphKey& key, const std::string& file)
{
  Store& store = TheStore();
  std::lock_guard<std::mutex> lock(store.Mutex);
  Entry* e = Find(store, hash, key);
  GraphPointer kept = e ? e->Graph.lock() : nullptr;
  if (!kept)
  {
    if (!e)
    {
      store.Entries.push_back(Entry());
      e = &store.Entries.back();
      e->Hash = hash;
      e->Key = key;
    }
    e->Graph = graph;
    e->Files.clear();
    kept = graph;
  }
  if (!file.empty())
  {
    e->Files.insert(file);
  }
  Touch(store, kept);
  return kept;
}
} // namespace

//------------------------------------------------------------------------------
const char* vtkSaddleVertexGraphCache::OriginName(Origin origin)
{
  switch (origin)
  {
    case Origin::Memory:
      return "memory";
    case Origin::File:
      return "loaded";
    case Origin::Built:
    default:
      return "built";
  }
}

//------------------------------------------------------------------------------
vtkSaddleVertexGraphCache::Result vtkSaddleVertexGraphCache::Get(const gs::TriangleMesh& mesh,
  std::uint64_t meshHash, const gs::SaddleVertexGraphOptions& options, const std::string& fileName,
  const gs::ProgressCallback& progress)
{
  Result result;
  const int nv = mesh.NumberOfVertices();
  const bool dgg = options.Construction == gs::GraphConstruction::DiscreteGeodesic;
  // Invalid requests go straight to the build, whose error says why.
  const bool validOptions = nv > 0 && gs::SaddleVertexGraph::CheckOptions(options).Ok();
  GraphKey key;
  key.Construction = options.Construction;
  key.K = gs::SaddleVertexGraph::EffectiveK(options, nv);
  key.Accuracy = dgg ? options.Accuracy : 0.0;
  key.ReachedStencil = dgg && options.ReachedStencil;

  // 0. A file name that may not be written (a user's file, a FIFO, a directory): an error
  // before any work; nothing is read from it or written to it.
  if (!fileName.empty())
  {
    result.Status = gs::SaddleVertexGraph::CheckCacheFileName(fileName);
    if (!result.Status.Ok())
    {
      result.Status = gs::Status::Error("CacheFileName: " + result.Status.Message());
      return result;
    }
  }

  // 1. Memory.
  if (validOptions)
  {
    GraphPointer graph;
    {
      Store& store = TheStore();
      std::lock_guard<std::mutex> lock(store.Mutex);
      if (Entry* e = Find(store, meshHash, key))
      {
        graph = e->Graph.lock();
        if (graph)
        {
          Touch(store, graph);
        }
      }
    }
    if (graph)
    {
      if (!fileName.empty())
      {
        SaveIfNeeded(graph, meshHash, key, fileName, result.Warnings);
      }
      result.Graph = graph;
      result.From = Origin::Memory;
      return result;
    }
  }

  // 2. The cache file.
  if (validOptions && !fileName.empty() && FileExists(fileName))
  {
    auto graph = std::make_shared<gs::SaddleVertexGraph>();
    gs::Status loaded = graph->Load(fileName, meshHash, options);
    if (loaded.Ok())
    {
      // The checksum proves no integrity against intent: check the graph against the mesh.
      const gs::Status verified = graph->Verify(mesh);
      if (!verified.Ok())
      {
        loaded = gs::Status::Error(
          "it does not match the mesh: " + verified.Message());
      }
    }
    if (loaded.Ok())
    {
      result.Graph = Insert(graph, meshHash, key, fileName);
      result.From = Origin::File;
      return result;
    }
    result.Warnings.push_back("cache file not used (" + loaded.Message() + "); rebuilding");
  }

  // 3. Build (any false from the callback, its final call included, aborts it).
  auto graph = std::make_shared<gs::SaddleVertexGraph>();
  result.Status = graph->Build(mesh, options, progress);
  if (!result.Status.Ok())
  {
    return result;
  }
  result.Graph = Insert(graph, meshHash, key, std::string());
  result.From = Origin::Built;
  if (!fileName.empty())
  {
    SaveIfNeeded(result.Graph, meshHash, key, fileName, result.Warnings);
  }
  return result;
}

//------------------------------------------------------------------------------
void vtkSaddleVertexGraphCache::Clear()
{
  Store& store = TheStore();
  std::lock_guard<std::mutex> lock(store.Mutex);
  store.Entries.clear();
  store.Recent.clear();
}

//------------------------------------------------------------------------------
std::size_t vtkSaddleVertexGraphCache::NumberOfGraphs()
{
  Store& store = TheStore();
  std::lock_guard<std::mutex> lock(store.Mutex);
  return store.Recent.size();
}

vtkSaddleVertexGraphCache::Result vtkSaddleVertexGraphCache::GetFor(vtkAlgorithm* algorithm,
  const gs::TriangleMesh& mesh, std::uint64_t meshHash, const gs::SaddleVertexGraphOptions& options,
  const std::string& fileName, double progressStart, double progressSpan)
{
  Result found = Get(mesh, meshHash, options, fileName, [=](double fraction) {
    algorithm->UpdateProgress(progressStart + progressSpan * fraction);
    return !algorithm->CheckAbort();
  });
  for (const std::string& warning : found.Warnings)
  {
    vtkWarningWithObjectMacro(algorithm,
      "" << GraphName(options) << " (CacheFileName " << fileName << "): " << warning);
  }
  if (!found.Status.Ok() && !found.Status.IsAborted())
  {
    vtkErrorWithObjectMacro(algorithm, "" << GraphName(options) << ": " << found.Status.Message());
  }
  return found;
}
