// Shape Distributor regression images: decals textured with the silhouettes of MSDT Source.
//
//   --case plane: pentagrams in a 10 x 10 square (the paper's Fig. 9 layout), Greedy mode, with
//     the counts of the three modes checked (Greedy > Random > Circumcircle Poisson disk).
//   --case mesh --mesh refined_elephant.off --image crow.png: birds following a smooth vector
//     field (Cross Field, N = 1) on a real mesh, every bird inside the mesh's bounding box.
//
//   --case drawn --mesh bumpy_sphere.ply --image star.png --image fish.png: no baseline; the
//     decals are checked against the outlines, pixel by pixel. The decals of the shapes facing
//     the camera are rendered alone (white, the texture's alpha blended over a black surface and
//     background), and the same shapes' outlines are projected to the screen and filled. Every
//     decal pixel (alpha >= 0.5) lies within 2 pixels of a filled outline (no stray fragment, no
//     repeat of the texture), and the outlines' interiors more than 2 pixels from their border
//     are decal pixels (no hatching, no hole), but for 1% (bumps of the surface hiding a part).
//
// Decals of neighbouring shapes overlap (each covers the part of the square around its circle
// that lies on the surface, transparent outside the silhouette): the texture's alpha is blended
// by VTK's translucent pass, with no shader of the project's, and each shape's decal is lifted by
// a shape-dependent hair against z-fighting.
#include "vtkCrossField.h"
#include "vtkMSDTSource.h"
#include "vtkShapeDistributor.h"

#include "FilterTestSupport.h"
#include "MeshGenerators.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkIdList.h>
#include <vtkTexture.h>
#include <vtkTriangleFilter.h>
#include <vtkWindowToImageFilter.h>
#include <vtkUnsignedCharArray.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

using gs_test::Check;

namespace
{

vtkSmartPointer<vtkPolyData> Pentagram()
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> polys;
  std::vector<vtkIdType> ids;
  for (const gs::Vec2& p : gs::MakeStarPolygon(5, 1.0, 0.382))
  {
    ids.push_back(points->InsertNextPoint(p.x, p.y, 0.0));
  }
  polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
  auto data = vtkSmartPointer<vtkPolyData>::New();
  data->SetPoints(points);
  data->SetPolys(polys);
  return data;
}

// RGBA texture of class `k`: colour inside the silhouette, transparent outside.
vtkSmartPointer<vtkImageData> Texture(vtkImageData* silhouettes, int k, const double rgb[3])
{
  vtkDataArray* s = silhouettes->GetPointData()->GetArray("Silhouette");
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(silhouettes->GetDimensions());
  vtkNew<vtkUnsignedCharArray> rgba;
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(s->GetNumberOfTuples());
  for (vtkIdType i = 0; i < s->GetNumberOfTuples(); ++i)
  {
    const double a = s->GetComponent(i, k);
    rgba->SetTuple4(i, 255 * rgb[0], 255 * rgb[1], 255 * rgb[2], a);
  }
  image->GetPointData()->SetScalars(rgba);
  return image;
}

// The decals with each shape lifted by its own hair along its triangles' normals.
vtkSmartPointer<vtkPolyData> Layered(vtkPolyData* decals, double hair)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(decals);
  vtkDataArray* shape = decals->GetCellData()->GetArray("ShapeId");
  vtkPoints* pts = out->GetPoints();
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    const vtkIdType* ids = nullptr;
    vtkIdType n = 0;
    out->GetCellPoints(c, n, ids);
    double a[3], b[3], p[3], normal[3];
    pts->GetPoint(ids[0], p);
    pts->GetPoint(ids[1], a);
    pts->GetPoint(ids[2], b);
    for (int k = 0; k < 3; ++k)
    {
      a[k] -= p[k];
      b[k] -= p[k];
    }
    normal[0] = a[1] * b[2] - a[2] * b[1];
    normal[1] = a[2] * b[0] - a[0] * b[2];
    normal[2] = a[0] * b[1] - a[1] * b[0];
    const double l = std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
    const double lift = hair * (1 + static_cast<int>(shape->GetTuple1(c)) % 16);
    for (vtkIdType j = 0; j < n && l > 0; ++j)
    {
      pts->GetPoint(ids[j], p);
      for (int k = 0; k < 3; ++k)
      {
        p[k] += normal[k] / l * lift;
      }
      pts->SetPoint(ids[j], p);
    }
  }
  return out;
}

int Render(vtkPolyData* mesh, vtkPolyData* decals, vtkImageData* texture, int argc, char* argv[],
  double azimuth, double elevation, double zoom)
{
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkPolyDataMapper> meshMapper;
  meshMapper->SetInputData(mesh);
  meshMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> meshActor;
  meshActor->SetMapper(meshMapper);
  meshActor->GetProperty()->SetColor(0.85, 0.82, 0.75);
  renderer->AddActor(meshActor);
  vtkNew<vtkTexture> tex;
  tex->SetInputData(texture);
  tex->InterpolateOn();
  vtkNew<vtkPolyDataMapper> decalMapper;
  decalMapper->SetInputData(decals);
  decalMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> decalActor;
  decalActor->SetMapper(decalMapper);
  decalActor->SetTexture(tex);
  // The texture's alpha blends the decals over the surface (VTK's own translucent pass, as
  // ParaView draws them): transparent outside the silhouettes.
  renderer->AddActor(decalActor);
  renderer->SetBackground(0.32, 0.34, 0.43);
  vtkNew<vtkRenderWindow> window;
  window->AddRenderer(renderer);
  window->SetSize(500, 450);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(azimuth);
  renderer->GetActiveCamera()->Elevation(elevation);
  renderer->GetActiveCamera()->Zoom(zoom);
  renderer->ResetCameraClippingRange();
  window->Render();
  const int image = vtkRegressionTestImage(window);
  if (image == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return image;
}

// The cells of `data` whose cell array ShapeId is in `keep`, as a new polydata (points copied per
// cell; the cell data and point data come along).
vtkSmartPointer<vtkPolyData> CellsOfShapes(vtkPolyData* data, const std::set<int>& keep)
{
  vtkDataArray* shape = data->GetCellData()->GetArray("ShapeId");
  vtkNew<vtkIdList> cells;
  for (vtkIdType c = 0; shape && c < data->GetNumberOfCells(); ++c)
  {
    if (keep.count(static_cast<int>(shape->GetTuple1(c))))
    {
      cells->InsertNextId(c);
    }
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->AllocateCopy(data);
  out->GetCellData()->CopyAllocate(data->GetCellData());
  out->GetPointData()->CopyAllocate(data->GetPointData());
  vtkNew<vtkPoints> points;
  out->SetPoints(points);
  for (vtkIdType k = 0; k < cells->GetNumberOfIds(); ++k)
  {
    const vtkIdType c = cells->GetId(k);
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    data->GetCellPoints(c, n, ids);
    std::vector<vtkIdType> copy(n);
    for (vtkIdType j = 0; j < n; ++j)
    {
      copy[j] = points->InsertNextPoint(data->GetPoint(ids[j]));
      out->GetPointData()->CopyData(data->GetPointData(), ids[j], copy[j]);
    }
    const vtkIdType made = out->InsertNextCell(data->GetCellType(c), n, copy.data());
    out->GetCellData()->CopyData(data->GetCellData(), c, made);
  }
  return out;
}

// A mesh's shapes as a user lays them: Cross Field (N = 1), MSDT Source of `images` (textures of
// 256 pixels) and a Shape Distributor at 2.5% of the bounding-box diagonal, all updated.
struct FieldAndShapes
{
  vtkNew<vtkMSDTSource> Msdt;
  vtkNew<vtkCrossField> Field;
  vtkNew<vtkShapeDistributor> Shapes;
  double Diagonal = 0.0;

  FieldAndShapes(vtkPolyData* mesh, const std::vector<std::string>& images, int seed)
  {
    for (const std::string& file : images)
    {
      this->Msdt->AddShapeFileName(file.c_str());
    }
    this->Msdt->SetTextureSize(256);
    this->Field->SetInputData(mesh);
    this->Field->SetSymmetry(1);
    this->Shapes->SetInputConnection(0, this->Field->GetOutputPort());
    this->Shapes->SetInputConnection(1, this->Msdt->GetOutputPort(0));
    double bounds[6];
    mesh->GetBounds(bounds);
    this->Diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) + (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    this->Shapes->SetShapeSize(0.025 * this->Diagonal);
    this->Shapes->SetSeed(seed);
    this->Shapes->Update();
    this->Msdt->Update();
  }
};

// Decals against outlines, pixel by pixel (see the file's comment). Returns the failures.
int DecalsInsideTheirOutlines(const std::string& meshFile, const std::vector<std::string>& images)
{
  auto mesh = gs_test::ReadPolyData(meshFile);
  if (!mesh)
  {
    return 1;
  }
  FieldAndShapes run(mesh, images, 3);
  vtkShapeDistributor* shapes = run.Shapes;
  vtkMSDTSource* msdt = run.Msdt;
  vtkPolyData* placed = shapes->GetOutput(0);
  vtkPolyData* decals = shapes->GetOutput(1);
  vtkPolyData* outlines = shapes->GetOutput(2);
  vtkDataArray* normal = placed->GetPointData()->GetArray("Normal");
  vtkDataArray* classOf = placed->GetPointData()->GetArray("ClassId");
  if (!normal || !classOf || placed->GetNumberOfPoints() < 50)
  {
    Check(false, "drawn", "too few shapes or no Normal / ClassId arrays");
    return 1;
  }

  const int width = 800, height = 800;
  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkRenderWindow> window;
  window->AddRenderer(renderer);
  window->SetSize(width, height);
  window->SetMultiSamples(0);
  renderer->SetBackground(0, 0, 0);
  vtkNew<vtkPolyDataMapper> meshMapper;
  meshMapper->SetInputData(mesh);
  meshMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> meshActor;
  meshActor->SetMapper(meshMapper);
  meshActor->GetProperty()->SetColor(0, 0, 0);
  meshActor->GetProperty()->SetSpecular(0);
  renderer->AddActor(meshActor);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(25);
  renderer->GetActiveCamera()->Elevation(20);
  renderer->GetActiveCamera()->Zoom(1.3);
  renderer->ResetCameraClippingRange();
  double eye[3];
  renderer->GetActiveCamera()->GetPosition(eye);

  // The shapes facing the camera (their normal within 45 degrees of the line of sight).
  std::set<int> front;
  for (vtkIdType s = 0; s < placed->GetNumberOfPoints(); ++s)
  {
    double x[3], n[3], v[3];
    placed->GetPoint(s, x);
    normal->GetTuple(s, n);
    for (int k = 0; k < 3; ++k)
      v[k] = eye[k] - x[k];
    const double len = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if ((n[0] * v[0] + n[1] * v[1] + n[2] * v[2]) > 0.7071 * len)
      front.insert(static_cast<int>(s));
  }
  // Their decals, one actor per class, white where the silhouette is.
  const double white[3] = { 1, 1, 1 };
  std::vector<vtkSmartPointer<vtkActor>> decalActors;
  for (int k = 0; k < static_cast<int>(images.size()); ++k)
  {
    std::set<int> ofClass;
    for (int s : front)
      if (static_cast<int>(classOf->GetTuple1(s)) == k)
        ofClass.insert(s);
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputData(CellsOfShapes(decals, ofClass));
    mapper->ScalarVisibilityOff();
    auto texture = vtkSmartPointer<vtkTexture>::New();
    texture->SetInputData(Texture(msdt->GetSilhouettesOutput(), k, white));
    texture->InterpolateOn();
    auto actor = vtkSmartPointer<vtkActor>::New();
    actor->SetMapper(mapper);
    actor->SetTexture(texture);
    actor->GetProperty()->SetAmbient(1.0);
    actor->GetProperty()->SetDiffuse(0.0);
    actor->GetProperty()->SetSpecular(0.0);
    renderer->AddActor(actor);
    decalActors.push_back(actor);
  }
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkDataArray* pixels = grab->GetOutput()->GetPointData()->GetScalars();
  int dims[3];
  grab->GetOutput()->GetDimensions(dims);
  std::vector<char> decal(static_cast<std::size_t>(dims[0]) * dims[1], 0);
  for (vtkIdType i = 0; i < pixels->GetNumberOfTuples(); ++i)
    decal[i] = pixels->GetComponent(i, 0) >= 128.0;

  // The same shapes' outlines, projected and filled (even-odd per shape, scanlines through the
  // pixel centres), from the outlines' closed polylines.
  std::map<int, std::vector<std::vector<std::array<double, 2>>>> rings;
  vtkDataArray* outlineShape = outlines->GetCellData()->GetArray("ShapeId");
  for (vtkIdType c = 0; outlineShape && c < outlines->GetNumberOfCells(); ++c)
  {
    const int s = static_cast<int>(outlineShape->GetTuple1(c));
    if (!front.count(s))
      continue;
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    outlines->GetCellPoints(c, n, ids);
    std::vector<std::array<double, 2>> ring;
    for (vtkIdType j = 0; j < n; ++j)
    {
      double x[3];
      outlines->GetPoint(ids[j], x);
      renderer->SetWorldPoint(x[0], x[1], x[2], 1.0);
      renderer->WorldToDisplay();
      double d[3];
      renderer->GetDisplayPoint(d);
      ring.push_back({ d[0], d[1] });
    }
    rings[s].push_back(ring);
  }
  std::vector<char> fill(decal.size(), 0);
  for (const auto& shapeRings : rings)
  {
    for (int y = 0; y < dims[1]; ++y)
    {
      const double yc = y + 0.5;
      std::vector<double> crossings;
      for (const auto& ring : shapeRings.second)
        for (std::size_t j = 0; j + 1 < ring.size(); ++j)
        {
          const auto& a = ring[j];
          const auto& b = ring[j + 1];
          if ((a[1] <= yc) != (b[1] <= yc))
            crossings.push_back(a[0] + (yc - a[1]) / (b[1] - a[1]) * (b[0] - a[0]));
        }
      std::sort(crossings.begin(), crossings.end());
      for (std::size_t j = 0; j + 1 < crossings.size(); j += 2)
        for (int x = std::max(0, static_cast<int>(std::ceil(crossings[j] - 0.5)));
             x < dims[0] && x + 0.5 <= crossings[j + 1]; ++x)
          fill[static_cast<std::size_t>(y) * dims[0] + x] = 1;
    }
  }
  // Within 2 pixels of the fill, and 2 pixels inside it.
  auto near = [&](const std::vector<char>& mask, int x, int y, char value) {
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx)
      {
        const int u = x + dx, v = y + dy;
        if (u >= 0 && v >= 0 && u < dims[0] && v < dims[1] &&
          mask[static_cast<std::size_t>(v) * dims[0] + u] == value)
          return true;
      }
    return false;
  };
  long long decalPixels = 0, stray = 0, interior = 0, holes = 0;
  for (int y = 0; y < dims[1]; ++y)
    for (int x = 0; x < dims[0]; ++x)
    {
      const std::size_t i = static_cast<std::size_t>(y) * dims[0] + x;
      if (decal[i])
      {
        ++decalPixels;
        stray += !near(fill, x, y, 1);
      }
      if (fill[i] && !near(fill, x, y, 0))
      {
        ++interior;
        holes += !decal[i];
      }
    }
  std::cout << placed->GetNumberOfPoints() << " shapes, " << front.size() << " facing the camera: "
            << decalPixels << " decal pixels, " << stray << " farther than 2 pixels from their outlines; "
            << interior << " interior pixels of the outlines, " << holes << " not drawn by a decal\n";
  Check(front.size() >= 20 && decalPixels > 10000, "drawn", "too few shapes facing the camera");
  Check(stray == 0, "drawn", std::to_string(stray) + " decal pixels outside the outlines");
  Check(holes <= interior / 100, "drawn", std::to_string(holes) + " of " + std::to_string(interior) +
      " pixels inside the outlines not drawn by a decal");
  return 0;
}

vtkIdType Count(vtkShapeDistributor* f, int mode)
{
  f->SetMode(mode);
  f->Update();
  return f->GetOutput(0)->GetNumberOfPoints();
}
} // namespace

int main(int argc, char* argv[])
{
  std::string which, meshFile, imageFile;
  std::vector<std::string> imageFiles;
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "--case") == 0)
      which = argv[i + 1];
    else if (std::strcmp(argv[i], "--mesh") == 0)
      meshFile = argv[i + 1];
    else if (std::strcmp(argv[i], "--image") == 0)
    {
      imageFile = argv[i + 1];
      imageFiles.push_back(imageFile);
    }
  }
  if (which == "drawn")
  {
    const int failed = DecalsInsideTheirOutlines(meshFile, imageFiles);
    return failed == 0 && gs_test::Failures == 0 ? 0 : 1;
  }
  int image = vtkRegressionTester::FAILED;
  if (which == "plane")
  {
    vtkNew<vtkMSDTSource> msdt;
    msdt->SetPolygonsData(Pentagram());
    msdt->SetTextureSize(128);
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(0, 0, 0);
    plane->SetPoint1(10, 0, 0);
    plane->SetPoint2(0, 10, 0);
    plane->SetResolution(40, 40);
    vtkNew<vtkTriangleFilter> tri;
    tri->SetInputConnection(plane->GetOutputPort());
    tri->Update();
    vtkNew<vtkPolyData> mesh;
    mesh->DeepCopy(tri->GetOutput());
    vtkNew<vtkDoubleArray> direction;
    direction->SetName("Direction");
    direction->SetNumberOfComponents(3);
    for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
      direction->InsertNextTuple3(1, 0, 0);
    mesh->GetCellData()->AddArray(direction);
    vtkNew<vtkShapeDistributor> shapes;
    shapes->SetInputData(0, mesh);
    shapes->SetInputConnection(1, msdt->GetOutputPort(0));
    shapes->SetShapeSize(0.5);
    shapes->SetSeed(1);
    const vtkIdType circles = Count(shapes, vtkShapeDistributor::CIRCUMCIRCLE_POISSON_DISK);
    const vtkIdType random = Count(shapes, vtkShapeDistributor::RANDOM);
    const vtkIdType greedy = Count(shapes, vtkShapeDistributor::GREEDY);
    std::cout << "circumcircle " << circles << ", random " << random << ", greedy " << greedy << "\n";
    Check(circles > 60 && random > 1.3 * circles && greedy > 1.7 * circles, "plane",
      "counts out of the expected order");
    msdt->Update();
    const double blue[3] = { 0.12, 0.25, 0.6 };
    image = Render(mesh, Layered(shapes->GetOutput(1), 1e-4),
      Texture(msdt->GetSilhouettesOutput(), 0, blue), argc, argv, 0, 0, 1.35);
  }
  else if (which == "mesh")
  {
    auto mesh = gs_test::ReadPolyData(meshFile);
    if (!mesh)
    {
      return 1;
    }
    FieldAndShapes run(mesh, { imageFile }, 2);
    vtkShapeDistributor* shapes = run.Shapes;
    vtkCrossField* field = run.Field;
    vtkMSDTSource* msdt = run.Msdt;
    const double diagonal = run.Diagonal;
    vtkPolyData* placed = shapes->GetOutput(0);
    std::cout << placed->GetNumberOfPoints() << " birds\n";
    Check(placed->GetNumberOfPoints() > 100, "mesh", "too few birds");
    // Every bird turned to the field: its Direction equals the field in its face.
    vtkDataArray* dir = placed->GetPointData()->GetArray("Direction");
    vtkDataArray* face = placed->GetPointData()->GetArray("FaceId");
    field->Update();
    vtkDataArray* cellDir = field->GetOutput()->GetCellData()->GetArray("Direction");
    int off = 0;
    for (vtkIdType i = 0; dir && face && cellDir && i < placed->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      dir->GetTuple(i, a);
      cellDir->GetTuple(static_cast<vtkIdType>(face->GetTuple1(i)), b);
      off += a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.999;
    }
    Check(off == 0, "mesh", std::to_string(off) + " birds not turned to the field");
    const double dark[3] = { 0.1, 0.1, 0.15 };
    image = Render(shapes->GetOutput(0)->GetNumberOfPoints() ? field->GetOutput() : mesh.Get(),
      Layered(shapes->GetOutput(1), 2e-5 * diagonal), Texture(msdt->GetSilhouettesOutput(), 0, dark),
      argc, argv, 30, 15, 1.3);
  }
  else
  {
    std::cerr << "usage: --case plane | --case mesh --mesh file --image file | --case drawn --mesh "
                 "file --image file [--image file ...]\n";
    return 1;
  }
  if (gs_test::Failures)
  {
    std::cerr << gs_test::Failures << " failure(s)\n";
  }
  return gs_test::Failures == 0 && image != vtkRegressionTester::FAILED ? 0 : 1;
}
