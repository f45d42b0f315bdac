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
  const int n = this->Symmetry;
  if (n != 1 && n != 2 && n != 4)
  {
    vtkErrorMacro("Symmetry must be 1 (vector field), 2 (line field) or 4 (cross field); it is "
      << n << ".");
    return 1;
  }
  if (this->Mode != SMOOTHEST && this->Mode != PRESCRIBED_SINGULARITIES)
  {
    vtkErrorMacro("Unknown Mode " << this->Mode
                                  << ": 0 (Smoothest) or 1 (Prescribed singularities).");
    return 1;
  }
  if (!(this->CurvatureAlignment >= 0.0) || !std::isfinite(this->CurvatureAlignment))
  {
    vtkErrorMacro("CurvatureAlignment must be finite and >= 0 (it is "
      << this->CurvatureAlignment << ").");
    return 1;
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

  // 2. The core mesh and solver, kept while the input is unchanged.
  Cache& cache = vtkSurfaceMeshConverter::Update(this->MeshCache, input);
  if (!vtkSurfaceMeshConverter::Report(cache.Mesh, this))
  {
    return 1;
  }
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  const std::vector<int>& pointToVertex = cache.Mesh.Build.PointToVertex;
  if (!cache.Solver)
  {
    cache.Solver.reset(new gs::DirectionFieldSolver(mesh));
  }
  gs::DirectionFieldSolver& solver = *cache.Solver;
  this->UpdateProgress(0.1);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 3. Singularities: snapped to the nearest vertex, with their Index.
  std::vector<gs::VertexSingularity> placed;
  if (singularities && this->Mode == PRESCRIBED_SINGULARITIES &&
    singularities->GetNumberOfPoints() > 0)
  {
    vtkDataArray* index = singularities->GetPointData()->GetArray("Index");
    if (!index || index->GetNumberOfComponents() != 1)
    {
      vtkErrorMacro("The Singularities input needs a point array \"Index\" with one component "
                    "(the index of each singularity, a multiple of 1/Symmetry).");
      return 1;
    }
    for (vtkIdType i = 0; i < singularities->GetNumberOfPoints(); ++i)
    {
      double x[3];
      singularities->GetPoint(i, x);
      gs::SurfacePoint p;
      std::string reason;
      if (!cache.Locator().Snap(x, p, reason))
      {
        vtkErrorMacro("Singularity " << i << ": " << reason << ".");
        return 1;
      }
      const auto corner = std::max_element(p.Bary.begin(), p.Bary.end());
      const int v = mesh.Face(p.Face)[static_cast<size_t>(corner - p.Bary.begin())];
      placed.push_back({ v, index->GetComponent(i, 0) });
    }
  }
  else if (this->Mode == PRESCRIBED_SINGULARITIES && mesh.EulerCharacteristic() != 0 &&
    mesh.BoundaryLoops().empty())
  {
    vtkErrorMacro("The Prescribed singularities mode needs singularities whose indices sum to the "
                  "Euler characteristic "
      << mesh.EulerCharacteristic()
      << ": connect a Singularities input (points with a point array \"Index\").");
    return 1;
  }

  // 4. Strokes: every line cell, snapped and traced across faces; each piece constrains its face.
  std::vector<gs::FaceDirectionConstraint> constraints;
  if (strokes && strokes->GetNumberOfLines() > 0)
  {
    auto it = vtk::TakeSmartPointer(strokes->GetLines()->NewIterator());
    vtkIdType cellId = 0;
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cellId)
    {
      vtkIdType npts = 0;
      const vtkIdType* pts = nullptr;
      it->GetCurrentCell(npts, pts);
      std::vector<gs::SurfacePoint> curve;
      std::string reason;
      if (!cache.SnapCurve(strokes->GetPoints(), npts, pts, curve, reason))
      {
        vtkErrorMacro("Stroke " << cellId << ": " << reason << ".");
        return 1;
      }
      if (curve.size() < 2)
      {
        vtkWarningMacro("Stroke " << cellId << " has fewer than two distinct points on the "
                                             "surface: ignored.");
        continue;
      }
      // The stroke's own segments in space: each crossed face takes the direction of the
      // segment closest to the piece inside it, projected onto the face (the traced pieces
      // bend where the path is re-aimed near vertices; their direction is not used).
      std::vector<gs::Vec3> polyline;
      for (vtkIdType k = 0; k < npts; ++k)
      {
        double x[3];
        strokes->GetPoints()->GetPoint(pts[k], x);
        polyline.emplace_back(x[0], x[1], x[2]);
      }
      auto segmentDirection = [&](const gs::Vec3& m) {
        double best = std::numeric_limits<double>::infinity();
        gs::Vec3 direction(0, 0, 0);
        for (size_t k = 0; k + 1 < polyline.size(); ++k)
        {
          const gs::Vec3 a = polyline[k], ab = polyline[k + 1] - polyline[k];
          const double l2 = gs::Dot(ab, ab);
          if (!(l2 > 0))
          {
            continue;
          }
          const double t = std::min(1.0, std::max(0.0, gs::Dot(m - a, ab) / l2));
          const double d = gs::Norm(a + ab * t - m);
          if (d < best)
          {
            best = d;
            direction = ab;
          }
        }
        return direction;
      };
      // Faces crossed over less than this length are not constrained (a stroke through a vertex
      // grazes the faces around it).
      const double minimumLength = MinimumCrossedLength * mesh.MeanEdgeLength();
      std::vector<std::pair<int, double>> crossed; // face, length inside, in stroke order
      std::vector<gs::Vec3> middles;
      for (const gs::CurvePiece& piece : gs::TraceSurfaceCurve(mesh, curve))
      {
        const double l = gs::Norm(piece.B - piece.A);
        if (!crossed.empty() && crossed.back().first == piece.Face)
        {
          crossed.back().second += l;
          continue;
        }
        crossed.emplace_back(piece.Face, l);
        middles.push_back((piece.A + piece.B) * 0.5);
      }
      for (size_t k = 0; k < crossed.size(); ++k)
      {
        if (crossed[k].second < minimumLength)
        {
          continue;
        }
        const gs::Vec3 d = segmentDirection(middles[k]);
        const gs::Vec3 normal = mesh.FaceNormal(crossed[k].first);
        const gs::Vec3 tangent = d - normal * gs::Dot(d, normal);
        if (gs::Norm(tangent) > 1e-9 * gs::Norm(d))
        {
          constraints.push_back({ crossed[k].first, tangent });
        }
      }
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
  this->UpdateProgress(0.2);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 5. Solve.
  std::vector<double> angles;
  std::string error;
  const bool ok = this->Mode == SMOOTHEST
    ? solver.SolveSmoothest(n, this->CurvatureAlignment, constraints, angles, error)
    : solver.SolvePrescribed(n, placed, constraints, angles, error);
  if (!ok)
  {
    vtkErrorMacro("Cross field: " << error << ".");
    return 1;
  }
  this->UpdateProgress(0.8);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 6. Output: the surface with the arrays.
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
  this->UpdateProgress(1.0);
  return 1;
}
