// The bad-input matrix: every mesh filter (SVG Geodesic Distance, Geodesic Polar Coordinates,
// Cross Field, Shape Distributor) on every kind of bad or unusual mesh, plus MSDT Source on bad
// images. Malformed input must give an error message and an empty output (never a crash or a
// hang); unusual but valid input (quads and polygons, tiny and huge coordinates, many connected
// components, many boundary loops) must work, and scaling the mesh by 1e-12 or 1e12 must scale
// the results (scale invariance checked to 1e-6). Sources far off the surface are refused.
#include "FilterTestSupport.h"

#include "vtkCrossField.h"
#include "vtkGeodesicPolarCoordinates.h"
#include "vtkMSDTSource.h"
#include "vtkSVGGeodesicDistance.h"
#include "vtkShapeDistributor.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRegularPolygonSource.h>
#include <vtkSphereSource.h>
#include <vtkUnsignedCharArray.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <map>

using namespace gs_test;

namespace
{
vtkSmartPointer<vtkPolyData> Sphere(int resolution = 16, double radius = 1.0,
  const double centre[3] = nullptr)
{
  vtkNew<vtkSphereSource> s;
  s->SetThetaResolution(resolution);
  s->SetPhiResolution(resolution);
  s->SetRadius(radius);
  if (centre)
  {
    s->SetCenter(centre[0], centre[1], centre[2]);
  }
  s->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  s->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(s->GetOutput());
  out->GetPointData()->Initialize(); // no normals
  return out;
}

vtkSmartPointer<vtkPolyData> Scaled(vtkPolyData* mesh, double scale)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(mesh);
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double x[3];
    out->GetPoint(i, x);
    out->GetPoints()->SetPoint(i, scale * x[0], scale * x[1], scale * x[2]);
  }
  return out;
}

// A copy of `mesh` with one more triangle (new points given by coordinates, or existing ids).
vtkSmartPointer<vtkPolyData> WithTriangle(vtkPolyData* mesh, vtkIdType a, vtkIdType b, vtkIdType c)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(mesh);
  const vtkIdType ids[3] = { a, b, c };
  out->GetPolys()->InsertNextCell(3, ids);
  return out;
}

// A 40 x 40 grid of quads (triangulated) with one quad in every 4 x 4 block removed: 81 holes
// that share no vertex, so the surface stays manifold with 82 boundary loops.
vtkSmartPointer<vtkPolyData> ManyHoles()
{
  const int n = 40;
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int j = 0; j <= n; ++j)
  {
    for (int i = 0; i <= n; ++i)
    {
      points->InsertNextPoint(i / double(n), j / double(n), 0.0);
    }
  }
  vtkNew<vtkCellArray> polys;
  for (int j = 0; j < n; ++j)
  {
    for (int i = 0; i < n; ++i)
    {
      if (i % 4 == 2 && j % 4 == 2)
      {
        continue;
      }
      const vtkIdType a = j * (n + 1) + i, b = a + 1, c = a + n + 2, d = a + n + 1;
      const vtkIdType t1[3] = { a, b, c }, t2[3] = { a, c, d };
      polys->InsertNextCell(3, t1);
      polys->InsertNextCell(3, t2);
    }
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points);
  out->SetPolys(polys);
  return out;
}

// 64 small spheres in a row.
vtkSmartPointer<vtkPolyData> ManyComponents()
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> polys;
  for (int k = 0; k < 64; ++k)
  {
    const double centre[3] = { 0.5 * (k % 8), 0.5 * (k / 8), 0.0 };
    vtkSmartPointer<vtkPolyData> s = Sphere(8, 0.2, centre);
    const vtkIdType offset = points->GetNumberOfPoints();
    for (vtkIdType i = 0; i < s->GetNumberOfPoints(); ++i)
    {
      points->InsertNextPoint(s->GetPoint(i));
    }
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < s->GetNumberOfCells(); ++c)
    {
      s->GetCellPoints(c, ids);
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        ids->SetId(i, ids->GetId(i) + offset);
      }
      polys->InsertNextCell(ids);
    }
  }
  out->SetPoints(points);
  out->SetPolys(polys);
  return out;
}

// Adds the arrays the distributor reads: a cell "Direction" (each cell's first edge, tangent)
// and a point "Density" of 1.
void AddFields(vtkPolyData* mesh)
{
  vtkNew<vtkDoubleArray> direction;
  direction->SetName("Direction");
  direction->SetNumberOfComponents(3);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    double d[3] = { 1, 0, 0 };
    if (ids->GetNumberOfIds() >= 2)
    {
      double a[3], b[3];
      mesh->GetPoint(ids->GetId(0), a);
      mesh->GetPoint(ids->GetId(1), b);
      for (int k = 0; k < 3; ++k)
      {
        d[k] = b[k] - a[k];
      }
    }
    direction->InsertNextTuple(d);
  }
  mesh->GetCellData()->AddArray(direction);
  vtkNew<vtkDoubleArray> density;
  density->SetName("Density");
  density->SetNumberOfTuples(mesh->GetNumberOfPoints());
  density->FillValue(1.0);
  mesh->GetPointData()->AddArray(density);
}

struct Outcome
{
  bool Empty = true;
  std::vector<std::string> Errors, Warnings;
  vtkSmartPointer<vtkPolyData> Output;
};

Outcome Execute(vtkAlgorithm* filter, int port = 0)
{
  vtkNew<MessageRecorder> recorder;
  filter->Modified();
  UpdateRecording(filter, recorder);
  Outcome r;
  r.Output = vtkSmartPointer<vtkPolyData>::New();
  if (vtkPolyData* out = vtkPolyData::SafeDownCast(filter->GetOutputDataObject(port)))
  {
    r.Output->DeepCopy(out);
  }
  r.Empty = r.Output->GetNumberOfPoints() == 0;
  r.Errors = recorder->Errors;
  r.Warnings = recorder->Warnings;
  return r;
}

// The largest finite value of a point array (0 when none).
double MaxFinite(vtkPolyData* data, const char* name)
{
  vtkDataArray* a = data ? data->GetPointData()->GetArray(name) : nullptr;
  double m = 0.0;
  for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
  {
    if (std::isfinite(a->GetTuple1(i)))
    {
      m = std::max(m, a->GetTuple1(i));
    }
  }
  return m;
}

enum class Expect
{
  Error,  // an error message, an empty output
  Works,  // a non-empty output, no error
};

struct Case
{
  std::string Name;
  vtkSmartPointer<vtkPolyData> Mesh;
  Expect Expected;
  std::string Keyword; // the error message names the problem (Error cases)
  double Scale = 0.0;  // > 0: a scaled copy of the reference sphere (results must scale)
};

bool WriteGray(const std::string& file, int width, int height,
  const std::function<unsigned char(int, int)>& pixel)
{
  auto out = OIIO::ImageOutput::create(file);
  if (!out)
  {
    return false;
  }
  OIIO::ImageSpec spec(width, height, 1, OIIO::TypeDesc::UINT8);
  if (!out->open(file, spec))
  {
    return false;
  }
  std::vector<unsigned char> row(static_cast<size_t>(width));
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      row[static_cast<size_t>(x)] = pixel(x, y);
    }
    if (!out->write_scanline(y, 0, OIIO::TypeDesc::UINT8, row.data()))
    {
      return false;
    }
  }
  return out->close();
}
} // namespace

int main(int argc, char* argv[])
{
  std::string temp = ".";
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::string(argv[i]) == "--temp")
    {
      temp = argv[++i];
    }
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  vtkSmartPointer<vtkPolyData> sphere = Sphere();

  std::vector<Case> cases;
  cases.push_back({ "empty", vtkSmartPointer<vtkPolyData>::New(), Expect::Error, "empty" });
  {
    auto points = vtkSmartPointer<vtkPolyData>::New();
    points->SetPoints(sphere->GetPoints());
    vtkNew<vtkCellArray> verts;
    for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
    {
      verts->InsertNextCell(1, &i);
    }
    points->SetVerts(verts);
    cases.push_back({ "points only", points, Expect::Error, "" });
    auto lines = vtkSmartPointer<vtkPolyData>::New();
    lines->SetPoints(sphere->GetPoints());
    vtkNew<vtkCellArray> polyline;
    const vtkIdType ids[4] = { 0, 1, 2, 3 };
    polyline->InsertNextCell(4, ids);
    lines->SetLines(polyline);
    cases.push_back({ "lines only", lines, Expect::Error, "" });
  }
  cases.push_back({ "quads", gs_test::UnitSquare(12, false, true), Expect::Works, "" });
  {
    vtkNew<vtkRegularPolygonSource> polygon;
    polygon->SetNumberOfSides(24);
    polygon->SetRadius(1.0);
    polygon->GeneratePolylineOff();
    polygon->Update();
    auto p = vtkSmartPointer<vtkPolyData>::New();
    p->DeepCopy(polygon->GetOutput());
    cases.push_back({ "polygon", p, Expect::Works, "" });
  }
  {
    // A third triangle on the edge of two neighbouring faces (a fin): non-manifold edge.
    vtkNew<vtkIdList> ids;
    sphere->GetCellPoints(40, ids);
    auto fin = vtkSmartPointer<vtkPolyData>::New();
    fin->DeepCopy(sphere);
    const vtkIdType apex = fin->GetPoints()->InsertNextPoint(3.0, 3.0, 3.0);
    const vtkIdType t[3] = { ids->GetId(0), ids->GetId(1), apex };
    fin->GetPolys()->InsertNextCell(3, t);
    cases.push_back({ "non-manifold edge", fin, Expect::Error, "manifold" });
    // A triangle hanging from one vertex: non-manifold vertex.
    auto hang = vtkSmartPointer<vtkPolyData>::New();
    hang->DeepCopy(sphere);
    const vtkIdType p1 = hang->GetPoints()->InsertNextPoint(3.0, 3.0, 3.0);
    const vtkIdType p2 = hang->GetPoints()->InsertNextPoint(3.0, 3.5, 3.0);
    const vtkIdType h[3] = { ids->GetId(2), p1, p2 };
    hang->GetPolys()->InsertNextCell(3, h);
    cases.push_back({ "non-manifold vertex", hang, Expect::Error, "manifold" });
    cases.push_back({ "duplicate triangle",
      WithTriangle(sphere, ids->GetId(0), ids->GetId(1), ids->GetId(2)), Expect::Error,
      "uplicate" });
    cases.push_back({ "degenerate triangle (repeated corner)",
      WithTriangle(sphere, ids->GetId(0), ids->GetId(0), ids->GetId(1)), Expect::Error,
      "egenerate" });
  }
  for (double bad : { nan, inf })
  {
    auto m = vtkSmartPointer<vtkPolyData>::New();
    m->DeepCopy(sphere);
    m->GetPoints()->SetPoint(5, bad, 0.0, 0.0);
    cases.push_back({ std::isnan(bad) ? "NaN coordinates" : "Inf coordinates", m, Expect::Error,
      "" });
  }
  cases.push_back({ "reference sphere", sphere, Expect::Works, "", 1.0 });
  cases.push_back({ "tiny (1e-12)", Scaled(sphere, 1e-12), Expect::Works, "", 1e-12 });
  cases.push_back({ "huge (1e12)", Scaled(sphere, 1e12), Expect::Works, "", 1e12 });
  // Below what double precision can square (areas underflow): refused, "rescale the mesh".
  cases.push_back({ "tiny (1e-80)", Scaled(sphere, 1e-80), Expect::Error, "rescale" });
  cases.push_back({ "tiny (1e-200)", Scaled(sphere, 1e-200), Expect::Error, "rescale" });
  cases.push_back({ "64 components", ManyComponents(), Expect::Works, "" });
  cases.push_back({ "82 boundary loops", ManyHoles(), Expect::Works, "" });
  for (Case& c : cases)
  {
    AddFields(c.Mesh);
  }

  // Tables for the distributor: a pentagram polygon.
  vtkNew<vtkMSDTSource> msdt;
  {
    vtkNew<vtkPolyData> star;
    vtkNew<vtkPoints> pts;
    vtkNew<vtkCellArray> ring;
    std::vector<vtkIdType> ids;
    for (int k = 0; k < 10; ++k)
    {
      const double a = M_PI / 2 + k * M_PI / 5, r = k % 2 ? 0.38 : 1.0;
      ids.push_back(pts->InsertNextPoint(r * std::cos(a), r * std::sin(a), 0.0));
    }
    ring->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    star->SetPoints(pts);
    star->SetPolys(ring);
    msdt->SetInputDataObject(0, star);
    msdt->SetAngleBins(32);
    msdt->SetDistanceSteps(32);
    msdt->Update();
    Check(msdt->GetTablesOutput()->GetNumberOfPoints() > 0, "MSDT", "no tables for the star");
  }

  // Every filter on every case.
  using Runner = std::function<Outcome(Case&)>;
  std::map<std::string, Runner> filters;
  filters["SVG Geodesic Distance"] = [](Case& c) {
    vtkNew<vtkSVGGeodesicDistance> f;
    f->SetInputData(c.Mesh);
    f->AddSourceVertexId(0);
    return Execute(f);
  };
  filters["Geodesic Polar Coordinates"] = [](Case& c) {
    vtkNew<vtkGeodesicPolarCoordinates> f;
    f->SetInputData(c.Mesh);
    f->SetSourceVertexId(0);
    f->SetRadius(c.Scale > 0 ? 0.8 * c.Scale : 0.3);
    f->SetDecalSize(c.Scale > 0 ? 0.5 * c.Scale : 0.2);
    return Execute(f);
  };
  filters["Cross Field"] = [](Case& c) {
    vtkNew<vtkCrossField> f;
    f->SetInputData(c.Mesh);
    return Execute(f);
  };
  filters["Shape Distributor"] = [&msdt](Case& c) {
    vtkNew<vtkShapeDistributor> f;
    f->SetInputData(c.Mesh);
    f->SetInputConnection(1, msdt->GetOutputPort(0));
    f->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "Direction");
    f->SetInputArrayToProcess(1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Density");
    f->SetShapeSize(c.Scale > 0 ? 0.15 * c.Scale : 0.05);
    f->SetMaximumShapes(200);
    f->SetSeed(4);
    return Execute(f);
  };

  std::map<std::string, std::map<std::string, Outcome>> results;
  for (auto& [filterName, run] : filters)
  {
    for (Case& c : cases)
    {
      const Outcome r = run(c);
      results[filterName][c.Name] = r;
      const std::string test = filterName + " / " + c.Name;
      std::cout << test << ": " << (r.Empty ? "empty" : "output") << ", " << r.Errors.size()
                << " error(s)" << (r.Errors.empty() ? "" : ": " + r.Errors[0].substr(0, 140))
                << "\n";
      if (c.Expected == Expect::Error)
      {
        Check(r.Empty && !r.Errors.empty(), test, "expected an error and an empty output");
        Check(c.Keyword.empty() || Mentions(r.Errors, c.Keyword), test,
          "the error does not mention '" + c.Keyword + "'");
      }
      else
      {
        Check(!r.Empty && r.Errors.empty(), test, "expected an output and no error");
      }
    }
  }

  // Scale invariance: distances and polar radii scale, directions and shape counts do not.
  const double reference = MaxFinite(results["SVG Geodesic Distance"]["reference sphere"].Output,
    "GeodesicDistance");
  Check(std::abs(reference - M_PI) < 0.05, "scale", "the reference sphere's farthest distance is "
      + std::to_string(reference) + ", not about pi");
  const double polarReference =
    MaxFinite(results["Geodesic Polar Coordinates"]["reference sphere"].Output, "PolarRadius");
  const vtkIdType shapesReference =
    results["Shape Distributor"]["reference sphere"].Output->GetNumberOfPoints();
  Check(shapesReference > 10, "scale", "too few shapes on the reference sphere");
  for (const char* name : { "tiny (1e-12)", "huge (1e12)" })
  {
    double scale = 0.0;
    for (const Case& c : cases)
    {
      if (c.Name == name)
      {
        scale = c.Scale;
      }
    }
    const double d =
      MaxFinite(results["SVG Geodesic Distance"][name].Output, "GeodesicDistance") / scale;
    Check(std::abs(d - reference) <= 1e-6 * reference, name,
      "distances do not scale: " + std::to_string(d) + " vs " + std::to_string(reference));
    const double p =
      MaxFinite(results["Geodesic Polar Coordinates"][name].Output, "PolarRadius") / scale;
    Check(std::abs(p - polarReference) <= 1e-6 * polarReference, name,
      "polar radii do not scale: " + std::to_string(p) + " vs " + std::to_string(polarReference));
    vtkDataArray* a = results["Cross Field"]["reference sphere"].Output->GetCellData()->GetArray(
      "Direction");
    vtkDataArray* b = results["Cross Field"][name].Output->GetCellData()->GetArray("Direction");
    double worst = a && b ? 0.0 : 1.0;
    for (vtkIdType i = 0; a && b && i < a->GetNumberOfTuples(); ++i)
    {
      for (int k = 0; k < 3; ++k)
      {
        worst = std::max(worst, std::abs(a->GetComponent(i, k) - b->GetComponent(i, k)));
      }
    }
    Check(worst < 1e-6, name, "cross field directions differ by " + std::to_string(worst));
    const vtkIdType shapes = results["Shape Distributor"][name].Output->GetNumberOfPoints();
    Check(shapes == shapesReference, name,
      "shape count " + std::to_string(shapes) + " vs " + std::to_string(shapesReference));
  }

  // Many components: the distance is finite on the source's sphere only; shapes on most spheres.
  {
    vtkPolyData* out = results["SVG Geodesic Distance"]["64 components"].Output;
    vtkDataArray* d = out ? out->GetPointData()->GetArray("GeodesicDistance") : nullptr;
    vtkIdType finite = 0;
    for (vtkIdType i = 0; d && i < d->GetNumberOfTuples(); ++i)
    {
      finite += std::isfinite(d->GetTuple1(i)) ? 1 : 0;
    }
    Check(d && finite > 0 && finite * 64 == d->GetNumberOfTuples(), "64 components",
      "finite distances on " + std::to_string(finite) + " points, expected one sphere's");
  }

  // Sources off the surface: refused with the reason; near the surface: snapped.
  for (double offset : { 0.1, 10.0 })
  {
    vtkNew<vtkSVGGeodesicDistance> f;
    f->SetInputData(sphere);
    vtkNew<vtkPolyData> source;
    vtkNew<vtkPoints> p;
    p->InsertNextPoint(0.0, 0.0, 1.0 + offset);
    source->SetPoints(p);
    f->SetSourcesData(source);
    const Outcome r = Execute(f);
    const std::string test = "source " + std::to_string(offset) + " off the surface";
    if (offset < 1.0)
    {
      Check(!r.Empty && r.Errors.empty(), test, "not snapped");
    }
    else
    {
      Check(r.Empty && Mentions(r.Errors, "from the surface"), test, "not refused");
    }
  }
  {
    vtkNew<vtkCrossField> f;
    f->SetInputData(sphere);
    f->SetMode(vtkCrossField::PRESCRIBED_SINGULARITIES);
    f->SetSymmetry(1);
    vtkNew<vtkPolyData> singularities;
    vtkNew<vtkPoints> p;
    p->InsertNextPoint(0.0, 0.0, 1.0);
    p->InsertNextPoint(0.0, 0.0, -30.0);
    singularities->SetPoints(p);
    vtkNew<vtkDoubleArray> index;
    index->SetName("Index");
    index->InsertNextValue(1.0);
    index->InsertNextValue(1.0);
    singularities->GetPointData()->AddArray(index);
    f->SetInputData(1, singularities);
    const Outcome r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "from the surface"), "singularity off the surface",
      "not refused");
  }

  // MSDT Source on bad images: unreadable, empty file, not an image, all transparent (errors);
  // a 16384 x 16384 image (read reduced, a warning, the same shape as a small image).
  {
    const std::string emptyFile = temp + "/matrix_empty.png";
    std::ofstream(emptyFile).close();
    const std::string textFile = temp + "/matrix_text.png";
    std::ofstream(textFile) << "not an image\n";
    const std::string blank = temp + "/matrix_blank.png";
    WriteGray(blank, 64, 64, [](int, int) { return 255; }); // all light: no silhouette
    for (const std::string& file : { temp + "/matrix_missing.png", emptyFile, textFile, blank })
    {
      vtkNew<vtkMSDTSource> s;
      s->AddShapeFileName(file.c_str());
      const Outcome r = Execute(s, 1);
      Check(r.Empty && !r.Errors.empty(), "MSDT " + file, "expected an error");
    }
    // A dark disk of radius 0.3 of the image, off centre, on white: small and huge.
    auto disk = [](int size) {
      return [size](int x, int y) -> unsigned char {
        const double u = (x + 0.5) / size - 0.45, v = (y + 0.5) / size - 0.5;
        return u * u + v * v < 0.09 ? 0 : 255;
      };
    };
    const std::string small = temp + "/matrix_disk_512.png";
    const std::string huge = temp + "/matrix_disk_16384.png";
    Check(WriteGray(small, 512, 512, disk(512)), "MSDT", "cannot write " + small);
    Check(WriteGray(huge, 16384, 16384, disk(16384)), "MSDT", "cannot write " + huge);
    double radius[2] = { 0, 0 };
    for (int k = 0; k < 2; ++k)
    {
      vtkNew<vtkMSDTSource> s;
      s->AddShapeFileName((k ? huge : small).c_str());
      s->SetAngleBins(16);
      s->SetDistanceSteps(16);
      const Outcome r = Execute(s, 1);
      Check(!r.Empty && r.Errors.empty(), "MSDT disk", "no tables");
      Check(k == 0 || Mentions(r.Warnings, "reduced by 4"), "MSDT 16K", "no reduction warning");
      vtkDataArray* v = s->GetTablesOutput()->GetPointData()->GetArray("SafeDistance");
      radius[k] = v ? v->GetTuple1(0) : 0.0;
    }
    // Safe distances are in circumradius units: a disk's is 2 whatever the resolution.
    Check(std::abs(radius[0] - radius[1]) < 0.02 && radius[0] > 1.9, "MSDT 16K",
      "safe distance " + std::to_string(radius[1]) + " vs " + std::to_string(radius[0]));
    std::remove(huge.c_str());
  }

  std::cout << (Failures ? "FAILED" : "passed") << " (" << Failures << " failure(s))\n";
  return Failures ? 1 : 0;
}
