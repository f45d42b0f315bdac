// The graphs' cache files (Save, Load, CheckCacheFileName) and the check of a loaded graph
// against its mesh (Verify).
#include "SaddleVertexGraph.h"

#include "ExactGeodesic.h"
#include "Hash.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include <cerrno>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace gs
{

namespace
{
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
} // namespace

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

// The fields of a cache file after its magic, in file order, which its checksum covers in the
// same order: Save writes and sums the graph's, Load sums what it read.
struct CacheFields
{
  const std::uint64_t& MeshHash;
  const void* Key; // K (int32) for a saddle vertex graph, the accuracy (double) otherwise
  std::size_t KeySize;
  const double& Seconds;
  const std::int64_t& Nv;
  const std::int64_t& Ne;
  const std::vector<std::int64_t>& Offsets;
  const std::vector<int>& Targets;
  const std::vector<double>& Weights;
  const std::int64_t& Ns;
  const std::vector<std::int64_t>& StencilOffsets;
  // The stencil as the file stores it: targets, distances and positions in arrays of their own.
  const std::vector<int>& StencilTargets;
  const std::vector<double>& StencilR;
  const std::vector<double>& StencilXY;
  const std::vector<double>& WrapXY;
  const std::vector<int>& VertexOf;

  // Calls f(data, bytes) for each field, in file order.
  template <class F>
  void ForEach(const F& f) const
  {
    auto array = [&f](const auto& v) { f(v.data(), v.size() * sizeof(v[0])); };
    f(&MeshHash, sizeof(MeshHash));
    f(Key, KeySize);
    f(&Seconds, sizeof(Seconds));
    f(&Nv, sizeof(Nv));
    f(&Ne, sizeof(Ne));
    array(Offsets);
    array(Targets);
    array(Weights);
    f(&Ns, sizeof(Ns));
    array(StencilOffsets);
    array(StencilTargets);
    array(StencilR);
    array(StencilXY);
    array(WrapXY);
    array(VertexOf);
  }
  std::uint64_t Checksum() const
  {
    Hasher sum;
    ForEach([&sum](const void* data, std::size_t n) { sum.Add(data, n); });
    return sum.H;
  }
};

// What Load reads of a cache file, in file order (see CacheFields), and the node order derived
// from it (NodeOf).
struct CacheFile
{
  explicit CacheFile(bool dgg)
    : Dgg(dgg)
  {
  }
  // Where the key is read: the accuracy for a discrete geodesic graph, K otherwise.
  void* Key() { return Dgg ? static_cast<void*>(&Accuracy) : static_cast<void*>(&K); }
  std::int64_t KeySize() const { return Dgg ? sizeof(Accuracy) : sizeof(K); }
  CacheFields Fields()
  {
    return { Hash, Key(), static_cast<std::size_t>(KeySize()), Seconds, Nv, Ne, Offsets, Targets,
      Weights, Ns, StencilOffsets, StencilTargets, StencilR, StencilXY, WrapXY, VertexOf };
  }

  const bool Dgg;
  std::int64_t Size = 0; // bytes
  // Size of everything before the stencil count.
  std::int64_t LinksEnd = 0;
  char FileMagic[8] = {};
  std::uint64_t Hash = 0;
  std::int32_t K = 0;
  double Accuracy = 0.0;
  double Seconds = 0.0;
  std::int64_t Nv = 0, Ne = 0;
  std::vector<std::int64_t> Offsets;
  std::vector<int> Targets;
  std::vector<double> Weights;
  std::int64_t Ns = -1;
  std::vector<std::int64_t> StencilOffsets;
  std::vector<int> StencilTargets;
  std::vector<double> StencilR, StencilXY, WrapXY;
  std::vector<int> VertexOf, NodeOf;
  std::uint64_t Stored = 0; // the checksum
};

// Reads the magic and the header (Load): an error when the file is not a graph cache file of
// the kind and format version asked for, was made for another mesh, accuracy or K, or is not as
// long as its header says.
Status ReadHeader(FileReader& in, const std::string& path, std::uint64_t meshHash,
  const SaddleVertexGraphOptions& options, CacheFile& f)
{
  const bool dgg = f.Dgg;
  const int k = options.K;
  in.read(f.FileMagic, sizeof(f.FileMagic));
  const bool reachedStencil = dgg && options.ReachedStencil;
  const char* expected = dgg ? (reachedStencil ? DGRMagic : DGGMagic) : Magic;
  if (in && std::memcmp(f.FileMagic, expected, 5) != 0 && GraphKind(f.FileMagic))
  {
    return Status::Error(
      path + " holds " + GraphKind(f.FileMagic) + ", not " + GraphKind(expected));
  }
  in.read(reinterpret_cast<char*>(&f.Hash), sizeof(f.Hash));
  in.read(static_cast<char*>(f.Key()), f.KeySize());
  in.read(reinterpret_cast<char*>(&f.Seconds), sizeof(f.Seconds));
  in.read(reinterpret_cast<char*>(&f.Nv), sizeof(f.Nv));
  in.read(reinterpret_cast<char*>(&f.Ne), sizeof(f.Ne));
  if (!in || std::memcmp(f.FileMagic, expected, sizeof(Magic)) != 0)
  {
    // (Format 004 added the node order; earlier files are rebuilt.)
    return Status::Error(in && std::memcmp(f.FileMagic, expected, 5) == 0
      ? path + " is a geodesic graph cache file of another format version"
      : path + " is not a geodesic graph cache file");
  }
  if (f.Hash != meshHash)
  {
    return Status::Error(path + " was made for another mesh");
  }
  // K is clamped to the vertex count when building: compare the clamped request.
  if (dgg && f.Accuracy != options.Accuracy)
  {
    return Status::Error(path + " was made for the accuracy " + std::to_string(f.Accuracy) +
      ", not " + std::to_string(options.Accuracy));
  }
  if (!dgg && f.Nv >= 1 && static_cast<std::int64_t>(f.K) != std::min<std::int64_t>(k, f.Nv))
  {
    return Status::Error(
      path + " was made with K = " + std::to_string(f.K) + ", not " + std::to_string(k));
  }
  const std::int64_t header =
    sizeof(Magic) + sizeof(f.Hash) + f.KeySize() + sizeof(f.Seconds) + 2 * sizeof(std::int64_t);
  // Size of everything before the stencil count, and what the stencil adds for ns entries.
  f.LinksEnd = header + (f.Nv + 1) * 8 + f.Ne * 12;
  if (f.Nv < 1 || f.Ne < 0 || f.Nv > (1LL << 31) || f.Ne > (1LL << 40) || f.Size < f.LinksEnd + 16)
  {
    return Status::Error(path + " is truncated or corrupt (size does not match its header)");
  }
  return Status();
}

// Reads the arrays after the header, up to the checksum (Load): the links, then, once the file's
// size matches the stencil's count, the stencil and the node order.
Status ReadArrays(FileReader& in, const std::string& path, CacheFile& f)
{
  const std::int64_t nv = f.Nv, ne = f.Ne;
  f.Offsets.resize(nv + 1);
  f.Targets.resize(ne);
  f.Weights.resize(ne);
  in.read(reinterpret_cast<char*>(f.Offsets.data()), f.Offsets.size() * sizeof(std::int64_t));
  in.read(reinterpret_cast<char*>(f.Targets.data()), f.Targets.size() * sizeof(int));
  in.read(reinterpret_cast<char*>(f.Weights.data()), f.Weights.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(&f.Ns), sizeof(f.Ns));
  const std::int64_t ns = f.Ns;
  if (!in || ns < 0 || ns > (1LL << 40) ||
    f.Size != f.LinksEnd + 8 + (nv + 1) * 8 + ns * (4 + 8 + 16) + 16 * nv + 4 * nv + 8)
  {
    return Status::Error(path + " is truncated or corrupt (size does not match its header)");
  }
  f.StencilOffsets.resize(nv + 1);
  f.StencilTargets.resize(ns);
  f.StencilR.resize(ns);
  f.StencilXY.resize(2 * ns);
  f.WrapXY.resize(2 * nv);
  f.VertexOf.resize(nv);
  in.read(reinterpret_cast<char*>(f.StencilOffsets.data()),
    f.StencilOffsets.size() * sizeof(std::int64_t));
  in.read(reinterpret_cast<char*>(f.StencilTargets.data()), f.StencilTargets.size() * sizeof(int));
  in.read(reinterpret_cast<char*>(f.StencilR.data()), f.StencilR.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(f.StencilXY.data()), f.StencilXY.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(f.WrapXY.data()), f.WrapXY.size() * sizeof(double));
  in.read(reinterpret_cast<char*>(f.VertexOf.data()), f.VertexOf.size() * sizeof(int));
  in.read(reinterpret_cast<char*>(&f.Stored), sizeof(f.Stored));
  if (!in)
  {
    return Status::Error(path + " is truncated");
  }
  return Status();
}

// Structural checks, so that even a forged file with a valid checksum cannot cause
// out-of-range reads: offsets, link and stencil targets and values, and the node order (a
// permutation of the vertices, whose inverse goes to NodeOf).
Status CheckStructure(const std::string& path, CacheFile& f)
{
  const std::int64_t nv = f.Nv, ne = f.Ne, ns = f.Ns;
  auto validOffsets = [nv](const std::vector<std::int64_t>& o, std::int64_t total) {
    if (o[0] != 0 || o[nv] != total)
      return false;
    for (std::int64_t v = 0; v < nv; ++v)
      if (o[v + 1] < o[v])
        return false;
    return true;
  };
  if (!validOffsets(f.Offsets, ne) || !validOffsets(f.StencilOffsets, ns))
  {
    return Status::Error(path + " is corrupt (bad offsets)");
  }
  for (std::int64_t e = 0; e < ne; ++e)
  {
    if (f.Targets[e] < 0 || f.Targets[e] >= nv || !(f.Weights[e] >= 0.0) ||
      !std::isfinite(f.Weights[e]))
    {
      return Status::Error(path + " is corrupt (bad link)");
    }
  }
  for (std::int64_t e = 0; e < ns; ++e)
  {
    if (f.StencilTargets[e] < 0 || f.StencilTargets[e] >= nv || !std::isfinite(f.StencilR[e]) ||
      !std::isfinite(f.StencilXY[2 * e]) || !std::isfinite(f.StencilXY[2 * e + 1]))
    {
      return Status::Error(path + " is corrupt (bad stencil)");
    }
  }
  for (double w : f.WrapXY)
  {
    if (!std::isfinite(w))
    {
      return Status::Error(path + " is corrupt (bad stencil)");
    }
  }
  // The node order must be a permutation of the vertices.
  f.NodeOf.assign(nv, -1);
  for (std::int64_t n = 0; n < nv; ++n)
  {
    const int v = f.VertexOf[n];
    if (v < 0 || v >= nv || f.NodeOf[v] >= 0)
    {
      return Status::Error(path + " is corrupt (bad node order)");
    }
    f.NodeOf[v] = static_cast<int>(n);
  }
  return Status();
}
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
  const CacheFields fields{ meshHash, key, keySize, seconds, nv, ne, Offsets, Targets, Weights, ns,
    StencilOffsets, stencilTargets, stencilR, stencilXY, WrapXY, VertexOf };
  const std::uint64_t sum = fields.Checksum();
  put(dgg ? (ReachedStencil ? DGRMagic : DGGMagic) : Magic, sizeof(Magic));
  fields.ForEach(put);
  put(&sum, sizeof(sum));
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
  CacheFile file(dgg);
  file.Size = static_cast<std::int64_t>(st.st_size);
  if (const Status header = ReadHeader(in, path, meshHash, options, file); !header.Ok())
  {
    return header;
  }
  if (const Status arrays = ReadArrays(in, path, file); !arrays.Ok())
  {
    return arrays;
  }
  if (file.Fields().Checksum() != file.Stored)
  {
    return Status::Error(path + " is corrupt (checksum mismatch)");
  }
  if (const Status formed = CheckStructure(path, file); !formed.Ok())
  {
    return formed;
  }
  Offsets = std::move(file.Offsets);
  Targets = std::move(file.Targets);
  Weights = std::move(file.Weights);
  StencilOffsets = std::move(file.StencilOffsets);
  Stencil.resize(file.Ns);
  for (std::int64_t e = 0; e < file.Ns; ++e)
  {
    Stencil[e].Target = file.StencilTargets[e];
    Stencil[e].X = file.StencilXY[2 * e];
    Stencil[e].Y = file.StencilXY[2 * e + 1];
  }
  WrapXY = std::move(file.WrapXY);
  VertexOf = std::move(file.VertexOf);
  NodeOf = std::move(file.NodeOf);
  IndexLinksInStencils();
  Construction = options.Construction;
  K = dgg ? 0 : file.K;
  Accuracy = dgg ? file.Accuracy : 0.0;
  ReachedStencil = dgg && options.ReachedStencil;
  Seconds = std::isfinite(file.Seconds) && file.Seconds >= 0.0 ? file.Seconds : 0.0;
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

} // namespace gs
