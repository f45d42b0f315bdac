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

#include <cerrno>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs
{

namespace
{
// Blocks freed inside the heap stay resident until they are handed back to the system: the
// build does so after each slab of its gathering, so that the per-vertex blocks gathered and the
// arrays they fill are not both resident whole (Build; the peak at 711K vertices with reached
// stencils went from 3.9 KB to 2.1 KB per vertex with the gathering in slabs).
void ReturnFreedMemory()
{
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

constexpr double Inf = std::numeric_limits<double>::infinity();
// Cache file formats: the saddle vertex graph's header holds K (int32) after the mesh hash, the
// discrete geodesic graph's the accuracy (double); the rest is laid out alike.
constexpr char Magic[8] = { 'G', 'S', 'S', 'V', 'G', '0', '0', '4' };
constexpr char DGGMagic[8] = { 'G', 'S', 'D', 'G', 'G', '0', '0', '1' };
// A discrete geodesic graph whose stencils hold its reached vertices too (the same layout).
constexpr char DGRMagic[8] = { 'G', 'S', 'D', 'G', 'R', '0', '0', '1' };
// What a cache file holds, from its magic's first five characters (null: not a graph file).
const char* GraphKind(const char* magic)
{
  return std::memcmp(magic, Magic, 5) == 0 ? "a saddle vertex graph"
    : std::memcmp(magic, DGGMagic, 5) == 0 ? "a discrete geodesic graph"
    : std::memcmp(magic, DGRMagic, 5) == 0 ? "a discrete geodesic graph with reached stencils"
                                            : nullptr;
}

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

int SaddleVertexGraph::LocalDiskSize() const
{
  if (Construction == GraphConstruction::SaddleVertex)
  {
    return std::max(K, 1);
  }
  // A path from the source leaves the exactly solved disk (radius r) through one of its vertices,
  // at most about half an edge (l / 2) off the geodesic: a detour of l^2 / (8 r) over a path at
  // least r long, within epsilon when r^2 >= l^2 / (8 epsilon), that is for about
  // pi r^2 / (0.87 l^2) = 0.45 / epsilon vertices.
  const double epsilon = DGGEpsilonPerAccuracy * std::max(Accuracy, 1e-5);
  const double wanted = std::ceil(0.45 / epsilon);
  return static_cast<int>(std::min<double>(std::max(50.0, wanted), std::max(NumberOfVertices(), 1)));
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
  const double estimate = EstimatedBuildBytes(nv, options);
  const double available = AvailableMemoryBytes();
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

  // Nodes: the vertices in Z-order (see OrderNodes).
  OrderNodes(mesh);
  // What each node's solve finds, in one block per node (made by the thread that solves it): its
  // polar stencil (see makeStencil), then its links (target vertex in Target, length in X).
  // Gathered below into the graph's stencil array and the links' arrays; one block a node, so
  // that the blocks freed behind the gathering leave whole pages free to hand back.
  std::vector<std::vector<StencilEntry>> made(nv);
  std::vector<int> stencilSize(nv, 0);
  WrapXY.assign(2 * static_cast<std::size_t>(nv), 0.0);
  // (ReachedStencil: the reached, covered vertices join the stencils, not the links.)
  const bool reachedStencil = dgg && options.ReachedStencil;
  // Node n's polar stencil: its vertex's links, then (with `reached`) its reached vertices,
  // sorted by departure angle (ties by that order), at (r cos a, r sin a); the first entry also
  // turned by the vertex's total angle, for the pair that closes the fan. `order`: scratch.
  auto makeStencil = [&](int n, const std::vector<DGGPropagation::Link>& links,
                       const std::vector<DGGPropagation::Link>* reached, std::vector<int>& order) {
    const std::size_t nl = links.size(), size = nl + (reached ? reached->size() : 0);
    auto item = [&](std::size_t i) -> const DGGPropagation::Link& {
      return i < nl ? links[i] : (*reached)[i - nl];
    };
    order.resize(size);
    for (std::size_t i = 0; i < size; ++i)
    {
      order[i] = static_cast<int>(i);
    }
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      const double aa = item(a).Angle, ab = item(b).Angle;
      return aa < ab || (aa == ab && a < b);
    });
    std::vector<StencilEntry>& out = made[n];
    out.resize(size + nl);
    stencilSize[n] = static_cast<int>(size);
    for (std::size_t i = 0; i < size; ++i)
    {
      const DGGPropagation::Link& l = item(static_cast<std::size_t>(order[i]));
      const double r = l.Distance, a = l.Angle;
      out[i].Target = NodeOf[l.Target];
      out[i].X = r * std::cos(a);
      out[i].Y = r * std::sin(a);
      if (i == 0)
      {
        const double wrapped = a + mesh.TotalAngle(VertexOf[n]);
        WrapXY[2 * static_cast<std::size_t>(n)] = r * std::cos(wrapped);
        WrapXY[2 * static_cast<std::size_t>(n) + 1] = r * std::sin(wrapped);
      }
    }
    for (std::size_t i = 0; i < nl; ++i)
    {
      out[size + i] = { links[i].Distance, 0.0, links[i].Target };
    }
  };
  std::atomic<int> done(0);
  std::atomic<bool> aborted(false);
  const int buildThreads =
    options.NumberOfThreads > 0 ? options.NumberOfThreads : omp_get_max_threads();
#pragma omp parallel num_threads(buildThreads)
  {
    // (Each engine allocates per-vertex state: only the one this graph uses is made.)
    std::unique_ptr<ExactGeodesicSolver> solver(dgg ? nullptr : new ExactGeodesicSolver(mesh));
    ExactGeodesicOptions opt;
    opt.MaximumFinalVertices = k;
    std::unique_ptr<DGGPropagation> propagation(dgg ? new DGGPropagation(mesh) : nullptr);
    std::vector<DGGPropagation::Link> links, reached;
    std::vector<int> order;
    const double epsilon = DGGEpsilonPerAccuracy * options.Accuracy;
    int masterCount = 0;
    // Sources in node order: consecutive solves then cover overlapping neighbourhoods, whose
    // mesh data and solver state the previous solve left in the cache.
#pragma omp for schedule(dynamic, 64)
    for (int node = 0; node < nv; ++node)
    {
      if (aborted.load(std::memory_order_relaxed))
      {
        continue;
      }
      const int s = VertexOf[node];
      if (dgg)
      {
        propagation->Run(s, epsilon, links, reachedStencil ? &reached : nullptr);
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
      makeStencil(node, links, reachedStencil ? &reached : nullptr, order);
      const int n = ++done;
#ifdef _OPENMP
      const bool master = omp_get_thread_num() == 0;
#else
      const bool master = true;
#endif
      // The calling thread reports (and may abort) every few of its own vertices.
      if (master && progress && (++masterCount % 16 == 0) && !progress(0.95 * n / nv))
      {
        aborted = true;
      }
    }
  }
  if (aborted)
  {
    return Status::Aborted();
  }

  // Everything below is laid out by node (the vertices in Z-order, see OrderNodes).

  // The blocks, gathered into the stencil array and the links' arrays, in slabs of nodes in
  // order (each slab on the build's threads): the stencil array is allocated without being
  // written, so that its pages become resident as the slabs fill them, while the blocks gathered
  // are freed and handed back to the system after each slab. The blocks and the array are then
  // never both resident whole (with reached stencils they are most of the graph).
  StencilOffsets.assign(nv + 1, 0);
  std::vector<std::int64_t> linkOffsets(nv + 1, 0);
  for (int n = 0; n < nv; ++n)
  {
    StencilOffsets[n + 1] = StencilOffsets[n] + stencilSize[n];
    linkOffsets[n + 1] =
      linkOffsets[n] + static_cast<std::int64_t>(made[n].size()) - stencilSize[n];
  }
  Stencil.clear();
  Stencil.resize(StencilOffsets[nv]);
  std::vector<int> linkTargets(linkOffsets[nv]); // vertices
  std::vector<double> linkLengths(linkOffsets[nv]);
  // (Slabs of about 32 MB of stencil, at most 32: handing memory back costs a pass over the
  // heap, about 1 ms, which a small graph need not pay for every 1/32 of its nodes.)
  const int slabs = static_cast<int>(std::min<std::int64_t>(32,
    1 + StencilOffsets[nv] * static_cast<std::int64_t>(sizeof(StencilEntry)) / GatherSlabBytes));
  for (int slab = 0; slab < slabs; ++slab)
  {
    const int first = static_cast<int>(static_cast<long long>(nv) * slab / slabs);
    const int last = static_cast<int>(static_cast<long long>(nv) * (slab + 1) / slabs);
#pragma omp parallel for schedule(dynamic, 256) num_threads(buildThreads)
    for (int n = first; n < last; ++n)
    {
      const std::vector<StencilEntry>& block = made[n];
      std::copy(block.begin(), block.begin() + stencilSize[n], Stencil.begin() + StencilOffsets[n]);
      for (std::int64_t i = 0; i < linkOffsets[n + 1] - linkOffsets[n]; ++i)
      {
        const StencilEntry& link = block[stencilSize[n] + i];
        linkTargets[linkOffsets[n] + i] = link.Target;
        linkLengths[linkOffsets[n] + i] = link.X;
      }
      std::vector<StencilEntry>().swap(made[n]);
    }
    ReturnFreedMemory();
  }
  std::vector<std::vector<StencilEntry>>().swap(made);
  std::vector<int>().swap(stencilSize);

  // Symmetrize and add the mesh edges; duplicates keep the smallest weight, so that both
  // directions of a link carry the same value. Each thread fills the buckets of its own range of
  // nodes, visiting every entry in the same order (the buckets come out as a serial fill makes
  // them, for any thread count; the random writes, most of the time, are shared out). Counting
  // and filling walk the entries with the same visitor, so that they agree.
  const int fillThreads = std::min(buildThreads, 8);
  std::vector<std::int64_t> count(nv + 1, 0);
  std::vector<std::int64_t> fill;
  std::vector<std::pair<int, double>> raw;
  // Calls add(bucket node, other node, weight) for both directions of every link and mesh edge.
  auto forEachEntry = [&](auto&& add) {
    for (int s = 0; s < nv; ++s)
    {
      const int ns = NodeOf[s];
      for (std::int64_t e = linkOffsets[ns]; e < linkOffsets[ns + 1]; ++e)
      {
        const int target = NodeOf[linkTargets[e]];
        add(ns, target, linkLengths[e]);
        add(target, ns, linkLengths[e]);
      }
    }
    for (int h = 0; h < mesh.NumberOfHalfedges(); ++h)
    {
      const int a = NodeOf[mesh.Origin(h)], b = NodeOf[mesh.Destination(h)];
      add(a, b, mesh.EdgeLength(h));
      add(b, a, mesh.EdgeLength(h));
    }
  };
#pragma omp parallel num_threads(fillThreads)
  {
    const int t = omp_get_thread_num(), nt = omp_get_num_threads();
    const int lo = static_cast<int>(static_cast<long long>(nv) * t / nt);
    const int hi = static_cast<int>(static_cast<long long>(nv) * (t + 1) / nt);
    forEachEntry([&](int bucket, int, double) {
      if (bucket >= lo && bucket < hi)
      {
        count[bucket + 1]++;
      }
    });
#pragma omp barrier
#pragma omp single
    {
      for (int n = 0; n < nv; ++n)
      {
        count[n + 1] += count[n];
      }
      raw.resize(static_cast<std::size_t>(count[nv]));
      fill.assign(count.begin(), count.end() - 1);
    }
    forEachEntry([&](int bucket, int other, double weight) {
      if (bucket >= lo && bucket < hi)
      {
        raw[fill[bucket]++] = { other, weight };
      }
    });
  }
  std::vector<int>().swap(linkTargets);
  std::vector<double>().swap(linkLengths);
  std::vector<std::int64_t> kept(nv + 1, 0);
#pragma omp parallel for schedule(dynamic, 256) num_threads(buildThreads)
  for (int n = 0; n < nv; ++n)
  {
    auto first = raw.begin() + count[n], last = raw.begin() + count[n + 1];
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
  Offsets.assign(nv + 1, 0);
  for (int n = 0; n < nv; ++n)
  {
    Offsets[n + 1] = Offsets[n] + kept[n + 1];
  }
  Targets.resize(Offsets[nv]);
  Weights.resize(Offsets[nv]);
#pragma omp parallel for schedule(static) num_threads(fillThreads)
  for (int n = 0; n < nv; ++n)
  {
    for (std::int64_t i = 0; i < kept[n + 1]; ++i)
    {
      Targets[Offsets[n] + i] = raw[count[n] + i].first;
      Weights[Offsets[n] + i] = raw[count[n] + i].second;
    }
  }
  std::vector<std::pair<int, double>>().swap(raw); // before the link index adds its array
  IndexLinksInStencils();
  if (progress && !progress(1.0))
  {
    Clear();
    return Status::Aborted();
  }
  Construction = options.Construction;
  K = EffectiveK(options, nv);
  Accuracy = dgg ? options.Accuracy : 0.0;
  ReachedStencil = reachedStencil;
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

namespace
{
// What lies at a cache file's path.
enum class PathKind
{
  Missing,
  Regular,
  Other, // a directory, a FIFO, a device, a socket: never opened (a FIFO would block the open)
  Unknown // stat failed for another reason than a missing file (e.g. permissions)
};

PathKind KindOfPath(const std::string& path)
{
  struct stat st;
  if (::stat(path.c_str(), &st) != 0)
  {
    return errno == ENOENT ? PathKind::Missing : PathKind::Unknown;
  }
  return S_ISREG(st.st_mode) ? PathKind::Regular : PathKind::Other;
}

// Whether the regular file at `path` starts as one of this project's graph cache files do (any
// construction, any format version).
bool HoldsGraphCache(const std::string& path)
{
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
  {
    return false;
  }
  char magic[8] = {};
  const ssize_t n = ::read(fd, magic, sizeof(magic));
  ::close(fd);
  return n == static_cast<ssize_t>(sizeof(magic)) && GraphKind(magic) != nullptr;
}

// A name beside `path` for a file that only this call creates (O_EXCL): the process id and a
// process-wide counter, so that concurrent writers in one or several processes never share one.
int CreateTemporaryBeside(const std::string& path, std::string& temporary)
{
  static std::atomic<unsigned> counter{ 0 };
  for (int attempt = 0; attempt < 100; ++attempt)
  {
    temporary = path + ".tmp." + std::to_string(static_cast<long>(::getpid())) + "." +
      std::to_string(counter.fetch_add(1));
    // 0666 before the umask: the permissions a plain file written there would get.
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST)
    {
      return fd;
    }
  }
  return -1;
}

// Reads a file through a descriptor (Load opens it without blocking): read() fills a buffer or
// marks the reader failed, as an istream does.
class FileReader
{
public:
  explicit FileReader(int fd)
    : File(::fdopen(fd, "rb"))
  {
    if (!File)
    {
      ::close(fd);
    }
  }
  ~FileReader()
  {
    if (File)
    {
      std::fclose(File);
    }
  }
  FileReader(const FileReader&) = delete;
  FileReader& operator=(const FileReader&) = delete;
  void read(char* data, std::size_t n)
  {
    Good = Good && File && std::fread(data, 1, n, File) == n;
  }
  explicit operator bool() const { return Good && File; }
  bool operator!() const { return !static_cast<bool>(*this); }

private:
  std::FILE* File;
  bool Good = true;
};
} // namespace

Status SaddleVertexGraph::CheckCacheFileName(const std::string& path)
{
  switch (KindOfPath(path))
  {
    case PathKind::Missing:
      return Status();
    case PathKind::Other:
      return Status::Error(path + " is not a regular file (a directory, a pipe or a device); "
                                  "it is left untouched: choose another cache file name");
    case PathKind::Unknown:
      return Status::Error("cannot inspect " + path + " (" + std::strerror(errno) + ")");
    case PathKind::Regular:
    default:
      break;
  }
  if (!HoldsGraphCache(path))
  {
    return Status::Error(path + " exists and is not a geodesic graph cache file; it is left "
                                "untouched: choose another cache file name");
  }
  return Status();
}

Status SaddleVertexGraph::Save(const std::string& path, std::uint64_t meshHash) const
{
  const Status target = CheckCacheFileName(path);
  if (!target.Ok())
  {
    return target;
  }
  std::string temporary;
  const int fd = CreateTemporaryBeside(path, temporary);
  if (fd < 0)
  {
    return Status::Error("cannot write " + path + " (a temporary file beside it could not be "
                                                  "created: " + std::strerror(errno) + ")");
  }
  bool good = true;
  auto put = [fd, &good](const void* data, std::size_t n) {
    const char* p = static_cast<const char*>(data);
    while (good && n > 0)
    {
      const ssize_t written = ::write(fd, p, n);
      if (written < 0 && errno == EINTR)
      {
        continue;
      }
      if (written <= 0)
      {
        good = false;
        break;
      }
      p += written;
      n -= static_cast<std::size_t>(written);
    }
  };
  const std::int64_t nv = NumberOfVertices(), ne = NumberOfEntries();
  const bool dgg = Construction == GraphConstruction::DiscreteGeodesic;
  const std::int32_t k = K;
  const double accuracy = Accuracy;
  const void* key = dgg ? static_cast<const void*>(&accuracy) : static_cast<const void*>(&k);
  const std::size_t keySize = dgg ? sizeof(accuracy) : sizeof(k);
  const double seconds = Seconds;
  Hasher sum;
  sum.Add(&meshHash, sizeof(meshHash));
  sum.Add(key, keySize);
  sum.Add(&seconds, sizeof(seconds));
  sum.Add(&nv, sizeof(nv));
  sum.Add(&ne, sizeof(ne));
  sum.AddVector(Offsets);
  sum.AddVector(Targets);
  sum.AddVector(Weights);
  // The stencil as the file stores it: targets, distances and positions in arrays of their own.
  const std::int64_t ns = static_cast<std::int64_t>(Stencil.size());
  std::vector<int> stencilTargets(ns);
  std::vector<double> stencilR(ns), stencilXY(2 * ns);
  for (std::int64_t e = 0; e < ns; ++e)
  {
    stencilTargets[e] = Stencil[e].Target;
    stencilR[e] = StencilDistance(e);
    stencilXY[2 * e] = Stencil[e].X;
    stencilXY[2 * e + 1] = Stencil[e].Y;
  }
  sum.Add(&ns, sizeof(ns));
  sum.AddVector(StencilOffsets);
  sum.AddVector(stencilTargets);
  sum.AddVector(stencilR);
  sum.AddVector(stencilXY);
  sum.AddVector(WrapXY);
  sum.AddVector(VertexOf);
  put(dgg ? (ReachedStencil ? DGRMagic : DGGMagic) : Magic, sizeof(Magic));
  put(&meshHash, sizeof(meshHash));
  put(key, keySize);
  put(&seconds, sizeof(seconds));
  put(&nv, sizeof(nv));
  put(&ne, sizeof(ne));
  put(Offsets.data(), Offsets.size() * sizeof(std::int64_t));
  put(Targets.data(), Targets.size() * sizeof(int));
  put(Weights.data(), Weights.size() * sizeof(double));
  put(&ns, sizeof(ns));
  put(StencilOffsets.data(), StencilOffsets.size() * sizeof(std::int64_t));
  put(stencilTargets.data(), stencilTargets.size() * sizeof(int));
  put(stencilR.data(), stencilR.size() * sizeof(double));
  put(stencilXY.data(), stencilXY.size() * sizeof(double));
  put(WrapXY.data(), WrapXY.size() * sizeof(double));
  put(VertexOf.data(), VertexOf.size() * sizeof(int));
  put(&sum.H, sizeof(sum.H));
  const int writeError = good ? 0 : errno;
  // On disk before the rename, so that a crash cannot leave the new name on a partial file.
  good = good && ::fsync(fd) == 0;
  good = (::close(fd) == 0) && good;
  if (!good)
  {
    const std::string why = std::strerror(writeError ? writeError : errno);
    ::unlink(temporary.c_str());
    return Status::Error("error while writing " + path + " (" + why + "); the previous file, if "
                                                                     "any, is unchanged");
  }
  // Checked again just before the rename: what took the name meanwhile is not replaced either.
  const Status still = CheckCacheFileName(path);
  if (!still.Ok() || ::rename(temporary.c_str(), path.c_str()) != 0)
  {
    const std::string why = still.Ok() ? std::string(std::strerror(errno)) : still.Message();
    ::unlink(temporary.c_str());
    return Status::Error("cannot write " + path + " (" + why + ")");
  }
  return Status();
}

Status SaddleVertexGraph::Load(const std::string& path, std::uint64_t meshHash, int k)
{
  SaddleVertexGraphOptions options;
  options.K = k;
  return Load(path, meshHash, options);
}

Status SaddleVertexGraph::Load(
  const std::string& path, std::uint64_t meshHash, const SaddleVertexGraphOptions& options)
{
  const bool dgg = options.Construction == GraphConstruction::DiscreteGeodesic;
  const int k = options.K;
  Clear();
  // (A FIFO or a device is never read: opened without blocking, then checked on the open
  // descriptor, so that nothing put at the path meanwhile can block the read either.)
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0)
  {
    return Status::Error(errno == ENOENT ? path + " does not exist"
                                         : "cannot open " + path + " (" + std::strerror(errno) + ")");
  }
  struct stat st;
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
  {
    ::close(fd);
    return Status::Error(path + " is not a regular file");
  }
  FileReader in(fd);
  const std::int64_t fileSize = static_cast<std::int64_t>(st.st_size);
  char magic[8] = {};
  std::uint64_t hash = 0;
  std::int32_t fileK = 0;
  double fileAccuracy = 0.0;
  void* key = dgg ? static_cast<void*>(&fileAccuracy) : static_cast<void*>(&fileK);
  const std::int64_t keySize = dgg ? sizeof(fileAccuracy) : sizeof(fileK);
  double seconds = 0.0;
  std::int64_t nv = 0, ne = 0;
  in.read(magic, sizeof(magic));
  const bool reachedStencil = dgg && options.ReachedStencil;
  const char* expected = dgg ? (reachedStencil ? DGRMagic : DGGMagic) : Magic;
  if (in && std::memcmp(magic, expected, 5) != 0 && GraphKind(magic))
  {
    return Status::Error(
      path + " holds " + GraphKind(magic) + ", not " + GraphKind(expected));
  }
  in.read(reinterpret_cast<char*>(&hash), sizeof(hash));
  in.read(static_cast<char*>(key), keySize);
  in.read(reinterpret_cast<char*>(&seconds), sizeof(seconds));
  in.read(reinterpret_cast<char*>(&nv), sizeof(nv));
  in.read(reinterpret_cast<char*>(&ne), sizeof(ne));
  if (!in || std::memcmp(magic, expected, sizeof(Magic)) != 0)
  {
    // (Format 004 added the node order; earlier files are rebuilt.)
    return Status::Error(in && std::memcmp(magic, expected, 5) == 0
      ? path + " is a geodesic graph cache file of another format version"
      : path + " is not a geodesic graph cache file");
  }
  if (hash != meshHash)
  {
    return Status::Error(path + " was made for another mesh");
  }
  // K is clamped to the vertex count when building: compare the clamped request.
  if (dgg && fileAccuracy != options.Accuracy)
  {
    return Status::Error(path + " was made for the accuracy " + std::to_string(fileAccuracy) +
      ", not " + std::to_string(options.Accuracy));
  }
  if (!dgg && nv >= 1 && static_cast<std::int64_t>(fileK) != std::min<std::int64_t>(k, nv))
  {
    return Status::Error(
      path + " was made with K = " + std::to_string(fileK) + ", not " + std::to_string(k));
  }
  const std::int64_t header =
    sizeof(Magic) + sizeof(hash) + keySize + sizeof(seconds) + 2 * sizeof(std::int64_t);
  // Size of everything before the stencil count, and what the stencil adds for ns entries.
  const std::int64_t linksEnd = header + (nv + 1) * 8 + ne * 12;
  if (nv < 1 || ne < 0 || nv > (1LL << 31) || ne > (1LL << 40) || fileSize < linksEnd + 16)
  {
    return Status::Error(path + " is truncated or corrupt (size does not match its header)");
  }
  std::vector<std::int64_t> offsets(nv + 1);
  std::vector<int> targets(ne);
  std::vector<double> weights(ne);
  std::int64_t ns = -1;
  in.read(reinterpret_cast<char*>(offsets.data()), offsets.size() * sizeof(std::int64_t));
  in.read(reinterpret_cast<char*>(targets.data()), targets.size() * sizeof(int));
  in.read(reinterpret_cast<char*>(weights.data()), weights.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(&ns), sizeof(ns));
  if (!in || ns < 0 || ns > (1LL << 40) ||
    fileSize != linksEnd + 8 + (nv + 1) * 8 + ns * (4 + 8 + 16) + 16 * nv + 4 * nv + 8)
  {
    return Status::Error(path + " is truncated or corrupt (size does not match its header)");
  }
  std::vector<std::int64_t> stencilOffsets(nv + 1);
  std::vector<int> stencilTargets(ns);
  std::vector<double> stencilR(ns), stencilXY(2 * ns), wrapXY(2 * nv);
  std::vector<int> vertexOf(nv);
  std::uint64_t stored = 0;
  in.read(reinterpret_cast<char*>(stencilOffsets.data()), stencilOffsets.size() * sizeof(std::int64_t));
  in.read(reinterpret_cast<char*>(stencilTargets.data()), stencilTargets.size() * sizeof(int));
  in.read(reinterpret_cast<char*>(stencilR.data()), stencilR.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(stencilXY.data()), stencilXY.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(wrapXY.data()), wrapXY.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(vertexOf.data()), vertexOf.size() * sizeof(int));
  in.read(reinterpret_cast<char*>(&stored), sizeof(stored));
  if (!in)
  {
    return Status::Error(path + " is truncated");
  }
  Hasher sum;
  sum.Add(&hash, sizeof(hash));
  sum.Add(key, static_cast<std::size_t>(keySize));
  sum.Add(&seconds, sizeof(seconds));
  sum.Add(&nv, sizeof(nv));
  sum.Add(&ne, sizeof(ne));
  sum.AddVector(offsets);
  sum.AddVector(targets);
  sum.AddVector(weights);
  sum.Add(&ns, sizeof(ns));
  sum.AddVector(stencilOffsets);
  sum.AddVector(stencilTargets);
  sum.AddVector(stencilR);
  sum.AddVector(stencilXY);
  sum.AddVector(wrapXY);
  sum.AddVector(vertexOf);
  if (sum.H != stored)
  {
    return Status::Error(path + " is corrupt (checksum mismatch)");
  }
  // Structural checks, so that even a forged file with a valid checksum cannot cause
  // out-of-range reads.
  auto validOffsets = [nv](const std::vector<std::int64_t>& o, std::int64_t total) {
    if (o[0] != 0 || o[nv] != total)
      return false;
    for (std::int64_t v = 0; v < nv; ++v)
      if (o[v + 1] < o[v])
        return false;
    return true;
  };
  if (!validOffsets(offsets, ne) || !validOffsets(stencilOffsets, ns))
  {
    return Status::Error(path + " is corrupt (bad offsets)");
  }
  for (std::int64_t e = 0; e < ne; ++e)
  {
    if (targets[e] < 0 || targets[e] >= nv || !(weights[e] >= 0.0) || !std::isfinite(weights[e]))
    {
      return Status::Error(path + " is corrupt (bad link)");
    }
  }
  for (std::int64_t e = 0; e < ns; ++e)
  {
    if (stencilTargets[e] < 0 || stencilTargets[e] >= nv || !std::isfinite(stencilR[e]) ||
      !std::isfinite(stencilXY[2 * e]) || !std::isfinite(stencilXY[2 * e + 1]))
    {
      return Status::Error(path + " is corrupt (bad stencil)");
    }
  }
  for (double w : wrapXY)
  {
    if (!std::isfinite(w))
    {
      return Status::Error(path + " is corrupt (bad stencil)");
    }
  }
  // The node order must be a permutation of the vertices.
  std::vector<int> nodeOf(nv, -1);
  for (std::int64_t n = 0; n < nv; ++n)
  {
    const int v = vertexOf[n];
    if (v < 0 || v >= nv || nodeOf[v] >= 0)
    {
      return Status::Error(path + " is corrupt (bad node order)");
    }
    nodeOf[v] = static_cast<int>(n);
  }
  Offsets = std::move(offsets);
  Targets = std::move(targets);
  Weights = std::move(weights);
  StencilOffsets = std::move(stencilOffsets);
  Stencil.resize(ns);
  for (std::int64_t e = 0; e < ns; ++e)
  {
    Stencil[e].Target = stencilTargets[e];
    Stencil[e].X = stencilXY[2 * e];
    Stencil[e].Y = stencilXY[2 * e + 1];
  }
  WrapXY = std::move(wrapXY);
  VertexOf = std::move(vertexOf);
  NodeOf = std::move(nodeOf);
  IndexLinksInStencils();
  Construction = options.Construction;
  K = dgg ? 0 : fileK;
  Accuracy = dgg ? fileAccuracy : 0.0;
  ReachedStencil = reachedStencil;
  Seconds = std::isfinite(seconds) && seconds >= 0.0 ? seconds : 0.0;
  return Status();
}

Status SaddleVertexGraph::Verify(const TriangleMesh& mesh) const
{
  const Status sameSize = CheckMesh(mesh);
  if (!sameSize.Ok())
  {
    return sameSize;
  }
  const int nv = NumberOfVertices();
  // Rounding allowance: relative to the length compared, and absolute at the mesh's scale.
  const double slack = 1e-12 * mesh.BoundingBoxDiagonal();
  auto below = [slack](double w, double bound) { return w < bound * (1.0 - 1e-9) - slack; };
  auto differs = [slack](double w, double exact) {
    return std::abs(w - exact) > 1e-9 * exact + slack;
  };
  auto describe = [this, &mesh](int node, std::int64_t e) {
    const int u = Vertex(node), x = Vertex(Target(e));
    return "the link from vertex " + std::to_string(u) + " to vertex " + std::to_string(x) +
      " (weight " + std::to_string(Weight(e)) + ", straight distance " +
      std::to_string(Norm(mesh.Position(u) - mesh.Position(x))) + ")";
  };
  // A saddle vertex graph links each vertex to the vertices whose shortest geodesic is direct:
  // its weights are geodesic distances. A discrete geodesic graph may keep a direct geodesic
  // that is longer than the shortest path (around the other side of a bump), and its stencils
  // may hold another geodesic to the same vertex: its weights are only bounded from below.
  const bool shortest = Construction == GraphConstruction::SaddleVertex;
  // 1. Every link at least as long as the straight segment between its ends (no path on the
  // surface is shorter); in a saddle vertex graph, equal to its entry in its target's polar
  // stencil where it has one.
  // 2. Every mesh edge a link whose weight is the edge's length (graphs keep every edge).
  // The first failing node in node order (the same message for any thread count).
  auto linkFault = [&](int n, std::int64_t e) -> const char* {
    const int x = Vertex(Target(e));
    if (below(Weight(e), Norm(mesh.Position(Vertex(n)) - mesh.Position(x))))
    {
      return " is shorter than the straight distance";
    }
    const int s = shortest ? LinkStencil[e] : -1;
    return s >= 0 && differs(Weight(e), StencilDistance(StencilBegin(Target(e)) + s))
      ? " differs from its stencil entry"
      : nullptr;
  };
  auto edgesFault = [&](int n) {
    bool fault = false;
    mesh.ForEachOutgoingHalfedge(Vertex(n), [&](int h) {
      const int x = Node(mesh.Destination(h));
      const auto first = Targets.begin() + Begin(n), last = Targets.begin() + End(n);
      const auto it = std::lower_bound(first, last, x);
      fault = fault || it == last || *it != x ||
        differs(Weights[it - Targets.begin()], mesh.EdgeLength(h));
    });
    return fault;
  };
  int firstBad = nv;
#pragma omp parallel for schedule(dynamic, 4096) reduction(min : firstBad)
  for (int n = 0; n < nv; ++n)
  {
    bool fault = edgesFault(n);
    for (std::int64_t e = Begin(n); e < End(n) && !fault; ++e)
    {
      fault = linkFault(n, e) != nullptr;
    }
    if (fault)
    {
      firstBad = std::min(firstBad, n);
    }
  }
  if (firstBad < nv)
  {
    for (std::int64_t e = Begin(firstBad); e < End(firstBad); ++e)
    {
      if (const char* fault = linkFault(firstBad, e))
      {
        return Status::Error(describe(firstBad, e) + fault);
      }
    }
    return Status::Error("a mesh edge at vertex " + std::to_string(Vertex(firstBad)) +
      " is missing from the graph or has a weight other than its length");
  }
  // 3. Every link of a sample of vertices, spread over the surface (nodes are in spatial
  // order), equal to the exact geodesic distance between its ends (a discrete geodesic graph's:
  // at least that distance). The solves stop at the longest link (and at MaximumVerified
  // vertices: longer links of a discrete geodesic graph go unchecked).
  constexpr int Samples = 48;
  constexpr int MaximumVerified = 4096;
  ExactGeodesicSolver exact(mesh);
  const int samples = std::min(nv, Samples);
  for (int i = 0; i < samples; ++i)
  {
    const int n = static_cast<int>((static_cast<std::int64_t>(2 * i + 1) * nv) / (2 * samples));
    double longest = 0.0;
    for (std::int64_t e = Begin(n); e < End(n); ++e)
    {
      longest = std::max(longest, Weight(e));
    }
    ExactGeodesicOptions options;
    options.MaximumDistance = longest * (1.0 + 1e-6) + slack;
    options.MaximumFinalVertices = MaximumVerified;
    if (!exact.Solve(Vertex(n), options).Ok())
    {
      continue;
    }
    for (std::int64_t e = Begin(n); e < End(n); ++e)
    {
      const double d = exact.Distance(Vertex(Target(e)));
      if (std::isfinite(d) && (shortest ? differs(Weight(e), d) : below(Weight(e), d)))
      {
        return Status::Error(describe(n, e) + (shortest ? " differs from" : " is shorter than") +
          " the exact geodesic distance " + std::to_string(d));
      }
    }
  }
  return Status();
}

GraphDistanceSolver::GraphDistanceSolver(const SaddleVertexGraph& graph)
  : Graph(graph)
{
  const int nv = Graph.NumberOfVertices();
  Dist.assign(nv, Inf);
  Pred.assign(nv, { -1, -1 });
  InQueue.assign(nv, 0);
  Ring.assign(nv + 1, 0);
}

void GraphDistanceSolver::Solve(const std::vector<std::pair<int, double>>& seeds,
  GraphAlgorithm algorithm, double maxDistance)
{
  for (int v : Touched)
  {
    Dist[v] = Inf;
    Pred[v] = { -1, -1 };
    InQueue[v] = 0;
  }
  Touched.clear();
  NumRelaxations = 0;
  const double limit = maxDistance > 0.0 ? maxDistance : Inf;
  for (const auto& s : seeds)
  {
    if (s.first < 0 || s.first >= Graph.NumberOfVertices() || !(s.second <= limit))
    {
      continue;
    }
    if (Dist[s.first] == Inf)
    {
      Touched.push_back(s.first);
    }
    Dist[s.first] = std::min(Dist[s.first], s.second);
  }
  if (algorithm == GraphAlgorithm::Dijkstra)
  {
    SolveDijkstra(limit);
  }
  else
  {
    SolveLabelCorrecting(limit);
  }
}

void GraphDistanceSolver::SolveLabelCorrecting(double limit)
{
  // A circular deque holding each vertex at most once. SLF (small label first): a vertex whose
  // new label is below the front's goes to the front. LLL (large label last): a front vertex
  // whose label exceeds the queue's mean is moved to the back before extraction.
  //
  // The arrays are reached through local pointers: through the members, the stores of a
  // relaxation made the compiler reload every array's address for every link scanned (the scan
  // is most of the solve: about 55 links per popped vertex).
  double* const dist = Dist.data();
  unsigned char* const inQueue = InQueue.data();
  PredLink* const pred = Pred.data();
  int* const ring = Ring.data();
  const std::int64_t* const offsets = Graph.Offsets.data();
  const int* const targets = Graph.Targets.data();
  const double* const weights = Graph.Weights.data();
  std::int64_t relaxations = 0;
  const std::size_t cap = Ring.size();
  std::size_t head = 0, size = 0;
  double sum = 0.0;
  // (Index arithmetic by comparison, not %: a division per queue operation cost ~10% of the
  // solve.)
  auto wrap = [cap](std::size_t i) { return i >= cap ? i - cap : i; };
  for (int v : Touched)
  {
    inQueue[v] = 1;
    ring[wrap(head + size)] = v;
    ++size;
    sum += dist[v];
  }
  while (size > 0)
  {
    const double mean = sum / static_cast<double>(size);
    for (std::size_t tries = 0; tries < size && dist[ring[head]] > mean; ++tries)
    {
      const int v = ring[head];
      head = wrap(head + 1);
      ring[wrap(head + size - 1)] = v;
    }
    const int u = ring[head];
    head = wrap(head + 1);
    --size;
    // The queue says which vertices come next: their adjacency (a random place in memory, most
    // of the solve's time otherwise) is fetched while u is scanned, the offsets a little earlier.
    // (LLL may still move them back; measured 1.5x faster on 26K-vertex meshes.)
    if (size > 5)
    {
      Graph.PrefetchOffsets(ring[wrap(head + 5)]);
    }
    if (size > 1)
    {
      Graph.PrefetchAdjacency(ring[wrap(head + 1)]);
    }
    inQueue[u] = 0;
    sum -= dist[u];
    if (size == 0)
    {
      sum = 0.0; // no drift accumulates across emptyings
    }
    const double du = dist[u];
    const std::int64_t first = offsets[u], end = offsets[u + 1];
    // Most links relax nothing: with SSE2, two links are tested at once and only those that
    // improve go through the (scalar) update below.
    auto relax = [&](std::int64_t e) {
      const int v = targets[e];
      const double nd = du + weights[e];
      if (!(nd < dist[v]) || !(nd <= limit))
      {
        return;
      }
      ++relaxations;
      if (dist[v] == Inf)
      {
        Touched.push_back(v);
      }
      pred[v] = { e, u };
      if (inQueue[v])
      {
        sum += nd - dist[v];
        dist[v] = nd;
        return;
      }
      dist[v] = nd;
      inQueue[v] = 1;
      sum += nd;
      if (size > 0 && nd < dist[ring[head]])
      {
        head = head == 0 ? cap - 1 : head - 1;
        ring[head] = v;
      }
      else
      {
        ring[wrap(head + size)] = v;
      }
      ++size;
    };
    std::int64_t e = first;
#if defined(__SSE2__)
    const __m128d du2 = _mm_set1_pd(du);
    for (; e + 2 <= end; e += 2)
    {
      const __m128d nd = _mm_add_pd(du2, _mm_loadu_pd(weights + e));
      const __m128d old = _mm_set_pd(dist[targets[e + 1]], dist[targets[e]]);
      const int better = _mm_movemask_pd(_mm_cmplt_pd(nd, old));
      if (better & 1)
      {
        relax(e);
      }
      if (better & 2)
      {
        relax(e + 1);
      }
    }
#endif
    for (; e < end; ++e)
    {
      relax(e);
    }
  }
  NumRelaxations += relaxations;
}

void GraphDistanceSolver::SolveDijkstra(double limit)
{
  struct Item
  {
    double D;
    int V;
    bool operator<(const Item& o) const { return D > o.D; }
  };
  std::vector<Item> heap;
  heap.reserve(Touched.size() * 4 + 16);
  for (int v : Touched)
  {
    heap.push_back({ Dist[v], v });
  }
  std::make_heap(heap.begin(), heap.end());
  while (!heap.empty())
  {
    std::pop_heap(heap.begin(), heap.end());
    const Item it = heap.back();
    heap.pop_back();
    if (it.D > Dist[it.V])
    {
      continue;
    }
    for (std::int64_t e = Graph.Begin(it.V), end = Graph.End(it.V); e < end; ++e)
    {
      const int v = Graph.Target(e);
      const double nd = it.D + Graph.Weight(e);
      if (nd < Dist[v] && nd <= limit)
      {
        ++NumRelaxations;
        if (Dist[v] == Inf)
        {
          Touched.push_back(v);
        }
        Dist[v] = nd;
        Pred[v] = { e, it.V };
        heap.push_back({ nd, v });
        std::push_heap(heap.begin(), heap.end());
      }
    }
  }
}

} // namespace gs
