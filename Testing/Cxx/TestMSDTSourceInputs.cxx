// vtkMSDTSource: images (alpha and luminance) written by the test, polygon input with ClassId,
// long-shape parts, field data, errors (unreadable / all-transparent images, bad parameters,
// no shape), abort. Needs no external data.
#include "vtkMSDTSource.h"

#include "Silhouette.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <array>
#include <cmath>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>

namespace
{
int Failures = 0;
#define CHECK(cond)                                                                                \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __LINE__ << ": CHECK failed: " #cond "\n";                                      \
      ++Failures;                                                                                  \
    }                                                                                              \
  } while (0)

int Errors = 0;
std::string LastError;
void CountError(vtkObject*, unsigned long, void*, void* message)
{
  ++Errors;
  LastError = message ? static_cast<const char*>(message) : "";
}

int Warnings = 0;
std::string LastWarning;
void CountWarning(vtkObject*, unsigned long, void*, void* message)
{
  ++Warnings;
  LastWarning = message ? static_cast<const char*>(message) : "";
}

gs::SilhouetteMask Disk(int size, double radius)
{
  gs::SilhouetteMask m;
  m.Width = m.Height = size;
  m.Inside.assign(static_cast<std::size_t>(size) * size, 0);
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x)
      m.Inside[static_cast<std::size_t>(y) * size + x] =
        std::hypot(x + 0.5 - size / 2.0, y + 0.5 - size / 2.0) <= radius;
  return m;
}

// Runs the source and returns the number of errors it reported.
int Run(vtkMSDTSource* source)
{
  Errors = 0;
  source->Update();
  return Errors;
}
} // namespace

int main(int argc, char* argv[])
{
  std::string temp = ".";
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--temp") == 0)
      temp = argv[i + 1];
  const std::string diskRGBA = temp + "/msdt_disk_rgba.png";
  const std::string diskGrey = temp + "/msdt_disk_grey.jpg";
  const std::string empty = temp + "/msdt_empty.png";
  gs::SilhouetteMask none = Disk(16, 0.1); // all transparent
  for (const gs::Status written : { gs::WriteSilhouetteImage(Disk(80, 30), diskRGBA, true),
         gs::WriteSilhouetteImage(Disk(80, 15), diskGrey, false),
         gs::WriteSilhouetteImage(none, empty, true) })
  {
    if (!written.Ok())
    {
      std::cerr << written.Message() << "\n";
      return 1;
    }
  }

  vtkNew<vtkCallbackCommand> onError;
  onError->SetCallback(CountError);

  // 1. Two disks (alpha PNG, luminance JPEG): 4 tables, radii 1 and 1/2.
  vtkNew<vtkMSDTSource> source;
  source->AddObserver(vtkCommand::ErrorEvent, onError);
  source->AddShapeFileName(diskRGBA.c_str());
  source->AddShapeFileName(diskGrey.c_str());
  source->SetAngleBins(32);
  source->SetDistanceSteps(40);
  CHECK(Run(source) == 0);
  vtkImageData* tables = source->GetTablesOutput();
  int dims[3];
  tables->GetDimensions(dims);
  CHECK(dims[0] == 32 && dims[1] == 32 && dims[2] == 4);
  vtkDataArray* values = tables->GetPointData()->GetArray("SafeDistance");
  CHECK(values && values->GetNumberOfTuples() == 32 * 32 * 4);
  vtkFieldData* fd = tables->GetFieldData();
  vtkDataArray* radius = fd->GetArray("ClassRadius");
  CHECK(radius && radius->GetNumberOfTuples() == 2);
  if (radius && values)
  {
    CHECK(radius->GetTuple1(0) == 1.0);
    CHECK(std::abs(radius->GetTuple1(1) - 0.5) < 0.05);
    // Every entry of pair (a, b) is r_a + r_b within one step.
    const double r[2] = { radius->GetTuple1(0), radius->GetTuple1(1) };
    for (int pair = 0; pair < 4; ++pair)
    {
      const double sum = r[pair / 2] + r[pair % 2], step = sum / 40;
      CHECK(std::abs(fd->GetArray("PairDistanceStep")->GetTuple1(pair) - step) < 1e-12);
      for (int k = 0; k < 32 * 32; ++k)
      {
        const double v = values->GetTuple1(pair * 32 * 32 + k);
        if (!(v <= sum + 1e-12 && v >= sum - step - 1e-12))
        {
          std::cerr << "pair " << pair << " entry " << k << ": " << v << " vs " << sum << "\n";
          ++Failures;
          break;
        }
      }
    }
  }
  vtkStringArray* names = vtkStringArray::SafeDownCast(fd->GetAbstractArray("ClassName"));
  CHECK(names && names->GetValue(1) == diskGrey);
  CHECK(fd->GetArray("Scale") && std::abs(fd->GetArray("Scale")->GetTuple1(0) - 30.0) < 1.0);
  vtkPolyData* outlines = source->GetOutlinesOutput();
  CHECK(outlines->GetNumberOfCells() == 2);
  CHECK(outlines->GetCellData()->GetArray("ClassId") != nullptr);
  double bounds[6];
  outlines->GetBounds(bounds);
  CHECK(std::abs(bounds[1] - 1.0) < 0.05 && std::abs(bounds[0] + 1.0) < 0.05);
  vtkImageData* silhouettes = source->GetSilhouettesOutput();
  CHECK(silhouettes->GetPointData()->GetScalars() &&
    silhouettes->GetPointData()->GetScalars()->GetNumberOfComponents() == 2);
  // Centre texel inside both, corner texel outside.
  if (silhouettes->GetPointData()->GetScalars())
  {
    vtkDataArray* s = silhouettes->GetPointData()->GetScalars();
    CHECK(s->GetComponent(128 * 256 + 128, 0) == 255 && s->GetComponent(128 * 256 + 128, 1) == 255);
    CHECK(s->GetComponent(0, 0) == 0 && s->GetComponent(0, 1) == 0);
  }
  std::ostringstream print;
  source->Print(print);
  for (const char* p : { "AngleBins: 32", "DistanceSteps: 40", "AlphaThreshold", "LuminanceThreshold",
         "MaximumAspectRatio", "TextureSize", "msdt_disk_grey.jpg" })
    CHECK(print.str().find(p) != std::string::npos);

  // 2. Errors: empty outputs and an error message.
  auto expectError = [&](vtkMSDTSource* s, const char* what) {
    const int errors = Run(s);
    if (errors == 0 || s->GetTablesOutput()->GetNumberOfPoints() != 0 ||
      s->GetOutlinesOutput()->GetNumberOfCells() != 0)
    {
      std::cerr << "no error / non-empty output for " << what << "\n";
      ++Failures;
    }
  };
  source->SetAngleBins(0);
  expectError(source, "AngleBins 0");
  source->SetAngleBins(32);
  source->SetDistanceSteps(0);
  expectError(source, "DistanceSteps 0");
  // (Before any work: 2^20 steps would take minutes.)
  source->SetDistanceSteps(1 << 20);
  expectError(source, "DistanceSteps 2^20");
  source->SetDistanceSteps(40);
  source->SetMaximumAspectRatio(0.5);
  expectError(source, "MaximumAspectRatio 0.5");
  source->SetMaximumAspectRatio(2);
  source->SetAlphaThreshold(-1);
  expectError(source, "AlphaThreshold -1");
  source->SetAlphaThreshold(0.5);
  source->AddShapeFileName((temp + "/no_such_file.png").c_str());
  expectError(source, "missing file");
  source->RemoveAllShapeFileNames();
  expectError(source, "no shape");
  source->AddShapeFileName(empty.c_str());
  expectError(source, "all-transparent image");
  source->RemoveAllShapeFileNames();

  // 3. Polygons: class 7 = a square frame with a hole, class 3 = a 6:1 rectangle (3 parts).
  vtkNew<vtkPolyData> polys;
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkIntArray> classIds;
  classIds->SetName("ClassId");
  auto ring = [&](std::initializer_list<std::pair<double, double>> corners, int id, bool closed) {
    cells->InsertNextCell(static_cast<int>(corners.size() + (closed ? 1 : 0)));
    vtkIdType first = pts->GetNumberOfPoints();
    for (auto c : corners)
      cells->InsertCellPoint(pts->InsertNextPoint(c.first, c.second, 0.0));
    if (closed)
      cells->InsertCellPoint(first);
    classIds->InsertNextValue(id);
  };
  ring({ { -2, -2 }, { 2, -2 }, { 2, 2 }, { -2, 2 } }, 7, false);
  ring({ { -1, -1 }, { 1, -1 }, { 1, 1 }, { -1, 1 } }, 7, true);
  ring({ { 10, 0 }, { 16, 0 }, { 16, 1 }, { 10, 1 } }, 3, false);
  polys->SetPoints(pts);
  polys->SetPolys(cells);
  polys->GetCellData()->AddArray(classIds);
  source->SetPolygonsData(polys);
  source->SetAngleBins(16);
  source->SetDistanceSteps(16);
  CHECK(Run(source) == 0);
  tables = source->GetTablesOutput();
  tables->GetDimensions(dims);
  CHECK(dims[2] == 16); // 1 + 3 parts: 16 pairs
  fd = tables->GetFieldData();
  vtkDataArray* parts = fd->GetArray("ClassNumberOfParts");
  CHECK(parts && parts->GetTuple1(0) == 1 && parts->GetTuple1(1) == 3);
  CHECK(fd->GetArray("PartClassId") && fd->GetArray("PartClassId")->GetTuple1(3) == 1);
  CHECK(std::abs(fd->GetArray("Scale")->GetTuple1(0) - 2 * std::sqrt(2.0)) < 1e-9);
  CHECK(source->GetOutlinesOutput()->GetNumberOfCells() == 3);

  // 3b. Polylines: an open one (last point not the first) is closed with a warning; closed
  //     ones (first point repeated) and polygon cells (implicitly closed) give none.
  {
    vtkNew<vtkCallbackCommand> onWarning;
    onWarning->SetCallback(CountWarning);
    vtkNew<vtkMSDTSource> lines;
    lines->AddObserver(vtkCommand::ErrorEvent, onError);
    lines->AddObserver(vtkCommand::WarningEvent, onWarning);
    lines->SetAngleBins(8);
    lines->SetDistanceSteps(8);
    auto polylines = [](bool closeFirst, bool closeSecond) {
      vtkNew<vtkPoints> p;
      vtkNew<vtkCellArray> c;
      for (int k = 0; k < 2; ++k)
      {
        const double x = 10.0 * k;
        const vtkIdType a = p->InsertNextPoint(x, 0, 0), b = p->InsertNextPoint(x + 2, 0, 0),
                        d = p->InsertNextPoint(x + 2, 1, 0), e = p->InsertNextPoint(x, 1, 0);
        const bool closed = k == 0 ? closeFirst : closeSecond;
        c->InsertNextCell(closed ? 5 : 4);
        for (vtkIdType id : { a, b, d, e })
          c->InsertCellPoint(id);
        if (closed)
          c->InsertCellPoint(a);
      }
      vtkNew<vtkPolyData> pd;
      pd->SetPoints(p);
      pd->SetLines(c);
      return vtkSmartPointer<vtkPolyData>(pd.GetPointer());
    };
    lines->SetPolygonsData(polylines(true, false));
    Warnings = 0;
    CHECK(Run(lines) == 0);
    CHECK(Warnings == 1);
    CHECK(LastWarning.find("1 open polyline(s)") != std::string::npos &&
      LastWarning.find("treated as closed") != std::string::npos);
    // Open or not, the shape is the same rectangle: 2 classes of one part each.
    CHECK(lines->GetTablesOutput()->GetFieldData()->GetArray("ClassRadius") &&
      lines->GetTablesOutput()->GetFieldData()->GetArray("ClassRadius")->GetNumberOfTuples() == 2);
    CHECK(lines->GetOutlinesOutput()->GetNumberOfCells() == 2);
    lines->SetPolygonsData(polylines(false, false));
    Warnings = 0;
    CHECK(Run(lines) == 0);
    CHECK(Warnings == 1 && LastWarning.find("2 open polyline(s)") != std::string::npos);
    lines->SetPolygonsData(polylines(true, true));
    Warnings = 0;
    CHECK(Run(lines) == 0);
    CHECK(Warnings == 0);
    // The same open rings as polygon cells: no warning.
    vtkSmartPointer<vtkPolyData> asPolygons = polylines(false, false);
    asPolygons->SetPolys(asPolygons->GetLines());
    asPolygons->SetLines(nullptr);
    lines->SetPolygonsData(asPolygons);
    Warnings = 0;
    CHECK(Run(lines) == 0);
    CHECK(Warnings == 0 && lines->GetOutlinesOutput()->GetNumberOfCells() == 2);
  }

  // 3b. Classes far apart in size (an image in pixels next to a polygon drawn in unit
  // coordinates: 30 times smaller): a warning naming both; a polygon in pixel units: none.
  for (const double side : { 2.0, 40.0 })
  {
    vtkNew<vtkMSDTSource> mixed;
    vtkNew<vtkCallbackCommand> onWarning;
    onWarning->SetCallback(CountWarning);
    mixed->AddObserver(vtkCommand::WarningEvent, onWarning);
    mixed->AddShapeFileName(diskRGBA.c_str());
    vtkNew<vtkPoints> p;
    vtkNew<vtkCellArray> c;
    c->InsertNextCell(4);
    for (const auto& xy : { std::array<double, 2>{ 0, 0 }, std::array<double, 2>{ side, 0 },
           std::array<double, 2>{ side, side }, std::array<double, 2>{ 0, side } })
    {
      c->InsertCellPoint(p->InsertNextPoint(xy[0], xy[1], 0.0));
    }
    vtkNew<vtkPolyData> square;
    square->SetPoints(p);
    square->SetPolys(c);
    mixed->SetPolygonsData(square);
    mixed->SetAngleBins(16);
    mixed->SetDistanceSteps(16);
    Warnings = 0;
    LastWarning.clear();
    CHECK(Run(mixed) == 0);
    if (side == 2.0)
    {
      CHECK(Warnings == 1 && LastWarning.find("times larger than 'polygon cell 0'") != std::string::npos &&
        LastWarning.find("pixel units") != std::string::npos);
    }
    else
    {
      CHECK(Warnings == 0);
    }
  }

  // 4. Guards: a surface connected as polygons (not in a plane of constant z), and tables
  // that would not fit in memory (refused before allocation).
  {
    vtkNew<vtkMSDTSource> guarded;
    vtkNew<vtkCallbackCommand> onError;
    onError->SetCallback(CountError);
    guarded->AddObserver(vtkCommand::ErrorEvent, onError);
    vtkNew<vtkPoints> pts;
    vtkNew<vtkCellArray> cells;
    const double corners[4][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
    for (const auto& c : corners)
      pts->InsertNextPoint(c);
    for (const auto& t : { std::array<vtkIdType, 3>{ 0, 2, 1 }, { 0, 1, 3 }, { 0, 3, 2 }, { 1, 2, 3 } })
      cells->InsertNextCell(3, t.data());
    vtkNew<vtkPolyData> surface;
    surface->SetPoints(pts);
    surface->SetPolys(cells);
    guarded->SetPolygonsData(surface);
    CHECK(Run(guarded) >= 1);
    CHECK(LastError.find("plane of constant z") != std::string::npos);
    CHECK(guarded->GetTablesOutput()->GetNumberOfPoints() == 0);

    // Polygons the core refuses (a ring without area, then a non-finite point): its message.
    vtkNew<vtkPoints> flatPoints;
    vtkNew<vtkCellArray> flatCells;
    const vtkIdType flat[3] = { flatPoints->InsertNextPoint(0, 0, 0),
      flatPoints->InsertNextPoint(1, 0, 0), flatPoints->InsertNextPoint(2, 0, 0) };
    flatCells->InsertNextCell(3, flat);
    vtkNew<vtkPolyData> flatPolygon;
    flatPolygon->SetPoints(flatPoints);
    flatPolygon->SetPolys(flatCells);
    guarded->SetPolygonsData(flatPolygon);
    CHECK(Run(guarded) >= 1);
    CHECK(LastError.find("shape 'polygon cell 0' is empty: its rings enclose no area under the even-odd rule") != std::string::npos);
    flatPoints->SetPoint(2, std::nan(""), 1, 0);
    flatPoints->Modified();
    CHECK(Run(guarded) >= 1);
    CHECK(LastError.find("shape 'polygon cell 0' has non-finite coordinates") != std::string::npos);
    CHECK(guarded->GetTablesOutput()->GetNumberOfPoints() == 0);

    // 400 small squares, one class each, at 128 angle bins: 400^2 x 128^2 doubles = 21 GB.
    vtkNew<vtkPoints> squarePoints;
    vtkNew<vtkCellArray> squares;
    for (int k = 0; k < 400; ++k)
    {
      const double x = 3.0 * (k % 20), y = 3.0 * (k / 20);
      vtkIdType ids[4];
      ids[0] = squarePoints->InsertNextPoint(x, y, 0);
      ids[1] = squarePoints->InsertNextPoint(x + 1, y, 0);
      ids[2] = squarePoints->InsertNextPoint(x + 1, y + 1, 0);
      ids[3] = squarePoints->InsertNextPoint(x, y + 1, 0);
      squares->InsertNextCell(4, ids);
    }
    vtkNew<vtkPolyData> many;
    many->SetPoints(squarePoints);
    many->SetPolys(squares);
    guarded->SetPolygonsData(many);
    guarded->SetAngleBins(128);
    CHECK(Run(guarded) >= 1);
    CHECK(LastError.find("MB of tables") != std::string::npos);
    CHECK(guarded->GetTablesOutput()->GetNumberOfPoints() == 0);
  }

  // 5. Abort: empty output, no error.
  vtkNew<vtkCallbackCommand> abort;
  abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  source->AddObserver(vtkCommand::ProgressEvent, abort);
  source->SetAngleBins(17);
  Run(source);
  CHECK(source->GetTablesOutput()->GetNumberOfPoints() == 0);

  if (Failures == 0)
    std::cout << "TestMSDTSourceInputs passed\n";
  return Failures == 0 ? 0 : 1;
}
