// Saddle vertex graph (Ying, Wang, He 2013): a sparse graph whose shortest paths are geodesic
// distances. Every vertex is linked to each vertex of its K-nearest geodesic disk that it reaches
// by a direct geodesic (one through no saddle or boundary vertex), with the exact length; mesh
// edges are always kept so that the graph is connected wherever the mesh is. A shortest path on
// the surface is a chain of direct geodesics between pseudo-source vertices, so graph distances
// are exact whenever each link is shorter than the K-disk radius, and near-exact otherwise.
//
// The same class holds a discrete geodesic graph (GraphConstruction::DiscreteGeodesic,
// DiscreteGeodesicGraph.h): direct geodesics too, but only those that no route through another
// vertex approximates within the accuracy asked for, however long; its distances are within
// that accuracy of the geodesic distance (measured, see the README).
//
// Built in parallel (OpenMP), identical for any thread count, stored as CSR, savable to a cache
// file keyed by a hash of the mesh geometry.
#pragma once

#include "Memory.h"
#include "Status.h"
#include "TriangleMesh.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

namespace gs
{

// Called with the fraction done (0..1) from the calling thread; returning false aborts.
using ProgressCallback = std::function<bool(double)>;

// Which links a graph keeps (both give graphs of the same form, solved by the same solvers).
enum class GraphConstruction
{
  // Saddle vertex graph: every direct geodesic within each vertex's K-nearest geodesic disk.
  SaddleVertex,
  // Discrete geodesic graph (DiscreteGeodesicGraph.h): only the direct geodesics that no route
  // through another vertex approximates within the accuracy; reaches as far as needed.
  DiscreteGeodesic
};

struct SaddleVertexGraphOptions
{
  GraphConstruction Construction = GraphConstruction::SaddleVertex;
  int K = 50;              // SaddleVertex: geodesic disk size (number of nearest vertices)
  double Accuracy = 1e-3;  // DiscreteGeodesic: largest relative error aimed at, 1e-5 .. 0.1
  // DiscreteGeodesic: each vertex's polar stencil (what the unfolding refinement unfolds over)
  // also holds the vertices its propagation reached along direct geodesics but found covered
  // (not links: the graph and its graph distances are the same). About three times the stencil
  // at accuracy 0.1, for a refined mean error 2-3x smaller (below the saddle vertex graph's of
  // K = 50 on the meshes measured, README) and a refined solve 20-30% slower; on irregular flat
  // meshes, where the links-only refinement is exact or nearly, near-exact but a little less
  // accurate (test DiscreteGeodesicGraph.ReachedStencilNearExactOnJitteredPlanes).
  bool ReachedStencil = false;
  int NumberOfThreads = 0; // 0: OpenMP's default
};

class SaddleVertexGraph
{
public:
  // Builds the graph. Returns Status::Aborted() when the progress callback aborts (its last
  // call, with 1.0, may still abort) and an error when the request is invalid; the graph is then
  // empty. The calling thread reports progress every 16 of the vertices it solves.
  Status Build(const TriangleMesh& mesh, const SaddleVertexGraphOptions& options,
    const ProgressCallback& progress);
  // Ok when Build accepts `options`: K >= 1 for a saddle vertex graph, an accuracy within
  // 1e-5 .. 0.1 for a discrete geodesic graph; otherwise an error saying which is wrong.
  static Status CheckOptions(const SaddleVertexGraphOptions& options);
  // The K that Build gives a saddle vertex graph of `options` on `numberOfVertices` vertices
  // (K clamped to the vertex count, as Build does); 0 for a discrete geodesic graph.
  static int EffectiveK(const SaddleVertexGraphOptions& options, int numberOfVertices);

  bool Empty() const { return Offsets.size() <= 1; }
  int NumberOfVertices() const { return Offsets.empty() ? 0 : static_cast<int>(Offsets.size()) - 1; }
  // Directed adjacency entries (each undirected link counts twice).
  std::int64_t NumberOfEntries() const { return static_cast<std::int64_t>(Targets.size()); }
  double MeanDegree() const
  {
    return NumberOfVertices() ? static_cast<double>(Targets.size()) / NumberOfVertices() : 0.0;
  }
  GraphConstruction GetConstruction() const { return Construction; }
  // The saddle vertex graph's K (0 for a discrete geodesic graph).
  int GetK() const { return K; }
  // The discrete geodesic graph's accuracy (0 for a saddle vertex graph).
  double GetAccuracy() const { return Accuracy; }
  // Whether the discrete geodesic graph's stencils hold its reached vertices too
  // (SaddleVertexGraphOptions::ReachedStencil).
  bool GetReachedStencil() const { return ReachedStencil; }
  // How many nearest vertices an exact solve from a point or curve source should reach before
  // it seeds the graph: K for a saddle vertex graph; for a discrete geodesic graph the disk
  // whose edge-sized gaps between seeds cost at most its epsilon (about 0.45 / epsilon
  // vertices, at least 50; see DiscreteGeodesicGraph.h for epsilon).
  int LocalDiskSize() const;
  // The same for a graph of `construction` with K = k (clamped) or `accuracy` on a surface of
  // `numberOfVertices` vertices.
  static int LocalDiskSizeFor(
    GraphConstruction construction, int k, double accuracy, std::int64_t numberOfVertices);
  // The epsilon of the discrete geodesic graph's propagation (DGGPropagation::Run) for the
  // accuracy asked for (see DiscreteGeodesicGraph.h).
  static double DiscreteGeodesicEpsilon(double accuracy);
  double BuildSeconds() const { return Seconds; }
  std::size_t MemoryBytes() const;
  // Build gathers the per-vertex stencils into the graph's array in slabs of nodes holding about
  // this many bytes of stencil (at most 32 slabs), handing the gathered memory back to the
  // system after each: the build's peak then holds the stencils about once, not twice.
  static constexpr std::int64_t GatherSlabBytes = std::int64_t(32) << 20;

  // Peak memory (bytes) that Build is expected to add for K on `numberOfVertices` vertices: an
  // upper estimate from the peaks SVGBenchmark measures (README, "Memory"). Build refuses a
  // request whose estimate exceeds 80% of AvailableMemoryBytes(), before allocating.
  static double EstimatedBuildBytes(int numberOfVertices, int k);
  static double EstimatedBuildBytes(int numberOfVertices, const SaddleVertexGraphOptions& options);
  // Memory the system can give now: MemAvailable of /proc/meminfo, else free physical pages;
  // 0 when unknown (no check). GS_AVAILABLE_MEMORY (bytes) overrides it, for tests.
  static double AvailableMemoryBytes();
  void Clear();

  // The graph's nodes are the mesh vertices renumbered for memory locality (Z-order of their
  // positions: a solve's wavefront then touches neighbouring entries of the per-node arrays).
  // Everything below (adjacency, stencils) and GraphDistanceSolver work on nodes: Node(v) is
  // mesh vertex v's node, Vertex(n) node n's mesh vertex. SVGGeodesicSolver speaks mesh
  // vertices.
  int Node(int vertex) const { return NodeOf[vertex]; }
  int Vertex(int node) const { return VertexOf[node]; }

  // Neighbours of node v: Targets[Begin(v) .. End(v)) with Weights, sorted by target node.
  std::int64_t Begin(int v) const { return Offsets[v]; }
  std::int64_t End(int v) const { return Offsets[v + 1]; }
  int Target(std::int64_t e) const { return Targets[e]; }
  double Weight(std::int64_t e) const { return Weights[e]; }
  // Memory hints for solvers that know which vertex they will scan next (a queue): first the
  // offsets, then (once they are cached) the whole adjacency.
  void PrefetchOffsets(int v) const { Prefetch(&Offsets[v]); }
  void PrefetchAdjacency(int v) const
  {
    const std::int64_t first = Offsets[v], last = Offsets[v + 1];
    for (std::int64_t i = first; i < last; i += 16)
    {
      Prefetch(&Targets[i]);
    }
    for (std::int64_t i = first; i < last; i += 8)
    {
      Prefetch(&Weights[i]);
    }
  }

  // The polar stencil of v: the vertices of v's own K-disk reached by direct geodesics, sorted by
  // the angle at which their geodesic leaves v (the log map), with their position (r cos a,
  // r sin a) in v's developed tangent plane and their exact distance r (the position's norm, to
  // rounding). StencilWrap gives the first entry's position turned by v's total angle, for the
  // pair that closes the fan.
  std::int64_t StencilBegin(int v) const { return StencilOffsets[v]; }
  std::int64_t StencilEnd(int v) const { return StencilOffsets[v + 1]; }
  int StencilTarget(std::int64_t e) const { return Stencil[e].Target; }
  double StencilDistance(std::int64_t e) const
  {
    return std::sqrt(Stencil[e].X * Stencil[e].X + Stencil[e].Y * Stencil[e].Y);
  }
  double StencilX(std::int64_t e) const { return Stencil[e].X; }
  double StencilY(std::int64_t e) const { return Stencil[e].Y; }
  double StencilWrapX(int v) const { return WrapXY[2 * v]; }
  double StencilWrapY(int v) const { return WrapXY[2 * v + 1]; }
  // For the link e from u to Target(e): u's position in Target(e)'s stencil (an offset from
  // StencilBegin(Target(e))), or -1 when u is not in it. Derived at build and load time, so
  // that a solve can tell each vertex where its predecessor lies in its stencil.
  int LinkStencilIndex(std::int64_t e) const { return LinkStencil[e]; }
  // Memory hints for sweeps that visit vertices in an order known in advance (each vertex's
  // stencil is a random access otherwise): first the offsets (and the link's stencil index), a
  // few vertices later the entries.
  void PrefetchStencilOffsets(int v, std::int64_t link = -1) const
  {
    Prefetch(&StencilOffsets[v]);
    if (link >= 0)
    {
      Prefetch(&LinkStencil[link]);
    }
  }
  // Entries index - 8 .. index + 8 of v's stencil (all of it when index < 0).
  void PrefetchStencil(int v, int index = -1) const
  {
    const std::int64_t first = StencilOffsets[v], last = StencilOffsets[v + 1];
    const std::int64_t b = index >= 0 ? std::max(first, first + index - 8) : first;
    const std::int64_t e = index >= 0 ? std::min(last, first + index + 9) : last;
    // (24-byte entries: 8 per three 64-byte cache lines.)
    for (std::int64_t i = b; i < e; i += 2)
    {
      Prefetch(&Stencil[i]);
    }
    if (e > b)
    {
      Prefetch(&Stencil[e - 1].Target);
    }
  }

  // A hash of the mesh geometry and connectivity (positions bit for bit, faces).
  static std::uint64_t HashMesh(const TriangleMesh& mesh);
  // Ok when the graph may serve `mesh` (it has as many vertices); otherwise an error saying that
  // it was built for another mesh.
  Status CheckMesh(const TriangleMesh& mesh) const;
  // Cache files: Save writes the graph with the mesh hash, K and its build time; Load accepts a
  // file only if it is intact (checksum), for the same mesh hash and K (clamped to the vertex
  // count, as Build does), and well-formed; otherwise it returns an error saying why and leaves
  // the graph empty. BuildSeconds() of a loaded graph is the original build's.
  //
  // Save never destroys what it does not own: it writes a temporary file beside `path` and
  // renames it into place, so that an interrupted or failed write leaves the previous file
  // whole and concurrent writers leave one writer's whole file, never a mixture; and it refuses
  // (CheckCacheFileName) a path holding anything but one of these cache files. Load never opens
  // what is not a regular file (the open of a FIFO would block).
  //
  // The checksum only detects accidental damage (anyone can recompute it): Verify checks a
  // loaded graph against the mesh.
  Status Save(const std::string& path, std::uint64_t meshHash) const;
  // Ok when `path` is free for a cache file: missing, or a regular file that starts as a graph
  // cache file of this project does (any construction or format version); otherwise an error
  // naming the file and saying it is left untouched.
  static Status CheckCacheFileName(const std::string& path);
  // What the mesh can check of a graph cheaply (a loaded cache file may be forged): the vertex
  // count; every link at least the straight distance between its ends; every mesh edge a link
  // weighing the edge's length; every link of 48 vertices spread over the surface at least the
  // exact geodesic distance (up to the 4096 nearest vertices); and for a saddle vertex graph,
  // whose links are shortest geodesics, those links equal to the exact distance and every link
  // equal to its entry in its target's polar stencil (within 1e-9 relative). A discrete
  // geodesic graph may keep direct geodesics longer than the shortest path: its weights are
  // bounded from below only (a forged longer link makes distances longer, never shorter).
  // O(links) plus 48 small exact solves. Ok, or an error naming the first link that fails.
  Status Verify(const TriangleMesh& mesh) const;
  Status Load(const std::string& path, std::uint64_t meshHash, int k);
  // The same for any construction: a discrete geodesic graph's file (its own format) must have
  // been saved for exactly the same accuracy.
  Status Load(
    const std::string& path, std::uint64_t meshHash, const SaddleVertexGraphOptions& options);

  bool operator==(const SaddleVertexGraph& o) const
  {
    return Construction == o.Construction && K == o.K && Accuracy == o.Accuracy &&
      ReachedStencil == o.ReachedStencil && Offsets == o.Offsets && Targets == o.Targets &&
      Weights == o.Weights && StencilOffsets == o.StencilOffsets && Stencil == o.Stencil && WrapXY == o.WrapXY &&
      VertexOf == o.VertexOf;
  }

private:
  friend class GraphDistanceSolver; // its scan reads the adjacency arrays directly
  std::vector<std::int64_t> Offsets;
  std::vector<int> Targets;
  std::vector<double> Weights;
  std::vector<std::int64_t> StencilOffsets;
  // A stencil entry's position in the tangent plane and target node together: the refinement
  // sweep reads all of each entry it visits (in separate arrays, three cache misses per stencil;
  // interleaved, the refined solve is 1.2x faster on 178K vertices). The entry's distance is its
  // position's norm (24 bytes an entry instead of 32 with the distance stored: the graph's peak
  // at 711K vertices 13% lower). Cache files keep the separate arrays, distances included (Save
  // gathers them, Load interleaves).
  struct StencilEntry
  {
    double X, Y;
    int Target;
    bool operator==(const StencilEntry& o) const
    {
      return X == o.X && Y == o.Y && Target == o.Target;
    }
  };
  // (Resized without writing: the build's gathering touches its pages as it fills them.)
  template <class T>
  struct UninitializedAllocator : std::allocator<T>
  {
    template <class U>
    struct rebind
    {
      using other = UninitializedAllocator<U>;
    };
    UninitializedAllocator() = default;
    template <class U>
    UninitializedAllocator(const UninitializedAllocator<U>&) noexcept
    {
    }
    template <class U>
    void construct(U* p) noexcept
    {
      ::new (static_cast<void*>(p)) U; // default-initialized: left as it is
    }
    template <class U, class... Args>
    void construct(U* p, Args&&... args)
    {
      ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
    }
  };
  std::vector<StencilEntry, UninitializedAllocator<StencilEntry>> Stencil;
  std::vector<double> WrapXY;
  std::vector<int> LinkStencil;
  std::vector<int> NodeOf, VertexOf;
  void OrderNodes(const TriangleMesh& mesh);
  void IndexLinksInStencils();
  // Build's steps after OrderNodes and the state they hand each other (SaddleVertexGraph.cpp).
  struct Builder;
  GraphConstruction Construction = GraphConstruction::SaddleVertex;
  int K = 0;
  double Accuracy = 0.0;
  bool ReachedStencil = false;
  double Seconds = 0.0;
};

// A vertex's polar stencil laid out (SaddleVertexGraph's stencils, and those of a partitioned
// surface's pieces: the same arithmetic): entries 0 .. size - 1, of geodesic length distance(i)
// leaving the vertex at angle(i), sorted by angle (ties by index) into `order`; emit(k, i, x, y)
// places entry i k-th at (r cos a, r sin a); (wrapX, wrapY) is the first one turned by the
// vertex's total angle, for the pair that closes the fan.
template <class Distance, class Angle, class Emit>
void LayOutPolarStencil(std::size_t size, const Distance& distance, const Angle& angle,
  double totalAngle, std::vector<int>& order, const Emit& emit, double& wrapX, double& wrapY)
{
  order.resize(size);
  for (std::size_t i = 0; i < size; ++i)
  {
    order[i] = static_cast<int>(i);
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    const double aa = angle(static_cast<std::size_t>(a)), ab = angle(static_cast<std::size_t>(b));
    return aa < ab || (aa == ab && a < b);
  });
  for (std::size_t k = 0; k < size; ++k)
  {
    const std::size_t i = static_cast<std::size_t>(order[k]);
    const double r = distance(i), a = angle(i);
    emit(k, i, r * std::cos(a), r * std::sin(a));
    if (k == 0)
    {
      const double wrapped = a + totalAngle;
      wrapX = r * std::cos(wrapped);
      wrapY = r * std::sin(wrapped);
    }
  }
}

enum class GraphAlgorithm
{
  LabelCorrecting, // SLF insertion, LLL extraction (the paper's choice)
  Dijkstra         // binary heap
};

// Single- or multi-source shortest paths on a saddle vertex graph, between its nodes
// (SaddleVertexGraph::Node). Reusable: a solve resets only what the previous one touched.
class GraphDistanceSolver
{
public:
  explicit GraphDistanceSolver(const SaddleVertexGraph& graph);

  // Seeds are (node, initial distance). Nodes farther than maxDistance (> 0) stay
  // unreached (infinite); maxDistance <= 0 means unlimited.
  void Solve(const std::vector<std::pair<int, double>>& seeds, GraphAlgorithm algorithm,
    double maxDistance = 0.0);
  double Distance(int v) const { return Dist[v]; }
  const std::vector<double>& Distances() const { return Dist; }
  // Nodes reached by the last solve (unordered).
  const std::vector<int>& Reached() const { return Touched; }
  std::int64_t Relaxations() const { return NumRelaxations; }
  // The node whose link gave v its distance (-1 for seeds and unreached vertices). When several
  // links give it exactly, the one from the smallest mesh vertex (a rule that does not depend on
  // the order of the search, so that a search over processes finds the same).
  int Predecessor(int v) const { return Pred[v].Vertex; }
  // The link (adjacency entry of the predecessor) that gave v its distance, or -1.
  std::int64_t PredecessorLink(int v) const { return Pred[v].Link; }
  void PrefetchPredecessor(int v) const { Prefetch(&Pred[v]); }
  // Refinement passes may lower a reached vertex's distance.
  void Lower(int v, double d) { Dist[v] = d; }

private:
  // A tie: link e from u gives v exactly its distance; it becomes v's predecessor link when u's
  // mesh vertex is smaller than the predecessor's (a seed keeps none).
  void KeepSmallerPredecessor(int v, std::int64_t e, int u)
  {
    if (Pred[v].Vertex >= 0 && Graph.Vertex(u) < Graph.Vertex(Pred[v].Vertex))
    {
      Pred[v] = { e, u };
    }
  }
  // The label-correcting queue's next vertices' adjacency and offsets into the cache (the queue
  // in Ring from `head`, `size` vertices).
  void PrefetchQueued(std::size_t head, std::size_t size) const;
  void SolveLabelCorrecting(double maxDistance);
  void SolveDijkstra(double maxDistance);

  const SaddleVertexGraph& Graph;
  std::vector<double> Dist;
  struct PredLink
  {
    std::int64_t Link; // the predecessor's adjacency entry that reached v
    int Vertex;
  };
  std::vector<PredLink> Pred;
  std::vector<unsigned char> InQueue;
  std::vector<int> Touched;
  std::vector<int> Ring; // circular deque for the label-correcting queue
  std::int64_t NumRelaxations = 0;
};

} // namespace gs
