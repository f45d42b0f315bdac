// Shape Distributor regression images: decals textured with the silhouettes of MSDT Source.
//
//   --case plane: pentagrams in a 10 x 10 square (the paper's Fig. 9 layout), Greedy mode, with
//     the counts of the three modes checked (Greedy > Random > Circumcircle Poisson disk).
//   --case mesh --mesh refined_elephant.off --image crow.png: birds following a smooth vector
//     field (Cross Field, N = 1) on a real mesh, every bird inside the mesh's bounding box.
//
// Decals of neighbouring shapes overlap (each covers the square around its circle, transparent
// outside the silhouette): the texture is drawn as a cut-out (fragments with alpha < 0.5 are
// discarded by a shader replacement), and each shape's decal is lifted by a shape-dependent hair
// against z-fighting.
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
#include <vtkShaderProperty.h>
#include <vtkTexture.h>
#include <vtkTriangleFilter.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <string>

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
  // Cut-out texture: fragments outside the silhouettes are discarded (alpha test), so the
  // overlapping decal squares of neighbours never hide each other.
  decalActor->ForceOpaqueOn();
  decalActor->GetShaderProperty()->AddFragmentShaderReplacement("//VTK::Light::Impl", true,
    "//VTK::Light::Impl\n  if (gl_FragData[0].a < 0.5) { discard; }\n", false);
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
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "--case") == 0)
      which = argv[i + 1];
    else if (std::strcmp(argv[i], "--mesh") == 0)
      meshFile = argv[i + 1];
    else if (std::strcmp(argv[i], "--image") == 0)
      imageFile = argv[i + 1];
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
    vtkNew<vtkMSDTSource> msdt;
    msdt->AddShapeFileName(imageFile.c_str());
    msdt->SetTextureSize(256);
    vtkNew<vtkCrossField> field;
    field->SetInputData(mesh);
    field->SetSymmetry(1);
    vtkNew<vtkShapeDistributor> shapes;
    shapes->SetInputConnection(0, field->GetOutputPort());
    shapes->SetInputConnection(1, msdt->GetOutputPort(0));
    double bounds[6];
    mesh->GetBounds(bounds);
    const double diagonal = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) + (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    shapes->SetShapeSize(0.025 * diagonal);
    shapes->SetSeed(2);
    shapes->Update();
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
    msdt->Update();
    const double dark[3] = { 0.1, 0.1, 0.15 };
    image = Render(shapes->GetOutput(0)->GetNumberOfPoints() ? field->GetOutput() : mesh.Get(),
      Layered(shapes->GetOutput(1), 2e-5 * diagonal), Texture(msdt->GetSilhouettesOutput(), 0, dark),
      argc, argv, 30, 15, 1.3);
  }
  else
  {
    std::cerr << "usage: --case plane | --case mesh --mesh file --image file\n";
    return 1;
  }
  if (gs_test::Failures)
  {
    std::cerr << gs_test::Failures << " failure(s)\n";
  }
  return gs_test::Failures == 0 && image != vtkRegressionTester::FAILED ? 0 : 1;
}
