// Shared by the filter tests: failure counting, the messages a filter emits, the unit square and
// real meshes (OFF/PLY read by the core) as vtkPolyData.
#pragma once

#include "MeshIO.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkNew.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

namespace gs_test
{

inline int Failures = 0;

// Counts and prints a failed check of `test`.
inline void Check(bool condition, const std::string& test, const std::string& what)
{
  if (!condition)
  {
    std::cerr << "FAILED " << test << ": " << what << "\n";
    ++Failures;
  }
}

// Records the error and warning messages an object emits.
class MessageRecorder : public vtkCommand
{
public:
  static MessageRecorder* New() { return new MessageRecorder; }
  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    const std::string text = callData ? static_cast<const char*>(callData) : "";
    (event == vtkCommand::ErrorEvent ? this->Errors : this->Warnings).push_back(text);
  }
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
};

// Updates `algorithm` with its error and warning messages recorded in `recorder` (the
// observers are removed again).
inline void UpdateRecording(vtkAlgorithm* algorithm, MessageRecorder* recorder)
{
  const unsigned long e = algorithm->AddObserver(vtkCommand::ErrorEvent, recorder);
  const unsigned long w = algorithm->AddObserver(vtkCommand::WarningEvent, recorder);
  algorithm->Update();
  algorithm->RemoveObserver(e);
  algorithm->RemoveObserver(w);
}

// Whether one of `messages` contains `keyword`.
inline bool Mentions(const std::vector<std::string>& messages, const std::string& keyword)
{
  return std::any_of(messages.begin(), messages.end(),
    [&](const std::string& m) { return m.find(keyword) != std::string::npos; });
}

// The unit square [0, 1]^2 as n x n quads (vtkPlaneSource), optionally triangulated, without
// point data (the source's normals and texture coordinates dropped); double or float points.
inline vtkSmartPointer<vtkPolyData> UnitSquare(int n, bool triangulate, bool doublePoints = false)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(0.0, 0.0, 0.0);
  plane->SetPoint1(1.0, 0.0, 0.0);
  plane->SetPoint2(0.0, 1.0, 0.0);
  plane->SetResolution(n, n);
  if (doublePoints)
  {
    plane->SetOutputPointsPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  if (triangulate)
  {
    vtkNew<vtkTriangleFilter> triangles;
    triangles->SetInputConnection(plane->GetOutputPort());
    triangles->Update();
    mesh->DeepCopy(triangles->GetOutput());
  }
  else
  {
    plane->Update();
    mesh->DeepCopy(plane->GetOutput());
  }
  mesh->GetPointData()->Initialize();
  return mesh;
}

// A mesh file read by the core (gs::ReadMesh) as triangles with double points; null (and the
// reason on stderr) when it cannot be read.
inline vtkSmartPointer<vtkPolyData> ReadPolyData(const std::string& file)
{
  gs::TriangleSoup soup;
  std::string error;
  if (!gs::ReadMesh(file, soup, error))
  {
    std::cerr << file << ": " << error << "\n";
    return nullptr;
  }
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const gs::Vec3& p : soup.Points)
  {
    points->InsertNextPoint(p.x, p.y, p.z);
  }
  vtkNew<vtkCellArray> triangles;
  for (const auto& t : soup.Triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    triangles->InsertNextCell(3, ids);
  }
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->SetPoints(points);
  mesh->SetPolys(triangles);
  return mesh;
}

} // namespace gs_test
