// vtkSVGGeodesicDistance with the saddle-vertex-graph solvers:
//  - each Solver value on bundled meshes against the Exact solver (mean relative error < 1e-2
//    at K = 50; label-correcting and Dijkstra equal within 1e-9); unfolding refinement on the
//    developable cylinder;
//  - curve sources (polylines on the Sources port) on the planar grid against the analytic
//    distance to the polyline, alone and mixed with point sources;
//  - the graph cache: built once, reused from memory by other instances and re-executed
//    upstreams, CacheFileName round trip, corrupt and stale files rebuilt with a warning;
//  - K = 0 and an abort during the graph build: empty output, no crash, nothing cached.
//
// Usage: TestSVGGeodesicDistanceSolvers --data <Data dir> --temp <writable dir>
#include "vtkSVGGeodesicDistance.h"

#include "FilterTestSupport.h"
#include "Hash.h"
#include "vtkSaddleVertexGraphCache.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPLYReader.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

using gs_test::Check;
using gs_test::Failures;
using gs_test::Mentions;
using gs_test::MessageRecorder;
using gs_test::UpdateRecording;

namespace
{
std::string DataDir = "Data";
std::string TempDir = ".";



// Sets AbortExecute at the first progress report inside the graph build (0.1 .. 0.8).
class AbortDuringBuild : public vtkCommand
{
public:
  static AbortDuringBuild* New() { return new AbortDuringBuild; }
  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    const double progress = *static_cast<double*>(callData);
    if (progress > 0.1 && progress < 0.8)
    {
      ++this->Calls;
      static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
    }
  }
  int Calls = 0;
};

struct Run
{
  vtkSmartPointer<vtkPolyData> Output;
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
  double Seconds = 0.0;

  std::vector<double> Distances(const char* name = "GeodesicDistance") const
  {
    std::vector<double> d;
    if (auto* a = vtkDoubleArray::SafeDownCast(this->Output->GetPointData()->GetArray(name)))
    {
      d.assign(a->GetPointer(0), a->GetPointer(0) + a->GetNumberOfTuples());
    }
    return d;
  }
  std::string Origin() const
  {
    auto* a = vtkStringArray::SafeDownCast(
      this->Output->GetFieldData()->GetAbstractArray("SVGGraphOrigin"));
    return a && a->GetNumberOfValues() == 1 ? a->GetValue(0) : std::string("(none)");
  }
  double FieldValue(const char* name) const
  {
    auto* a = vtkDoubleArray::SafeDownCast(this->Output->GetFieldData()->GetArray(name));
    return a && a->GetNumberOfTuples() == 1 ? a->GetValue(0) : std::nan("");
  }
  bool Empty() const
  {
    return this->Output->GetNumberOfPoints() == 0 && this->Output->GetNumberOfCells() == 0;
  }
};

// Runs `filter` (already configured) and records its messages.
Run Execute(vtkSVGGeodesicDistance* filter)
{
  vtkNew<MessageRecorder> recorder;
  const auto t0 = std::chrono::steady_clock::now();
  UpdateRecording(filter, recorder);
  Run r;
  r.Seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.Output = vtkSmartPointer<vtkPolyData>::New();
  r.Output->DeepCopy(filter->GetOutput());
  r.Errors = recorder->Errors;
  r.Warnings = recorder->Warnings;
  return r;
}

Run Solve(vtkPolyData* mesh, int solver, const std::vector<vtkIdType>& ids,
  vtkPolyData* sources = nullptr, int k = 50, const std::string& cacheFile = std::string(),
  bool refine = false)
{
  vtkNew<vtkSVGGeodesicDistance> filter;
  filter->SetInputData(mesh);
  filter->SetSolver(solver);
  filter->SetK(k);
  filter->SetCacheFileName(cacheFile.c_str());
  filter->SetUnfoldingRefinement(refine);
  for (vtkIdType id : ids)
  {
    filter->AddSourceVertexId(id);
  }
  if (sources)
  {
    filter->SetSourcesData(sources);
  }
  return Execute(filter);
}

vtkSmartPointer<vtkPolyData> ReadMesh(const std::string& name)
{
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName((DataDir + "/" + name).c_str());
  reader->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(reader->GetOutput());
  if (mesh->GetNumberOfPoints() == 0)
  {
    Check(false, "ReadMesh", "could not read " + name);
  }
  return mesh;
}

struct Errors
{
  double Mean = 0.0;
  double Max = 0.0;
  int Count = 0;
};

// Relative error of `d` against `reference` over the points farther than 1e-9 (the source
// itself has no relative error). Missing or non-finite values count as an error of 1e300.
Errors RelativeErrors(const std::vector<double>& d, const std::vector<double>& reference)
{
  Errors e;
  if (d.size() != reference.size() || d.empty())
  {
    e.Mean = e.Max = 1e300;
    return e;
  }
  for (size_t i = 0; i < d.size(); ++i)
  {
    if (!(reference[i] > 1e-9))
    {
      continue;
    }
    const double r = std::isfinite(d[i]) ? std::abs(d[i] - reference[i]) / reference[i] : 1e300;
    e.Mean += r;
    e.Max = std::max(e.Max, r);
    ++e.Count;
  }
  e.Mean = e.Count ? e.Mean / e.Count : 1e300;
  return e;
}

double MaxAbsoluteDifference(const std::vector<double>& a, const std::vector<double>& b)
{
  if (a.size() != b.size() || a.empty())
  {
    return 1e300;
  }
  double worst = 0.0;
  for (size_t i = 0; i < a.size(); ++i)
  {
    const double diff = std::abs(a[i] - b[i]);
    worst = std::max(worst, std::isfinite(diff) ? diff : 1e300);
  }
  return worst;
}

// The test filters share the process-wide graph cache: start each cache test from nothing.
void ResetGraphCache()
{
  vtkSaddleVertexGraphCache::Clear();
}

//------------------------------------------------------------------------------
void TestSolversAgainstExact()
{
  const std::string test = "SolversAgainstExact";
  ResetGraphCache();
  for (const char* name : { "torus.ply", "cylinder.ply" })
  {
    auto mesh = ReadMesh(name);
    const std::vector<vtkIdType> sources = { 0, mesh->GetNumberOfPoints() / 2 + 7 };
    const Run exact = Solve(mesh, vtkSVGGeodesicDistance::EXACT, sources);
    const Run lc = Solve(mesh, vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING, sources);
    const Run dijkstra = Solve(mesh, vtkSVGGeodesicDistance::SVG_DIJKSTRA, sources);
    for (const Run* r : { &exact, &lc, &dijkstra })
    {
      Check(r->Errors.empty() && r->Warnings.empty(), test, std::string(name) + ": messages");
    }
    const Errors e = RelativeErrors(lc.Distances(), exact.Distances());
    const double same = MaxAbsoluteDifference(lc.Distances(), dijkstra.Distances());
    std::cout << test << " " << name << ": " << mesh->GetNumberOfPoints()
              << " points, K=50: mean relative error " << e.Mean << ", max " << e.Max
              << "; |label-correcting - Dijkstra| <= " << same << "; graph "
              << lc.FieldValue("SVGMeanDegree") << " links/vertex built in "
              << lc.FieldValue("SVGBuildSeconds") << " s (" << lc.Origin() << "); runs: exact "
              << exact.Seconds << " s, label-correcting " << lc.Seconds << " s, Dijkstra "
              << dijkstra.Seconds << " s\n";
    Check(e.Mean < 1e-2, test, std::string(name) + ": mean relative error too large");
    Check(same <= 1e-9, test, std::string(name) + ": label-correcting differs from Dijkstra");
    // The graph is built once (label-correcting run) and reused by the Dijkstra run.
    Check(lc.Origin() == "built" && dijkstra.Origin() == "memory", test,
      std::string(name) + ": graph origins " + lc.Origin() + ", " + dijkstra.Origin());
    Check(lc.FieldValue("SVGMeanDegree") >= 6.0 && lc.FieldValue("SVGBuildSeconds") > 0.0, test,
      std::string(name) + ": field data describing the graph");
    Check(exact.Output->GetFieldData()->GetAbstractArray("SVGGraphOrigin") == nullptr, test,
      "the Exact solver reports a graph");
  }

  // Unfolding refinement on the developable cylinder: exact up to rounding.
  auto cylinder = ReadMesh("cylinder.ply");
  const Run exact = Solve(cylinder, vtkSVGGeodesicDistance::EXACT, { 0 });
  const Run refined =
    Solve(cylinder, vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING, { 0 }, nullptr, 50, "", true);
  const Errors e = RelativeErrors(refined.Distances(), exact.Distances());
  std::cout << test << " cylinder.ply with UnfoldingRefinement: mean relative error " << e.Mean
            << ", max " << e.Max << "\n";
  Check(e.Max < 1e-6, test, "refined distances on the cylinder are not exact");
}

//------------------------------------------------------------------------------
// Analytic distance from p to the polyline `curve` (in the plane z = 0).
double DistanceToPolyline(const double p[3], const std::vector<std::array<double, 2>>& curve)
{
  double best = std::hypot(p[0] - curve[0][0], p[1] - curve[0][1]);
  for (size_t i = 0; i + 1 < curve.size(); ++i)
  {
    const double ax = curve[i][0], ay = curve[i][1];
    const double bx = curve[i + 1][0] - ax, by = curve[i + 1][1] - ay;
    double t = ((p[0] - ax) * bx + (p[1] - ay) * by) / (bx * bx + by * by);
    t = std::min(1.0, std::max(0.0, t));
    best = std::min(best, std::hypot(p[0] - ax - t * bx, p[1] - ay - t * by));
  }
  return best;
}

// Sources: one polyline cell per curve, then the free points (no cell).
vtkSmartPointer<vtkPolyData> MakeSources(const std::vector<std::vector<std::array<double, 2>>>& curves,
  const std::vector<std::array<double, 2>>& freePoints, double z = 0.0)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  for (const auto& curve : curves)
  {
    std::vector<vtkIdType> ids;
    for (const auto& p : curve)
    {
      ids.push_back(points->InsertNextPoint(p[0], p[1], z));
    }
    lines->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  }
  for (const auto& p : freePoints)
  {
    points->InsertNextPoint(p[0], p[1], z);
  }
  auto sources = vtkSmartPointer<vtkPolyData>::New();
  sources->SetPoints(points);
  sources->SetLines(lines);
  return sources;
}

void TestCurveSources()
{
  const std::string test = "CurveSources";
  auto grid = ReadMesh("planar_grid.ply"); // unit square, 20 x 20 cells
  // A bent polyline (two segments, vertices off the mesh vertices) floating 0.01 above the
  // plane (snapped onto it), a single straight segment, and the bent one plus a free point.
  const std::vector<std::array<double, 2>> bent = { { { 0.23, 0.31 } }, { { 0.61, 0.47 } },
    { { 0.78, 0.83 } } };
  const std::vector<std::array<double, 2>> segment = { { { 0.12, 0.74 } }, { { 0.87, 0.21 } } };
  const std::array<double, 2> point = { { 0.15, 0.9 } };
  struct Case
  {
    const char* Name;
    vtkSmartPointer<vtkPolyData> Sources;
    std::vector<std::vector<std::array<double, 2>>> Curves; // a free point is a 1-point curve
  };
  const std::vector<Case> cases = { { "bent polyline", MakeSources({ bent }, {}, 0.01), { bent } },
    { "segment", MakeSources({ segment }, {}), { segment } },
    { "polyline and point", MakeSources({ bent }, { point }), { bent, { point } } } };
  for (const Case& c : cases)
  {
    for (int solver : { vtkSVGGeodesicDistance::EXACT, vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING,
           vtkSVGGeodesicDistance::SVG_DIJKSTRA, vtkSVGGeodesicDistance::VIRTUAL_SOURCES })
    {
      const Run r = Solve(grid, solver, {}, c.Sources);
      const std::string what =
        std::string(c.Name) + " [" + vtkSVGGeodesicDistance::GetSolverName(solver) + "]";
      Check(r.Errors.empty(), test,
        what + ": unexpected error " + (r.Errors.empty() ? std::string() : r.Errors[0]));
      const std::vector<double> d = r.Distances();
      std::vector<double> analytic(d.size());
      for (size_t i = 0; i < d.size(); ++i)
      {
        double p[3];
        r.Output->GetPoint(static_cast<vtkIdType>(i), p);
        analytic[i] = 1e300;
        for (const auto& curve : c.Curves)
        {
          analytic[i] = std::min(analytic[i], DistanceToPolyline(p, curve));
        }
      }
      const Errors e = RelativeErrors(d, analytic);
      std::cout << test << " " << what << ": mean relative error " << e.Mean << ", max " << e.Max
                << " over " << e.Count << " points\n";
      // Virtual sources carry each straight run of the curve as one segment: exact on the plane
      // (measured 2e-15 mean; 1e-2 when they carried samples of it).
      const double bound = solver == vtkSVGGeodesicDistance::VIRTUAL_SOURCES ? 1e-9 : 1e-2;
      Check(e.Count > 400 && e.Mean < bound, test, what + ": mean relative error too large");
    }
  }
}

//------------------------------------------------------------------------------
bool FileExists(const std::string& path)
{
  std::ifstream in(path);
  return static_cast<bool>(in);
}


void TestGraphCache()
{
  const std::string test = "GraphCache";
  const std::string file = TempDir + "/TestSVGGeodesicDistanceSolvers_torus.svgg";
  std::remove(file.c_str());
  ResetGraphCache();
  auto torus = ReadMesh("torus.ply");
  const int lc = vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING;

  // 1. Built and saved.
  const Run first = Solve(torus, lc, { 3 }, nullptr, 50, file);
  Check(first.Origin() == "built" && first.Warnings.empty() && first.Errors.empty(), test,
    "first run: origin " + first.Origin());
  Check(FileExists(file), test, "the cache file was not written");
  const std::vector<double> reference = first.Distances();

  // 2. Another instance, and an upstream that produces a new polydata with the same geometry:
  //    from memory, no rebuild.
  const Run second = Solve(torus, lc, { 3 }, nullptr, 50, file);
  auto copy = vtkSmartPointer<vtkPolyData>::New();
  copy->DeepCopy(torus);
  const Run third = Solve(copy, vtkSVGGeodesicDistance::SVG_DIJKSTRA, { 3 }, nullptr, 50);
  Check(second.Origin() == "memory" && third.Origin() == "memory", test,
    "same mesh again: origins " + second.Origin() + ", " + third.Origin());
  Check(MaxAbsoluteDifference(second.Distances(), reference) == 0.0 &&
      MaxAbsoluteDifference(third.Distances(), reference) <= 1e-9,
    test, "reused graph gives other distances");
  std::cout << test << ": built in " << first.Seconds << " s, reused from memory in "
            << second.Seconds << " s\n";

  // 3. A new process (memory cleared): loaded from the file, identical distances.
  ResetGraphCache();
  const Run loaded = Solve(torus, lc, { 3 }, nullptr, 50, file);
  Check(loaded.Origin() == "loaded" && loaded.Warnings.empty(), test,
    "after clearing memory: origin " + loaded.Origin());
  Check(MaxAbsoluteDifference(loaded.Distances(), reference) == 0.0, test,
    "loaded graph gives other distances");
  std::cout << test << ": loaded from the file in " << loaded.Seconds << " s\n";

  // 4. A file that is not a cache: an error, the file untouched. A corrupt cache file (one
  //    flipped byte): a warning, a rebuild, identical distances, the file rewritten.
  std::string good;
  {
    std::ifstream in(file, std::ios::binary);
    good.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string garbageText = "this is not a saddle vertex graph, just garbage 0123456789";
  {
    std::ofstream garbage(file, std::ios::binary | std::ios::trunc);
    garbage << garbageText;
  }
  ResetGraphCache();
  const Run foreign = Solve(torus, lc, { 3 }, nullptr, 50, file);
  {
    std::ifstream in(file, std::ios::binary);
    const std::string after((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Check(Mentions(foreign.Errors, "not a geodesic graph cache file") && foreign.Empty() &&
        after == garbageText,
      test, "a file that is not a cache: no error, or the file was changed");
  }
  {
    std::string flipped = good;
    flipped[good.size() / 2] ^= 0x10;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << flipped;
  }
  ResetGraphCache();
  const Run corrupt = Solve(torus, lc, { 3 }, nullptr, 50, file);
  Check(corrupt.Origin() == "built" && Mentions(corrupt.Warnings, "rebuilding") &&
      corrupt.Errors.empty(),
    test, "corrupt file: origin " + corrupt.Origin() + ", no rebuild warning");
  Check(MaxAbsoluteDifference(corrupt.Distances(), reference) == 0.0, test,
    "rebuilt graph gives other distances");
  // A truncated file (a valid header, half the data).
  {
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  }
  ResetGraphCache();
  const Run truncated = Solve(torus, lc, { 3 }, nullptr, 50, file);
  Check(truncated.Origin() == "built" && Mentions(truncated.Warnings, "rebuilding"), test,
    "truncated file: origin " + truncated.Origin());
  ResetGraphCache();
  const Run reloaded = Solve(torus, lc, { 3 }, nullptr, 50, file);
  Check(reloaded.Origin() == "loaded", test, "the rebuilt graph was not saved again");

  // 5. A stale file (another K): a warning and a rebuild for the new K.
  ResetGraphCache();
  const Run stale = Solve(torus, lc, { 3 }, nullptr, 20, file);
  Check(stale.Origin() == "built" && Mentions(stale.Warnings, "rebuilding"), test,
    "file for another K: origin " + stale.Origin());
  // ... and a changed mesh (one point moved) does not reuse the graph in memory.
  auto moved = vtkSmartPointer<vtkPolyData>::New();
  moved->DeepCopy(torus);
  double p[3];
  moved->GetPoint(10, p);
  p[2] += 1e-3;
  moved->GetPoints()->SetPoint(10, p);
  const Run changed = Solve(moved, lc, { 3 }, nullptr, 20);
  Check(changed.Origin() == "built", test, "moved point: origin " + changed.Origin());

  // 6. An unwritable file: a warning, the distances anyway.
  ResetGraphCache();
  const Run unwritable =
    Solve(torus, lc, { 3 }, nullptr, 50, TempDir + "/no/such/directory/graph.svgg");
  Check(unwritable.Origin() == "built" && Mentions(unwritable.Warnings, "save") &&
      MaxAbsoluteDifference(unwritable.Distances(), reference) == 0.0,
    test, "unwritable cache file");

  // 7. A forged file (every weight halved, the checksum recomputed): it loads, fails the check
  //    against the mesh, a warning and a rebuild with the right distances; the file rewritten.
  ResetGraphCache();
  Solve(torus, lc, { 3 }, nullptr, 50, file);
  {
    std::ifstream in(file, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    std::int64_t nv = 0, ne = 0;
    std::memcpy(&nv, &bytes[28], 8);
    std::memcpy(&ne, &bytes[36], 8);
    const std::size_t weights = 44 + 8 * (nv + 1) + 4 * ne;
    for (std::int64_t e = 0; e < ne; ++e)
    {
      double w;
      std::memcpy(&w, &bytes[weights + 8 * e], 8);
      w *= 0.5;
      std::memcpy(&bytes[weights + 8 * e], &w, 8);
    }
    gs::Hasher sum;
    sum.Add(bytes.data() + 8, bytes.size() - 16);
    std::memcpy(&bytes[bytes.size() - 8], &sum.H, 8);
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  ResetGraphCache();
  const Run forged = Solve(torus, lc, { 3 }, nullptr, 50, file);
  Check(forged.Origin() == "built" && Mentions(forged.Warnings, "does not match the mesh") &&
      MaxAbsoluteDifference(forged.Distances(), reference) == 0.0,
    test, "forged cache file: origin " + forged.Origin());
  ResetGraphCache();
  Check(Solve(torus, lc, { 3 }, nullptr, 50, file).Origin() == "loaded", test,
    "the forged file was not replaced by the rebuilt graph");
  std::remove(file.c_str());

  // 8. A user's file at the cache path is never touched, whether the graph is in memory or
  //    not: an error naming it before any work, an empty output.
  const std::string users = TempDir + "/TestSVGGeodesicDistanceSolvers_users_mesh.ply";
  const std::string content = "ply\nformat ascii 1.0\nelement vertex 0\nend_header\n";
  {
    std::ofstream out(users, std::ios::binary | std::ios::trunc);
    out << content;
  }
  for (bool inMemory : { true, false })
  {
    ResetGraphCache();
    if (inMemory)
    {
      Solve(torus, lc, { 3 }, nullptr, 50);
    }
    const Run refused = Solve(torus, lc, { 3 }, nullptr, 50, users);
    std::ifstream in(users, std::ios::binary);
    const std::string after((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    Check(Mentions(refused.Errors, "CacheFileName") && Mentions(refused.Errors, users) &&
        Mentions(refused.Errors, "left untouched") && refused.Empty(),
      test, std::string("a user's file as CacheFileName (graph ") +
        (inMemory ? "in memory" : "not in memory") + "): no error naming it");
    Check(after == content, test, "a user's file at the cache path was changed");
  }
  std::remove(users.c_str());
}

//------------------------------------------------------------------------------
void TestBadK()
{
  const std::string test = "BadK";
  auto grid = ReadMesh("planar_grid.ply");
  for (int solver : { vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING,
         vtkSVGGeodesicDistance::SVG_DIJKSTRA })
  {
    const Run r = Solve(grid, solver, { 0 }, nullptr, 0);
    Check(!r.Errors.empty() && Mentions(r.Errors, "K") && r.Empty(), test,
      "K = 0: no error or non-empty output");
  }
  // K is not used by the Exact solver; K larger than the vertex count is clamped.
  const Run exact = Solve(grid, vtkSVGGeodesicDistance::EXACT, { 0 }, nullptr, 0);
  Check(exact.Errors.empty() && !exact.Empty(), test, "Exact with K = 0");
  const Run large = Solve(grid, vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING, { 0 }, nullptr, 5000);
  const Errors e = RelativeErrors(large.Distances(), exact.Distances());
  Check(large.Errors.empty() && e.Max < 1e-9, test,
    "K = 5000 (all vertices) is not exact on the plane");
}

//------------------------------------------------------------------------------
void TestAbortDuringBuild()
{
  const std::string test = "AbortDuringBuild";
  ResetGraphCache();
  // 101 x 101 vertices: the build reports progress many times.
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(100, 100);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(triangles->GetOutput());

  vtkNew<vtkSVGGeodesicDistance> filter;
  filter->SetInputData(mesh);
  filter->SetSolverToSVGLabelCorrecting();
  filter->AddSourceVertexId(0);
  vtkNew<AbortDuringBuild> aborter;
  filter->AddObserver(vtkCommand::ProgressEvent, aborter);
  const Run aborted = Execute(filter);
  Check(aborter->Calls > 0, test, "no progress reported during the build");
  Check(aborted.Empty(), test, "aborted run has a non-empty output");
  Check(vtkSaddleVertexGraphCache::NumberOfGraphs() == 0, test, "an aborted graph was cached");
  std::cout << test << ": aborted after " << aborted.Seconds << " s\n";

  // A new run builds the graph from scratch and succeeds.
  const Run again = Solve(mesh, vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING, { 0 });
  Check(again.Origin() == "built" && !again.Empty() && again.Errors.empty(), test,
    "run after the abort: origin " + again.Origin());
  std::cout << test << ": full build of " << mesh->GetNumberOfPoints() << " vertices took "
            << again.FieldValue("SVGBuildSeconds") << " s\n";
}

//------------------------------------------------------------------------------
// The DGG solver as users call it: its largest error within Accuracy against the exact solver,
// with and without refinement, vertex and point sources; cached by accuracy (memory and its own
// file format); an accuracy out of range is an error naming it.
void TestDiscreteGeodesicGraph()
{
  const std::string test = "DiscreteGeodesicGraph";
  ResetGraphCache();
  auto mesh = ReadMesh("bumpy_sphere.ply");
  auto run = [&](double accuracy, bool refine, const std::vector<vtkIdType>& ids,
               vtkPolyData* sources, const std::string& file) {
    vtkNew<vtkSVGGeodesicDistance> filter;
    filter->SetInputData(mesh);
    filter->SetSolver(vtkSVGGeodesicDistance::DGG);
    filter->SetGraphAccuracy(accuracy);
    filter->SetUnfoldingRefinement(refine);
    filter->SetCacheFileName(file.c_str());
    for (vtkIdType id : ids)
      filter->AddSourceVertexId(id);
    if (sources)
      filter->SetSourcesData(sources);
    return Execute(filter);
  };
  const std::vector<vtkIdType> ids = { 3, 1500 };
  const Run exact = Solve(mesh, vtkSVGGeodesicDistance::EXACT, ids);
  for (double accuracy : { 1e-2, 2e-3 })
  {
    for (bool refine : { false, true })
    {
      const Run dgg = run(accuracy, refine, ids, nullptr, "");
      const Errors e = RelativeErrors(dgg.Distances(), exact.Distances());
      std::cout << test << " bumpy_sphere.ply, accuracy " << accuracy
                << (refine ? " refined" : " graph only") << ": mean relative error " << e.Mean
                << ", max " << e.Max << ", " << dgg.FieldValue("SVGMeanDegree")
                << " links/vertex (" << dgg.Origin() << ")\n";
      Check(dgg.Errors.empty() && dgg.Warnings.empty(), test, "messages");
      Check(e.Count > 1000 && e.Max <= accuracy, test, "largest error above the accuracy");
      Check(dgg.Origin() == (refine ? "memory" : "built"), test, "origin " + dgg.Origin());
    }
  }
  // A point source inside a face (between two vertices, snapped to the surface).
  vtkNew<vtkPolyData> point;
  vtkNew<vtkPoints> points;
  double p[3], q[3];
  mesh->GetPoint(40, p);
  mesh->GetPoint(41, q);
  points->InsertNextPoint(
    0.6 * p[0] + 0.4 * q[0], 0.6 * p[1] + 0.4 * q[1], 0.6 * p[2] + 0.4 * q[2]);
  point->SetPoints(points);
  const Run exactPoint = Solve(mesh, vtkSVGGeodesicDistance::EXACT, {}, point);
  const Run dggPoint = run(1e-2, true, {}, point, "");
  const Errors ep = RelativeErrors(dggPoint.Distances(), exactPoint.Distances());
  std::cout << test << " point source, accuracy 0.01: mean " << ep.Mean << ", max " << ep.Max
            << "\n";
  Check(dggPoint.Errors.empty() && ep.Count > 1000 && ep.Max <= 1e-2, test, "point source");

  // Its own cache file: written, loaded by an emptied cache, refused for another accuracy.
  const std::string file = TempDir + "/dgg_cache.svgg";
  std::remove(file.c_str());
  const Run saved = run(1e-2, true, ids, nullptr, file);
  Check(saved.Origin() == "memory" && FileExists(file), test, "cache file not written");
  ResetGraphCache();
  const Run loaded = run(1e-2, true, ids, nullptr, file);
  Check(loaded.Origin() == "loaded" && loaded.Warnings.empty() &&
      MaxAbsoluteDifference(loaded.Distances(), saved.Distances()) == 0.0,
    test, "cache file not loaded as saved: origin " + loaded.Origin());
  const Run other = run(5e-3, true, ids, nullptr, file);
  Check(other.Origin() == "built" && Mentions(other.Warnings, "accuracy"), test,
    "a file of another accuracy was used");
  // The SVG solver does not take a DGG file (another format): it warns and rebuilds.
  const Run svg = Solve(mesh, vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING, ids, nullptr, 50, file);
  Check(svg.Origin() == "built" && Mentions(svg.Warnings, "rebuilding"), test,
    "the SVG solver used a DGG file");
  std::remove(file.c_str());

  // ReachedStencil: a graph of its own (built, not the plain one from memory), the same
  // distances without refinement, a smaller refined mean error, still within the accuracy.
  auto runReached = [&](bool refine, bool reached) {
    vtkNew<vtkSVGGeodesicDistance> filter;
    filter->SetInputData(mesh);
    filter->SetSolver(vtkSVGGeodesicDistance::DGG);
    filter->SetGraphAccuracy(0.1);
    filter->SetReachedStencil(reached);
    filter->SetUnfoldingRefinement(refine);
    for (vtkIdType id : ids)
      filter->AddSourceVertexId(id);
    return Execute(filter);
  };
  const Run plainGraph = runReached(false, false);
  const Run reachedGraph = runReached(false, true);
  Check(reachedGraph.Origin() == "built" && reachedGraph.Errors.empty(), test,
    "the reached-stencil graph came from " + reachedGraph.Origin());
  Check(MaxAbsoluteDifference(plainGraph.Distances(), reachedGraph.Distances()) == 0.0, test,
    "ReachedStencil changed the graph distances");
  const Errors plainRefined = RelativeErrors(runReached(true, false).Distances(), exact.Distances());
  const Run reachedRun = runReached(true, true);
  const Errors reachedRefined = RelativeErrors(reachedRun.Distances(), exact.Distances());
  std::cout << test << " bumpy_sphere.ply, accuracy 0.1 refined: mean relative error "
            << plainRefined.Mean << " with links-only stencils, " << reachedRefined.Mean
            << " with ReachedStencil (" << reachedRun.Origin() << ")\n";
  Check(reachedRun.Origin() == "memory" && reachedRefined.Max <= 0.1 &&
      reachedRefined.Mean < 0.75 * plainRefined.Mean,
    test, "ReachedStencil did not refine closer");

  for (double bad : { 0.0, -1e-3, 0.5, std::nan("") })
  {
    const Run r = run(bad, true, ids, nullptr, "");
    Check(!r.Errors.empty() && Mentions(r.Errors, "accuracy") && r.Empty(), test,
      "accuracy " + std::to_string(bad) + " accepted");
  }
}
}

//------------------------------------------------------------------------------
// The no-precompute solver as users call it: no graph (no field data, nothing cached), near the
// exact solver on curved meshes (measured: torus mean 1.0e-3, max 1.2e-2; the developable
// cylinder exact to rounding), MaximumDistance, and an abort from the progress observer.
void TestVirtualSources()
{
  const std::string test = "VirtualSources";
  ResetGraphCache();
  for (const char* name : { "torus.ply", "cylinder.ply" })
  {
    auto mesh = ReadMesh(name);
    const std::vector<vtkIdType> sources = { 0, mesh->GetNumberOfPoints() / 2 + 7 };
    const Run exact = Solve(mesh, vtkSVGGeodesicDistance::EXACT, sources);
    const Run vsp = Solve(mesh, vtkSVGGeodesicDistance::VIRTUAL_SOURCES, sources);
    Check(vsp.Errors.empty() && vsp.Warnings.empty(), test, std::string(name) + ": messages");
    const Errors e = RelativeErrors(vsp.Distances(), exact.Distances());
    std::cout << test << " " << name << ": mean relative error " << e.Mean << ", max " << e.Max
              << " over " << e.Count << " points; exact " << exact.Seconds << " s, virtual sources "
              << vsp.Seconds << " s\n";
    Check(e.Count + 2 >= mesh->GetNumberOfPoints(), test, std::string(name) + ": points missing");
    Check(e.Mean < 3e-3 && e.Max < 3e-2, test, std::string(name) + ": error too large");
    Check(vsp.Output->GetFieldData()->GetAbstractArray("SVGGraphOrigin") == nullptr, test,
      std::string(name) + ": the virtual sources solver reports a graph");
  }
  Check(vtkSaddleVertexGraphCache::NumberOfGraphs() == 0, test, "a graph was built or cached");

  // MaximumDistance: NaN beyond, the same values within.
  auto grid = ReadMesh("planar_grid.ply");
  vtkNew<vtkSVGGeodesicDistance> limited;
  limited->SetInputData(grid);
  limited->SetSolverToVirtualSources();
  limited->AddSourceVertexId(0);
  limited->SetMaximumDistance(0.5);
  const Run near = Execute(limited);
  const std::vector<double> d = near.Distances();
  int beyond = 0, wrong = 0;
  double q[3];
  grid->GetPoint(0, q);
  for (size_t i = 0; i < d.size(); ++i)
  {
    double p[3];
    near.Output->GetPoint(static_cast<vtkIdType>(i), p);
    const double r = std::hypot(p[0] - q[0], p[1] - q[1]);
    beyond += std::isnan(d[i]);
    wrong += r < 0.499 ? !(std::abs(d[i] - r) < 1e-9) : r > 0.501 ? !std::isnan(d[i]) : 0;
  }
  std::cout << test << " MaximumDistance 0.5 on the unit square: " << beyond << " points NaN, "
            << wrong << " wrong\n";
  Check(beyond > 0 && wrong == 0, test, "MaximumDistance");

  // 401 x 401 vertices: the solve reports progress several times.
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(400, 400);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(plane->GetOutputPort());
  triangles->Update();
  auto big = vtkSmartPointer<vtkPolyData>::New();
  big->DeepCopy(triangles->GetOutput());
  vtkNew<vtkSVGGeodesicDistance> aborted;
  aborted->SetInputData(big);
  aborted->SetSolverToVirtualSources();
  aborted->AddSourceVertexId(0);
  vtkNew<AbortDuringBuild> aborter; // aborts at the first report between 10% and 80%
  aborted->AddObserver(vtkCommand::ProgressEvent, aborter);
  const Run stopped = Execute(aborted);
  std::cout << test << " abort during the solve on " << big->GetNumberOfPoints()
            << " points: " << stopped.Output->GetNumberOfPoints() << " output points, "
            << stopped.Errors.size() << " errors\n";
  Check(aborter->Calls > 0 && stopped.Empty() && stopped.Errors.empty(), test, "abort");
  aborted->RemoveAllObservers();
  aborted->AbortExecuteOff();
  aborted->Modified();
  const Run whole = Execute(aborted);
  Check(!whole.Empty() && whole.Errors.empty(), test, "a run after the abort");
}

int main(int argc, char* argv[])
{
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "--data") == 0)
    {
      DataDir = argv[i + 1];
    }
    else if (std::strcmp(argv[i], "--temp") == 0)
    {
      TempDir = argv[i + 1];
    }
  }
  TestSolversAgainstExact();
  TestCurveSources();
  TestGraphCache();
  TestBadK();
  TestAbortDuringBuild();
  TestDiscreteGeodesicGraph();
  TestVirtualSources();
  if (Failures > 0)
  {
    std::cerr << Failures << " check(s) failed\n";
    return 1;
  }
  std::cout << "all checks passed\n";
  return 0;
}
