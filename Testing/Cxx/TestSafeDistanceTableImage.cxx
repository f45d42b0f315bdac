// The tables image in one place (vtkSafeDistanceTableImage): core tables -> image -> core tables
// give back every value the image carries, bit for bit; MSDT Source's output reads back and
// writes again identically; images that are not MSDT Source's are refused with a message.
#include "vtkSafeDistanceTableImage.h"

#include "vtkMSDTSource.h"

#include "MeshGenerators.h"
#include "SafeDistanceTable.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <cstdio>
#include <string>
#include <vector>

namespace
{
int failures = 0;

void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    ++failures;
    std::printf("FAILED: %s\n", what.c_str());
  }
}

bool Same(const gs::Vec2& a, const gs::Vec2& b)
{
  return a.x == b.x && a.y == b.y;
}

void Compare(const gs::SafeDistanceTables& a, const gs::SafeDistanceTables& b, const std::string& what)
{
  Check(a.AngleBins == b.AngleBins && a.DistanceSteps == b.DistanceSteps &&
      a.RotationSamples == b.RotationSamples && a.Scale == b.Scale,
    what + ": table parameters");
  Check(a.Values == b.Values, what + ": values");
  Check(a.Classes.size() == b.Classes.size() && a.Parts.size() == b.Parts.size(), what + ": sizes");
  for (std::size_t k = 0; k < a.Classes.size() && k < b.Classes.size(); ++k)
  {
    const gs::SafeDistanceClass &x = a.Classes[k], &y = b.Classes[k];
    Check(x.Name == y.Name && x.Radius == y.Radius && x.AspectRatio == y.AspectRatio &&
        Same(x.MajorAxis, y.MajorAxis) && Same(x.SourceCircle.Centre, y.SourceCircle.Centre) &&
        x.Parts == y.Parts,
      what + ": class " + std::to_string(k));
    bool rings = x.Outline.Rings.size() == y.Outline.Rings.size();
    for (std::size_t r = 0; rings && r < x.Outline.Rings.size(); ++r)
    {
      rings = x.Outline.Rings[r].size() == y.Outline.Rings[r].size();
      for (std::size_t i = 0; rings && i < x.Outline.Rings[r].size(); ++i)
      {
        rings = Same(x.Outline.Rings[r][i], y.Outline.Rings[r][i]);
      }
    }
    Check(rings, what + ": outline of class " + std::to_string(k));
  }
  for (std::size_t p = 0; p < a.Parts.size() && p < b.Parts.size(); ++p)
  {
    const gs::SafeDistancePart &x = a.Parts[p], &y = b.Parts[p];
    Check(x.ClassId == y.ClassId && x.Index == y.Index && Same(x.Centre, y.Centre) && x.Radius == y.Radius,
      what + ": part " + std::to_string(p));
  }
}
} // namespace

int main()
{
  // 1. Core tables (a star and a 5:1 bar split into parts) through the image and back.
  std::vector<gs::SafeDistanceInput> in;
  in.push_back({ "star", gs::ShapeFromPolygons({ gs::MakeStarPolygon(5, 1.0, 0.4) }) });
  in.push_back({ "bar", gs::ShapeFromPolygons({ { { -2.5, -0.5 }, { 2.5, -0.5 }, { 2.5, 0.5 }, { -2.5, 0.5 } } }) });
  gs::SafeDistanceOptions options;
  options.AngleBins = 16;
  options.DistanceSteps = 32;
  const gs::Result<gs::SafeDistanceTables> computed = gs::ComputeSafeDistanceTables(in, options);
  Check(computed.Ok(), "core tables: " + computed.Message());
  Check(computed->NumberOfParts() > 2, "the bar is split into parts");
  vtkNew<vtkImageData> image;
  vtkSafeDistanceTableImage::ToImage(*computed, image);
  int dims[3];
  image->GetDimensions(dims);
  const int P = computed->NumberOfParts();
  Check(dims[0] == 16 && dims[1] == 16 && dims[2] == P * P, "image dimensions");
  Check(image->GetPointData()->GetScalars() &&
      std::string(image->GetPointData()->GetScalars()->GetName()) == vtkSafeDistanceTableImage::SafeDistance,
    "SafeDistance is the active scalars");
  const gs::Result<gs::SafeDistanceTables> back = vtkSafeDistanceTableImage::FromImage(image);
  Check(back.Ok(), "read back: " + back.Message());
  Compare(*computed, *back, "core -> image -> core");

  // 2. MSDT Source's output (polygons with a ClassId) reads back and writes again identically.
  vtkNew<vtkPolyData> polygons;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  for (const gs::Vec2& q : gs::MakeStarPolygon(5, 10.0, 4.0))
  {
    points->InsertNextPoint(q.x, q.y, 0.0);
  }
  lines->InsertNextCell(points->GetNumberOfPoints() + 1);
  for (vtkIdType i = 0; i <= points->GetNumberOfPoints(); ++i)
  {
    lines->InsertCellPoint(i % points->GetNumberOfPoints());
  }
  polygons->SetPoints(points);
  polygons->SetLines(lines);
  vtkNew<vtkMSDTSource> source;
  source->SetPolygonsData(polygons);
  source->SetAngleBins(8);
  source->SetDistanceSteps(16);
  source->Update();
  vtkImageData* produced = vtkImageData::SafeDownCast(source->GetOutputDataObject(0));
  const gs::Result<gs::SafeDistanceTables> read = vtkSafeDistanceTableImage::FromImage(produced);
  Check(produced && read.Ok(), "MSDT Source's output: " + read.Message());
  const gs::SafeDistanceTables& fromSource = *read;
  vtkNew<vtkImageData> rewritten;
  vtkSafeDistanceTableImage::ToImage(fromSource, rewritten);
  const gs::Result<gs::SafeDistanceTables> again = vtkSafeDistanceTableImage::FromImage(rewritten);
  Check(again.Ok(), "rewritten: " + again.Message());
  Compare(fromSource, *again, "MSDT Source -> core -> image -> core");
  Check(fromSource.AngleBins == 8 && fromSource.Classes.size() == 1 && fromSource.Scale > 9.0,
    "MSDT Source's tables: 8 bins, one class, scale = the star's radius in polygon units");

  // 3. Not MSDT Source's: refused with a message.
  vtkNew<vtkImageData> plain;
  plain->SetDimensions(4, 4, 1);
  const gs::Result<gs::SafeDistanceTables> fromPlain = vtkSafeDistanceTableImage::FromImage(plain);
  Check(!fromPlain.Ok() && fromPlain.Message().find("MSDT Source") != std::string::npos,
    "a plain image is refused: " + fromPlain.Message());
  vtkNew<vtkImageData> broken;
  broken->DeepCopy(image);
  broken->GetFieldData()->RemoveArray(vtkSafeDistanceTableImage::PartRadius);
  Check(!vtkSafeDistanceTableImage::FromImage(broken).Ok(), "missing PartRadius is refused");
  vtkNew<vtkImageData> inconsistent;
  inconsistent->DeepCopy(image);
  vtkDataArray* values = inconsistent->GetPointData()->GetArray(vtkSafeDistanceTableImage::SafeDistance);
  values->SetNumberOfTuples(values->GetNumberOfTuples() - 1);
  const gs::Result<gs::SafeDistanceTables> fromInconsistent =
    vtkSafeDistanceTableImage::FromImage(inconsistent);
  Check(!fromInconsistent.Ok() && fromInconsistent.Message().find("inconsistent") != std::string::npos,
    "too few values are refused: " + fromInconsistent.Message());

  std::printf("%s (%d part(s), %zu values)\n", failures ? "FAILED" : "OK", P, computed->Values.size());
  return failures ? 1 : 0;
}
