// vtkSVGGeodesicDistance on malformed and unusual input: each malformed case must give an
// error message and an empty output with every solver, never a crash; the unusual-but-valid
// cases (quads, unreferenced points, split OBJ-style vertices, source points) must give the
// right distances (checked to 1e-9 with the Exact solver, and for the graph solvers where their
// result is exact too).
#include "vtkSVGGeodesicDistance.h"

#include "FilterTestSupport.h"

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <cctype>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using gs_test::Check;
using gs_test::Failures;
using gs_test::Mentions;
using gs_test::MessageRecorder;

namespace
{

struct RunResult
{
  vtkSmartPointer<vtkPolyData> Output;
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
  vtkDoubleArray* Distance() const
  {
    return vtkDoubleArray::SafeDownCast(
      this->Output->GetPointData()->GetArray("GeodesicDistance"));
  }
};

const int AllSolvers[] = { vtkSVGGeodesicDistance::EXACT,
  vtkSVGGeodesicDistance::SVG_LABEL_CORRECTING, vtkSVGGeodesicDistance::SVG_DIJKSTRA };

RunResult Run(vtkPolyData* mesh, const std::vector<vtkIdType>& sourceIds,
  vtkPolyData* sourcePoints = nullptr, double maximumDistance = 0.0,
  int solver = vtkSVGGeodesicDistance::EXACT)
{
  vtkNew<vtkSVGGeodesicDistance> filter;
  filter->SetSolver(solver);
  vtkNew<MessageRecorder> recorder;
  filter->AddObserver(vtkCommand::ErrorEvent, recorder);
  filter->AddObserver(vtkCommand::WarningEvent, recorder);
  filter->SetInputData(mesh);
  for (vtkIdType id : sourceIds)
  {
    filter->AddSourceVertexId(id);
  }
  if (sourcePoints)
  {
    filter->SetSourcesData(sourcePoints);
  }
  filter->SetMaximumDistance(maximumDistance);
  filter->Update();
  RunResult result;
  result.Output = filter->GetOutput();
  result.Errors = recorder->Errors;
  result.Warnings = recorder->Warnings;
  return result;
}

vtkSmartPointer<vtkPolyData> MakeMesh(
  const std::vector<std::array<double, 3>>& points, const std::vector<std::vector<vtkIdType>>& cells)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (const auto& p : points)
  {
    pts->InsertNextPoint(p.data());
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& c : cells)
  {
    polys->InsertNextCell(static_cast<vtkIdType>(c.size()), c.data());
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(pts);
  mesh->SetPolys(polys);
  return mesh;
}

// A malformed input: an error mentioning `keyword`, an empty output, with every solver.
void ExpectRejected(const std::string& name, vtkPolyData* mesh, const std::vector<vtkIdType>& ids,
  const std::string& keyword)
{
  for (int solver : AllSolvers)
  {
    const std::string test = name + "[" + vtkSVGGeodesicDistance::GetSolverName(solver) + "]";
    const RunResult r = Run(mesh, ids, nullptr, 0.0, solver);
    Check(!r.Errors.empty(), test, "no error message");
    Check(r.Output->GetNumberOfPoints() == 0 && r.Output->GetNumberOfCells() == 0, test,
      "output is not empty");
    bool mentioned = false;
    for (const std::string& e : r.Errors)
    {
      std::string lower = e;
      for (char& c : lower)
      {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      }
      mentioned = mentioned || lower.find(keyword) != std::string::npos;
      std::cout << test << ": error: " << e;
    }
    Check(mentioned, test, "no error mentions '" + keyword + "'");
  }
}

// Two triangles forming the unit square, the shared diagonal 1-2.
const std::vector<std::array<double, 3>> SquarePoints = { { { 0, 0, 0 } }, { { 1, 0, 0 } },
  { { 0, 1, 0 } }, { { 1, 1, 0 } } };

void TestEmpty()
{
  vtkNew<vtkPolyData> empty;
  ExpectRejected("Empty", empty, { 0 }, "empty");
}

void TestPointsOnly()
{
  auto mesh = MakeMesh(SquarePoints, {});
  ExpectRejected("PointsOnly", mesh, { 0 }, "triangle");
}

void TestLinesOnly()
{
  auto mesh = MakeMesh(SquarePoints, {});
  vtkNew<vtkCellArray> lines;
  const vtkIdType line[2] = { 0, 1 };
  lines->InsertNextCell(2, line);
  mesh->SetLines(lines);
  ExpectRejected("LinesOnly", mesh, { 0 }, "triangle");
}

void TestNonManifoldEdge()
{
  // Three triangles on the edge 0-1.
  auto mesh = MakeMesh({ { { 0, 0, 0 } }, { { 1, 0, 0 } }, { { 0.5, 1, 0 } }, { { 0.5, -1, 0 } },
                         { { 0.5, 0, 1 } } },
    { { 0, 1, 2 }, { 1, 0, 3 }, { 0, 1, 4 } });
  ExpectRejected("NonManifoldEdge", mesh, { 0 }, "manifold");
}

void TestNonManifoldVertex()
{
  // Two triangles touching only at vertex 0 (a bow tie).
  auto mesh = MakeMesh({ { { 0, 0, 0 } }, { { 1, 0, 0 } }, { { 1, 1, 0 } }, { { -1, 0, 0 } },
                         { { -1, -1, 0 } } },
    { { 0, 1, 2 }, { 0, 3, 4 } });
  ExpectRejected("NonManifoldVertex", mesh, { 0 }, "manifold");
}

void TestDuplicateTriangles()
{
  auto mesh = MakeMesh(SquarePoints, { { 0, 1, 2 }, { 1, 3, 2 }, { 1, 3, 2 } });
  ExpectRejected("DuplicateTriangles", mesh, { 0 }, "duplicate");
}

void TestDegenerateTriangle()
{
  // Triangle 1-4-3 has three collinear corners: zero area.
  auto mesh = MakeMesh({ { { 0, 0, 0 } }, { { 1, 0, 0 } }, { { 0, 1, 0 } }, { { 1, 1, 0 } },
                         { { 1, 0.5, 0 } } },
    { { 0, 1, 2 }, { 1, 4, 3 }, { 1, 3, 2 } });
  ExpectRejected("DegenerateTriangle", mesh, { 0 }, "degenerate");
}

void TestRepeatedCorner()
{
  auto mesh = MakeMesh(SquarePoints, { { 0, 1, 2 }, { 1, 1, 3 } });
  ExpectRejected("RepeatedCorner", mesh, { 0 }, "degenerate");
}

void TestNaNCoordinate()
{
  auto points = SquarePoints;
  points[3][1] = std::numeric_limits<double>::quiet_NaN();
  auto mesh = MakeMesh(points, { { 0, 1, 2 }, { 1, 3, 2 } });
  ExpectRejected("NaNCoordinate", mesh, { 0 }, "finite");
}

void TestInfiniteCoordinate()
{
  auto points = SquarePoints;
  points[2][2] = std::numeric_limits<double>::infinity();
  auto mesh = MakeMesh(points, { { 0, 1, 2 }, { 1, 3, 2 } });
  ExpectRejected("InfiniteCoordinate", mesh, { 0 }, "finite");
}

void TestMissingSource()
{
  auto mesh = gs_test::UnitSquare(4, true);
  ExpectRejected("MissingSource", mesh, {}, "no source");
}

void TestOutOfRangeSource()
{
  auto mesh = gs_test::UnitSquare(4, true);
  ExpectRejected("OutOfRangeSource", mesh, { 25 }, "out of range");
  ExpectRejected("NegativeSource", mesh, { -1 }, "out of range");
}

void TestUnreferencedSource()
{
  auto points = SquarePoints;
  points.push_back({ { 5, 5, 5 } });
  auto mesh = MakeMesh(points, { { 0, 1, 2 }, { 1, 3, 2 } });
  ExpectRejected("UnreferencedSource", mesh, { 4 }, "not used");
}

void TestUnreferencedPoints()
{
  const std::string test = "UnreferencedPoints";
  auto points = SquarePoints;
  points.insert(points.begin() + 2, { { 5, 5, 5 } }); // point 2 is used by no triangle
  points.push_back({ { 7, 7, 7 } });                   // nor is point 5
  auto mesh = MakeMesh(points, { { 0, 1, 3 }, { 1, 4, 3 } });
  for (int solver : AllSolvers)
  {
    const RunResult r = Run(mesh, { 0 }, nullptr, 0.0, solver);
    Check(r.Errors.empty(), test, "unexpected error");
    vtkDoubleArray* d = r.Distance();
    Check(d && d->GetNumberOfTuples() == 6, test, "missing or wrongly sized array");
    if (d && d->GetNumberOfTuples() == 6)
    {
      Check(std::isnan(d->GetValue(2)) && std::isnan(d->GetValue(5)), test,
        "unreferenced points are not NaN");
      Check(std::abs(d->GetValue(0)) < 1e-12 && std::abs(d->GetValue(1) - 1.0) < 1e-12 &&
          std::abs(d->GetValue(3) - 1.0) < 1e-12 &&
          std::abs(d->GetValue(4) - std::sqrt(2.0)) < 1e-12,
        test, "wrong distances on the square");
    }
  }
}

void TestQuads()
{
  const std::string test = "Quads";
  auto quads = gs_test::UnitSquare(8, false);
  const RunResult r = Run(quads, { 0 });
  Check(r.Errors.empty(), test, "unexpected error");
  Check(!r.Warnings.empty(), test, "no warning about the triangulation");
  Check(r.Output->GetNumberOfPolys() == 2 * 8 * 8, test, "output is not the triangulation");
  vtkDoubleArray* d = r.Distance();
  Check(d && d->GetNumberOfTuples() == quads->GetNumberOfPoints(), test, "array size");
  // Point 0 is the corner (0, 0): planar, so the distance is Euclidean.
  for (vtkIdType i = 0; d && i < d->GetNumberOfTuples(); ++i)
  {
    double p[3];
    r.Output->GetPoint(i, p);
    if (std::abs(d->GetValue(i) - std::hypot(p[0], p[1])) > 1e-9)
    {
      Check(false, test, "distance is not Euclidean at point " + std::to_string(i));
      break;
    }
  }
}

void TestSplitVertices()
{
  // OBJ-style soup: every triangle has its own copies of its corners.
  const std::string test = "SplitVertices";
  auto shared = gs_test::UnitSquare(6, true);
  vtkNew<vtkPoints> soupPoints;
  soupPoints->SetDataTypeToDouble();
  vtkNew<vtkCellArray> soupTriangles;
  std::vector<vtkIdType> original; // soup point -> shared point
  for (vtkIdType c = 0; c < shared->GetNumberOfCells(); ++c)
  {
    vtkIdType npts;
    const vtkIdType* pts;
    shared->GetCellPoints(c, npts, pts);
    vtkIdType corners[3];
    for (int k = 0; k < 3; ++k)
    {
      corners[k] = soupPoints->InsertNextPoint(shared->GetPoint(pts[k]));
      original.push_back(pts[k]);
    }
    soupTriangles->InsertNextCell(3, corners);
  }
  vtkNew<vtkPolyData> soup;
  soup->SetPoints(soupPoints);
  soup->SetPolys(soupTriangles);

  // Source: a soup copy of shared point 10.
  vtkIdType soupSource = -1;
  for (size_t i = 0; i < original.size() && soupSource < 0; ++i)
  {
    if (original[i] == 10)
    {
      soupSource = static_cast<vtkIdType>(i);
    }
  }
  for (int solver : AllSolvers)
  {
    const RunResult a = Run(shared, { 10 }, nullptr, 0.0, solver);
    const RunResult b = Run(soup, { soupSource }, nullptr, 0.0, solver);
    Check(a.Errors.empty() && b.Errors.empty(), test, "unexpected error");
    vtkDoubleArray* da = a.Distance();
    vtkDoubleArray* db = b.Distance();
    Check(da && db && db->GetNumberOfTuples() == static_cast<vtkIdType>(original.size()), test,
      "missing or wrongly sized array");
    for (size_t i = 0; da && db && i < original.size(); ++i)
    {
      const double expected = da->GetValue(original[i]);
      if (!(std::abs(db->GetValue(static_cast<vtkIdType>(i)) - expected) <= 1e-12))
      {
        Check(false, test, "welded distance differs at soup point " + std::to_string(i));
        break;
      }
    }
  }
}

void TestSourcePoints()
{
  // Source points snapped to the surface: one inside a triangle, one slightly above the plane.
  const std::string test = "SourcePoints";
  auto mesh = gs_test::UnitSquare(10, true);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  pts->InsertNextPoint(0.23, 0.41, 0.0);
  pts->InsertNextPoint(0.81, 0.77, 0.3); // snaps to (0.81, 0.77, 0)
  vtkNew<vtkPolyData> sources;
  sources->SetPoints(pts);
  const RunResult r = Run(mesh, { 0 }, sources);
  Check(r.Errors.empty(), test, "unexpected error");
  vtkDoubleArray* d = r.Distance();
  Check(d != nullptr, test, "missing array");
  for (vtkIdType i = 0; d && i < d->GetNumberOfTuples(); ++i)
  {
    double p[3];
    r.Output->GetPoint(i, p);
    const double expected =
      std::min(std::hypot(p[0] - 0.23, p[1] - 0.41), std::hypot(p[0] - 0.81, p[1] - 0.77));
    if (std::abs(d->GetValue(i) - expected) > 1e-9)
    {
      Check(false, test,
        "distance at point " + std::to_string(i) + " differs from " + std::to_string(expected) +
          " by " + std::to_string(d->GetValue(i) - expected));
      break;
    }
  }
}

void TestEmptySourcePoints()
{
  auto mesh = gs_test::UnitSquare(4, true);
  vtkNew<vtkPolyData> sources;
  vtkNew<vtkPoints> none;
  sources->SetPoints(none);
  const RunResult r = Run(mesh, { 0 }, sources);
  Check(!r.Errors.empty() && r.Output->GetNumberOfPoints() == 0, "EmptySourcePoints",
    "no error or non-empty output");
}

void TestMaximumDistance()
{
  const std::string test = "MaximumDistance";
  auto mesh = gs_test::UnitSquare(10, true);
  const double limit = 0.5;
  const RunResult r = Run(mesh, { 0 }, nullptr, limit);
  Check(r.Errors.empty(), test, "unexpected error");
  vtkDoubleArray* d = r.Distance();
  for (vtkIdType i = 0; d && i < d->GetNumberOfTuples(); ++i)
  {
    double p[3];
    r.Output->GetPoint(i, p);
    const double expected = std::hypot(p[0], p[1]);
    const double value = d->GetValue(i);
    const bool ok = expected < limit - 1e-9   ? std::abs(value - expected) < 1e-9
      : expected > limit + 1e-9 ? std::isnan(value)
                                : true;
    if (!ok)
    {
      Check(false, test, "wrong value at point " + std::to_string(i));
      break;
    }
  }
}

// MaximumDistance negative or NaN: an error naming it, an empty output; infinity: unlimited.
void TestBadMaximumDistance()
{
  auto mesh = gs_test::UnitSquare(4, true);
  for (double bad : { -1.0, std::numeric_limits<double>::quiet_NaN() })
  {
    for (int solver : AllSolvers)
    {
      const std::string test = "BadMaximumDistance[" + std::to_string(bad) + ", " +
        vtkSVGGeodesicDistance::GetSolverName(solver) + "]";
      const RunResult r = Run(mesh, { 0 }, nullptr, bad, solver);
      bool named = false;
      for (const std::string& e : r.Errors)
      {
        named = named || e.find("MaximumDistance must be at least 0") != std::string::npos;
      }
      Check(named && r.Output->GetNumberOfPoints() == 0, test, "no error naming MaximumDistance");
    }
  }
  const RunResult unlimited = Run(mesh, { 0 }, nullptr, std::numeric_limits<double>::infinity());
  vtkDoubleArray* d = unlimited.Distance();
  bool finite = unlimited.Errors.empty() && d && d->GetNumberOfTuples() == 25;
  for (vtkIdType i = 0; finite && i < d->GetNumberOfTuples(); ++i)
  {
    finite = std::isfinite(d->GetValue(i));
  }
  Check(finite, "BadMaximumDistance[inf]", "infinity is not unlimited");
}

void TestPrintSelf()
{
  vtkNew<vtkSVGGeodesicDistance> filter;
  Check(filter->GetSolver() == vtkSVGGeodesicDistance::VIRTUAL_SOURCES && filter->GetK() == 50 &&
      std::string(filter->GetCacheFileName()).empty() && filter->GetUnfoldingRefinement(),
    "Defaults", "Solver Virtual sources (no precompute), K 50, no cache file, refinement on");
  filter->AddSourceVertexId(3);
  filter->AddSourceVertexId(8);
  filter->SetMaximumDistance(2.5);
  filter->SetResultArrayName("d");
  filter->SetSolverToSVGDijkstra();
  filter->SetK(7);
  filter->SetCacheFileName("/tmp/graph.svgg");
  filter->UnfoldingRefinementOff();
  std::ostringstream os;
  filter->Print(os);
  const std::string text = os.str();
  for (const char* expected :
    { "Solver: 2 (SVG (Dijkstra))", "SourceVertexIds (2): 3 8", "MaximumDistance: 2.5",
      "ResultArrayName: d", "K: 7", "CacheFileName: /tmp/graph.svgg", "UnfoldingRefinement: off" })
  {
    Check(text.find(expected) != std::string::npos, "PrintSelf", std::string("no ") + expected);
  }
}

void TestDisconnected()
{
  // Two separate squares: the one without the source is unreachable (NaN).
  const std::string test = "Disconnected";
  auto mesh = MakeMesh({ { { 0, 0, 0 } }, { { 1, 0, 0 } }, { { 0, 1, 0 } }, { { 1, 1, 0 } },
                         { { 3, 0, 0 } }, { { 4, 0, 0 } }, { { 3, 1, 0 } }, { { 4, 1, 0 } } },
    { { 0, 1, 2 }, { 1, 3, 2 }, { 4, 5, 6 }, { 5, 7, 6 } });
  for (int solver : AllSolvers)
  {
    const RunResult r = Run(mesh, { 0 }, nullptr, 0.0, solver);
    Check(r.Errors.empty(), test, "unexpected error");
    vtkDoubleArray* d = r.Distance();
    Check(d && std::abs(d->GetValue(3) - std::sqrt(2.0)) < 1e-12 && std::isnan(d->GetValue(4)) &&
        std::isnan(d->GetValue(7)),
      test, "wrong distances");
  }
}
}

int main()
{
  TestEmpty();
  TestPointsOnly();
  TestLinesOnly();
  TestNonManifoldEdge();
  TestNonManifoldVertex();
  TestDuplicateTriangles();
  TestDegenerateTriangle();
  TestRepeatedCorner();
  TestNaNCoordinate();
  TestInfiniteCoordinate();
  TestMissingSource();
  TestOutOfRangeSource();
  TestUnreferencedSource();
  TestUnreferencedPoints();
  TestQuads();
  TestSplitVertices();
  TestSourcePoints();
  TestEmptySourcePoints();
  TestMaximumDistance();
  TestBadMaximumDistance();
  TestDisconnected();
  TestPrintSelf();
  if (Failures > 0)
  {
    std::cerr << Failures << " check(s) failed\n";
    return 1;
  }
  std::cout << "all checks passed\n";
  return 0;
}
