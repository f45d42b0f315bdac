// Shape Distributor as a filter: a working pipeline (MSDT Source from polygons + a plane with a
// cell direction array), its outputs and arrays, and the bad-input matrix: missing or foreign
// tables, missing / wrong-typed arrays, quads (triangulated with a warning), empty and
// non-manifold meshes, NaN points, NaN / zero densities, absurd parameters, abort. Each bad case
// gives a clear error (or warning) and empty outputs, never a crash.
#include "vtkMSDTSource.h"
#include "vtkShapeDistributor.h"

#include "FilterTestSupport.h"
#include "MeshGenerators.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>

using gs_test::Check;
using gs_test::Mentions;
using gs_test::MessageRecorder;

namespace
{

// A pentagram (class 0) and a 4:1 bar (class 1) as polygons for MSDT Source.
vtkSmartPointer<vtkPolyData> Shapes()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkIntArray> classId;
  classId->SetName("ClassId");
  std::vector<vtkIdType> ids;
  for (const gs::Vec2& p : gs::MakeStarPolygon(5, 1.0, 0.382))
  {
    ids.push_back(points->InsertNextPoint(p.x, p.y, 0.0));
  }
  polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  classId->InsertNextValue(0);
  ids.clear();
  for (const auto& p : { std::array<double, 2>{ -2, -0.5 }, { 2, -0.5 }, { 2, 0.5 }, { -2, 0.5 } })
  {
    ids.push_back(points->InsertNextPoint(p[0], p[1], 0.0));
  }
  polys->InsertNextCell(4, ids.data());
  classId->InsertNextValue(1);
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetPolys(polys);
  data->GetCellData()->AddArray(classId);
  return data;
}

// The unit square, n x n quads split into triangles, with a constant cell array Direction and a
// density ramp f = 0.6 + 0.4 x.
vtkSmartPointer<vtkPolyData> Plane(int n, bool triangulate = true)
{
  vtkSmartPointer<vtkPolyData> data = gs_test::UnitSquare(n, triangulate);
  vtkNew<vtkDoubleArray> direction;
  direction->SetName("Direction");
  direction->SetNumberOfComponents(3);
  for (vtkIdType c = 0; c < data->GetNumberOfCells(); ++c)
  {
    direction->InsertNextTuple3(1.0, 0.0, 0.0);
  }
  data->GetCellData()->AddArray(direction);
  vtkNew<vtkDoubleArray> density;
  density->SetName("Density");
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    density->InsertNextValue(0.6 + 0.4 * data->GetPoint(i)[0]);
  }
  data->GetPointData()->AddArray(density);
  return data;
}

struct Run
{
  vtkNew<vtkShapeDistributor> Filter;
  vtkNew<MessageRecorder> Messages;
  Run(vtkDataObject* mesh, vtkAlgorithmOutput* tables)
  {
    this->Filter->SetInputDataObject(0, mesh);
    if (tables)
    {
      this->Filter->SetInputConnection(1, tables);
    }
    this->Filter->AddObserver(vtkCommand::ErrorEvent, this->Messages);
    this->Filter->AddObserver(vtkCommand::WarningEvent, this->Messages);
    this->Filter->SetShapeSize(0.06);
    this->Filter->SetSeed(5);
    this->Filter->SetMaximalFailures(3000);
  }
  vtkPolyData* Out(int port) { return vtkPolyData::SafeDownCast(this->Filter->GetOutputDataObject(port)); }
  void Update() { this->Filter->Update(); }
  bool Empty() { return Out(0)->GetNumberOfPoints() == 0 && Out(1)->GetNumberOfCells() == 0 && Out(2)->GetNumberOfCells() == 0; }
};

void ExpectError(Run& run, const std::string& test, const std::string& keyword)
{
  run.Update();
  Check(!run.Messages->Errors.empty(), test, "no error reported");
  Check(Mentions(run.Messages->Errors, keyword), test,
    "the error does not mention '" + keyword + "'" +
      (run.Messages->Errors.empty() ? std::string() : ": " + run.Messages->Errors[0]));
  Check(run.Empty(), test, "outputs should be empty");
}
} // namespace

int main(int, char*[])
{
  vtkNew<vtkMSDTSource> msdt;
  msdt->SetPolygonsData(Shapes());
  msdt->SetAngleBins(32);
  msdt->SetDistanceSteps(32);
  msdt->Update();
  vtkAlgorithmOutput* tables = msdt->GetOutputPort(0);

  // 1. A working run: arrays, counts, both classes, density-scaled shapes.
  {
    auto mesh = Plane(30);
    Run run(mesh, tables);
    run.Filter->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Density");
    run.Update();
    Check(run.Messages->Errors.empty(), "pipeline", "unexpected error");
    vtkPolyData* placed = run.Out(0);
    const vtkIdType n = placed->GetNumberOfPoints();
    Check(n > 50, "pipeline", "too few shapes: " + std::to_string(n));
    for (const char* name : { "ClassId", "Scale", "Direction", "Normal", "FaceId" })
    {
      Check(placed->GetPointData()->GetArray(name) != nullptr, "pipeline", std::string("no point array ") + name);
    }
    Check(placed->GetNumberOfVerts() == n, "pipeline", "one vertex cell per shape");
    vtkDataArray* cls = placed->GetPointData()->GetArray("ClassId");
    vtkDataArray* scale = placed->GetPointData()->GetArray("Scale");
    vtkDataArray* faceId = placed->GetPointData()->GetArray("FaceId");
    bool both[2] = { false, false };
    for (vtkIdType i = 0; cls && scale && faceId && i < n; ++i)
    {
      const int c = static_cast<int>(cls->GetTuple1(i));
      both[c == 1] = true;
      Check(std::abs(scale->GetTuple1(i) - (0.6 + 0.4 * placed->GetPoint(i)[0])) < 1e-9, "pipeline",
        "Scale is not the density at the centre");
      Check(faceId->GetTuple1(i) >= 0 && faceId->GetTuple1(i) < mesh->GetNumberOfCells(), "pipeline",
        "FaceId out of range");
    }
    Check(both[0] && both[1], "pipeline", "both classes expected");
    Check(placed->GetFieldData()->GetArray("Maximal") &&
        placed->GetFieldData()->GetArray("Maximal")->GetTuple1(0) == 1.0,
      "pipeline", "field data Maximal should be 1");
    vtkPolyData* decals = run.Out(1);
    Check(decals->GetNumberOfCells() > n, "pipeline", "decals too small");
    Check(decals->GetPointData()->GetTCoords() != nullptr, "pipeline", "decals without texture coordinates");
    Check(decals->GetCellData()->GetArray("ShapeId") && decals->GetCellData()->GetArray("ClassId"),
      "pipeline", "decal cell arrays");
    vtkPolyData* outlines = run.Out(2);
    Check(outlines->GetNumberOfLines() >= n, "pipeline", "one outline per shape at least");
    // Re-running with another density only: same mesh, no new conversion (no error either).
    run.Filter->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "None");
    run.Update();
    Check(run.Out(0)->GetNumberOfPoints() > 0 && run.Messages->Errors.empty(), "pipeline", "no density");
    // Modes and thread counts.
    run.Filter->SetMode(vtkShapeDistributor::CIRCUMCIRCLE_POISSON_DISK);
    run.Update();
    const vtkIdType circles = run.Out(0)->GetNumberOfPoints();
    run.Filter->SetMode(vtkShapeDistributor::GREEDY);
    run.Update();
    const vtkIdType greedy = run.Out(0)->GetNumberOfPoints();
    Check(circles > 0 && greedy > circles, "modes", "greedy should beat circumcircles");
    run.Filter->SetNumberOfThreads(1);
    run.Update();
    Check(run.Out(0)->GetNumberOfPoints() == greedy, "threads", "1 thread differs");
    // KeepInside: every circle on the unit square (radius 0.06 at density 1; star is class 0).
    run.Filter->SetMode(vtkShapeDistributor::RANDOM);
    run.Filter->KeepInsideOn();
    run.Update();
    {
      vtkPolyData* inside = run.Out(0);
      vtkDataArray* sc = inside->GetPointData()->GetArray("Scale");
      vtkDataArray* cl = inside->GetPointData()->GetArray("ClassId");
      bool ok = inside->GetNumberOfPoints() > 0 && sc && cl;
      for (vtkIdType i = 0; ok && i < inside->GetNumberOfPoints(); ++i)
      {
        const double* x = inside->GetPoint(i);
        // The bar (class 1) has its own circumradius: check the star's only.
        const double r = cl->GetTuple1(i) == 0 ? 0.06 * sc->GetTuple1(i) : 0.0;
        ok = x[0] >= r - 1e-9 && x[0] <= 1 - r + 1e-9 && x[1] >= r - 1e-9 && x[1] <= 1 - r + 1e-9;
      }
      Check(ok, "KeepInside", "a star hangs over the square's side");
    }
    run.Filter->KeepInsideOff();
    // A point direction array works as well.
    vtkNew<vtkDoubleArray> pointDirection;
    pointDirection->SetName("PointDirection");
    pointDirection->SetNumberOfComponents(3);
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      pointDirection->InsertNextTuple3(0.0, 1.0, 0.0);
    }
    mesh->GetPointData()->AddArray(pointDirection);
    mesh->Modified();
    run.Filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "PointDirection");
    run.Update();
    vtkDataArray* dir = run.Out(0)->GetPointData()->GetArray("Direction");
    Check(dir && dir->GetNumberOfTuples() > 0 && std::abs(dir->GetComponent(0, 1) - 1.0) < 1e-9,
      "point directions", "the shapes should follow the point array");
  }

  // 2. Missing tables, foreign tables.
  {
    Run run(Plane(4), nullptr);
    run.Filter->SetInputDataObject(1, nullptr);
    run.Update();
    Check(run.Empty(), "no tables", "outputs should be empty");
  }
  {
    vtkNew<vtkImageData> foreign;
    foreign->SetDimensions(4, 4, 1);
    foreign->AllocateScalars(VTK_DOUBLE, 1);
    Run run(Plane(4), nullptr);
    run.Filter->SetInputDataObject(1, foreign);
    ExpectError(run, "foreign tables", "MSDT Source");
  }
  // 3. Arrays.
  {
    Run run(Plane(4), tables);
    run.Filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "Nope");
    ExpectError(run, "missing direction", "DirectionArray");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Density");
    ExpectError(run, "1-component direction", "3 components");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_NONE, "Direction");
    ExpectError(run, "field-data direction", "point or cell array");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Nope");
    ExpectError(run, "missing density", "DensityArray");
  }
  // Directions that are all zero, all NaN or all normal to the plane: an error naming the array;
  // a third of them zero: shapes, and a warning with the share.
  for (double fill : { 0.0, std::numeric_limits<double>::quiet_NaN(), 1.0 })
  {
    auto mesh = Plane(6);
    vtkNew<vtkDoubleArray> d;
    d->SetName("Useless");
    d->SetNumberOfComponents(3);
    for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
    {
      // (1.0: along the plane's normal, z.)
      d->InsertNextTuple3(fill == 1.0 ? 0.0 : fill, fill == 1.0 ? 0.0 : fill, fill);
    }
    mesh->GetCellData()->AddArray(d);
    Run run(mesh, tables);
    run.Filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "Useless");
    ExpectError(run, "unusable directions", "\"Useless\" has no usable vector");
  }
  {
    auto mesh = Plane(6);
    vtkNew<vtkDoubleArray> d;
    d->SetName("Partly");
    d->SetNumberOfComponents(3);
    for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
    {
      d->InsertNextTuple3(c % 3 == 0 ? 0.0 : 1.0, 0.0, 0.0);
    }
    mesh->GetCellData()->AddArray(d);
    Run run(mesh, tables);
    run.Filter->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "Partly");
    run.Update();
    Check(run.Messages->Errors.empty() && run.Out(0)->GetNumberOfPoints() > 0 &&
        Mentions(run.Messages->Warnings, "random orientation"),
      "partly zero directions", "no shapes, or no warning");
  }
  {
    auto mesh = Plane(4);
    vtkDataArray* f = mesh->GetPointData()->GetArray("Density");
    for (vtkIdType i = 0; i < f->GetNumberOfTuples(); ++i)
    {
      f->SetTuple1(i, i % 2 ? std::numeric_limits<double>::quiet_NaN() : 0.0);
    }
    Run run(mesh, tables);
    run.Filter->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Density");
    ExpectError(run, "NaN and zero density", "density");
  }
  // 4. Meshes: quads (triangulated, warning), empty, NaN point, non-manifold edge.
  {
    Run run(Plane(10, false), tables);
    run.Update();
    Check(run.Out(0)->GetNumberOfPoints() > 0, "quads", "quads should be triangulated and used");
    Check(!run.Messages->Warnings.empty(), "quads", "a warning about the triangulation expected");
  }
  {
    vtkNew<vtkPolyData> empty;
    Run run(empty, tables);
    run.Update();
    Check(!run.Messages->Errors.empty() && run.Empty(), "empty mesh", "error and empty outputs expected");
  }
  {
    auto mesh = Plane(4);
    mesh->GetPoints()->SetPoint(3, std::numeric_limits<double>::quiet_NaN(), 0, 0);
    Run run(mesh, tables);
    run.Update();
    Check(!run.Messages->Errors.empty() && run.Empty(), "NaN point", "error and empty outputs expected");
  }
  {
    // Three triangles on one edge.
    vtkNew<vtkPoints> pts;
    pts->InsertNextPoint(0, 0, 0);
    pts->InsertNextPoint(1, 0, 0);
    pts->InsertNextPoint(0.5, 1, 0);
    pts->InsertNextPoint(0.5, -1, 0);
    pts->InsertNextPoint(0.5, 0, 1);
    vtkNew<vtkCellArray> tris;
    for (vtkIdType c : { 2, 3, 4 })
    {
      const vtkIdType ids[3] = { 0, 1, c };
      tris->InsertNextCell(3, ids);
    }
    vtkNew<vtkPolyData> mesh;
    mesh->SetPoints(pts);
    mesh->SetPolys(tris);
    vtkNew<vtkDoubleArray> d;
    d->SetName("Direction");
    d->SetNumberOfComponents(3);
    for (int c = 0; c < 3; ++c)
      d->InsertNextTuple3(1, 0, 0);
    mesh->GetCellData()->AddArray(d);
    Run run(mesh, tables);
    ExpectError(run, "non-manifold", "manifold");
  }
  // 5. Parameters.
  {
    Run run(Plane(4), tables);
    run.Filter->SetShapeSize(-1.0);
    ExpectError(run, "negative size", "ShapeSize");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetShapeSize(1e-12);
    ExpectError(run, "tiny size", "ShapeSize");
  }
  for (const double tolerance : { -0.01, std::numeric_limits<double>::quiet_NaN() })
  {
    Run run(Plane(4), tables);
    run.Filter->SetShapeSize(0.5);
    run.Filter->SetDecalTolerance(tolerance);
    ExpectError(run, "bad DecalTolerance", "DecalTolerance");
  }
  {
    // ShapeSize 0: automatic, 4% of the largest bounding-box side (stated in the field data).
    Run run(Plane(4), tables);
    run.Filter->SetShapeSize(0.0);
    run.Update();
    vtkDataArray* used = run.Out(0)->GetFieldData()->GetArray("ShapeSizeUsed");
    double bounds[6];
    Plane(4)->GetBounds(bounds);
    const double side = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
    Check(run.Messages->Errors.empty() && used && std::abs(used->GetComponent(0, 0) - 0.04 * side) <= 1e-12 * side &&
        run.Out(0)->GetNumberOfPoints() > 0,
      "automatic size", "ShapeSizeUsed = 4% of the largest side, shapes placed");
  }
  {
    // Far larger than the mesh: an error before any work, naming ShapeSize.
    Run run(Plane(4), tables);
    run.Filter->SetShapeSize(100.0);
    ExpectError(run, "huge size", "ShapeSize 100 makes shapes larger than the surface");
  }
  {
    // A density factor of 1e6 makes shapes a million times larger: the same error, naming it.
    auto mesh = Plane(4);
    vtkDataArray* f = mesh->GetPointData()->GetArray("Density");
    for (vtkIdType i = 0; i < f->GetNumberOfTuples(); ++i)
    {
      f->SetTuple1(i, 1e6);
    }
    Run run(mesh, tables);
    run.Filter->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Density");
    ExpectError(run, "huge density", "larger than the surface");
  }
  {
    // Sizes so small the run would not fit in memory: refused before any work (the available
    // memory set to 100 MB for the test).
    setenv("GS_AVAILABLE_MEMORY", "1e8", 1);
    Run run(Plane(4), tables);
    run.Filter->SetShapeSize(1e-4);
    ExpectError(run, "memory", "GB available");
    unsetenv("GS_AVAILABLE_MEMORY");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetNumberOfClassWeights(3);
    ExpectError(run, "class weights", "ClassWeights");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetClassWeight(0, 0.0);
    run.Filter->SetClassWeight(1, 0.0);
    ExpectError(run, "zero weights", "ClassWeights");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetMode(7);
    ExpectError(run, "mode", "Mode");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetK(-3);
    ExpectError(run, "negative K", "K must be at least 1");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetSolver(4); // (Virtual sources: no polar charts)
    ExpectError(run, "solver without charts", "Unknown Solver 4");
  }
  // Each option out of range: an error naming the property and its value.
  {
    Run run(Plane(4), tables);
    run.Filter->SetHolonomyMargin(250);
    ExpectError(run, "HolonomyMargin 250", "HolonomyMargin must be from 0 to 100; it is 250");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetDistortionLimit(std::nan(""));
    ExpectError(run, "DistortionLimit NaN", "DistortionLimit must be at least 0");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetMaximumShapes(-2);
    ExpectError(run, "MaximumShapes -2", "MaximumShapes must be at least 0 (0: no limit); it is -2");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetNumberOfThreads(-1);
    ExpectError(run, "NumberOfThreads -1", "NumberOfThreads must be at least 0");
  }
  // More threads than processors: capped, with a warning; the same shapes as one thread.
  {
    Run many(Plane(6), tables);
    many.Filter->SetNumberOfThreads(1000);
    many.Update();
    Run one(Plane(6), tables);
    one.Filter->SetNumberOfThreads(1);
    one.Update();
    Check(many.Messages->Errors.empty() && Mentions(many.Messages->Warnings, "NumberOfThreads 1000") &&
        Mentions(many.Messages->Warnings, "processors"),
      "NumberOfThreads 1000", "no warning about the cap");
    Check(many.Out(0)->GetNumberOfPoints() > 0 &&
        many.Out(0)->GetNumberOfPoints() == one.Out(0)->GetNumberOfPoints(),
      "NumberOfThreads 1000", "not the shapes of one thread");
  }
  {
    Run run(Plane(8), tables);
    run.Filter->SetSolver(vtkShapeDistributor::EXACT); // exact charts
    run.Update();
    Check(run.Messages->Errors.empty() && run.Out(0)->GetNumberOfPoints() > 0, "Solver EXACT", "exact charts should work");
  }
  {
    // Charts on a discrete geodesic graph: shapes, none overlapping by the drawn check.
    Run run(Plane(8), tables);
    run.Filter->SetGraphAccuracy(0.02);
    run.Filter->SetVerifyOverlaps(true);
    run.Update();
    vtkDataArray* pairs = run.Out(0)->GetFieldData()->GetArray("OverlappingPairs");
    Check(run.Messages->Errors.empty() && run.Out(0)->GetNumberOfPoints() > 0 && pairs &&
        pairs->GetTuple1(0) == 0.0,
      "GraphAccuracy", "charts on a discrete geodesic graph should work without overlaps");
  }
  {
    Run run(Plane(4), tables);
    run.Filter->SetGraphAccuracy(0.5);
    ExpectError(run, "graph accuracy out of range", "accuracy");
  }
  // 6. Abort: empty outputs, no error.
  {
    Run run(Plane(30), tables);
    run.Filter->SetShapeSize(0.02);
    vtkNew<vtkCallbackCommand> abort;
    abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    });
    run.Filter->AddObserver(vtkCommand::ProgressEvent, abort);
    run.Update();
    Check(run.Out(0)->GetNumberOfPoints() == 0, "abort", "aborted run should give no shapes");
  }
  if (gs_test::Failures)
  {
    std::cerr << gs_test::Failures << " failure(s)\n";
    return 1;
  }
  std::cout << "OK\n";
  return 0;
}
