#include "vtkGeodesicPolarCoordinates.h"

#include "vtkCachedSurface.h"
#include "vtkDistributedSurface.h"
#include "vtkSurfacePieces.h"
#include "vtkSurfacePointLocator.h"

#include "GeodesicPolarCoordinates.h"
#include "GeodesicShooting.h"
#include "SurfacePoint.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
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

vtkStandardNewMacro(vtkGeodesicPolarCoordinates);

// The converted mesh and what is derived from it (vtkCachedSurface), kept while the input mesh
// is unchanged, so that changing only the source, the radius or the reference direction does
// not convert the mesh again, and the engine over it.
struct vtkGeodesicPolarCoordinates::Cache : vtkCachedSurface
{
  std::unique_ptr<gs::GeodesicPolarCoordinates> Polar; // over Mesh.Build.Mesh and Graph()
};

// One Execute's source and results, step to step.
struct vtkGeodesicPolarCoordinates::Run
{
  bool CurveSource = false;            // the Source input has line cells
  gs::SurfacePoint Point;              // a point source (snapped, or SourceVertexId)
  std::vector<gs::SurfacePoint> Curve; // a curve source, snapped
  double ReferenceAngle = 0.0;         // theta's zero, a tangent angle at Point
};

namespace
{
// A snapped point this close to a corner (in barycentric weight) is that vertex: the source then
// has the vertex's angle sum and first edge, as with SourceVertexId.
constexpr double VertexSnapTolerance = 1e-12;
// Mapping to input points checks for abort every this many points.
constexpr size_t AbortCheckInterval = 1 << 14;
}

//------------------------------------------------------------------------------
vtkGeodesicPolarCoordinates::vtkGeodesicPolarCoordinates()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(1);
}

//------------------------------------------------------------------------------
vtkGeodesicPolarCoordinates::~vtkGeodesicPolarCoordinates() = default;

//------------------------------------------------------------------------------
const char* vtkGeodesicPolarCoordinates::GetAngleModeName(int mode)
{
  switch (mode)
  {
    case GEODESIC_DIRECTION:
      return "Geodesic direction";
    case ISO_CURVE_ARC_LENGTH:
      return "Iso-curve arc length";
    default:
      return "unknown";
  }
}

//------------------------------------------------------------------------------
int vtkGeodesicPolarCoordinates::FillInputPortInformation(int port, vtkInformation* info)
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
  return 0;
}

//------------------------------------------------------------------------------
int vtkGeodesicPolarCoordinates::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Under MPI, the exact chart about SourceVertexId or a point of the Source input (either angle
  // mode; iso-curve angles within a finite radius), or the curve coordinates about its first
  // line cell (a finite radius), are computed on the pieces when they hold triangles only (the
  // same decision on every process: it depends on properties, on the Source input's cells and
  // on CanUse, which is collective); everything else gathers.
  const vtkDistributedSurface distributed(outputVector->GetInformationObject(0));
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (distributed && input && output && this->Solver == EXACT)
  {
    const bool sourcePort = inputVector[1]->GetNumberOfInformationObjects() > 0;
    vtkSmartPointer<vtkPolyData> all = sourcePort
      ? distributed.GatherAuxiliaryEverywhere(vtkPointSet::GetData(inputVector[1], 0))
      : nullptr;
    // (With line cells, a curve source: its first polyline, the points unused, as serially.)
    std::vector<double> xyz;
    vtkSmartPointer<vtkPolyData> curves;
    if (all)
    {
      vtkDistributedSurface::SplitPointsAndCurves(all, xyz, curves);
    }
    const bool curve = curves != nullptr;
    const bool pieces = curve ? std::isfinite(this->Radius)
                              : this->AngleMode == GEODESIC_DIRECTION ||
        (this->AngleMode == ISO_CURVE_ARC_LENGTH && std::isfinite(this->Radius));
    vtkSmartPointer<vtkPolyData> own =
      pieces ? vtkSurfacePieces::OwnCellsInPlace(this, distributed, this->Pieces, input) : nullptr;
    if (own)
    {
      return this->ExecutePieces(
        input, own, output, sourcePort ? &xyz : nullptr, curves.Get());
    }
  }
  return vtkDistributedSurface::RequestData(this, inputVector, outputVector,
    [this](vtkPolyData* whole, const std::vector<vtkPointSet*>& auxiliaries, vtkPolyData* result) {
      return this->Execute(whole, auxiliaries[0], result);
    });
}

//------------------------------------------------------------------------------
int vtkGeodesicPolarCoordinates::ExecutePieces(vtkPolyData* input, vtkPolyData* own,
  vtkPolyData* output, const std::vector<double>* sourceXyz, vtkPolyData* curve)
{
  output->Initialize(); // empty unless everything succeeds
  this->UpdateProgress(0.0);
  std::vector<double> rho, theta;
  gs::PiecePolarCoordinates chart;
  if (curve)
  {
    // The first line cell, as serially.
    if (curve->GetNumberOfLines() > 1)
    {
      vtkWarningMacro("The Source input has " << curve->GetNumberOfLines()
                                              << " line cells: only the first one is used.");
    }
    const bool referenceSet = this->ReferenceDirection[0] != 0.0 ||
      this->ReferenceDirection[1] != 0.0 || this->ReferenceDirection[2] != 0.0;
    if (referenceSet || this->AngleMode != GEODESIC_DIRECTION)
    {
      vtkWarningMacro("Curve source: ReferenceDirection, AngleMode and Solver apply to point "
                      "sources only and are ignored (offset and arc length from exact geodesics).");
    }
    vtkNew<vtkPolyData> first;
    first->SetPoints(curve->GetPoints());
    vtkNew<vtkCellArray> line;
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    auto it = vtk::TakeSmartPointer(curve->GetLines()->NewIterator());
    it->GoToFirstCell();
    it->GetCurrentCell(npts, pts);
    line->InsertNextCell(npts, pts);
    first->SetLines(line);
    if (!this->CheckParameters() || !this->Pieces->UsePiece(this, own, input->GetMTime()) ||
      !this->Pieces->PolarCurve(this, own, first, this->Radius, rho, theta, chart))
    {
      return 1;
    }
    return this->WritePieceOutput(own, output, rho, theta, chart, true);
  }
  // The Source input's points (every process has them all), as serially: the first one.
  std::vector<gs::Vec3> points;
  for (std::size_t i = 0; sourceXyz && i + 2 < sourceXyz->size(); i += 3)
  {
    points.emplace_back((*sourceXyz)[i], (*sourceXyz)[i + 1], (*sourceXyz)[i + 2]);
  }
  if (sourceXyz && points.empty())
  {
    vtkErrorMacro("The Source input has no point.");
    return 1;
  }
  if (points.size() > 1)
  {
    vtkWarningMacro("The Source input has " << points.size() << " points: only the first one is used.");
  }
  // (CheckParameters: the same outcome on every process.)
  if (!this->CheckParameters() || !this->Pieces->UsePiece(this, own, input->GetMTime()) ||
    !this->Pieces->Polar(this, own, this->SourceVertexId, points, this->Radius,
      this->ReferenceDirection, this->AngleMode == ISO_CURVE_ARC_LENGTH, rho, theta, chart))
  {
    return 1;
  }
  if (chart.ReferenceNormal)
  {
    this->WarnReferenceNormal();
  }
  this->WarnIsoCurveKept(chart.IsoCurveKept);
  return this->WritePieceOutput(own, output, rho, theta, chart, false);
}

//------------------------------------------------------------------------------
int vtkGeodesicPolarCoordinates::WritePieceOutput(vtkPolyData* own, vtkPolyData* output,
  const std::vector<double>& rho, const std::vector<double>& theta,
  const gs::PiecePolarCoordinates& chart, bool curve)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const vtkIdType n = static_cast<vtkIdType>(rho.size());
  vtkNew<vtkDoubleArray> rhoArray, thetaArray, decal;
  rhoArray->SetName(curve ? "Offset" : "GeodesicDistance");
  rhoArray->SetNumberOfTuples(n);
  thetaArray->SetName(curve ? "ArcLength" : "PolarAngle");
  thetaArray->SetNumberOfTuples(n);
  decal->SetName("DecalCoordinates");
  decal->SetNumberOfComponents(2);
  decal->SetNumberOfTuples(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    double r = rho[static_cast<std::size_t>(i)], t = theta[static_cast<std::size_t>(i)];
    if (!std::isfinite(r) || std::abs(r) > this->Radius || !std::isfinite(t))
    {
      r = t = nan;
    }
    rhoArray->SetValue(i, r);
    thetaArray->SetValue(i, t);
    // As WriteOutput: a curve's (u, delta) band of width DecalSize -> [0, 1]; a point's square of
    // side DecalSize centred on the source -> [0, 1]^2 (NaN stays NaN).
    decal->SetTypedComponent(i, 0, curve ? t : r * std::cos(t) / this->DecalSize + 0.5);
    decal->SetTypedComponent(i, 1, curve ? r / this->DecalSize + 0.5 : r * std::sin(t) / this->DecalSize + 0.5);
  }
  SetOutputArrays(output, own, rhoArray, thetaArray, decal);
  vtkNew<vtkFieldData> fieldData;
  fieldData->ShallowCopy(own->GetFieldData());
  vtkNew<vtkDoubleArray> sum;
  sum->SetName(curve ? "CurveLength" : "SourceAngleSum");
  sum->InsertNextValue(curve ? chart.CurveLength : chart.SourceAngleSum);
  fieldData->AddArray(sum);
  // What this process held, and the chart's process (the band grew where the chart needed).
  for (const auto& value : { std::make_pair("PieceFaces", this->Pieces->Piece().Mesh().NumberOfFaces()),
         std::make_pair("PieceChartFaces", chart.ChartFaces) })
  {
    vtkNew<vtkIntArray> a;
    a->SetName(value.first);
    a->InsertNextValue(value.second);
    fieldData->AddArray(a);
  }
  output->SetFieldData(fieldData);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkGeodesicPolarCoordinates::Execute(vtkPolyData* input, vtkPointSet* source, vtkPolyData* output)
{
  output->Initialize(); // empty unless everything succeeds
  this->UpdateProgress(0.0);

  // 1. Parameters.
  if (!this->CheckParameters())
  {
    return 1;
  }
  // A Source with line cells is a curve source: its first polyline.
  vtkPolyData* polySource = vtkPolyData::SafeDownCast(source);
  Run run;
  run.CurveSource = polySource && polySource->GetNumberOfLines() > 0;
  if (source && source->GetNumberOfPoints() == 0)
  {
    vtkErrorMacro("The Source input has no point.");
    return 1;
  }

  // 2. The core mesh, converted once while the input is unchanged.
  Cache& cache = vtkSurfaceMeshConverter::Update(this->MeshCache, input);
  if (!vtkSurfaceMeshConverter::Report(cache.Mesh, this))
  {
    return 1;
  }
  this->UpdateProgress(0.2);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 3. The source: the first polyline of port 1 (a curve), its first point, or SourceVertexId;
  //    snapped to the surface.
  if (!this->FindSource(cache, source, run))
  {
    return 1;
  }

  // 4. Theta's zero as a tangent angle at the source.
  this->ResolveReferenceAngle(cache, run);

  // 5. Solve: exact geodesics truncated at the radius (Solver EXACT), or on a geodesic graph
  //    from the process-wide cache (built with progress 0.3 .. 0.7 when new): the saddle vertex
  //    graph of K, or the discrete geodesic graph of K and GraphAccuracy.
  if (!this->Solve(cache, run))
  {
    return 1;
  }
  this->UpdateProgress(0.8);
  if (this->CheckAbort())
  {
    return 1;
  }

  // 6. Map back to every input point (welded points share their vertex's coordinates).
  return this->WriteOutput(cache, run, output);
}

//------------------------------------------------------------------------------
bool vtkGeodesicPolarCoordinates::CheckParameters()
{
  if (this->AngleMode != GEODESIC_DIRECTION && this->AngleMode != ISO_CURVE_ARC_LENGTH)
  {
    vtkErrorMacro("Unknown AngleMode " << this->AngleMode
                                       << ": 0 (Geodesic direction) or 1 (Iso-curve arc length).");
    return false;
  }
  // (Radius first: a numpy caller's DecalSize defaults to twice the radius.)
  if (!(this->Radius > 0.0))
  {
    vtkErrorMacro("Radius must be > 0 (0, negative or NaN is an error; infinity means the whole "
                  "reachable surface); it is "
      << this->Radius << ".");
    return false;
  }
  if (!(this->DecalSize > 0.0) || !std::isfinite(this->DecalSize))
  {
    vtkErrorMacro("DecalSize must be finite and > 0 (it is " << this->DecalSize << ").");
    return false;
  }
  const double* reference = this->ReferenceDirection;
  if (!std::isfinite(reference[0]) || !std::isfinite(reference[1]) ||
    !std::isfinite(reference[2]))
  {
    vtkErrorMacro("ReferenceDirection (" << reference[0] << ", " << reference[1] << ", "
                                         << reference[2] << ") is not finite.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkGeodesicPolarCoordinates::FindSource(Cache& cache, vtkPointSet* source, Run& run)
{
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  vtkPolyData* polySource = vtkPolyData::SafeDownCast(source);
  std::vector<gs::SurfacePoint>& curve = run.Curve;
  gs::SurfacePoint& sourcePoint = run.Point;
  if (run.CurveSource)
  {
    if (polySource->GetNumberOfLines() > 1)
    {
      vtkWarningMacro("The Source input has " << polySource->GetNumberOfLines()
                                              << " line cells: only the first one is used.");
    }
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    auto it = vtk::TakeSmartPointer(polySource->GetLines()->NewIterator());
    it->GoToFirstCell();
    it->GetCurrentCell(npts, pts);
    gs::Result<std::vector<gs::SurfacePoint>> snapped =
      cache.SnapCurve(polySource->GetPoints(), npts, pts);
    if (!snapped.Ok())
    {
      vtkErrorMacro("Source curve: " << snapped.Message() << ".");
      return false;
    }
    curve = std::move(*snapped);
    if (curve.size() < 2)
    {
      vtkErrorMacro("The Source curve has fewer than two distinct points on the surface.");
      return false;
    }
    // Curve coordinates are (u, delta) from exact geodesics: say so when a setting is ignored.
    const bool referenceSet = this->ReferenceDirection[0] != 0.0 ||
      this->ReferenceDirection[1] != 0.0 || this->ReferenceDirection[2] != 0.0;
    if (referenceSet || this->AngleMode != GEODESIC_DIRECTION || this->Solver != EXACT)
    {
      vtkWarningMacro("Curve source: ReferenceDirection, AngleMode and Solver apply to point "
                      "sources only and are ignored (offset and arc length from exact geodesics).");
    }
  }
  else if (source)
  {
    if (source->GetNumberOfPoints() > 1)
    {
      vtkWarningMacro("The Source input has " << source->GetNumberOfPoints()
                                              << " points: only the first one is used.");
    }
    double x[3];
    source->GetPoint(0, x);
    const gs::Result<gs::SurfacePoint> snapped = cache.Locator().Snap(x);
    if (!snapped.Ok())
    {
      vtkErrorMacro("Source point 0: " << snapped.Message() << ".");
      return false;
    }
    sourcePoint = *snapped;
    const auto corner = std::max_element(sourcePoint.Bary.begin(), sourcePoint.Bary.end());
    if (*corner >= 1.0 - VertexSnapTolerance)
    {
      sourcePoint = gs::SurfacePoint::AtVertex(
        mesh.Face(sourcePoint.Face)[static_cast<size_t>(corner - sourcePoint.Bary.begin())]);
    }
  }
  else
  {
    const gs::Result<int> v = cache.VertexOfPoint(this->SourceVertexId);
    if (!v.Ok())
    {
      vtkErrorMacro("SourceVertexId " << v.Message() << ".");
      return false;
    }
    sourcePoint = gs::SurfacePoint::AtVertex(*v);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkGeodesicPolarCoordinates::ResolveReferenceAngle(const Cache& cache, Run& run)
{
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  const gs::SurfacePoint& sourcePoint = run.Point;
  const double* reference = this->ReferenceDirection;
  const bool firstEdgeReference =
    reference[0] == 0.0 && reference[1] == 0.0 && reference[2] == 0.0;
  double& referenceAngle = run.ReferenceAngle;
  referenceAngle = 0.0;
  if (!firstEdgeReference && !run.CurveSource)
  {
    const double angle = gs::TangentAngle(
      mesh, sourcePoint, gs::Vec3(reference[0], reference[1], reference[2]));
    if (std::isfinite(angle))
    {
      referenceAngle = angle;
    }
    else
    {
      this->WarnReferenceNormal();
    }
  }
}

//------------------------------------------------------------------------------
void vtkGeodesicPolarCoordinates::SetOutputArrays(vtkPolyData* output, vtkPolyData* surface,
  vtkDoubleArray* rho, vtkDoubleArray* theta, vtkDoubleArray* decal)
{
  output->ShallowCopy(surface);
  vtkPointData* pointData = output->GetPointData();
  pointData->AddArray(rho);
  pointData->AddArray(theta);
  pointData->SetActiveScalars(rho->GetName());
  pointData->SetTCoords(decal);
}

//------------------------------------------------------------------------------
void vtkGeodesicPolarCoordinates::WarnReferenceNormal()
{
  const double* reference = this->ReferenceDirection;
  vtkWarningMacro("ReferenceDirection (" << reference[0] << ", " << reference[1] << ", "
                                         << reference[2]
                                         << ") is normal to the surface at the source: "
                                            "using the source's first edge instead.");
}

//------------------------------------------------------------------------------
bool vtkGeodesicPolarCoordinates::Solve(Cache& cache, Run& run)
{
  const gs::TriangleMesh& mesh = cache.Mesh.Build.Mesh;
  if (!vtkCachedSurface::CheckEngine(this, this->Solver,
        { gs::GeodesicSolver::Exact, gs::GeodesicSolver::SVGLabelCorrecting, gs::GeodesicSolver::DGG },
        this->K))
  {
    return false;
  }
  bool graphChanged = false;
  if (!cache.UseEngineGraph(this, this->Solver, this->K, this->GraphAccuracy, std::string(), 0.3,
        0.4, graphChanged))
  {
    return false; // aborted, or the error is reported
  }
  if (!cache.Polar || graphChanged)
  {
    cache.Polar.reset();
    cache.Polar.reset(new gs::GeodesicPolarCoordinates(mesh, cache.Graph()));
  }
  gs::GeodesicPolarCoordinates& polar = *cache.Polar;
  const gs::Status solved = run.CurveSource
    ? polar.ComputeCurve(run.Curve, this->Radius)
    : polar.Compute(run.Point, this->Radius, run.ReferenceAngle);
  if (!solved.Ok())
  {
    vtkErrorMacro("Geodesic polar coordinates about the source "
      << (run.CurveSource ? "curve" : "point") << ": " << solved.Message() << ".");
    return false;
  }
  if (this->AngleMode == ISO_CURVE_ARC_LENGTH && !run.CurveSource)
  {
    const gs::Result<int> kept = polar.UseIsoCurveAngles();
    if (!kept.Ok())
    {
      vtkErrorMacro("Iso-curve angles: " << kept.Message() << ".");
      return false;
    }
    this->WarnIsoCurveKept(*kept);
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkGeodesicPolarCoordinates::WarnIsoCurveKept(int kept)
{
  if (kept > 0)
  {
    vtkWarningMacro(<< kept
                    << " point(s) whose iso-distance curve is not a closed loop round the source "
                       "(it meets the mesh boundary or misses the reference geodesic) keep the "
                       "geodesic-direction angle.");
  }
}

//------------------------------------------------------------------------------
int vtkGeodesicPolarCoordinates::WriteOutput(const Cache& cache, const Run& run, vtkPolyData* output)
{
  const std::vector<int>& pointToVertex = cache.Mesh.Build.PointToVertex;
  const gs::GeodesicPolarCoordinates& polar = *cache.Polar;
  const bool curveSource = run.CurveSource;
  const gs::CurveCoordinates& curveCoordinates = polar.Curve(); // a curve source's
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const vtkIdType numberOfPoints = static_cast<vtkIdType>(pointToVertex.size());
  vtkNew<vtkDoubleArray> rhoArray;
  rhoArray->SetName(curveSource ? "Offset" : "GeodesicDistance");
  rhoArray->SetNumberOfTuples(numberOfPoints);
  vtkNew<vtkDoubleArray> thetaArray;
  thetaArray->SetName(curveSource ? "ArcLength" : "PolarAngle");
  thetaArray->SetNumberOfTuples(numberOfPoints);
  vtkNew<vtkDoubleArray> decal;
  decal->SetName("DecalCoordinates");
  decal->SetNumberOfComponents(2);
  decal->SetNumberOfTuples(numberOfPoints);
  for (size_t i = 0; i < pointToVertex.size(); ++i)
  {
    if (i % AbortCheckInterval == AbortCheckInterval - 1)
    {
      this->UpdateProgress(0.8 + 0.2 * static_cast<double>(i) / pointToVertex.size());
      if (this->CheckAbort())
      {
        output->Initialize();
        return 1;
      }
    }
    const int v = pointToVertex[i];
    // (Curve source: rho is the offset, theta the arc length.)
    double rho = v < 0 ? nan : curveSource ? curveCoordinates.Offset[v] : polar.Rho(v);
    double theta = v < 0 ? nan : curveSource ? curveCoordinates.ArcLength[v] : polar.Theta(v);
    if (!std::isfinite(rho) || std::abs(rho) > this->Radius || !std::isfinite(theta))
    {
      rho = theta = nan;
    }
    const vtkIdType id = static_cast<vtkIdType>(i);
    rhoArray->SetValue(id, rho);
    thetaArray->SetValue(id, theta);
    if (curveSource)
    {
      // (u, delta): along the curve, and a band of width DecalSize centred on it -> [0, 1].
      decal->SetTypedComponent(id, 0, theta);
      decal->SetTypedComponent(id, 1, rho / this->DecalSize + 0.5);
    }
    else
    {
      // A square of side DecalSize centred on the source -> [0, 1]^2 (NaN stays NaN).
      decal->SetTypedComponent(id, 0, rho * std::cos(theta) / this->DecalSize + 0.5);
      decal->SetTypedComponent(id, 1, rho * std::sin(theta) / this->DecalSize + 0.5);
    }
  }

  SetOutputArrays(output, cache.Mesh.Surface, rhoArray, thetaArray, decal);

  // A fresh field data object: the surface's own (shallow-copied) one is left untouched.
  vtkNew<vtkFieldData> fieldData;
  if (vtkFieldData* inputFieldData = output->GetFieldData())
  {
    fieldData->ShallowCopy(inputFieldData);
  }
  vtkNew<vtkDoubleArray> summary;
  summary->SetName(curveSource ? "CurveLength" : "SourceAngleSum");
  summary->InsertNextValue(curveSource ? curveCoordinates.Length : polar.SourceAngleSum());
  fieldData->AddArray(summary);
  output->SetFieldData(fieldData);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGeodesicPolarCoordinates::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SourceVertexId: " << this->SourceVertexId << "\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "ReferenceDirection: (" << this->ReferenceDirection[0] << ", "
     << this->ReferenceDirection[1] << ", " << this->ReferenceDirection[2] << ")"
     << (this->ReferenceDirection[0] == 0.0 && this->ReferenceDirection[1] == 0.0 &&
            this->ReferenceDirection[2] == 0.0
          ? " (the source's first edge)"
          : "")
     << "\n";
  os << indent << "AngleMode: " << this->AngleMode << " (" << GetAngleModeName(this->AngleMode)
     << ")\n";
  os << indent << "DecalSize: " << this->DecalSize << "\n";
  os << indent << "Solver: " << this->Solver << " ("
     << gs::GeodesicSolverName(static_cast<gs::GeodesicSolver>(this->Solver)) << ")\n";
  os << indent << "K: " << this->K << "\n";
  os << indent << "GraphAccuracy: " << this->GraphAccuracy << "\n";
}
