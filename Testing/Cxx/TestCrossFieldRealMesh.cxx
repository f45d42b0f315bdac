// Cross Field on real meshes of higher genus (libcgal-demo's refined_elephant and turbine,
// extracted by the Core.ExtractCgalMeshes fixture): Poincare-Hopf for the smoothest fields,
// prescribed singularities exactly where placed (through the Singularities port), a stroke
// followed within a degree, and a regression image of the cross field as glyphs with its
// singularities marked.
#include "vtkCrossField.h"

#include "FilterTestSupport.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkGlyph3D.h>
#include <vtkIntArray.h>
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
#include <vtkSphereSource.h>
#include <vtkTriangle.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
int failures = 0;
void Check(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAILED: " << what << "\n";
    ++failures;
  }
}


double FieldValue(vtkPolyData* output, const char* name)
{
  vtkDataArray* a = output->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : std::nan("");
}

double PointIndexSum(vtkPolyData* output, int* count)
{
  vtkDataArray* index = output->GetPointData()->GetArray("SingularityIndex");
  double sum = 0.0;
  *count = 0;
  for (vtkIdType i = 0; index && i < index->GetNumberOfTuples(); ++i)
  {
    sum += index->GetTuple1(i);
    *count += index->GetTuple1(i) != 0.0;
  }
  return sum;
}
} // namespace

int main(int argc, char* argv[])
{
  std::vector<std::string> meshFiles;
  for (int i = 1; i + 1 < argc; ++i)
  {
    if (std::strcmp(argv[i], "--mesh") == 0)
    {
      meshFiles.push_back(argv[i + 1]);
    }
  }
  vtkSmartPointer<vtkPolyData> shown;
  vtkSmartPointer<vtkPolyData> shownField;
  for (size_t m = 0; m < meshFiles.size(); ++m)
  {
    vtkSmartPointer<vtkPolyData> mesh = gs_test::ReadPolyData(meshFiles[m]);
    if (!mesh)
    {
      return 1;
    }
    // Smoothest fields: Poincare-Hopf.
    vtkNew<vtkCrossField> field;
    field->SetInputData(mesh);
    int chi = 0;
    for (int n : { 1, 2, 4 })
    {
      field->SetSymmetry(n);
      const auto t0 = std::chrono::steady_clock::now();
      field->Update();
      const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      vtkPolyData* out = field->GetOutput();
      chi = static_cast<int>(FieldValue(out, "EulerCharacteristic"));
      int count = 0;
      const double sum = PointIndexSum(out, &count);
      std::cout << meshFiles[m] << ": N = " << n << ", Euler characteristic " << chi << ", "
                << count << " singularities, index sum " << sum << " (" << seconds << " s)\n";
      Check(chi <= -4, "expected a mesh of genus 3 or more");
      Check(std::abs(sum - chi) < 1e-9, "point index sum is not the Euler characteristic");
      Check(std::abs(FieldValue(out, "SingularityIndexSum") - chi) < 1e-9,
        "SingularityIndexSum is not the Euler characteristic");
    }
    if (m != 0)
    {
      continue;
    }
    // Prescribed: -1/4 at 4 |chi| vertices spread over the mesh, through the Singularities port.
    vtkNew<vtkPolyData> singular;
    vtkNew<vtkPoints> sp;
    vtkNew<vtkDoubleArray> index;
    index->SetName("Index");
    const int count = -4 * chi;
    std::vector<vtkIdType> ids;
    for (int k = 0; k < count; ++k)
    {
      const vtkIdType id = (2 * k + 1) * mesh->GetNumberOfPoints() / (2 * count);
      ids.push_back(id);
      sp->InsertNextPoint(mesh->GetPoint(id));
      index->InsertNextValue(-0.25);
    }
    singular->SetPoints(sp);
    singular->GetPointData()->AddArray(index);
    field->SetSymmetry(4);
    field->SetModeToPrescribedSingularities();
    field->SetSingularitiesData(singular);
    // A stroke across a few faces near the first vertex.
    vtkNew<vtkPolyData> stroke;
    {
      double a[3], b[3], c[3];
      vtkIdType npts;
      const vtkIdType* pts;
      mesh->GetPolys()->GetCellAtId(1000, npts, pts);
      mesh->GetPoint(pts[0], a);
      mesh->GetPoint(pts[1], b);
      mesh->GetPoint(pts[2], c);
      vtkNew<vtkPoints> p;
      p->InsertNextPoint((a[0] + c[0]) / 2, (a[1] + c[1]) / 2, (a[2] + c[2]) / 2);
      p->InsertNextPoint((b[0] + c[0]) / 2, (b[1] + c[1]) / 2, (b[2] + c[2]) / 2);
      vtkNew<vtkCellArray> line;
      const vtkIdType lp[2] = { 0, 1 };
      line->InsertNextCell(2, lp);
      stroke->SetPoints(p);
      stroke->SetLines(line);
    }
    field->SetStrokesData(stroke);
    const auto t0 = std::chrono::steady_clock::now();
    field->Update();
    const double first = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    vtkPolyData* out = field->GetOutput();
    vtkDataArray* result = out->GetPointData()->GetArray("SingularityIndex");
    Check(result != nullptr, "no SingularityIndex");
    if (!result)
    {
      return 1;
    }
    int found = 0;
    for (vtkIdType i = 0; i < result->GetNumberOfTuples(); ++i)
    {
      const bool wanted = std::find(ids.begin(), ids.end(), i) != ids.end();
      found += result->GetTuple1(i) != 0.0;
      Check(result->GetTuple1(i) == (wanted ? -0.25 : 0.0),
        "vertex " + std::to_string(i) + " has index " + std::to_string(result->GetTuple1(i)));
    }
    std::cout << "prescribed: " << found << " singularities for " << count << " placed (" << first
              << " s)\n";
    // The stroke's face 1000 follows the stroke (its direction is b - a).
    {
      double a[3], b[3], d[3];
      stroke->GetPoint(0, a);
      stroke->GetPoint(1, b);
      out->GetCellData()->GetArray("Direction")->GetTuple(1000, d);
      const double s[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
      const double ls = std::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
      const double dot = (s[0] * d[0] + s[1] * d[1] + s[2] * d[2]) / ls;
      // Cross field: d or d rotated by a multiple of 90 degrees; |cos| is 1 or 0.
      const double c = std::abs(dot);
      const double deviation = std::min(std::acos(std::min(1.0, c)), std::asin(std::min(1.0, c)));
      std::cout << "stroke deviation " << deviation * 180 / 3.14159265358979 << " degrees\n";
      Check(deviation < 1.0 * 3.14159265358979 / 180, "the field does not follow the stroke");
    }
    shown = vtkSmartPointer<vtkPolyData>::New();
    shown->DeepCopy(out);
  }
  if (!shown)
  {
    std::cerr << "no mesh given (--mesh)\n";
    return 1;
  }

  // Glyphs: the two axes of the cross at every 45th triangle, singularities as spheres.
  vtkNew<vtkPoints> gp;
  vtkNew<vtkCellArray> gl;
  vtkDataArray* dir = shown->GetCellData()->GetArray("Direction");
  double bounds[6];
  shown->GetBounds(bounds);
  const double size = std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
  const double half = 0.011 * size;
  for (vtkIdType c = 0; c < shown->GetNumberOfCells(); c += 45)
  {
    vtkIdType npts;
    const vtkIdType* pts;
    shown->GetPolys()->GetCellAtId(c, npts, pts);
    double p[3][3], centre[3], normal[3], d[3], e[3];
    for (int k = 0; k < 3; ++k)
    {
      shown->GetPoint(pts[k], p[k]);
    }
    vtkTriangle::TriangleCenter(p[0], p[1], p[2], centre);
    vtkTriangle::ComputeNormal(p[0], p[1], p[2], normal);
    dir->GetTuple(c, d);
    e[0] = normal[1] * d[2] - normal[2] * d[1];
    e[1] = normal[2] * d[0] - normal[0] * d[2];
    e[2] = normal[0] * d[1] - normal[1] * d[0];
    for (const double* axis : { d, e })
    {
      const vtkIdType a = gp->InsertNextPoint(centre[0] - half * axis[0], centre[1] - half * axis[1], centre[2] - half * axis[2]);
      const vtkIdType b = gp->InsertNextPoint(centre[0] + half * axis[0], centre[1] + half * axis[1], centre[2] + half * axis[2]);
      const vtkIdType ids[2] = { a, b };
      gl->InsertNextCell(2, ids);
    }
  }
  vtkNew<vtkPolyData> glyphs;
  glyphs->SetPoints(gp);
  glyphs->SetLines(gl);
  vtkNew<vtkPoints> sing;
  vtkDataArray* idx = shown->GetPointData()->GetArray("SingularityIndex");
  for (vtkIdType i = 0; i < shown->GetNumberOfPoints(); ++i)
  {
    if (idx->GetTuple1(i) != 0.0)
    {
      sing->InsertNextPoint(shown->GetPoint(i));
    }
  }
  vtkNew<vtkPolyData> singData;
  singData->SetPoints(sing);
  vtkNew<vtkSphereSource> ball;
  ball->SetRadius(0.012 * size);
  vtkNew<vtkGlyph3D> balls;
  balls->SetInputData(singData);
  balls->SetSourceConnection(ball->GetOutputPort());
  balls->SetScaleModeToDataScalingOff();

  vtkNew<vtkRenderer> renderer;
  vtkNew<vtkPolyData> surfaceOnly;
  surfaceOnly->SetPoints(shown->GetPoints());
  surfaceOnly->SetPolys(shown->GetPolys());
  vtkNew<vtkPolyDataNormals> normals;
  normals->SetInputData(surfaceOnly);
  normals->SplittingOff();
  vtkNew<vtkPolyDataMapper> surfaceMapper;
  surfaceMapper->SetInputConnection(normals->GetOutputPort());
  surfaceMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> surface;
  surface->SetMapper(surfaceMapper);
  surface->GetProperty()->SetColor(0.85, 0.85, 0.8);
  renderer->AddActor(surface);
  vtkNew<vtkPolyDataMapper> glyphMapper;
  glyphMapper->SetInputData(glyphs);
  vtkNew<vtkActor> glyphActor;
  glyphActor->SetMapper(glyphMapper);
  glyphActor->GetProperty()->SetColor(0.1, 0.2, 0.6);
  glyphActor->GetProperty()->SetLineWidth(1.5);
  renderer->AddActor(glyphActor);
  vtkNew<vtkPolyDataMapper> ballMapper;
  ballMapper->SetInputConnection(balls->GetOutputPort());
  ballMapper->ScalarVisibilityOff();
  vtkNew<vtkActor> ballActor;
  ballActor->SetMapper(ballMapper);
  ballActor->GetProperty()->SetColor(0.9, 0.1, 0.1);
  renderer->AddActor(ballActor);
  renderer->SetBackground(0.32, 0.34, 0.43);
  vtkNew<vtkRenderWindow> window;
  window->AddRenderer(renderer);
  window->SetSize(500, 400);
  window->SetMultiSamples(0);
  vtkNew<vtkRenderWindowInteractor> interactor;
  interactor->SetRenderWindow(window);
  renderer->ResetCamera();
  renderer->GetActiveCamera()->Azimuth(30);
  renderer->GetActiveCamera()->Elevation(15);
  renderer->GetActiveCamera()->Zoom(1.3);
  renderer->ResetCameraClippingRange();
  window->Render();
  const int image = vtkRegressionTestImage(window);
  if (image == vtkRegressionTester::DO_INTERACTOR)
  {
    interactor->Start();
  }
  return failures == 0 && image != vtkRegressionTester::FAILED ? 0 : 1;
}
