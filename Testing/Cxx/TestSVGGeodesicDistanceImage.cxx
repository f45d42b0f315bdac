// Regression image of vtkSVGGeodesicDistance on the bundled L-shaped domain (Data/lshape.ply),
// coloured bands plus isolines, and the analytic distances it must reproduce.
//
// The source is the vertex at (2, 1), the top of the lower arm. A point p is seen directly when
// p.y <= 1 (distance |p - s|); otherwise the geodesic bends around the re-entrant corner
// c = (1, 1): distance |s - c| + |c - p| = 1 + |p - c|. The mesh is planar, so the exact solver
// must match to rounding (the Exact solver; the image is its field).
#include "vtkSVGGeodesicDistance.h"

#include <vtkActor.h>
#include <vtkBandedPolyDataContourFilter.h>
#include <vtkCamera.h>
#include <vtkContourFilter.h>
#include <vtkDoubleArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPLYReader.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <string>

namespace
{
double AnalyticLShapeDistance(const double p[3])
{
  if (p[1] <= 1.0)
  {
    return std::hypot(p[0] - 2.0, p[1] - 1.0);
  }
  return 1.0 + std::hypot(p[0] - 1.0, p[1] - 1.0);
}

std::string DataDirectory(int argc, char* argv[])
{
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "--data") == 0)
    {
      return argv[i + 1];
    }
  }
  return "Data";
}
}

int main(int argc, char* argv[])
{
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName((DataDirectory(argc, argv) + "/lshape.ply").c_str());
  reader->Update();
  vtkPolyData* mesh = reader->GetOutput();
  if (mesh->GetNumberOfPoints() == 0)
  {
    std::cerr << "Could not read " << reader->GetFileName() << "\n";
    return 1;
  }

  // The source: the point at (2, 1).
  vtkIdType source = -1;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    if (std::abs(p[0] - 2.0) < 1e-12 && std::abs(p[1] - 1.0) < 1e-12)
    {
      source = i;
    }
  }
  if (source < 0)
  {
    std::cerr << "No vertex at (2, 1) in the L-shape.\n";
    return 1;
  }

  vtkNew<vtkSVGGeodesicDistance> geodesic;
  geodesic->SetInputConnection(reader->GetOutputPort());
  geodesic->SetSolverToExact();
  geodesic->AddSourceVertexId(source);
  geodesic->Update();
  vtkPolyData* output = geodesic->GetOutput();
  auto* distance =
    vtkDoubleArray::SafeDownCast(output->GetPointData()->GetArray("GeodesicDistance"));
  if (!distance || distance->GetNumberOfTuples() != mesh->GetNumberOfPoints())
  {
    std::cerr << "Missing or wrongly sized GeodesicDistance array.\n";
    return 1;
  }

  // Numbers: every vertex against the analytic distance, and the range [0, 1 + sqrt(2)].
  double worst = 0.0;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    double p[3];
    output->GetPoint(i, p);
    const double expected = AnalyticLShapeDistance(p);
    const double error = std::abs(distance->GetValue(i) - expected) / std::max(1.0, expected);
    worst = std::max(worst, std::isfinite(error) ? error : 1e300);
  }
  double range[2];
  distance->GetRange(range);
  const double expectedMaximum = 1.0 + std::sqrt(2.0);
  std::cout << "distance range [" << range[0] << ", " << range[1] << "], expected [0, "
            << expectedMaximum << "]; worst relative error " << worst << "\n";
  if (worst > 1e-9 || std::abs(range[0]) > 1e-12 ||
    std::abs(range[1] - expectedMaximum) > 1e-9 * expectedMaximum)
  {
    std::cerr << "Distances differ from the analytic L-shape distance.\n";
    return 1;
  }

  // Picture: 12 coloured bands, black isolines at the band boundaries, the source as a ball.
  const int bands = 12;
  vtkNew<vtkBandedPolyDataContourFilter> banded;
  banded->SetInputConnection(geodesic->GetOutputPort());
  banded->GenerateValues(bands + 1, 0.0, expectedMaximum);
  banded->SetScalarModeToIndex(); // the band between values k and k+1 gets scalar k

  vtkNew<vtkLookupTable> lut;
  lut->SetNumberOfTableValues(bands);
  lut->SetHueRange(0.66, 0.0);
  lut->Build();

  vtkNew<vtkPolyDataMapper> surfaceMapper;
  surfaceMapper->SetInputConnection(banded->GetOutputPort());
  surfaceMapper->SetScalarModeToUseCellData();
  surfaceMapper->SetLookupTable(lut);
  surfaceMapper->SetScalarRange(-0.5, bands - 0.5);
  vtkNew<vtkActor> surface;
  surface->SetMapper(surfaceMapper);

  vtkNew<vtkContourFilter> isolines;
  isolines->SetInputConnection(geodesic->GetOutputPort());
  isolines->GenerateValues(bands + 1, 0.0, expectedMaximum);
  vtkNew<vtkPolyDataMapper> lineMapper;
  lineMapper->SetInputConnection(isolines->GetOutputPort());
  lineMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> lines;
  lines->SetMapper(lineMapper);
  lines->GetProperty()->SetColor(0.0, 0.0, 0.0);
  lines->GetProperty()->SetLineWidth(2.0);
  lines->SetPosition(0.0, 0.0, 1e-3);

  vtkNew<vtkSphereSource> ball;
  ball->SetCenter(2.0, 1.0, 0.0);
  ball->SetRadius(0.04);
  ball->SetThetaResolution(24);
  ball->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(ball->GetOutputPort());
  vtkNew<vtkActor> ballActor;
  ballActor->SetMapper(ballMapper);
  ballActor->GetProperty()->SetColor(1.0, 1.0, 1.0);

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(surface);
  renderer->AddActor(lines);
  renderer->AddActor(ballActor);
  renderer->SetBackground(0.32, 0.34, 0.43);
  vtkNew<vtkRenderWindow> window;
  window->AddRenderer(renderer);
  window->SetSize(400, 400);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);

  renderer->ResetCamera();
  renderer->GetActiveCamera()->Zoom(1.3);
  window->Render();

  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return result == vtkRegressionTester::FAILED ? 1 : 0;
}
