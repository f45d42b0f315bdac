// Geodesic Polar Coordinates on a real scanned mesh (libcgal-demo's mannequin-devil, extracted by
// the Core.ExtractCgalMeshes fixture): a checkerboard decal through DecalCoordinates in
// Iso-curve arc length mode, regression image plus numbers: no face of the disc flips in decal
// coordinates (the iso-curve angles do not fold), and rho agrees with an exact solve.
#include "vtkGeodesicPolarCoordinates.h"
#include "vtkSVGGeodesicDistance.h"

#include "FilterTestSupport.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <string>

namespace
{
vtkSmartPointer<vtkImageData> Checkerboard(int side, int squares)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(side, side, 1);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* rgb = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  const int square = side / squares;
  for (int y = 0; y < side; ++y)
  {
    for (int x = 0; x < side; ++x)
    {
      const bool white = ((x / square) + (y / square)) % 2 == 0;
      const bool marked = x >= side / 2 && y >= side / 2; // theta in [0, pi / 2]
      const unsigned char c[3] = { static_cast<unsigned char>(white ? 255 : (marked ? 220 : 20)),
        static_cast<unsigned char>(white ? 255 : (marked ? 30 : 20)),
        static_cast<unsigned char>(white ? 255 : (marked ? 30 : 20)) };
      rgb->SetTypedTuple(static_cast<vtkIdType>(y) * side + x, c);
    }
  }
  return image;
}
}

int main(int argc, char* argv[])
{
  std::string meshFile;
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "--mesh") == 0)
    {
      meshFile = argv[i + 1];
    }
  }
  vtkSmartPointer<vtkPolyData> mesh = gs_test::ReadPolyData(meshFile);
  if (!mesh)
  {
    return 1;
  }

  // A source on the mannequin's chest, a disc of about a tenth of the model.
  const vtkIdType source = 4000;
  double bounds[6];
  mesh->GetBounds(bounds);
  const double size = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  const double radius = 0.22 * size;
  vtkNew<vtkGeodesicPolarCoordinates> polar;
  polar->SetInputData(mesh);
  polar->SetSourceVertexId(source);
  polar->SetRadius(radius);
  polar->SetAngleModeToIsoCurveArcLength();
  polar->SetDecalSize(2.0 * radius);
  polar->Update();
  vtkPolyData* output = polar->GetOutput();
  auto* rho = vtkDoubleArray::SafeDownCast(output->GetPointData()->GetArray("GeodesicDistance"));
  auto* decal = vtkDoubleArray::SafeDownCast(output->GetPointData()->GetTCoords());
  int failures = 0;
  auto check = [&](bool ok, const char* what) {
    if (!ok)
    {
      std::cerr << "FAILED: " << what << "\n";
      ++failures;
    }
  };
  check(rho && decal, "missing GeodesicDistance or DecalCoordinates");
  if (!rho || !decal)
  {
    return 1;
  }

  // rho against an exact solve through the other filter.
  vtkNew<vtkSVGGeodesicDistance> exact;
  exact->SetInputData(mesh);
  exact->SetSolverToExact();
  exact->AddSourceVertexId(source);
  exact->Update();
  auto* reference = vtkDoubleArray::SafeDownCast(exact->GetOutput()->GetPointData()->GetArray("GeodesicDistance"));
  double worst = 0.0;
  int inside = 0;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    if (std::isfinite(rho->GetValue(i)))
    {
      ++inside;
      worst = std::max(worst, std::abs(rho->GetValue(i) - reference->GetValue(i)));
    }
  }
  std::cout << inside << " points inside the disc, largest rho difference " << worst << "\n";
  check(inside > 500, "too few points inside the disc");
  check(worst < 1e-9 * size, "rho differs from the exact distance");

  // No face of the disc flips in decal coordinates.
  vtkNew<vtkCellArray> disc, rest;
  int flipped = 0;
  auto it = vtk::TakeSmartPointer(output->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* pts;
    it->GetCurrentCell(n, pts);
    double uv[3][2];
    bool finite = n == 3;
    for (vtkIdType k = 0; finite && k < 3; ++k)
    {
      decal->GetTypedTuple(pts[k], uv[k]);
      finite = std::isfinite(uv[k][0]) && std::isfinite(uv[k][1]);
    }
    if (!finite)
    {
      rest->InsertNextCell(n, pts);
      continue;
    }
    disc->InsertNextCell(n, pts);
    const double cross = (uv[1][0] - uv[0][0]) * (uv[2][1] - uv[0][1]) - (uv[1][1] - uv[0][1]) * (uv[2][0] - uv[0][0]);
    flipped += cross <= 0.0;
  }
  std::cout << flipped << " faces flipped in decal coordinates\n";
  check(flipped == 0, "faces flip in decal coordinates (iso-curve mode)");

  vtkNew<vtkPolyData> discData, restData;
  discData->SetPoints(output->GetPoints());
  discData->SetPolys(disc);
  discData->GetPointData()->SetTCoords(decal);
  restData->SetPoints(output->GetPoints());
  restData->SetPolys(rest);
  vtkNew<vtkRenderer> renderer;
  for (vtkPolyData* part : { discData.GetPointer(), restData.GetPointer() })
  {
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(part);
    normals->SplittingOff();
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(normals->GetOutputPort());
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    if (part == discData.GetPointer())
    {
      vtkNew<vtkTexture> texture;
      texture->SetInputData(Checkerboard(256, 8));
      texture->InterpolateOff();
      texture->EdgeClampOn();
      actor->SetTexture(texture);
    }
    else
    {
      actor->GetProperty()->SetColor(0.6, 0.6, 0.6);
    }
    renderer->AddActor(actor);
  }
  renderer->SetBackground(0.32, 0.34, 0.43);
  vtkNew<vtkRenderWindow> window;
  window->AddRenderer(renderer);
  window->SetSize(400, 400);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  // Look at the source along its normal, from outside.
  double s[3], n[3] = { 0, 0, 0 };
  output->GetPoint(source, s);
  {
    vtkNew<vtkPolyDataNormals> normals;
    normals->SetInputData(mesh);
    normals->ComputePointNormalsOn();
    normals->SplittingOff();
    normals->Update();
    normals->GetOutput()->GetPointData()->GetNormals()->GetTuple(source, n);
  }
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetFocalPoint(s);
  camera->SetPosition(s[0] + 1.1 * size * n[0], s[1] + 1.1 * size * n[1], s[2] + 1.1 * size * n[2]);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCameraClippingRange();
  window->Render();
  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return failures == 0 && result != vtkRegressionTester::FAILED ? 0 : 1;
}
