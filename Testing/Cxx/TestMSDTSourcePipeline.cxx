// vtkMSDTSource in a pipeline: the whole extents of the tables (ka x ka x P^2) and silhouettes
// are known after UpdateInformation, before any table is computed; downstream image filters
// (vtkImageShiftScale, vtkExtractVOI) consuming port 0 get the full tables; the shapes are read
// once per change of their inputs (cache keyed by file names, modification times and sizes,
// thresholds, MaximumAspectRatio and the polygons input); a polygons upstream is brought up to
// date during the information pass. Needs no external data.
#include "vtkMSDTSource.h"

#include "Silhouette.h"

#include <vtkDataArray.h>
#include <vtkExtractVOI.h>
#include <vtkImageData.h>
#include <vtkImageShiftScale.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkRegularPolygonSource.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <thread>

// The test seam of vtkMSDTSource (a friend): how often it read and split its shapes.
struct vtkMSDTSourceInspector
{
  static int ShapeLoads(vtkMSDTSource* source) { return source->NumberOfShapeLoads; }
};

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

// A w x h rectangle of inside pixels centred in a size x size mask.
gs::SilhouetteMask Rectangle(int size, int w, int h)
{
  gs::SilhouetteMask m;
  m.Width = m.Height = size;
  m.Inside.assign(static_cast<std::size_t>(size) * size, 0);
  for (int y = (size - h) / 2; y < (size + h) / 2; ++y)
    for (int x = (size - w) / 2; x < (size + w) / 2; ++x)
      m.Inside[static_cast<std::size_t>(y) * size + x] = 1;
  return m;
}

bool WholeExtentIs(vtkAlgorithm* algorithm, int port, const int expected[6])
{
  int extent[6] = { 1, 0, 1, 0, 1, 0 };
  vtkInformation* info = algorithm->GetOutputInformation(port);
  if (!info->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    std::cerr << "port " << port << ": no WHOLE_EXTENT\n";
    return false;
  }
  info->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent);
  for (int k = 0; k < 6; ++k)
  {
    if (extent[k] != expected[k])
    {
      std::cerr << "port " << port << ": whole extent " << extent[0] << " " << extent[1] << " "
                << extent[2] << " " << extent[3] << " " << extent[4] << " " << extent[5]
                << ", expected " << expected[0] << " " << expected[1] << " " << expected[2] << " "
                << expected[3] << " " << expected[4] << " " << expected[5] << "\n";
      return false;
    }
  }
  return true;
}
} // namespace

int main(int argc, char* argv[])
{
  std::string temp = ".";
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--temp") == 0)
      temp = argv[i + 1];
  const std::string square = temp + "/msdt_pipeline_square.png";
  const std::string bar = temp + "/msdt_pipeline_bar.png";
  // A square (1 part) and a 5:1 bar (aspect 5 > 2: 3 parts): P = 4 parts, 16 tables.
  for (const gs::Status written : { gs::WriteSilhouetteImage(Rectangle(64, 20, 20), square, true),
         gs::WriteSilhouetteImage(Rectangle(64, 50, 10), bar, true) })
  {
    if (!written.Ok())
    {
      std::cerr << written.Message() << "\n";
      return 1;
    }
  }

  vtkNew<vtkMSDTSource> source;
  source->AddShapeFileName(square.c_str());
  source->AddShapeFileName(bar.c_str());
  source->SetAngleBins(24);
  source->SetDistanceSteps(16);
  source->SetTextureSize(32);

  // 1. Whole extents after the information pass alone (no table computed yet).
  source->UpdateInformation();
  const int tablesExtent[6] = { 0, 23, 0, 23, 0, 15 };
  const int texturesExtent[6] = { 0, 31, 0, 31, 0, 0 };
  CHECK(WholeExtentIs(source, 0, tablesExtent));
  CHECK(WholeExtentIs(source, 2, texturesExtent));
  CHECK(vtkMSDTSourceInspector::ShapeLoads(source) == 1);
  double spacing[3] = { 0, 0, 0 };
  source->GetOutputInformation(0)->Get(vtkDataObject::SPACING(), spacing);
  CHECK(std::abs(spacing[0] - 2 * 3.14159265358979323846 / 24) < 1e-12 && spacing[2] == 1.0);
  vtkInformation* scalars = vtkDataObject::GetActiveFieldInformation(
    source->GetOutputInformation(2), vtkDataObject::FIELD_ASSOCIATION_POINTS,
    vtkDataSetAttributes::SCALARS);
  CHECK(scalars && scalars->Get(vtkDataObject::FIELD_NUMBER_OF_COMPONENTS()) == 2);

  // 2. Downstream image filters on port 0 get every table.
  vtkNew<vtkImageShiftScale> shiftScale;
  shiftScale->SetInputConnection(source->GetOutputPort(0));
  shiftScale->SetShift(0.0);
  shiftScale->SetScale(2.0);
  shiftScale->SetOutputScalarTypeToDouble();
  shiftScale->Update();
  CHECK(vtkMSDTSourceInspector::ShapeLoads(source) == 1); // RequestData used the cached parts
  vtkImageData* tables = source->GetTablesOutput();
  vtkImageData* scaled = shiftScale->GetOutput();
  int dims[3] = { 0, 0, 0 };
  scaled->GetDimensions(dims);
  CHECK(dims[0] == 24 && dims[1] == 24 && dims[2] == 16);
  vtkDataArray* values = tables->GetPointData()->GetArray("SafeDistance");
  vtkDataArray* doubled = scaled->GetPointData()->GetScalars();
  CHECK(values && doubled && doubled->GetNumberOfTuples() == 24 * 24 * 16);
  if (values && doubled && doubled->GetNumberOfTuples() == values->GetNumberOfTuples())
  {
    int wrong = 0;
    for (vtkIdType k = 0; k < values->GetNumberOfTuples(); ++k)
      wrong += doubled->GetTuple1(k) != 2.0 * values->GetTuple1(k);
    CHECK(wrong == 0);
    // Tables are not all equal (the bar is not round): the data is really there.
    double range[2];
    values->GetRange(range);
    CHECK(range[0] > 0.0 && range[1] > range[0]);
  }

  // The last pair (bar part 2 against itself) extracted as one slice.
  vtkNew<vtkExtractVOI> slice;
  slice->SetInputConnection(source->GetOutputPort(0));
  slice->SetVOI(0, 23, 0, 23, 15, 15);
  slice->Update();
  slice->GetOutput()->GetDimensions(dims);
  CHECK(dims[0] == 24 && dims[1] == 24 && dims[2] == 1);
  vtkDataArray* last = slice->GetOutput()->GetPointData()->GetArray("SafeDistance");
  CHECK(last && last->GetNumberOfTuples() == 24 * 24);
  if (last && values && values->GetNumberOfTuples() == 24 * 24 * 16)
  {
    int wrong = 0;
    for (vtkIdType k = 0; k < 24 * 24; ++k)
      wrong += last->GetTuple1(k) != values->GetTuple1(15 * 24 * 24 + k);
    CHECK(wrong == 0);
  }

  // 3. The cache: table parameters do not re-read the shapes, their inputs do.
  source->SetAngleBins(12);
  source->UpdateInformation();
  const int smaller[6] = { 0, 11, 0, 11, 0, 15 };
  CHECK(WholeExtentIs(source, 0, smaller));
  source->Update();
  CHECK(vtkMSDTSourceInspector::ShapeLoads(source) == 1);
  source->GetTablesOutput()->GetDimensions(dims);
  CHECK(dims[0] == 12 && dims[2] == 16);

  source->SetMaximumAspectRatio(10.0); // the bar is no longer split: 2 parts, 4 tables
  source->Update();
  CHECK(vtkMSDTSourceInspector::ShapeLoads(source) == 2);
  source->GetTablesOutput()->GetDimensions(dims);
  CHECK(dims[2] == 4);

  // Rewriting a file (new size, later modification time) re-reads it once Modified() is called
  // (a pipeline only re-executes when something is modified).
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (const gs::Status rewritten = gs::WriteSilhouetteImage(Rectangle(64, 60, 6), bar, true);
      !rewritten.Ok())
  {
    std::cerr << rewritten.Message() << "\n";
    return 1;
  }
  source->Modified();
  source->Update();
  CHECK(vtkMSDTSourceInspector::ShapeLoads(source) == 3);
  source->GetTablesOutput()->GetDimensions(dims);
  CHECK(dims[2] == 4); // aspect 10 is not above 10: still 2 parts
  source->Modified();   // nothing changed on disk: no read
  source->Update();
  CHECK(vtkMSDTSourceInspector::ShapeLoads(source) == 3);

  // 4. Polygons from an upstream algorithm: known in the information pass as well.
  vtkNew<vtkRegularPolygonSource> hexagon;
  hexagon->SetNumberOfSides(6);
  hexagon->SetRadius(3.0);
  hexagon->GeneratePolylineOff(); // the polygon cell only: one class
  vtkNew<vtkMSDTSource> polygons;
  polygons->SetPolygonsConnection(hexagon->GetOutputPort());
  polygons->SetAngleBins(8);
  polygons->SetDistanceSteps(8);
  polygons->UpdateInformation();
  const int oneTable[6] = { 0, 7, 0, 7, 0, 0 };
  CHECK(WholeExtentIs(polygons, 0, oneTable));
  vtkNew<vtkExtractVOI> all;
  all->SetInputConnection(polygons->GetOutputPort(0));
  all->SetVOI(0, 7, 0, 7, 0, 0);
  all->Update();
  CHECK(all->GetOutput()->GetNumberOfPoints() == 64);
  CHECK(vtkMSDTSourceInspector::ShapeLoads(polygons) == 1);
  hexagon->SetNumberOfSides(4); // upstream change: read again
  all->Update();
  CHECK(vtkMSDTSourceInspector::ShapeLoads(polygons) == 2);

  std::filesystem::remove(square);
  std::filesystem::remove(bar);
  if (Failures == 0)
    std::cout << "TestMSDTSourcePipeline passed\n";
  return Failures == 0 ? 0 : 1;
}
