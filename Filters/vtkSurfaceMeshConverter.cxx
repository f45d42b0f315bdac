#include "vtkSurfaceMeshConverter.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkIdList.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSetGet.h>
#include <vtkTriangleFilter.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <initializer_list>
#include <sstream>
#include <utility>

vtkSurfaceMeshConverter::Result vtkSurfaceMeshConverter::Convert(vtkPolyData* input)
{
  Result result;
  if (!input || input->GetNumberOfPoints() == 0)
  {
    result.Status = gs::Status::Error("the input mesh is empty (no points)");
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
    result.Status = gs::Status::Error(msg.str());
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
    result.Triangulated = true;
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
    result.Status = gs::Status::Error(msg.str());
    return result;
  }

  gs::Result<gs::MeshBuild> built = gs::TriangleMeshBuilder::Build(positions, triangles);
  if (!built.Ok())
  {
    result.Status = built;
    return result;
  }
  result.Build = std::move(*built);
  for (const std::string& w : result.Build.Warnings)
  {
    result.Warnings.push_back(w);
  }
  result.Status = gs::Status();
  return result;
}

namespace
{
vtkMTimeType Latest(std::initializer_list<vtkObject*> parts)
{
  vtkMTimeType t = 0;
  for (vtkObject* part : parts)
  {
    if (part)
    {
      t = std::max(t, part->GetMTime());
    }
  }
  return t;
}
} // namespace

vtkMTimeType vtkSurfaceMeshConverter::GeometryTime(vtkPolyData* input)
{
  return input ? Latest({ input->GetPoints(), input->GetVerts(), input->GetLines(), input->GetPolys(),
                   input->GetStrips() })
               : 0;
}

vtkMTimeType vtkSurfaceMeshConverter::AttributeTime(vtkPolyData* input)
{
  return input ? Latest({ input->GetPointData(), input->GetCellData(), input->GetFieldData() }) : 0;
}

std::uint64_t vtkSurfaceMeshConverter::ContentHash(vtkPolyData* input)
{
  // FNV-1a over 64-bit words of the point coordinates and the cell arrays (a few ms for a
  // million triangles; the conversion it saves takes a hundred times longer).
  std::uint64_t h = 1469598103934665603ull;
  auto words = [&h](const void* data, std::size_t bytes) {
    const unsigned char* p = static_cast<const unsigned char*>(data);
    std::size_t k = 0;
    for (; k + 8 <= bytes; k += 8)
    {
      std::uint64_t w;
      std::memcpy(&w, p + k, 8);
      h = (h ^ w) * 1099511628211ull;
    }
    for (; k < bytes; ++k)
    {
      h = (h ^ p[k]) * 1099511628211ull;
    }
  };
  auto array = [&](vtkDataArray* a) {
    if (!a)
    {
      words("-", 1);
      return;
    }
    const vtkIdType n = a->GetNumberOfValues();
    words(&n, sizeof(n));
    if (a->HasStandardMemoryLayout())
    {
      words(a->GetVoidPointer(0), static_cast<std::size_t>(n) * a->GetDataTypeSize());
    }
    else
    {
      for (vtkIdType i = 0; i < n; ++i)
      {
        const double v = a->GetComponent(i / a->GetNumberOfComponents(), static_cast<int>(i % a->GetNumberOfComponents()));
        words(&v, sizeof(v));
      }
    }
  };
  if (!input)
  {
    return h;
  }
  array(input->GetPoints() ? input->GetPoints()->GetData() : nullptr);
  for (vtkCellArray* cells : { input->GetVerts(), input->GetLines(), input->GetPolys(), input->GetStrips() })
  {
    array(cells ? cells->GetOffsetsArray() : nullptr);
    array(cells ? cells->GetConnectivityArray() : nullptr);
  }
  return h;
}

void vtkSurfaceMeshConverter::TakeAttributes(Result& mesh, vtkPolyData* input)
{
  if (mesh.Surface && input)
  {
    mesh.Surface->GetPointData()->ShallowCopy(input->GetPointData());
    mesh.Surface->GetCellData()->ShallowCopy(input->GetCellData());
    mesh.Surface->GetFieldData()->ShallowCopy(input->GetFieldData());
  }
}

bool vtkSurfaceMeshConverter::Report(const Result& result, vtkObject* algorithm)
{
  for (const std::string& warning : result.Warnings)
  {
    vtkWarningWithObjectMacro(algorithm, "Input mesh: " << warning);
  }
  if (!result.Status.Ok())
  {
    vtkErrorWithObjectMacro(algorithm, "Invalid input mesh: " << result.Status.Message());
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
std::vector<double> vtkSurfaceMeshConverter::PointArrayOnVertices(
  vtkDataArray* a, const gs::MeshBuild& build, double fill)
{
  const int components = a->GetNumberOfComponents();
  const std::vector<int>& pointToVertex = build.PointToVertex;
  std::vector<double> values(
    static_cast<std::size_t>(build.Mesh.NumberOfVertices()) * components, fill);
  const vtkIdType n =
    std::min(a->GetNumberOfTuples(), static_cast<vtkIdType>(pointToVertex.size()));
  for (vtkIdType i = 0; i < n; ++i)
  {
    const int v = pointToVertex[i];
    if (v >= 0)
    {
      for (int c = 0; c < components; ++c)
      {
        values[static_cast<std::size_t>(v) * components + c] = a->GetComponent(i, c);
      }
    }
  }
  return values;
}
