// Graph cache files as a user's disk sees them (SaddleVertexGraph::Save, CheckCacheFileName,
// Load, Verify): a file that is not a cache is never overwritten, a write replaces the file
// whole or not at all (interrupted, concurrent), a FIFO never blocks, and a forged file whose
// checksum was recomputed is caught by Verify against the mesh.
#include "Hash.h"
#include "MeshGenerators.h"
#include "SaddleVertexGraph.h"
#include "TestMeshes.h"
#include "TestStatus.h"

#include <gtest/gtest.h>

#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <sys/resource.h>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>
#include <vector>

using namespace gs;

namespace
{
std::string TempPath(const std::string& name)
{
  return std::string(::testing::TempDir()) + name;
}

std::string ReadBytes(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void WriteBytes(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
}

SaddleVertexGraph Build(const TriangleMesh& m, const SaddleVertexGraphOptions& o)
{
  SaddleVertexGraph g;
  EXPECT_TRUE(gs_test::Succeeded(g.Build(m, o, nullptr)));
  return g;
}

SaddleVertexGraphOptions SVG(int k)
{
  SaddleVertexGraphOptions o;
  o.K = k;
  return o;
}

SaddleVertexGraphOptions DGG(double accuracy, bool reached)
{
  SaddleVertexGraphOptions o;
  o.Construction = GraphConstruction::DiscreteGeodesic;
  o.Accuracy = accuracy;
  o.ReachedStencil = reached;
  return o;
}

// Files left beside `path` by writers (temporary files that were not renamed into place).
int FilesBeside(const std::string& path)
{
  const std::filesystem::path p(path);
  int n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(p.parent_path()))
  {
    const std::string name = entry.path().filename().string();
    if (name.rfind(p.filename().string() + ".tmp.", 0) == 0)
    {
      ++n;
    }
  }
  return n;
}

// The layout of a saddle vertex graph's file (SaddleVertexGraph::Save): magic, mesh hash, K,
// build seconds, vertex and entry counts, offsets, targets, weights, ...; the checksum (FNV-1a
// of everything after the magic) is the last 8 bytes.
struct SvgFile
{
  std::string Bytes;
  std::int64_t Vertices = 0, Entries = 0;
  explicit SvgFile(std::string bytes)
    : Bytes(std::move(bytes))
  {
    std::memcpy(&Vertices, &Bytes[28], 8);
    std::memcpy(&Entries, &Bytes[36], 8);
  }
  std::size_t TargetsAt() const { return 44 + 8 * (Vertices + 1); }
  std::size_t WeightsAt() const { return TargetsAt() + 4 * Entries; }
  double Weight(std::int64_t e) const
  {
    double w;
    std::memcpy(&w, &Bytes[WeightsAt() + 8 * e], 8);
    return w;
  }
  void SetWeight(std::int64_t e, double w) { std::memcpy(&Bytes[WeightsAt() + 8 * e], &w, 8); }
  // A forger's last step: the checksum recomputed.
  std::string Signed() const
  {
    std::string out = Bytes;
    Hasher sum;
    sum.Add(out.data() + 8, out.size() - 16);
    std::memcpy(&out[out.size() - 8], &sum.H, 8);
    return out;
  }
};
} // namespace

TEST(GraphCacheFiles, BuiltGraphsPassVerify)
{
  // Verify's checks hold for every construction on curved, open and flat meshes: links are
  // direct geodesics, at least their chords, equal to the exact distance.
  const std::vector<TriangleMesh> meshes = { gs_test::BuildMesh(gs_test::BumpySoup(2, 9, 0.1)),
    gs_test::BuildMesh(MakeCone(0.5, 1.0, 8, 24)),
    gs_test::BuildMesh(MakeTorus(1.0, 0.4, 24, 12)),
    gs_test::BuildMesh(MakePlanarGrid(12, 9, 1.0, 0.8)) };
  for (const TriangleMesh& m : meshes)
  {
    for (const SaddleVertexGraphOptions& o :
      { SVG(20), SVG(80), DGG(0.1, false), DGG(1e-3, false), DGG(0.03, true) })
    {
      const SaddleVertexGraph g = Build(m, o);
      EXPECT_TRUE(gs_test::Succeeded(g.Verify(m)))
        << "vertices " << m.NumberOfVertices() << ", K " << o.K << ", accuracy " << o.Accuracy;
    }
  }
}

TEST(GraphCacheFiles, ForgedFilesFailVerify)
{
  const TriangleMesh m = gs_test::BuildMesh(gs_test::BumpySoup(2, 9, 0.1));
  const std::uint64_t hash = SaddleVertexGraph::HashMesh(m);
  const std::string path = TempPath("gs_forged.svgg");
  std::remove(path.c_str());
  const SaddleVertexGraph g = Build(m, SVG(30));
  ASSERT_TRUE(gs_test::Succeeded(g.Save(path, hash)));
  const SvgFile original(ReadBytes(path));
  auto loadForged = [&](const std::function<void(SvgFile&)>& forge) {
    SvgFile f = original;
    forge(f);
    WriteBytes(path, f.Signed());
    SaddleVertexGraph loaded;
    EXPECT_TRUE(gs_test::Succeeded(loaded.Load(path, hash, 30))) << "the checksum was recomputed";
    return loaded.Verify(m);
  };
  // The unforged file passes.
  EXPECT_TRUE(gs_test::Succeeded(loadForged([](SvgFile&) {})));
  // Every weight halved (every distance halved), zeroed, doubled.
  EXPECT_TRUE(gs_test::FailedWith(loadForged([](SvgFile& f) {
    for (std::int64_t e = 0; e < f.Entries; ++e)
      f.SetWeight(e, 0.5 * f.Weight(e));
  }),
    "shorter than the straight distance"));
  EXPECT_TRUE(gs_test::FailedWith(loadForged([](SvgFile& f) {
    for (std::int64_t e = 0; e < f.Entries; ++e)
      f.SetWeight(e, 0.0);
  }),
    "shorter than the straight distance"));
  EXPECT_FALSE(loadForged([](SvgFile& f) {
    for (std::int64_t e = 0; e < f.Entries; ++e)
      f.SetWeight(e, 2.0 * f.Weight(e));
  }).Ok());
  // One link lengthened by 10%: the sampled exact check or the stencil check finds it.
  {
    const Status one = loadForged([](SvgFile& f) { f.SetWeight(0, 1.1 * f.Weight(0)); });
    EXPECT_FALSE(one.Ok());
  }
  // A graph with extra vertices (another mesh's graph under this mesh's hash).
  {
    const TriangleMesh bigger = gs_test::BuildMesh(gs_test::BumpySoup(3, 9, 0.1));
    const SaddleVertexGraph other = Build(bigger, SVG(30));
    ASSERT_TRUE(gs_test::Succeeded(other.Save(path, hash)));
    SaddleVertexGraph loaded;
    ASSERT_TRUE(gs_test::Succeeded(loaded.Load(path, hash, 30)));
    EXPECT_TRUE(gs_test::FailedWith(loaded.Verify(m), "another mesh"));
  }
  std::remove(path.c_str());
}

TEST(GraphCacheFiles, NeverOverwritesAFileThatIsNotACache)
{
  const TriangleMesh m = gs_test::BuildMesh(gs_test::BumpySoup(1, 3, 0.1));
  const std::uint64_t hash = SaddleVertexGraph::HashMesh(m);
  const SaddleVertexGraph g = Build(m, SVG(20));
  const std::string path = TempPath("gs_users_mesh.ply");
  const std::string users = "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n";
  WriteBytes(path, users);
  EXPECT_TRUE(gs_test::FailedWith(SaddleVertexGraph::CheckCacheFileName(path), "left untouched"));
  EXPECT_TRUE(gs_test::FailedWith(g.Save(path, hash), "not a geodesic graph cache file"));
  EXPECT_EQ(ReadBytes(path), users);
  // An empty file is not a cache either (it may be a user's placeholder).
  WriteBytes(path, "");
  EXPECT_FALSE(g.Save(path, hash).Ok());
  EXPECT_EQ(ReadBytes(path), "");
  std::remove(path.c_str());
  // A directory.
  const std::string dir = TempPath("gs_cache_dir.svgg");
  std::filesystem::create_directories(dir);
  EXPECT_TRUE(gs_test::FailedWith(g.Save(dir, hash), "not a regular file"));
  EXPECT_TRUE(std::filesystem::is_directory(dir));
  std::filesystem::remove(dir);
  // A cache file (of any construction) is replaced; a missing file is created.
  const std::string cache = TempPath("gs_cache_replace.svgg");
  std::remove(cache.c_str());
  EXPECT_TRUE(gs_test::Succeeded(SaddleVertexGraph::CheckCacheFileName(cache)));
  ASSERT_TRUE(gs_test::Succeeded(Build(m, DGG(0.1, false)).Save(cache, hash)));
  ASSERT_TRUE(gs_test::Succeeded(g.Save(cache, hash)));
  SaddleVertexGraph loaded;
  EXPECT_TRUE(gs_test::Succeeded(loaded.Load(cache, hash, 20)));
  EXPECT_TRUE(loaded == g);
  EXPECT_EQ(FilesBeside(cache), 0);
  std::remove(cache.c_str());
}

TEST(GraphCacheFiles, AFifoNeverBlocks)
{
  const TriangleMesh m = gs_test::BuildMesh(gs_test::BumpySoup(1, 3, 0.1));
  const std::uint64_t hash = SaddleVertexGraph::HashMesh(m);
  const std::string fifo = TempPath("gs_cache_fifo.svgg");
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // (Each call would block forever in open() if it opened the FIFO.)
  EXPECT_TRUE(gs_test::FailedWith(SaddleVertexGraph::CheckCacheFileName(fifo), "not a regular file"));
  SaddleVertexGraph loaded;
  EXPECT_TRUE(gs_test::FailedWith(loaded.Load(fifo, hash, 20), "not a regular file"));
  EXPECT_FALSE(Build(m, SVG(20)).Save(fifo, hash).Ok());
  struct stat st;
  ASSERT_EQ(::stat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  std::remove(fifo.c_str());
}

TEST(GraphCacheFiles, AnInterruptedWriteLeavesThePreviousFile)
{
  const TriangleMesh m = gs_test::BuildMesh(gs_test::BumpySoup(2, 9, 0.1));
  const std::uint64_t hash = SaddleVertexGraph::HashMesh(m);
  const std::string path = TempPath("gs_interrupted.svgg");
  std::remove(path.c_str());
  const SaddleVertexGraph small = Build(m, SVG(10));
  ASSERT_TRUE(gs_test::Succeeded(small.Save(path, hash)));
  const std::string before = ReadBytes(path);
  // A write that fails halfway (the file size limit: write() fails with EFBIG past it, as on a
  // full disk).
  const SaddleVertexGraph large = Build(m, SVG(60));
  struct rlimit old;
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);
  struct rlimit limited = old;
  limited.rlim_cur = before.size() + 1000;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limited), 0);
  const Status interrupted = large.Save(path, hash);
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previousHandler);
  EXPECT_TRUE(gs_test::FailedWith(interrupted, "the previous file, if any, is unchanged"));
  EXPECT_EQ(ReadBytes(path), before);
  EXPECT_EQ(FilesBeside(path), 0);
  SaddleVertexGraph loaded;
  EXPECT_TRUE(gs_test::Succeeded(loaded.Load(path, hash, 10)));
  std::remove(path.c_str());
}

TEST(GraphCacheFiles, ConcurrentWritersLeaveOneWholeFile)
{
  // Two graphs of two meshes written to one path at once, many times: the file is always one
  // of them whole (its checksum and its mesh hash agree), never a mixture.
  const TriangleMesh a = gs_test::BuildMesh(gs_test::BumpySoup(2, 9, 0.1));
  const TriangleMesh b = gs_test::BuildMesh(gs_test::BumpySoup(2, 11, 0.1));
  const std::uint64_t ha = SaddleVertexGraph::HashMesh(a), hb = SaddleVertexGraph::HashMesh(b);
  const SaddleVertexGraph ga = Build(a, SVG(40)), gb = Build(b, SVG(40));
  const std::string path = TempPath("gs_concurrent.svgg");
  std::remove(path.c_str());
  int whole = 0;
  for (int round = 0; round < 20; ++round)
  {
    Status sa, sb;
    std::thread ta([&] { sa = ga.Save(path, ha); });
    std::thread tb([&] { sb = gb.Save(path, hb); });
    ta.join();
    tb.join();
    EXPECT_TRUE(sa.Ok() && sb.Ok()) << sa.Message() << " / " << sb.Message();
    SaddleVertexGraph loaded;
    const bool isA = loaded.Load(path, ha, 40).Ok() && loaded == ga;
    const bool isB = !isA && loaded.Load(path, hb, 40).Ok() && loaded == gb;
    whole += isA || isB;
  }
  EXPECT_EQ(whole, 20);
  EXPECT_EQ(FilesBeside(path), 0);
  std::remove(path.c_str());
}
