#include "vtkSurfaceMeshConverter.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSetGet.h>
#include <vtkTriangleFilter.h>

#include <array>
#include <sstream>

vtkSurfaceMeshConverter::Result vtkSurfaceMeshConverter::Convert(vtkPolyData* input)
{
  Result result;
  if (!input || input->GetNumberOfPoints() == 0)
  {
    result.Error = "the input mesh is empty (no points)";
    return result;
  }

  // Do we need a triangulation? Only polygons with more than three points and strips need it.
  vtkIdType numberOfPolygons = 0;
  vtkIdType numberOfLargePolygons = 0;
  vtkIdType numberOfSmallPolygons = 0;
  {
    auto it = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
    vtkIdType npts;
    const vtkIdType* pts;
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      it->GetCurrentCell(npts, pts);
      ++numberOfPolygons;
      if (npts > 3)
      {
        ++numberOfLargePolygons;
      }
      else if (npts < 3)
      {
        ++numberOfSmallPolygons;
      }
    }
  }
  const vtkIdType numberOfStrips = input->GetNumberOfStrips();
  if (numberOfSmallPolygons > 0)
  {
    std::ostringstream msg;
    msg << numberOfSmallPolygons << " polygon(s) have fewer than 3 points (degenerate)";
    result.Error = msg.str();
    return result;
  }

  if (numberOfLargePolygons > 0 || numberOfStrips > 0)
  {
    vtkNew<vtkTriangleFilter> triangulate;
    triangulate->SetInputData(input);
    triangulate->PassVertsOff();
    triangulate->PassLinesOff();
    triangulate->Update();
    result.Surface = vtkSmartPointer<vtkPolyData>::New();
    result.Surface->ShallowCopy(triangulate->GetOutput());
    std::ostringstream msg;
    msg << "the input was triangulated (" << numberOfLargePolygons
        << " polygon(s) with more than 3 points, " << numberOfStrips
        << " triangle strip(s)); the output holds the triangles";
    result.Warnings.push_back(msg.str());
  }
  else
  {
    result.Surface = vtkSmartPointer<vtkPolyData>::New();
    result.Surface->ShallowCopy(input);
  }

  // Gather points and triangles; Triangles shares Surface's points and holds only its polygons.
  vtkPoints* points = result.Surface->GetPoints();
  const vtkIdType numberOfPoints = points ? points->GetNumberOfPoints() : 0;
  std::vector<gs::Vec3> positions(static_cast<size_t>(numberOfPoints));
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    positions[static_cast<size_t>(i)] = gs::Vec3(p[0], p[1], p[2]);
  }
  std::vector<std::array<long long, 3>> triangles;
  triangles.reserve(static_cast<size_t>(result.Surface->GetNumberOfPolys()));
  {
    auto it = vtk::TakeSmartPointer(result.Surface->GetPolys()->NewIterator());
    vtkIdType npts;
    const vtkIdType* pts;
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      it->GetCurrentCell(npts, pts);
      if (npts == 3)
      {
        triangles.push_back({ { pts[0], pts[1], pts[2] } });
      }
    }
  }
  result.Triangles = vtkSmartPointer<vtkPolyData>::New();
  result.Triangles->SetPoints(points);
  result.Triangles->SetPolys(result.Surface->GetPolys());

  if (triangles.empty())
  {
    std::ostringstream msg;
    msg << "the input mesh has no triangles or polygons (" << numberOfPoints << " points, "
        << input->GetNumberOfVerts() << " vertex cells, " << input->GetNumberOfLines()
        << " line cells; vertices and lines are ignored)";
    result.Error = msg.str();
    return result;
  }

  result.Build = gs::TriangleMeshBuilder::Build(positions, triangles);
  for (const std::string& w : result.Build.Warnings)
  {
    result.Warnings.push_back(w);
  }
  if (!result.Build.Ok)
  {
    result.Error = result.Build.Error.empty() ? "invalid mesh" : result.Build.Error;
    return result;
  }
  result.Ok = true;
  return result;
}

bool vtkSurfaceMeshConverter::IsCurrent(const Cached& cache, vtkPolyData* input)
{
  return cache.Input == input && input && cache.InputTime == input->GetMTime();
}

vtkMTimeType vtkSurfaceMeshConverter::InputTime(vtkPolyData* input)
{
  return input ? input->GetMTime() : 0;
}

bool vtkSurfaceMeshConverter::Report(const Result& result, vtkObject* algorithm)
{
  for (const std::string& warning : result.Warnings)
  {
    vtkWarningWithObjectMacro(algorithm, "Input mesh: " << warning);
  }
  if (!result.Ok)
  {
    vtkErrorWithObjectMacro(algorithm, "Invalid input mesh: " << result.Error);
    return false;
  }
  return true;
}
