// Regression image of vtkMSDTSource: a five-pointed star (drawn by the test, rasterized to a
// 128 x 128 PNG) shown as its silhouette texture with its outline (left) beside its safe
// distance table (right: alpha_A along x, alpha_B along y, blue = close, red = 2 radii).
// Numbers asserted as well: range, the swap symmetry T(i, j) ~ T(j + ka/2, i + ka/2), and the
// 5-fold symmetry of the star (a rotation by 72 degrees is 12.8 bins: compared within a bin).
#include "vtkMSDTSource.h"

#include "Silhouette.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkDataArray.h>
#include <vtkImageActor.h>
#include <vtkImageData.h>
#include <vtkImageMapToColors.h>
#include <vtkImageMapper3D.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindow.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

#include <cmath>
#include <cstring>
#include <iostream>
#include <string>

int main(int argc, char* argv[])
{
  std::string temp = ".";
  for (int i = 1; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "-T") == 0)
      temp = argv[i + 1];
  const double pi = 3.14159265358979323846;
  std::vector<gs::Vec2> star;
  for (int k = 0; k < 10; ++k)
  {
    const double a = pi / 2 + pi * k / 5, r = k % 2 == 0 ? 60.0 : 25.0;
    star.emplace_back(64 + r * std::cos(a), 64 + r * std::sin(a));
  }
  const std::string file = temp + "/msdt_star.png";
  if (const gs::Status written = gs::WriteSilhouetteImage(
        gs::RasterizeShape(gs::ShapeFromPolygons({ star }), 128, 128, { 0.0, 0.0 }, 1.0), file, true);
      !written.Ok())
  {
    std::cerr << written.Message() << "\n";
    return 1;
  }

  vtkNew<vtkMSDTSource> source;
  source->AddShapeFileName(file.c_str());
  source->Update();
  vtkImageData* table = source->GetTablesOutput();
  vtkDataArray* values = table->GetPointData()->GetArray("SafeDistance");
  if (!values || values->GetNumberOfTuples() != 64 * 64)
  {
    std::cerr << "no table\n";
    return 1;
  }
  int failures = 0;
  const double step = 2.0 / 64;
  double range[2];
  values->GetRange(range);
  if (!(range[1] <= 2.0 && range[0] > 0.5 && range[0] < 1.6))
  {
    std::cerr << "table range " << range[0] << " " << range[1] << "\n";
    ++failures;
  }
  auto T = [&](int i, int j) { return values->GetTuple1(((j + 64) % 64) * 64 + (i + 64) % 64); };
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j)
    {
      if (std::abs(T(i, j) - T(j + 32, i + 32)) > step + 1e-9)
      {
        std::cerr << "swap symmetry " << i << " " << j << "\n";
        ++failures;
      }
    }

  // Left: the silhouette texture (grey) and the outline (red). Right: the table.
  vtkNew<vtkLookupTable> grey;
  grey->SetRange(0, 255);
  grey->SetValueRange(0.95, 0.3);
  grey->SetSaturationRange(0, 0);
  grey->Build();
  vtkNew<vtkImageMapToColors> silhouetteColours;
  silhouetteColours->SetInputConnection(source->GetOutputPort(2));
  silhouetteColours->SetLookupTable(grey);
  vtkNew<vtkImageActor> silhouette;
  silhouette->GetMapper()->SetInputConnection(silhouetteColours->GetOutputPort());

  vtkNew<vtkPolyDataMapper> outlineMapper;
  outlineMapper->SetInputConnection(source->GetOutputPort(1));
  outlineMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> outline;
  outline->SetMapper(outlineMapper);
  outline->GetProperty()->SetColor(0.9, 0.1, 0.1);
  outline->GetProperty()->SetLineWidth(2);
  outline->SetPosition(0, 0, 0.01);

  vtkNew<vtkImageData> shown;
  shown->ShallowCopy(table);
  shown->SetSpacing(2.0 / 64, 2.0 / 64, 1);
  shown->SetOrigin(1.3, -1.0, 0);
  vtkNew<vtkLookupTable> rainbow;
  rainbow->SetRange(range[0], 2.0);
  rainbow->SetHueRange(0.667, 0.0);
  rainbow->Build();
  vtkNew<vtkImageMapToColors> tableColours;
  tableColours->SetInputData(shown);
  tableColours->SetLookupTable(rainbow);
  vtkNew<vtkImageActor> tableActor;
  tableActor->GetMapper()->SetInputConnection(tableColours->GetOutputPort());

  vtkNew<vtkRenderer> renderer;
  renderer->AddActor(silhouette);
  renderer->AddActor(outline);
  renderer->AddActor(tableActor);
  renderer->SetBackground(1, 1, 1);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(600, 300);
  window->AddRenderer(renderer);
  window->SetMultiSamples(0);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->ParallelProjectionOn();
  renderer->ResetCamera();
  renderer->GetActiveCamera()->SetParallelScale(1.15);
  window->Render();
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
    interactor->Start();
  return (result == vtkRegressionTester::FAILED || failures) ? 1 : 0;
}
