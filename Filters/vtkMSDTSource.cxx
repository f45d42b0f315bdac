#include "vtkMSDTSource.h"

#include "vtkDistributedSurface.h"
#include "vtkSafeDistanceTableImage.h"

#include "SafeDistanceTable.h"
#include "Silhouette.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDemandDrivenPipeline.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkStringArray.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <sstream>

vtkStandardNewMacro(vtkMSDTSource);

// Classes whose circumradii differ by more than this factor get a warning (UpdateShapes).
constexpr double MaximumSizeRatio = 20.0;

// The classes and parts of the last read (ComputeSafeDistanceParts, no table values yet),
// keyed by everything they depend on.
struct vtkMSDTSource::ShapeCache
{
  std::string Key;
  // Ok, or why the shapes could not be read (reported when the read happened).
  gs::Status Status = gs::Status::Error("the shapes have not been read");
  // No file name and no polygons: a new source whose properties are not set yet. Not reported
  // by RequestInformation (which the GUI and pvpython run as soon as the proxy exists), only
  // when the output is asked for.
  bool NoShape = false;
  gs::SafeDistanceTables Parts;
};

//------------------------------------------------------------------------------
vtkMSDTSource::vtkMSDTSource()
  : Shapes(new ShapeCache)
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(3);
}

vtkMSDTSource::~vtkMSDTSource() = default;

//------------------------------------------------------------------------------
void vtkMSDTSource::AddShapeFileName(const char* fileName)
{
  this->ShapeFileNames.emplace_back(fileName ? fileName : "");
  this->Modified();
}

void vtkMSDTSource::RemoveAllShapeFileNames()
{
  if (!this->ShapeFileNames.empty())
  {
    this->ShapeFileNames.clear();
    this->Modified();
  }
}

vtkImageData* vtkMSDTSource::GetTablesOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(0));
}

vtkPolyData* vtkMSDTSource::GetOutlinesOutput()
{
  return vtkPolyData::SafeDownCast(this->GetOutputDataObject(1));
}

vtkImageData* vtkMSDTSource::GetSilhouettesOutput()
{
  return vtkImageData::SafeDownCast(this->GetOutputDataObject(2));
}

//------------------------------------------------------------------------------
int vtkMSDTSource::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port != 0)
    return 0;
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  return 1;
}

int vtkMSDTSource::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 1 ? "vtkPolyData" : "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
vtkTypeBool vtkMSDTSource::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return this->RequestData(request, inputVector, outputVector);
  }
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_INFORMATION()))
  {
    return this->RequestInformation(request, inputVector, outputVector);
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

namespace
{
vtkSmartPointer<vtkIntArray> IntArray(const char* name)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  return a.GetPointer();
}

// Closed rings per class from polygon / polyline cells (z ignored), appended to `classes` (the
// core checks them: coordinates, area). Returns the number of polyline cells whose last point
// differs from their first (they are closed all the same).
vtkIdType PolygonClasses(vtkPolyData* input, std::vector<gs::SafeDistanceInput>& classes)
{
  vtkIdType openPolylines = 0;
  vtkDataArray* ids = input->GetCellData()->GetArray("ClassId");
  std::map<long long, std::vector<std::vector<gs::Vec2>>> byClass;
  std::vector<long long> order;
  const vtkIdType numVerts = input->GetNumberOfVerts();
  vtkIdType cellId = numVerts; // cells are numbered verts, lines, polys, strips
  for (vtkCellArray* cells : { input->GetLines(), input->GetPolys() })
  {
    auto it = vtk::TakeSmartPointer(cells->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cellId)
    {
      vtkIdType n;
      const vtkIdType* pts;
      it->GetCurrentCell(n, pts);
      std::vector<gs::Vec2> ring;
      for (vtkIdType k = 0; k < n; ++k)
      {
        double p[3];
        input->GetPoint(pts[k], p);
        ring.emplace_back(p[0], p[1]);
      }
      if (cells == input->GetLines() && n > 0 &&
        (ring.front().x != ring.back().x || ring.front().y != ring.back().y))
      {
        ++openPolylines;
      }
      const long long key = ids ? static_cast<long long>(ids->GetComponent(cellId, 0)) : cellId;
      if (!byClass.count(key))
        order.push_back(key);
      byClass[key].push_back(std::move(ring));
    }
  }
  for (long long key : order)
  {
    gs::SafeDistanceInput in;
    in.Name = (ids ? "polygons ClassId " : "polygon cell ") + std::to_string(key);
    in.Shape = gs::ShapeFromPolygons(byClass[key]);
    classes.push_back(std::move(in));
  }
  return openPolylines;
}

// What the classes and parts depend on: file names with modification times and sizes, the
// thresholds, MaximumAspectRatio and the polygons (data object and its modification time).
std::string ShapeKey(const std::vector<std::string>& files, double alpha, double luminance,
  double aspect, vtkPolyData* polygons)
{
  std::ostringstream key;
  key.precision(17);
  for (const std::string& file : files)
  {
    std::error_code ec;
    const auto time = std::filesystem::last_write_time(file, ec);
    const long long stamp = ec ? -1 : static_cast<long long>(time.time_since_epoch().count());
    const auto size = std::filesystem::file_size(file, ec);
    key << file << '\0' << stamp << ' ' << (ec ? -1 : static_cast<long long>(size)) << '\n';
  }
  key << alpha << ' ' << luminance << ' ' << aspect << ' ';
  if (polygons)
  {
    key << static_cast<const void*>(polygons) << ' ' << polygons->GetMTime();
  }
  return key.str();
}

// The tables' options from the source's parameters.
gs::SafeDistanceOptions TableOptions(vtkMSDTSource* source)
{
  gs::SafeDistanceOptions options;
  options.AngleBins = source->GetAngleBins();
  options.DistanceSteps = source->GetDistanceSteps();
  options.MaximumAspectRatio = source->GetMaximumAspectRatio();
  return options;
}

// The silhouettes image (port 2): TextureSize^2 texels over the square [-1, 1]^2 around a class's
// circle (class units, normalized by its radius), one component per class.
struct SilhouetteImageGeometry
{
  int Extent[6];
  double Spacing[3];
  double Origin[3];
  explicit SilhouetteImageGeometry(int ts)
    : Extent{ 0, ts - 1, 0, ts - 1, 0, 0 }
    , Spacing{ 2.0 / ts, 2.0 / ts, 1.0 }
    , Origin{ -1.0 + 1.0 / ts, -1.0 + 1.0 / ts, 0.0 }
  {
  }
};

// Port 1: each class's outline rings as closed polylines (class frame, z = 0), cell array ClassId.
void WriteOutlines(const gs::SafeDistanceTables& tables, vtkPolyData* outlines)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  auto classId = IntArray("ClassId");
  for (std::size_t c = 0; c < tables.Classes.size(); ++c)
  {
    for (const auto& ring : tables.Classes[c].Outline.Rings)
    {
      const vtkIdType first = points->GetNumberOfPoints();
      for (const gs::Vec2& p : ring)
      {
        points->InsertNextPoint(p.x, p.y, 0.0);
      }
      lines->InsertNextCell(static_cast<vtkIdType>(ring.size() + 1));
      for (std::size_t k = 0; k <= ring.size(); ++k)
      {
        lines->InsertCellPoint(first + static_cast<vtkIdType>(k % ring.size()));
      }
      classId->InsertNextValue(static_cast<int>(c));
    }
  }
  outlines->SetPoints(points);
  outlines->SetLines(lines);
  outlines->GetCellData()->AddArray(classId);
}

// Port 2: the point array Silhouette, one component per class: 255 inside the class, 0 outside
// (SilhouetteImageGeometry of `ts`).
void WriteSilhouettes(const gs::SafeDistanceTables& tables, int ts, vtkImageData* silhouettes)
{
  const int m = static_cast<int>(tables.Classes.size());
  SilhouetteImageGeometry geometry(ts);
  silhouettes->SetExtent(geometry.Extent);
  silhouettes->SetSpacing(geometry.Spacing);
  silhouettes->SetOrigin(geometry.Origin);
  vtkNew<vtkUnsignedCharArray> texels;
  texels->SetName("Silhouette");
  texels->SetNumberOfComponents(m);
  texels->SetNumberOfTuples(static_cast<vtkIdType>(ts) * ts);
  for (int c = 0; c < m; ++c)
  {
    const double r = tables.Classes[c].Radius;
    // The square about the class circle, [-r, r]^2, onto the texture square [0, 1]^2: the
    // decals' convention (gs::DecalTextureCoordinate, ShapeDecal.h).
    const gs::SilhouetteMask mask =
      gs::RasterizeShape(tables.Classes[c].Outline, ts, ts, { -r, -r }, 2.0 * r / ts);
    for (std::size_t k = 0; k < mask.Inside.size(); ++k)
    {
      texels->SetTypedComponent(static_cast<vtkIdType>(k), c, mask.Inside[k] ? 255 : 0);
    }
  }
  silhouettes->GetPointData()->SetScalars(texels);
}

// The first invalid parameter: the tables' options (checked by the core), the thresholds and
// TextureSize.
gs::Status CheckParameters(vtkMSDTSource* source)
{
  if (gs::Status options = gs::CheckSafeDistanceOptions(TableOptions(source)); !options.Ok())
  {
    return options;
  }
  const double alpha = source->GetAlphaThreshold(), luminance = source->GetLuminanceThreshold();
  if (!(alpha >= 0.0 && alpha <= 1.0) || !(luminance >= 0.0 && luminance <= 1.0))
  {
    return gs::Status::Error("AlphaThreshold and LuminanceThreshold must be in [0, 1]");
  }
  if (source->GetTextureSize() < 1 || source->GetTextureSize() > 8192)
  {
    return gs::Status::Error(
      "TextureSize must be in [1, 8192], got " + std::to_string(source->GetTextureSize()));
  }
  return gs::Status();
}
} // namespace

//------------------------------------------------------------------------------
void vtkMSDTSource::UpdateShapes(vtkInformationVector** inputVector)
{
  vtkPolyData* polygons = nullptr;
  if (this->GetNumberOfInputConnections(0) > 0)
  {
    // The number of parts depends on the polygons: bring them up to date now (in the
    // information pass their upstream has not executed yet).
    int port = 0;
    if (vtkAlgorithm* upstream = this->GetInputAlgorithm(0, 0, port))
    {
      upstream->Update(port);
    }
    polygons = vtkPolyData::GetData(inputVector[0], 0);
  }
  const std::string key = ShapeKey(this->ShapeFileNames, this->AlphaThreshold,
    this->LuminanceThreshold, this->MaximumAspectRatio, polygons);
  ShapeCache& cache = *this->Shapes;
  if (this->NumberOfShapeLoads > 0 && key == cache.Key)
  {
    return;
  }
  ++this->NumberOfShapeLoads;
  cache = ShapeCache();
  cache.Key = key;

  // Images, then polygons.
  std::vector<gs::SafeDistanceInput> classes;
  gs::SilhouetteThresholds thresholds;
  thresholds.AlphaThreshold = this->AlphaThreshold;
  thresholds.LuminanceThreshold = this->LuminanceThreshold;
  for (const std::string& file : this->ShapeFileNames)
  {
    const gs::Result<gs::SilhouetteImage> read = gs::ReadSilhouetteImage(file, thresholds);
    if (!read.Ok())
    {
      cache.Status =
        gs::Status::Error("Shape " + std::to_string(classes.size()) + ": " + read.Message());
      return;
    }
    if (read->ReductionFactor > 1)
    {
      vtkWarningMacro("Shape " << classes.size() << ": image '" << file << "' is "
                               << read->ImageWidth << " x " << read->ImageHeight
                               << " pixels; read reduced by " << read->ReductionFactor
                               << " (at most " << gs::MaximumSilhouetteImageSide
                               << " pixels on a side).");
    }
    classes.push_back({ file, gs::ShapeFromMask(read->Mask) });
  }
  if (polygons)
  {
    // A surface connected by mistake (pvpython connects the active source to the first input
    // of a new proxy): shape polygons lie in a plane of constant z.
    double bounds[6];
    polygons->GetBounds(bounds);
    if (polygons->GetNumberOfPoints() > 0 &&
      bounds[5] - bounds[4] > 1e-9 * std::max({ 1.0, bounds[1] - bounds[0], bounds[3] - bounds[2] }))
    {
      cache.Status = gs::Status::Error("Polygons input: the points are not in a plane of constant "
                                       "z (a surface mesh connected by mistake?)");
      return;
    }
    const vtkIdType open = PolygonClasses(polygons, classes);
    if (open > 0)
    {
      vtkWarningMacro("Polygons input: " << open << " open polyline(s) (last point not equal to "
                                         << "the first) treated as closed.");
    }
  }
  if (classes.empty())
  {
    cache.Status =
      gs::Status::Error("No shape: set ShapeFileNames (images) or use MSDT From Polygons");
    cache.NoShape = true;
    return;
  }
  gs::Result<gs::SafeDistanceTables> parts =
    gs::ComputeSafeDistanceParts(classes, TableOptions(this));
  if (!parts.Ok())
  {
    cache.Status = gs::Status::Error("Safe distance tables: " + parts.Message());
    return;
  }
  cache.Status = gs::Status();
  cache.Parts = std::move(*parts);
  // Classes are compared in their own units (images in pixels, polygons in theirs): a polygon
  // drawn in unit coordinates next to an image is then tens of times smaller, and a
  // distribution of it runs for minutes. Sizes that far apart are said.
  const auto& cls = cache.Parts.Classes;
  std::size_t smallest = 0, largest = 0;
  for (std::size_t c = 1; c < cls.size(); ++c)
  {
    smallest = cls[c].Radius < cls[smallest].Radius ? c : smallest;
    largest = cls[c].Radius > cls[largest].Radius ? c : largest;
  }
  if (!cls.empty() && cls[largest].Radius > MaximumSizeRatio * cls[smallest].Radius)
  {
    vtkWarningMacro("Shape '" << cls[largest].Name << "' is "
                              << cls[largest].Radius / cls[smallest].Radius << " times larger than '"
                              << cls[smallest].Name
                              << "' (circumradii compared in the shapes' own units: images in "
                                 "pixels, polygons in their coordinates). If that is not meant, "
                                 "draw the polygons in the images' pixel units; with shapes that "
                                 "small, a distribution places very many of them.");
  }
}

//------------------------------------------------------------------------------
int vtkMSDTSource::RequestInformation(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Whole extents: empty unless the parameters are valid and the shapes were read.
  const int none[6] = { 0, -1, 0, -1, 0, -1 };
  for (int port : { 0, 2 })
  {
    outputVector->GetInformationObject(port)->Set(
      vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), none, 6);
  }
  if (const gs::Status parameters = CheckParameters(this); !parameters.Ok())
  {
    vtkErrorMacro(<< parameters.Message() << ".");
    return 1;
  }
  this->UpdateShapes(inputVector);
  if (!this->Shapes->Status.Ok())
  {
    if (!this->Shapes->NoShape)
    {
      vtkErrorMacro(<< this->Shapes->Status.Message() << ".");
    }
    return 1;
  }
  const gs::SafeDistanceTables& parts = this->Shapes->Parts;
  const int ka = this->AngleBins, P = parts.NumberOfParts();
  const int m = static_cast<int>(parts.Classes.size());
  // Tables that would not fit in memory are refused before any allocation (the core checks
  // the same when it computes them).
  if (const gs::Status size = gs::CheckSafeDistanceTableSize(P, ka); !size.Ok())
  {
    vtkErrorMacro("Safe distance tables: " << m << " classes, " << size.Message() << ".");
    return 1;
  }

  // Port 0: ka x ka x P^2 tables (vtkSafeDistanceTableImage, as ToImage will write them).
  vtkSafeDistanceTableImage::SetInformation(ka, P, outputVector->GetInformationObject(0));

  // Port 2: TextureSize^2 silhouettes, one component per class.
  const SilhouetteImageGeometry geometry(this->TextureSize);
  vtkInformation* info = outputVector->GetInformationObject(2);
  info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), geometry.Extent, 6);
  info->Set(vtkDataObject::SPACING(), geometry.Spacing, 3);
  info->Set(vtkDataObject::ORIGIN(), geometry.Origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(info, VTK_UNSIGNED_CHAR, m);
  return 1;
}

//------------------------------------------------------------------------------
int vtkMSDTSource::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* tableImage = vtkImageData::GetData(outputVector, 0);
  vtkPolyData* outlines = vtkPolyData::GetData(outputVector, 1);
  vtkImageData* silhouettes = vtkImageData::GetData(outputVector, 2);
  if (!tableImage || !outlines || !silhouettes)
  {
    vtkErrorMacro("Missing outputs.");
    return 0;
  }
  tableImage->Initialize();
  outlines->Initialize();
  silhouettes->Initialize();
  // Under MPI the tables are computed once, on process 0 (its polygon input, if any, is read
  // there): the other processes output empty pieces (Shape Distributor takes process 0's).
  const vtkDistributedSurface distributed(outputVector->GetInformationObject(0));
  if (distributed && !distributed.IsRoot())
  {
    return 1;
  }
  this->UpdateProgress(0.0);

  // 1. Parameters and shapes (classes and parts). Their errors were reported by
  //    RequestInformation (same parameters, same cached shapes) unless the shapes were read
  //    again since.
  if (!CheckParameters(this).Ok())
  {
    return 1;
  }
  const int loads = this->NumberOfShapeLoads;
  this->UpdateShapes(inputVector); // normally a cache hit
  if (!this->Shapes->Status.Ok())
  {
    if (this->NumberOfShapeLoads != loads || this->Shapes->NoShape)
    {
      vtkErrorMacro(<< this->Shapes->Status.Message() << ".");
    }
    return 1;
  }
  this->UpdateProgress(0.1);

  // 2. The tables.
  const gs::Result<gs::SafeDistanceTables> result =
    gs::ComputeSafeDistanceValues(this->Shapes->Parts, TableOptions(this), [this](double p) {
      this->UpdateProgress(0.1 + 0.8 * p);
      return !this->CheckAbort();
    });
  if (!result.Ok())
  {
    if (!result.IsAborted())
    {
      vtkErrorMacro("Safe distance tables: " << result.Message() << ".");
    }
    return 1;
  }
  const gs::SafeDistanceTables& tables = *result;

  // 3. Port 0: the tables and their description (vtkSafeDistanceTableImage: the one definition
  //    of that image, read back by Shape Distributor).
  vtkSafeDistanceTableImage::ToImage(tables, tableImage);

  // 4. Port 1: the class outlines.
  WriteOutlines(tables, outlines);

  // 5. Port 2: silhouettes as decal textures (the square around each class's circle).
  WriteSilhouettes(tables, this->TextureSize, silhouettes);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkMSDTSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ShapeFileNames: " << this->ShapeFileNames.size() << "\n";
  for (const std::string& f : this->ShapeFileNames)
  {
    os << indent.GetNextIndent() << f << "\n";
  }
  os << indent << "AngleBins: " << this->AngleBins << "\n";
  os << indent << "DistanceSteps: " << this->DistanceSteps << "\n";
  os << indent << "AlphaThreshold: " << this->AlphaThreshold << "\n";
  os << indent << "LuminanceThreshold: " << this->LuminanceThreshold << "\n";
  os << indent << "MaximumAspectRatio: " << this->MaximumAspectRatio << "\n";
  os << indent << "TextureSize: " << this->TextureSize << "\n";
}
