#include "vtkCrossField.h"

#include "vtkDistributedSurface.h"
#include "vtkCachedSurface.h"
#include "vtkSurfacePointLocator.h"

#include "DirectionField.h"
#include "SurfaceCurve.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkCrossField);

// The converted mesh (vtkCachedSurface) and the direction-field solver (with its
// factorizations), kept while the input mesh is unchanged.
struct vtkCrossField::Cache : vtkCachedSurface
{
  std::unique_ptr<gs::DirectionFieldSolver> Solver; // refers to Mesh.Build.Mesh
};

// One Execute's singularities and stroke constraints, and the solved angles, step to step.
struct vtkCrossField::Run
{
  std::vector<gs::VertexSingularity> Singularities; // prescribed, on vertices
  std::vector<gs::FaceDirectionConstraint> Constraints; // from the strokes
  std::vector<double> Angles; // per face, the solve's result
};

namespace
{
// A face a stroke crosses over less than this many mean edge lengths is not constrained.
constexpr double MinimumCrossedLength = 0.1;
}

//------------------------------------------------------------------------------
vtkCrossField::vtkCrossField()
{
  this->SetNumberOfInputPorts(3);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkCrossField::~vtkCrossField() = default;

//------------------------------------------------------------------------------
void vtkCrossField::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Symmetry: " << this->Symmetry << "\n";
  os << indent << "Mode: " << (this->Mode == SMOOTHEST ? "Smoothest" : "Prescribed singularities")
     << "\n";
  os << indent << "CurvatureAlignment: " << this->CurvatureAlignment << "\n";
}

//------------------------------------------------------------------------------
int vtkCrossField::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  if (port == 2)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkCrossField::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  return vtkDistributedSurface::RequestData(this, inputVector, outputVector,
    [this](vtkPolyData* input, const std::vector<vtkPointSet*>& auxiliaries, vtkPolyData* output) {
      return this->Execute(input, auxiliaries[0], vtkPolyData::SafeDownCast(auxiliaries[1]), output);
    });
}

//------------------------------------------------------------------------------
int vtkCrossField::Execute(vtkPolyData* input, vtkPointSet* singularities, vtkPolyData* strokes, vtkPolyData* output)
{
  output->Initialize(); // empty unless everything succeeds
  this->UpdateProgress(0.0);

  // 1. Parameters.
  if (!this->CheckParameters(singularities))
  {
    return 1;
  }
  const int n = this->Symmetry;

  // 2. The core mesh and solver, kept while the input is unchanged.
  Cache& cache = vtkSurfaceMeshConverter::Update(this->MeshCache, input);
  if (!vtkSurfaceMeshConverter::Report(cache.Mesh, this))
  {
    return 1;
  }
  {
    // A field is smoothed across the edges that triangles share: with none (one triangle, a
    // soup of separate triangles) there is nothing to solve, and the solve's system is empty.
    const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
    bool shared = false;
    for (int h = 0; h < mesh.NumberOfHalfedges() && !shared; ++h)
    {
      shared = !mesh.IsBoundaryHalfedge(h);
    }
    if (!shared)
    {
      vtkErrorMacro("Cross Field needs triangles that share edges: the input's "
        << mesh.NumberOfFaces()
        << " triangle(s) share none (a single triangle or separate triangles have no field to "
           "smooth).");
      return 1;
    }
  }
  if (!cache.Solver)
  {
    cache.Solver.reset(new gs::DirectionFieldSolver(cache.Mesh.Build.Mesh));
  }
  gs::DirectionFieldSolver& solver = *cache.Solver;
  this->UpdateProgress(0.1);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 3. Singularities: snapped to the nearest vertex, with their Index.
  Run run;
  if (!this->FindSingularities(cache, singularities, run))
  {
    return 1;
  }

  // 4. Strokes: every line cell, snapped and traced across faces; each piece constrains its face.
  if (!this->ReadStrokes(cache, strokes, run))
  {
    return 1;
  }
  this->UpdateProgress(0.2);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 5. Solve.
  const gs::Status solved = this->Mode == SMOOTHEST
    ? solver.SolveSmoothest(n, this->CurvatureAlignment, run.Constraints, run.Angles)
    : solver.SolvePrescribed(n, run.Singularities, run.Constraints, run.Angles);
  if (!solved.Ok())
  {
    vtkErrorMacro("Cross field: " << solved.Message() << ".");
    return 1;
  }
  this->UpdateProgress(0.8);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 6. Output: the surface with the arrays.
  this->WriteOutput(cache, run, output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
bool vtkCrossField::CheckParameters(vtkPointSet* singularities)
{
  const int n = this->Symmetry;
  if (this->Mode != SMOOTHEST && this->Mode != PRESCRIBED_SINGULARITIES)
  {
    vtkErrorMacro("Unknown Mode " << this->Mode
                                  << ": 0 (Smoothest) or 1 (Prescribed singularities).");
    return false;
  }
  if (this->CurvatureAlignment > 0.0 && (n == 1 || this->Mode != SMOOTHEST))
  {
    vtkWarningMacro("CurvatureAlignment is used by the Smoothest mode with Symmetry 2 or 4 only; "
                    "it is ignored.");
  }
  if (singularities && this->Mode == SMOOTHEST && singularities->GetNumberOfPoints() > 0)
  {
    vtkWarningMacro("The Singularities input is ignored in the Smoothest mode (singularities are "
                    "placed automatically); choose Prescribed singularities to use it.");
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkCrossField::FindSingularities(Cache& cache, vtkPointSet* singularities, Run& run)
{
  std::vector<gs::VertexSingularity>& placed = run.Singularities;
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  if (singularities && this->Mode == PRESCRIBED_SINGULARITIES &&
    singularities->GetNumberOfPoints() > 0)
  {
    vtkDataArray* index = singularities->GetPointData()->GetArray("Index");
    if (!index || index->GetNumberOfComponents() != 1)
    {
      vtkErrorMacro("The Singularities input needs a point array \"Index\" with one component "
                    "(the index of each singularity, a multiple of 1/Symmetry).");
      return false;
    }
    for (vtkIdType i = 0; i < singularities->GetNumberOfPoints(); ++i)
    {
      double x[3];
      singularities->GetPoint(i, x);
      const gs::Result<gs::SurfacePoint> snapped = cache.Locator().Snap(x);
      if (!snapped.Ok())
      {
        vtkErrorMacro("Singularity " << i << ": " << snapped.Message() << ".");
        return false;
      }
      const gs::SurfacePoint& p = *snapped;
      const auto corner = std::max_element(p.Bary.begin(), p.Bary.end());
      const int v = mesh.Face(p.Face)[static_cast<size_t>(corner - p.Bary.begin())];
      placed.push_back({ v, index->GetComponent(i, 0) });
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkCrossField::ReadStrokes(Cache& cache, vtkPolyData* strokes, Run& run)
{
  std::vector<gs::FaceDirectionConstraint>& constraints = run.Constraints;
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  if (strokes && strokes->GetNumberOfLines() > 0)
  {
    auto it = vtk::TakeSmartPointer(strokes->GetLines()->NewIterator());
    vtkIdType cellId = 0;
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cellId)
    {
      vtkIdType npts = 0;
      const vtkIdType* pts = nullptr;
      it->GetCurrentCell(npts, pts);
      const gs::Result<std::vector<gs::SurfacePoint>> snapped =
        cache.SnapCurve(strokes->GetPoints(), npts, pts);
      if (!snapped.Ok())
      {
        vtkErrorMacro("Stroke " << cellId << ": " << snapped.Message() << ".");
        return false;
      }
      const std::vector<gs::SurfacePoint>& curve = *snapped;
      if (curve.size() < 2)
      {
        vtkWarningMacro("Stroke " << cellId << " has fewer than two distinct points on the "
                                             "surface: ignored.");
        continue;
      }
      // The stroke's own points in space (their segments give the faces' directions).
      std::vector<gs::Vec3> polyline;
      for (vtkIdType k = 0; k < npts; ++k)
      {
        double x[3];
        strokes->GetPoints()->GetPoint(pts[k], x);
        polyline.emplace_back(x[0], x[1], x[2]);
      }
      gs::AddStrokeConstraints(
        mesh, curve, polyline, MinimumCrossedLength * mesh.MeanEdgeLength(), constraints);
    }
    if (constraints.empty())
    {
      vtkWarningMacro("The Strokes input crosses no triangle: no direction constraint.");
    }
  }
  else if (strokes && strokes->GetNumberOfPoints() > 0)
  {
    vtkWarningMacro("The Strokes input has no line cell: no direction constraint.");
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkCrossField::WriteOutput(const Cache& cache, const Run& run, vtkPolyData* output)
{
  const std::vector<double>& angles = run.Angles;
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  const std::vector<int>& pointToVertex = cache.Mesh.Build.PointToVertex;
  const gs::DirectionFieldSolver& solver = *cache.Solver;
  const int n = this->Symmetry;
  output->ShallowCopy(cache.Mesh.Surface);
  const vtkIdType numberOfCells = output->GetNumberOfCells();
  const vtkIdType firstPolygon = output->GetNumberOfVerts() + output->GetNumberOfLines();
  vtkNew<vtkDoubleArray> cellDirection;
  cellDirection->SetName("Direction");
  cellDirection->SetNumberOfComponents(3);
  cellDirection->SetNumberOfTuples(numberOfCells);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (vtkIdType c = 0; c < numberOfCells; ++c)
  {
    const vtkIdType f = c - firstPolygon;
    if (f >= 0 && f < mesh.NumberOfFaces())
    {
      const gs::Vec3 d = solver.DirectionInFace(static_cast<int>(f), angles[f]);
      cellDirection->SetTuple3(c, d.x, d.y, d.z);
    }
    else
    {
      cellDirection->SetTuple3(c, nan, nan, nan);
    }
  }
  output->GetCellData()->AddArray(cellDirection);
  output->GetCellData()->SetActiveVectors("Direction");

  const int nv = mesh.NumberOfVertices();
  const std::vector<gs::Vec3> vertexDirection = solver.VertexDirections(n, angles);
  const std::vector<double> rawIndex = solver.VertexIndices(n, angles);
  std::vector<double> index(nv);
  for (int v = 0; v < nv; ++v)
  {
    index[v] = std::round(rawIndex[v] * n) / n; // boundary vertices: their turning, rounded
  }
  const double sum = solver.IndexSum(n, angles);

  const vtkIdType numberOfPoints = output->GetNumberOfPoints();
  vtkNew<vtkDoubleArray> pointDirection;
  pointDirection->SetName("Direction");
  pointDirection->SetNumberOfComponents(3);
  pointDirection->SetNumberOfTuples(numberOfPoints);
  vtkNew<vtkDoubleArray> pointIndex;
  pointIndex->SetName("SingularityIndex");
  pointIndex->SetNumberOfTuples(numberOfPoints);
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    const int v = i < static_cast<vtkIdType>(pointToVertex.size()) ? pointToVertex[i] : -1;
    if (v < 0)
    {
      pointDirection->SetTuple3(i, nan, nan, nan);
      pointIndex->SetValue(i, 0.0);
      continue;
    }
    pointDirection->SetTuple3(i, vertexDirection[v].x, vertexDirection[v].y, vertexDirection[v].z);
    pointIndex->SetValue(i, index[v]);
  }
  output->GetPointData()->AddArray(pointDirection);
  output->GetPointData()->AddArray(pointIndex);
  output->GetPointData()->SetActiveScalars("SingularityIndex");

  vtkNew<vtkIntArray> euler;
  euler->SetName("EulerCharacteristic");
  euler->InsertNextValue(mesh.EulerCharacteristic());
  output->GetFieldData()->AddArray(euler);
  vtkNew<vtkIntArray> symmetry;
  symmetry->SetName("Symmetry");
  symmetry->InsertNextValue(n);
  output->GetFieldData()->AddArray(symmetry);
  vtkNew<vtkDoubleArray> indexSum;
  indexSum->SetName("SingularityIndexSum");
  indexSum->InsertNextValue(sum);
  output->GetFieldData()->AddArray(indexSum);
}
