// vtkCrossField on malformed input and bad parameters: a clear error (or warning) and an empty
// output, never a crash; quads are triangulated; the solver is kept while the mesh is unchanged;
// abort gives an empty output.
//  - Errors: empty mesh, NaN coordinates, a non-manifold edge, Symmetry 3, unknown Mode,
//    negative or NaN CurvatureAlignment, Singularities without "Index", an index that is not a
//    multiple of 1/N, a wrong index sum (names both sums), a stroke point at NaN.
//  - Warnings: Singularities in the Smoothest mode, CurvatureAlignment with N = 1, quads.
#include "vtkCrossField.h"

#include "FilterTestSupport.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSphereSource.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

using gs_test::Check;
using gs_test::Failures;
using gs_test::Mentions;
using gs_test::MessageRecorder;
using gs_test::UpdateRecording;

namespace
{



vtkSmartPointer<vtkPolyData> Sphere()
{
  vtkNew<vtkSphereSource> s;
  s->SetThetaResolution(24);
  s->SetPhiResolution(16);
  s->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(s->GetOutput());
  return out;
}

vtkSmartPointer<vtkPolyData> Points(const std::vector<std::array<double, 3>>& p,
  const std::vector<double>& index, bool withIndex = true)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> a;
  a->SetName("Index");
  for (size_t i = 0; i < p.size(); ++i)
  {
    points->InsertNextPoint(p[i].data());
    a->InsertNextValue(index[i]);
  }
  out->SetPoints(points);
  if (withIndex)
  {
    out->GetPointData()->AddArray(a);
  }
  return out;
}

// Runs the filter; returns whether the output is empty and records the messages.
struct Run
{
  bool Empty = true;
  std::vector<std::string> Errors, Warnings;
};

Run Execute(vtkCrossField* filter)
{
  vtkNew<MessageRecorder> recorder;
  filter->Modified();
  UpdateRecording(filter, recorder);
  Run r;
  r.Empty = filter->GetOutput()->GetNumberOfCells() == 0;
  r.Errors = recorder->Errors;
  r.Warnings = recorder->Warnings;
  return r;
}
} // namespace

int main()
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Empty mesh.
  {
    vtkNew<vtkCrossField> f;
    vtkNew<vtkPolyData> empty;
    f->SetInputData(empty);
    const Run r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "empty"), "Empty", "no error for an empty mesh");
  }
  // NaN coordinates.
  {
    auto mesh = Sphere();
    mesh->GetPoints()->SetPoint(3, nan, 0, 0);
    vtkNew<vtkCrossField> f;
    f->SetInputData(mesh);
    const Run r = Execute(f);
    Check(r.Empty && !r.Errors.empty(), "NaN", "no error for NaN coordinates");
  }
  // A non-manifold edge: three triangles on one edge.
  {
    vtkNew<vtkPolyData> mesh;
    vtkNew<vtkPoints> p;
    p->InsertNextPoint(0, 0, 0);
    p->InsertNextPoint(1, 0, 0);
    p->InsertNextPoint(0, 1, 0);
    p->InsertNextPoint(0, -1, 0);
    p->InsertNextPoint(0, 0, 1);
    vtkNew<vtkCellArray> t;
    const vtkIdType a[3] = { 0, 1, 2 }, b[3] = { 1, 0, 3 }, c[3] = { 0, 1, 4 };
    t->InsertNextCell(3, a);
    t->InsertNextCell(3, b);
    t->InsertNextCell(3, c);
    mesh->SetPoints(p);
    mesh->SetPolys(t);
    vtkNew<vtkCrossField> f;
    f->SetInputData(mesh);
    const Run r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "manifold"), "NonManifold", "no error");
  }
  // A single triangle, and two separate triangles: no shared edge, no field to smooth (an error
  // that says so, not a failed factorization).
  for (int count : { 1, 2 })
  {
    vtkNew<vtkPolyData> mesh;
    vtkNew<vtkPoints> p;
    vtkNew<vtkCellArray> t;
    for (int i = 0; i < count; ++i)
    {
      const vtkIdType ids[3] = { p->InsertNextPoint(3 * i, 0, 0), p->InsertNextPoint(3 * i + 1, 0, 0),
        p->InsertNextPoint(3 * i, 1, 0) };
      t->InsertNextCell(3, ids);
    }
    mesh->SetPoints(p);
    mesh->SetPolys(t);
    vtkNew<vtkCrossField> f;
    f->SetInputData(mesh);
    const Run r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "share edges") && !Mentions(r.Errors, "factorization"),
      "NoSharedEdge", "no clear error for " + std::to_string(count) + " separate triangle(s)");
  }
  auto sphere = Sphere();
  // Bad parameters.
  {
    vtkNew<vtkCrossField> f;
    f->SetInputData(sphere);
    f->SetSymmetry(3);
    Run r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "Symmetry"), "Symmetry", "no error for N = 3");
    f->SetSymmetry(4);
    f->SetMode(7);
    r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "Mode"), "Mode", "no error for Mode 7");
    f->SetModeToSmoothest();
    f->SetCurvatureAlignment(-1.0);
    r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "CurvatureAlignment"), "Alignment", "no error for -1");
    f->SetCurvatureAlignment(nan);
    r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "CurvatureAlignment"), "Alignment", "no error for NaN");
    f->SetCurvatureAlignment(1.0);
    r = Execute(f);
    Check(!r.Empty && r.Errors.empty(), "Alignment", "alignment 1 failed");
    f->SetSymmetry(1);
    r = Execute(f);
    Check(!r.Empty && Mentions(r.Warnings, "CurvatureAlignment"), "Alignment", "no warning for N = 1");
    f->SetCurvatureAlignment(0.0);
  }
  // Singularities.
  {
    vtkNew<vtkCrossField> f;
    f->SetInputData(sphere);
    f->SetSymmetry(1);
    f->SetModeToPrescribedSingularities();
    Run r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "Euler characteristic 2"), "NoSingularities",
      "no error without singularities on a sphere");
    f->SetSingularitiesData(Points({ { 0, 0, 0.5 }, { 0, 0, -0.5 } }, { 1, 1 }, false));
    r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "Index"), "NoIndex", "no error without Index");
    f->SetSingularitiesData(Points({ { 0, 0, 0.5 }, { 0, 0, -0.5 } }, { 1, 0 }));
    r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "sum to 1") && Mentions(r.Errors, "Euler characteristic 2"),
      "WrongSum", "no error naming the sums");
    f->SetSymmetry(4);
    f->SetSingularitiesData(Points({ { 0, 0, 0.5 }, { 0, 0, -0.5 } }, { 0.3, 1.7 }));
    r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "multiple of 1/4"), "NotMultiple", "no error for 0.3");
    f->SetSingularitiesData(Points({ { nan, 0, 0.5 }, { 0, 0, -0.5 } }, { 1, 1 }));
    r = Execute(f);
    Check(r.Empty && !r.Errors.empty(), "NaNSingularity", "no error for a NaN singularity");
    f->SetSymmetry(1);
    f->SetSingularitiesData(Points({ { 0, 0, 0.5 }, { 0, 0, -0.5 } }, { 1, 1 }));
    r = Execute(f);
    Check(!r.Empty && r.Errors.empty(), "Poles", "two +1 at the poles failed");
    vtkDataArray* index = f->GetOutput()->GetPointData()->GetArray("SingularityIndex");
    double sum = 0.0;
    int count = 0;
    for (vtkIdType i = 0; index && i < index->GetNumberOfTuples(); ++i)
    {
      sum += index->GetTuple1(i);
      count += index->GetTuple1(i) != 0.0;
    }
    Check(count == 2 && sum == 2.0, "Poles", "not exactly two +1 singularities");
    // The same singularities in the Smoothest mode: a warning.
    f->SetModeToSmoothest();
    r = Execute(f);
    Check(!r.Empty && Mentions(r.Warnings, "Smoothest"), "SmoothestWarning", "no warning");
  }
  // Strokes: a NaN point is an error; a polyline across the plane works on quads (triangulated).
  {
    vtkNew<vtkPlaneSource> plane;
    plane->SetResolution(8, 8);
    plane->Update();
    vtkNew<vtkCrossField> f;
    f->SetInputConnection(plane->GetOutputPort());
    vtkNew<vtkPolyData> stroke;
    vtkNew<vtkPoints> p;
    p->InsertNextPoint(-0.3, -0.2, 0);
    p->InsertNextPoint(nan, 0.2, 0);
    vtkNew<vtkCellArray> l;
    const vtkIdType ids[2] = { 0, 1 };
    l->InsertNextCell(2, ids);
    stroke->SetPoints(p);
    stroke->SetLines(l);
    f->SetStrokesData(stroke);
    Run r = Execute(f);
    Check(r.Empty && Mentions(r.Errors, "Stroke 0"), "NaNStroke", "no error");
    p->SetPoint(1, 0.3, 0.2, 0);
    p->Modified();
    r = Execute(f);
    Check(!r.Empty && Mentions(r.Warnings, "triangulated"), "Quads", "quads not triangulated");
    vtkDataArray* d = f->GetOutput()->GetCellData()->GetArray("Direction");
    double worst = 0.0;
    for (vtkIdType c = 0; d && c < d->GetNumberOfTuples(); ++c)
    {
      double v[3];
      d->GetTuple(c, v);
      const double a = std::atan2(v[1], v[0]) - std::atan2(0.4, 0.6);
      const double q = 3.14159265358979323846 / 2;
      worst = std::max(worst, std::abs(std::remainder(a, q)));
    }
    Check(d && worst < 1e-5, "Quads", "the field does not follow the stroke");

    // Abort: empty output.
    vtkNew<vtkCallbackCommand> abort;
    abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
      static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
    });
    f->AddObserver(vtkCommand::ProgressEvent, abort);
    f->SetSymmetry(2);
    r = Execute(f);
    Check(r.Empty, "Abort", "aborted output not empty");
  }
  if (Failures == 0)
  {
    std::cout << "all checks passed\n";
  }
  return Failures == 0 ? 0 : 1;
}
