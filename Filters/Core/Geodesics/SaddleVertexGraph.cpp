#include "SaddleVertexGraph.h"

#include "DiscreteGeodesicGraph.h"
#include "ExactGeodesic.h"
#include "Hash.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>

#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs
{


namespace
{

// Build memory per vertex and per unit of K (bytes), above the peaks SVGBenchmark measured on
// armadillo, refined_elephant and mannequin-devil: 4.9-5.0 KB per vertex at K = 50, 9.2-10.1 KB
// at K = 100, 16.7-18.8 KB at K = 200 (about 95 bytes per unit of K).
constexpr double PER_VERTEX_BYTES = 1024.0;
constexpr double PER_LINK_BYTES = 100.0;
// The discrete geodesic graph's epsilon per unit of the accuracy asked for (see
// DiscreteGeodesicGraph.h).
constexpr double DGGEpsilonPerAccuracy = 0.2;

// The bits of a 21-bit integer spread to every third bit (for 63-bit Z-order keys).
std::uint64_t SpreadBits(std::uint64_t v)
{
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}
} // namespace

double SaddleVertexGraph::AvailableMemoryBytes()
{
  if (const char* forced = std::getenv("GS_AVAILABLE_MEMORY"))
  {
    const double bytes = std::atof(forced);
    if (bytes > 0)
    {
      return bytes;
    }
  }
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line))
  {
    if (line.rfind("MemAvailable:", 0) == 0)
    {
      const double kib = std::atof(line.c_str() + 13);
      if (kib > 0)
      {
        return 1024.0 * kib;
      }
    }
  }
  const long pages = sysconf(_SC_AVPHYS_PAGES);
  const long size = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && size > 0 ? static_cast<double>(pages) * static_cast<double>(size) : 0.0;
}

double SaddleVertexGraph::EstimatedBuildBytes(int numberOfVertices, int k)
{
  const double n = std::max(0, numberOfVertices);
  const double kk = std::max(1, std::min(k, numberOfVertices));
  return PER_VERTEX_BYTES * n + PER_LINK_BYTES * kk * n;
}

double SaddleVertexGraph::EstimatedBuildBytes(
  int numberOfVertices, const SaddleVertexGraphOptions& options)
{
  if (options.Construction == GraphConstruction::SaddleVertex)
  {
    return EstimatedBuildBytes(numberOfVertices, options.K);
  }
  // Links per vertex grow as 1 / sqrt(epsilon): counted as a K of 3 / sqrt(epsilon), above the
  // peaks SVGBenchmark measured on refined_elephant subdivided twice (711K vertices): 1.7 KB per
  // vertex at accuracy 0.1 (epsilon 0.02; estimate 3.2 KB; 2.1 KB with reached stencils,
  // estimate 5.3 KB), 2.9 KB at 0.03 (estimate 4.9 KB; measured before the builds' peaks were lowered).
  const double epsilon = DGGEpsilonPerAccuracy * std::max(options.Accuracy, 1e-5);
  // (ReachedStencil: the stencils hold about three times the links at accuracy 0.1, each entry
  // as costly as a saddle vertex graph's: counted as twice the K.)
  const double k = 3.0 / std::sqrt(epsilon) * (options.ReachedStencil ? 2.0 : 1.0);
  return EstimatedBuildBytes(numberOfVertices, static_cast<int>(std::ceil(k)));
}

double SaddleVertexGraph::DiscreteGeodesicEpsilon(double accuracy)
{
  return DGGEpsilonPerAccuracy * accuracy;
}

int SaddleVertexGraph::LocalDiskSize() const
{
  return LocalDiskSizeFor(Construction, K, Accuracy, NumberOfVertices());
}

int SaddleVertexGraph::LocalDiskSizeFor(
  GraphConstruction construction, int k, double accuracy, std::int64_t numberOfVertices)
{
  if (construction == GraphConstruction::SaddleVertex)
  {
    return std::max(k, 1);
  }
  // A path from the source leaves the exactly solved disk (radius r) through one of its vertices,
  // at most about half an edge (l / 2) off the geodesic: a detour of l^2 / (8 r) over a path at
  // least r long, within epsilon when r^2 >= l^2 / (8 epsilon), that is for about
  // pi r^2 / (0.87 l^2) = 0.45 / epsilon vertices.
  const double epsilon = DGGEpsilonPerAccuracy * std::max(accuracy, 1e-5);
  const double wanted = std::ceil(0.45 / epsilon);
  return static_cast<int>(std::min<double>(
    std::max(50.0, wanted), static_cast<double>(std::max<std::int64_t>(numberOfVertices, 1))));
}

std::size_t SaddleVertexGraph::MemoryBytes() const
{
  return (Offsets.size() + StencilOffsets.size()) * sizeof(std::int64_t) +
    Targets.size() * sizeof(int) + Stencil.size() * sizeof(StencilEntry) +
    (Weights.size() + WrapXY.size()) * sizeof(double) +
    (LinkStencil.size() + NodeOf.size() + VertexOf.size()) * sizeof(int);
}

void SaddleVertexGraph::Clear()
{
  Offsets.clear();
  Targets.clear();
  Weights.clear();
  StencilOffsets.clear();
  Stencil.clear();
  WrapXY.clear();
  LinkStencil.clear();
  NodeOf.clear();
  VertexOf.clear();
  Construction = GraphConstruction::SaddleVertex;
  K = 0;
  Accuracy = 0.0;
  ReachedStencil = false;
}

std::uint64_t SaddleVertexGraph::HashMesh(const TriangleMesh& mesh)
{
  Hasher h;
  const int nv = mesh.NumberOfVertices(), nf = mesh.NumberOfFaces();
  h.Add(&nv, sizeof(nv));
  h.Add(&nf, sizeof(nf));
  h.AddVector(mesh.GetPositions());
  for (int f = 0; f < nf; ++f)
  {
    h.Add(mesh.Face(f).data(), 3 * sizeof(int));
  }
  return h.H;
}

Status SaddleVertexGraph::CheckMesh(const TriangleMesh& mesh) const
{
  if (NumberOfVertices() != mesh.NumberOfVertices())
  {
    return Status::Error("the saddle vertex graph was built for another mesh (" +
      std::to_string(NumberOfVertices()) + " vertices; the mesh has " +
      std::to_string(mesh.NumberOfVertices()) + ")");
  }
  return Status();
}

Status SaddleVertexGraph::CheckOptions(const SaddleVertexGraphOptions& options)
{
  const bool dgg = options.Construction == GraphConstruction::DiscreteGeodesic;
  if (!dgg && options.K < 1)
  {
    return Status::Error("K must be at least 1 (got " + std::to_string(options.K) + ")");
  }
  if (dgg && !(options.Accuracy >= 1e-5 && options.Accuracy <= 0.1))
  {
    return Status::Error(
      "the accuracy of a discrete geodesic graph must be within 1e-5 .. 0.1 (got " +
      std::to_string(options.Accuracy) + ")");
  }
  return Status();
}

int SaddleVertexGraph::EffectiveK(const SaddleVertexGraphOptions& options, int numberOfVertices)
{
  return options.Construction == GraphConstruction::DiscreteGeodesic
    ? 0
    : std::min(options.K, numberOfVertices);
}

namespace
{
// Build refuses, before allocating, a request whose estimated peak exceeds 80% of the memory the
// system can give now: an error saying how much it needs and what to ask for instead.
Status CheckBuildMemory(int nv, int k, const SaddleVertexGraphOptions& options)
{
  const bool dgg = options.Construction == GraphConstruction::DiscreteGeodesic;
  const double estimate = SaddleVertexGraph::EstimatedBuildBytes(nv, options);
  const double available = SaddleVertexGraph::AvailableMemoryBytes();
  if (available > 0 && estimate > 0.8 * available)
  {
    return Status::Error(
      (dgg ? "a discrete geodesic graph with the accuracy " + std::to_string(options.Accuracy)
           : "a saddle vertex graph with K = " + std::to_string(k)) +
      " on " + std::to_string(nv) + " vertices needs about " +
      std::to_string(static_cast<long long>(estimate / 1048576.0)) +
      " MiB while building, more than the " +
      std::to_string(static_cast<long long>(available / 1048576.0)) + " MiB available; " +
      (dgg ? "ask for a coarser accuracy (memory grows as 1 / sqrt(accuracy))"
           : "lower K (memory grows linearly with K)"));
  }
  return Status();
}
} // namespace

// Build's steps and what they hand on (the graph's arrays are filled in node order, see
// OrderNodes): each node's solve makes a block of its own (SolveNodes, MakeStencil); the blocks
// are gathered into the stencil array and the links' arrays (GatherBlocks); both directions of
// every link and mesh edge are bucketed by node (BucketEntries); each bucket keeps the smallest
// weight per target, into the adjacency (KeepShortestEntries).
struct SaddleVertexGraph::Builder
{
  Builder(SaddleVertexGraph& graph, const TriangleMesh& mesh, const SaddleVertexGraphOptions& options,
    int k)
    : Graph(graph)
    , Mesh(mesh)
    , Options(options)
    , Nv(mesh.NumberOfVertices())
    , K(k)
    , Dgg(options.Construction == GraphConstruction::DiscreteGeodesic)
    // (ReachedStencil: the reached, covered vertices join the stencils, not the links.)
    , ReachedStencil(Dgg && options.ReachedStencil)
    , BuildThreads(options.NumberOfThreads > 0 ? options.NumberOfThreads : omp_get_max_threads())
    , FillThreads(std::min(BuildThreads, 8))
    , Made(Nv)
    , StencilSize(Nv, 0)
  {
    Graph.WrapXY.assign(2 * static_cast<std::size_t>(Nv), 0.0);
  }

  // Solves every node on the build's threads (false when the progress callback aborts). The
  // calling thread reports (and may abort) every 16 of its own nodes.
  bool SolveNodes(const ProgressCallback& progress)
  {
    std::atomic<int> done(0);
    std::atomic<bool> aborted(false);
#pragma omp parallel num_threads(BuildThreads)
    {
      // (Each engine allocates per-vertex state: only the one this graph uses is made.)
      std::unique_ptr<ExactGeodesicSolver> solver(Dgg ? nullptr : new ExactGeodesicSolver(Mesh));
      ExactGeodesicOptions opt;
      opt.MaximumFinalVertices = K;
      std::unique_ptr<DGGPropagation> propagation(Dgg ? new DGGPropagation(Mesh) : nullptr);
      std::vector<DGGPropagation::Link> links, reached;
      std::vector<int> order;
      const double epsilon = DiscreteGeodesicEpsilon(Options.Accuracy);
      int masterCount = 0;
      // Sources in node order: consecutive solves then cover overlapping neighbourhoods, whose
      // mesh data and solver state the previous solve left in the cache.
#pragma omp for schedule(dynamic, 64)
      for (int node = 0; node < Nv; ++node)
      {
        if (aborted.load(std::memory_order_relaxed))
        {
          continue;
        }
        const int s = Graph.VertexOf[node];
        if (Dgg)
        {
          propagation->Run(s, epsilon, links, ReachedStencil ? &reached : nullptr);
        }
        else
        {
          static_cast<void>(solver->Solve(s, opt)); // s is a vertex of the mesh: accepted
          links.clear();
          for (int v : solver->FinalVertices())
          {
            if (v != s && solver->IsDirect(v))
            {
              links.push_back({ v, solver->Distance(v), solver->DepartureAngle(v) });
            }
          }
        }
        MakeStencil(node, links, ReachedStencil ? &reached : nullptr, order);
        const int n = ++done;
#ifdef _OPENMP
        const bool master = omp_get_thread_num() == 0;
#else
        const bool master = true;
#endif
        // The calling thread reports (and may abort) every few of its own vertices.
        if (master && progress && (++masterCount % 16 == 0) && !progress(0.95 * n / Nv))
        {
          aborted = true;
        }
      }
    }
    return !aborted;
  }

  // Node n's block: its polar stencil (its vertex's links, then, with `reached`, its reached
  // vertices, sorted by departure angle, ties by that order, at (r cos a, r sin a); the first
  // entry also turned by the vertex's total angle, into WrapXY, for the pair that closes the
  // fan), then its links (target vertex in Target, length in X). `order`: scratch.
  void MakeStencil(int n, const std::vector<DGGPropagation::Link>& links,
    const std::vector<DGGPropagation::Link>* reached, std::vector<int>& order)
  {
    const std::size_t nl = links.size(), size = nl + (reached ? reached->size() : 0);
    auto item = [&](std::size_t i) -> const DGGPropagation::Link& {
      return i < nl ? links[i] : (*reached)[i - nl];
    };
    std::vector<StencilEntry>& out = Made[n];
    out.resize(size + nl);
    StencilSize[n] = static_cast<int>(size);
    LayOutPolarStencil(
      size, [&](std::size_t i) { return item(i).Distance; },
      [&](std::size_t i) { return item(i).Angle; }, Mesh.TotalAngle(Graph.VertexOf[n]), order,
      [&](std::size_t k, std::size_t i, double x, double y) {
        out[k].Target = Graph.NodeOf[item(i).Target];
        out[k].X = x;
        out[k].Y = y;
      },
      Graph.WrapXY[2 * static_cast<std::size_t>(n)], Graph.WrapXY[2 * static_cast<std::size_t>(n) + 1]);
    for (std::size_t i = 0; i < nl; ++i)
    {
      out[size + i] = { links[i].Distance, 0.0, links[i].Target };
    }
  }

  // The blocks, gathered into the stencil array and the links' arrays, in slabs of nodes in
  // order (each slab on the build's threads): the stencil array is allocated without being
  // written, so that its pages become resident as the slabs fill them, while the blocks gathered
  // are freed and handed back to the system after each slab. The blocks and the array are then
  // never both resident whole (with reached stencils they are most of the graph).
  void GatherBlocks()
  {
    Graph.StencilOffsets.assign(Nv + 1, 0);
    LinkOffsets.assign(Nv + 1, 0);
    for (int n = 0; n < Nv; ++n)
    {
      Graph.StencilOffsets[n + 1] = Graph.StencilOffsets[n] + StencilSize[n];
      LinkOffsets[n + 1] =
        LinkOffsets[n] + static_cast<std::int64_t>(Made[n].size()) - StencilSize[n];
    }
    Graph.Stencil.clear();
    Graph.Stencil.resize(Graph.StencilOffsets[Nv]);
    LinkTargets.resize(LinkOffsets[Nv]); // vertices
    LinkLengths.resize(LinkOffsets[Nv]);
    // (Slabs of about 32 MB of stencil, at most 32: handing memory back costs a pass over the
    // heap, about 1 ms, which a small graph need not pay for every 1/32 of its nodes.)
    const int slabs = static_cast<int>(std::min<std::int64_t>(32,
      1 + Graph.StencilOffsets[Nv] * static_cast<std::int64_t>(sizeof(StencilEntry)) / GatherSlabBytes));
    for (int slab = 0; slab < slabs; ++slab)
    {
      const int first = static_cast<int>(static_cast<long long>(Nv) * slab / slabs);
      const int last = static_cast<int>(static_cast<long long>(Nv) * (slab + 1) / slabs);
#pragma omp parallel for schedule(dynamic, 256) num_threads(BuildThreads)
      for (int n = first; n < last; ++n)
      {
        const std::vector<StencilEntry>& block = Made[n];
        std::copy(block.begin(), block.begin() + StencilSize[n],
          Graph.Stencil.begin() + Graph.StencilOffsets[n]);
        for (std::int64_t i = 0; i < LinkOffsets[n + 1] - LinkOffsets[n]; ++i)
        {
          const StencilEntry& link = block[StencilSize[n] + i];
          LinkTargets[LinkOffsets[n] + i] = link.Target;
          LinkLengths[LinkOffsets[n] + i] = link.X;
        }
        std::vector<StencilEntry>().swap(Made[n]);
      }
      ReturnFreedMemory();
    }
    std::vector<std::vector<StencilEntry>>().swap(Made);
    std::vector<int>().swap(StencilSize);
  }

  // Calls add(bucket node, other node, weight) for both directions of every link and mesh edge.
  template <class Add>
  void ForEachEntry(const Add& add) const
  {
    for (int s = 0; s < Nv; ++s)
    {
      const int ns = Graph.NodeOf[s];
      for (std::int64_t e = LinkOffsets[ns]; e < LinkOffsets[ns + 1]; ++e)
      {
        const int target = Graph.NodeOf[LinkTargets[e]];
        add(ns, target, LinkLengths[e]);
        add(target, ns, LinkLengths[e]);
      }
    }
    for (int h = 0; h < Mesh.NumberOfHalfedges(); ++h)
    {
      const int a = Graph.NodeOf[Mesh.Origin(h)], b = Graph.NodeOf[Mesh.Destination(h)];
      add(a, b, Mesh.EdgeLength(h));
      add(b, a, Mesh.EdgeLength(h));
    }
  }

  // Symmetrize and add the mesh edges: every entry into its node's bucket of Raw (Count: the
  // buckets' offsets). Each thread fills the buckets of its own range of nodes, visiting every
  // entry in the same order (the buckets come out as a serial fill makes them, for any thread
  // count; the random writes, most of the time, are shared out). Counting and filling walk the
  // entries with the same visitor, so that they agree.
  void BucketEntries()
  {
    Count.assign(Nv + 1, 0);
#pragma omp parallel num_threads(FillThreads)
    {
      const int t = omp_get_thread_num(), nt = omp_get_num_threads();
      const int lo = static_cast<int>(static_cast<long long>(Nv) * t / nt);
      const int hi = static_cast<int>(static_cast<long long>(Nv) * (t + 1) / nt);
      ForEachEntry([&](int bucket, int, double) {
        if (bucket >= lo && bucket < hi)
        {
          Count[bucket + 1]++;
        }
      });
#pragma omp barrier
#pragma omp single
      {
        for (int n = 0; n < Nv; ++n)
        {
          Count[n + 1] += Count[n];
        }
        Raw.resize(static_cast<std::size_t>(Count[Nv]));
        Fill.assign(Count.begin(), Count.end() - 1);
      }
      ForEachEntry([&](int bucket, int other, double weight) {
        if (bucket >= lo && bucket < hi)
        {
          Raw[Fill[bucket]++] = { other, weight };
        }
      });
    }
    std::vector<int>().swap(LinkTargets);
    std::vector<double>().swap(LinkLengths);
  }

  // Each bucket sorted, keeping the smallest weight per target (both directions of a link then
  // carry the same value), into the graph's adjacency.
  void KeepShortestEntries()
  {
    std::vector<std::int64_t> kept(Nv + 1, 0);
#pragma omp parallel for schedule(dynamic, 256) num_threads(BuildThreads)
    for (int n = 0; n < Nv; ++n)
    {
      auto first = Raw.begin() + Count[n], last = Raw.begin() + Count[n + 1];
      std::sort(first, last);
      // Sorted by (target, weight): the first of each run is the smallest weight.
      auto out = first;
      for (auto it = first; it != last; ++it)
      {
        if (out == first || (out - 1)->first != it->first)
        {
          *out++ = *it;
        }
      }
      kept[n + 1] = out - first;
    }
    Graph.Offsets.assign(Nv + 1, 0);
    for (int n = 0; n < Nv; ++n)
    {
      Graph.Offsets[n + 1] = Graph.Offsets[n] + kept[n + 1];
    }
    Graph.Targets.resize(Graph.Offsets[Nv]);
    Graph.Weights.resize(Graph.Offsets[Nv]);
#pragma omp parallel for schedule(static) num_threads(FillThreads)
    for (int n = 0; n < Nv; ++n)
    {
      for (std::int64_t i = 0; i < kept[n + 1]; ++i)
      {
        Graph.Targets[Graph.Offsets[n] + i] = Raw[Count[n] + i].first;
        Graph.Weights[Graph.Offsets[n] + i] = Raw[Count[n] + i].second;
      }
    }
    std::vector<std::pair<int, double>>().swap(Raw); // before the link index adds its array
  }

  SaddleVertexGraph& Graph;
  const TriangleMesh& Mesh;
  const SaddleVertexGraphOptions& Options;
  const int Nv, K;
  const bool Dgg, ReachedStencil;
  const int BuildThreads, FillThreads;
  // Per node, what its solve made: its stencil, then its links (see MakeStencil); the size of
  // the stencil part. One block a node, so that the blocks freed behind the gathering leave
  // whole pages free to hand back.
  std::vector<std::vector<StencilEntry>> Made;
  std::vector<int> StencilSize;
  // The links gathered by node: Link*[LinkOffsets[n] .. LinkOffsets[n + 1]) (target vertices).
  std::vector<std::int64_t> LinkOffsets;
  std::vector<int> LinkTargets;
  std::vector<double> LinkLengths;
  // Both directions of the links and mesh edges, (other node, weight) bucketed by node at Count;
  // Fill: the buckets' next free places while they fill.
  std::vector<std::int64_t> Count, Fill;
  std::vector<std::pair<int, double>> Raw;
};

Status SaddleVertexGraph::Build(const TriangleMesh& mesh, const SaddleVertexGraphOptions& options,
  const ProgressCallback& progress)
{
  const auto t0 = std::chrono::steady_clock::now();
  Clear();
  const int nv = mesh.NumberOfVertices();
  if (nv == 0)
  {
    return Status::Error("the mesh has no vertices");
  }
  if (Status valid = CheckOptions(options); !valid.Ok())
  {
    return valid;
  }
  const bool dgg = options.Construction == GraphConstruction::DiscreteGeodesic;
  const int k = std::min(options.K, nv);
  // Refuse before allocating what the machine cannot give now.
  if (Status fits = CheckBuildMemory(nv, k, options); !fits.Ok())
  {
    return fits;
  }

  // Nodes: the vertices in Z-order (see OrderNodes).
  OrderNodes(mesh);
  Builder builder(*this, mesh, options, k);
  if (!builder.SolveNodes(progress))
  {
    return Status::Aborted();
  }
  // Everything below is laid out by node (the vertices in Z-order, see OrderNodes).
  builder.GatherBlocks();
  builder.BucketEntries();
  builder.KeepShortestEntries();
  IndexLinksInStencils();
  if (progress && !progress(1.0))
  {
    Clear();
    return Status::Aborted();
  }
  Construction = options.Construction;
  K = EffectiveK(options, nv);
  Accuracy = dgg ? options.Accuracy : 0.0;
  ReachedStencil = builder.ReachedStencil;
  Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return Status();
}

void SaddleVertexGraph::OrderNodes(const TriangleMesh& mesh)
{
  // Nodes in Z-order of the vertex positions (ties by vertex index): vertices close on the
  // surface get close nodes, so that a solve's wavefront touches few cache lines and pages of
  // the per-node arrays (a mesh's own order may be anything, e.g. random).
  const int nv = mesh.NumberOfVertices();
  const Vec3& lo = mesh.BoundingBoxMin();
  const Vec3& hi = mesh.BoundingBoxMax();
  const double extent = std::max({ hi.x - lo.x, hi.y - lo.y, hi.z - lo.z });
  const double scale = extent > 0.0 ? 2097151.0 / extent : 0.0;
  auto cell = [scale](double t) {
    return static_cast<std::uint64_t>(std::min(2097151.0, std::max(0.0, t * scale)));
  };
  std::vector<std::pair<std::uint64_t, int>> keys(nv);
  for (int v = 0; v < nv; ++v)
  {
    const Vec3& p = mesh.Position(v);
    keys[v] = { SpreadBits(cell(p.x - lo.x)) | SpreadBits(cell(p.y - lo.y)) << 1 |
        SpreadBits(cell(p.z - lo.z)) << 2,
      v };
  }
  std::sort(keys.begin(), keys.end());
  VertexOf.resize(nv);
  NodeOf.resize(nv);
  for (int n = 0; n < nv; ++n)
  {
    VertexOf[n] = keys[n].second;
    NodeOf[keys[n].second] = n;
  }
}

void SaddleVertexGraph::IndexLinksInStencils()
{
  // Each stencil entry (u in x's stencil) is a link u -> x: found by binary search in u's
  // adjacency, which is sorted by target.
  LinkStencil.assign(Targets.size(), -1);
  const int nv = NumberOfVertices();
#pragma omp parallel for schedule(dynamic, 1024)
  for (int x = 0; x < nv; ++x)
  {
    for (std::int64_t s = StencilOffsets[x]; s < StencilOffsets[x + 1]; ++s)
    {
      const int u = Stencil[s].Target;
      const auto first = Targets.begin() + Offsets[u], last = Targets.begin() + Offsets[u + 1];
      const auto it = std::lower_bound(first, last, x);
      if (it != last && *it == x)
      {
        LinkStencil[it - Targets.begin()] = static_cast<int>(s - StencilOffsets[x]);
      }
    }
  }
}

} // namespace gs
