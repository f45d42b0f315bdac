// vtkGeodesicPolarCoordinates on the bundled planar grid (Data/planar_grid.ply, the unit square,
// 20 x 20 squares of side 0.05, normal +z) and on malformed input.
//  - Analytic: on a plane the geodesic polar coordinates about s are the plane's polar
//    coordinates: rho = |p - s|, theta = atan2(p - s) - (angle of the reference direction),
//    counter-clockwise about +z. Checked to 1e-9 for a vertex source (default first-edge
//    reference, an in-plane and a tilted ReferenceDirection) and for a point of the Source port
//    snapped inside a triangle; DecalCoordinates against their formula; NaN beyond the radius.
//  - Errors (message + empty output): empty mesh, SourceVertexId out of range or unreferenced,
//    Radius <= 0 or NaN, DecalSize <= 0, non-finite ReferenceDirection, unknown AngleMode,
//    curve source, empty Source. Warnings: a ReferenceDirection normal to the surface (falls back
//    to the first edge), a Source with several points (uses the first).
//  - The converted mesh is cached while the input is unchanged; abort gives an empty output.
#include "vtkGeodesicPolarCoordinates.h"

#include "FilterTestSupport.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPLYReader.h>
#include <vtkPlaneSource.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

using gs_test::Check;
using gs_test::Failures;
using gs_test::Mentions;
using gs_test::MessageRecorder;

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double Tolerance = 1e-9;





struct Parameters
{
  vtkIdType SourceVertexId = 0;
  double Radius = 1.0;
  double Reference[3] = { 0.0, 0.0, 0.0 };
  double DecalSize = 1.0;
  int AngleMode = vtkGeodesicPolarCoordinates::GEODESIC_DIRECTION;
  int Solver = vtkGeodesicPolarCoordinates::EXACT;
  int K = 50;
  double GraphAccuracy = 1e-3;
  vtkPointSet* Source = nullptr;
};

struct RunResult
{
  vtkSmartPointer<vtkPolyData> Output;
  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;
  vtkDoubleArray* Array(const char* name) const
  {
    return vtkDoubleArray::SafeDownCast(this->Output->GetPointData()->GetArray(name));
  }
  vtkDoubleArray* Rho() const { return this->Array("GeodesicDistance"); }
  vtkDoubleArray* Theta() const { return this->Array("PolarAngle"); }
  vtkDoubleArray* Decal() const { return this->Array("DecalCoordinates"); }
  bool Empty() const
  {
    return this->Output->GetNumberOfPoints() == 0 && this->Output->GetNumberOfCells() == 0;
  }
};

RunResult Run(vtkPolyData* mesh, const Parameters& p)
{
  vtkNew<vtkGeodesicPolarCoordinates> filter;
  vtkNew<MessageRecorder> recorder;
  filter->AddObserver(vtkCommand::ErrorEvent, recorder);
  filter->AddObserver(vtkCommand::WarningEvent, recorder);
  filter->SetInputData(mesh);
  filter->SetSourceVertexId(p.SourceVertexId);
  filter->SetRadius(p.Radius);
  filter->SetReferenceDirection(p.Reference[0], p.Reference[1], p.Reference[2]);
  filter->SetDecalSize(p.DecalSize);
  filter->SetAngleMode(p.AngleMode);
  filter->SetSolver(p.Solver);
  filter->SetK(p.K);
  filter->SetGraphAccuracy(p.GraphAccuracy);
  if (p.Source)
  {
    filter->SetSourceData(p.Source);
  }
  filter->Update();
  RunResult r;
  r.Output = vtkSmartPointer<vtkPolyData>::New();
  r.Output->ShallowCopy(filter->GetOutput());
  r.Errors = recorder->Errors;
  r.Warnings = recorder->Warnings;
  return r;
}

// Smallest difference between two angles.
double AngleDifference(double a, double b)
{
  const double d = std::remainder(a - b, 2.0 * Pi);
  return std::abs(d);
}

vtkSmartPointer<vtkPolyData> PointsPolyData(const std::vector<std::vector<double>>& points)
{
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (const auto& x : points)
  {
    pts->InsertNextPoint(x.data());
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pts);
  return poly;
}

// Checks r against the plane's polar coordinates about `s` with theta's zero at angle `zero`
// (about +z); returns the number of points inside the radius.
int CheckAnalytic(const std::string& test, const RunResult& r, const double s[3], double zero,
  double radius, double decalSize)
{
  vtkDoubleArray* rho = r.Rho();
  vtkDoubleArray* theta = r.Theta();
  vtkDoubleArray* decal = r.Decal();
  Check(r.Errors.empty(), test, "unexpected error");
  if (!rho || !theta || !decal)
  {
    Check(false, test, "missing GeodesicDistance, PolarAngle or DecalCoordinates");
    return 0;
  }
  const vtkIdType n = r.Output->GetNumberOfPoints();
  Check(rho->GetNumberOfTuples() == n && theta->GetNumberOfTuples() == n &&
      decal->GetNumberOfTuples() == n && decal->GetNumberOfComponents() == 2,
    test, "array sizes");
  Check(r.Output->GetPointData()->GetTCoords() == decal, test,
    "DecalCoordinates are not the active texture coordinates");
  Check(r.Output->GetPointData()->GetScalars() == rho, test,
    "GeodesicDistance is not the active scalars");
  int inside = 0;
  double worstRho = 0.0, worstTheta = 0.0, worstDecal = 0.0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    r.Output->GetPoint(i, p);
    const double dx = p[0] - s[0], dy = p[1] - s[1];
    const double d = std::hypot(dx, dy);
    const double rh = rho->GetValue(i), th = theta->GetValue(i);
    const double u = decal->GetTypedComponent(i, 0), v = decal->GetTypedComponent(i, 1);
    if (d > radius + Tolerance)
    {
      if (!(std::isnan(rh) && std::isnan(th) && std::isnan(u) && std::isnan(v)))
      {
        Check(false, test, "point " + std::to_string(i) + " beyond the radius is not NaN");
      }
      continue;
    }
    if (d < radius - Tolerance && !std::isfinite(rh))
    {
      Check(false, test, "point " + std::to_string(i) + " inside the radius is NaN");
      continue;
    }
    if (!std::isfinite(rh))
    {
      continue; // on the radius, up to rounding
    }
    ++inside;
    worstRho = std::max(worstRho, std::abs(rh - d));
    if (!(th >= 0.0 && th < 2.0 * Pi))
    {
      Check(false, test, "PolarAngle outside [0, 2 pi) at point " + std::to_string(i));
    }
    if (d > 1e-12)
    {
      worstTheta = std::max(worstTheta, AngleDifference(th, std::atan2(dy, dx) - zero));
    }
    else
    {
      Check(th == 0.0 && rh == 0.0, test, "source point's coordinates are not (0, 0)");
    }
    worstDecal = std::max(worstDecal,
      std::max(std::abs(u - (rh * std::cos(th) / decalSize + 0.5)),
        std::abs(v - (rh * std::sin(th) / decalSize + 0.5))));
  }
  std::cout << test << ": " << inside << " points inside, worst rho error " << worstRho
            << ", theta error " << worstTheta << ", decal error " << worstDecal << "\n";
  Check(worstRho <= Tolerance, test, "rho differs from |p - s|");
  Check(worstTheta <= Tolerance, test, "theta differs from the analytic polar angle");
  Check(worstDecal <= 1e-12, test, "DecalCoordinates differ from their formula");
  vtkDataArray* angleSum = r.Output->GetFieldData()->GetArray("SourceAngleSum");
  Check(angleSum && std::abs(angleSum->GetTuple1(0) - 2.0 * Pi) < 1e-12, test,
    "SourceAngleSum is not 2 pi on a plane");
  return inside;
}

// The planar grid's point closest to (x, y).
vtkIdType FindPoint(vtkPolyData* mesh, double x, double y)
{
  vtkIdType best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    const double d = std::hypot(p[0] - x, p[1] - y);
    if (d < bestDistance)
    {
      bestDistance = d;
      best = i;
    }
  }
  return best;
}

void TestVertexSource(vtkPolyData* grid)
{
  const vtkIdType s = FindPoint(grid, 0.5, 0.5);
  double ps[3];
  grid->GetPoint(s, ps);
  Parameters p;
  p.SourceVertexId = s;
  p.Radius = 0.3;
  p.DecalSize = 0.6;

  // Default reference: the source's first edge, a grid edge (a multiple of 45 degrees). The
  // offset is read from the output and then everything must be polar coordinates about it.
  const RunResult firstEdge = Run(grid, p);
  const vtkIdType east = FindPoint(grid, 0.55, 0.5);
  double zero = 0.0;
  if (firstEdge.Theta())
  {
    zero = -firstEdge.Theta()->GetValue(east); // theta(east) = 0 - zero
    const double steps = zero / (Pi / 4.0);
    Check(std::abs(steps - std::round(steps)) < 1e-9, "FirstEdgeReference",
      "first edge is not along a grid edge (offset " + std::to_string(zero) + ")");
  }
  const int inside = CheckAnalytic("FirstEdgeReference", firstEdge, ps, zero, 0.3, 0.6);
  Check(inside > 100, "FirstEdgeReference", "too few points inside the radius");

  // ReferenceDirection +x: theta is the plane's polar angle.
  p.Reference[0] = 1.0;
  CheckAnalytic("ReferenceX", Run(grid, p), ps, 0.0, 0.3, 0.6);

  // A tilted direction is projected onto the plane: (1, 1, 0.7) -> 45 degrees.
  p.Reference[1] = 1.0;
  p.Reference[2] = 0.7;
  p.DecalSize = 0.25; // decal smaller than the disc: coordinates outside [0, 1] are fine
  CheckAnalytic("ReferenceTilted", Run(grid, p), ps, Pi / 4.0, 0.3, 0.25);

  // A direction normal to the surface: warning, the first edge is used.
  p.Reference[0] = p.Reference[1] = 0.0;
  p.Reference[2] = -2.0;
  p.DecalSize = 0.6;
  const RunResult normal = Run(grid, p);
  Check(Mentions(normal.Warnings, "normal to the surface"), "NormalReference", "no warning");
  CheckAnalytic("NormalReference", normal, ps, zero, 0.3, 0.6);

  // The whole square (infinite radius): every point is inside.
  p.Reference[2] = 0.0;
  p.Radius = std::numeric_limits<double>::infinity();
  const int all = CheckAnalytic("InfiniteRadius", Run(grid, p), ps, zero,
    std::numeric_limits<double>::infinity(), 0.6);
  Check(all == grid->GetNumberOfPoints(), "InfiniteRadius", "not every point is inside");
}

void TestSourcePort(vtkPolyData* grid)
{
  // A point above the plane, over the interior of a triangle: snapped straight down.
  const double s[3] = { 0.5231, 0.4672, 0.0 };
  auto above = PointsPolyData({ { s[0], s[1], 0.3 } });
  Parameters p;
  p.Source = above;
  p.SourceVertexId = -5; // ignored when the Source port is connected
  p.Radius = 0.25;
  p.DecalSize = 0.5;
  p.Reference[0] = 0.0;
  p.Reference[1] = 1.0; // +y: theta = atan2 - pi/2
  CheckAnalytic("SourcePortFacePoint", Run(grid, p), s, Pi / 2.0, 0.25, 0.5);

  // A point on a grid vertex (above it): the vertex itself, same result as SourceVertexId.
  const vtkIdType v = FindPoint(grid, 0.25, 0.75);
  double pv[3];
  grid->GetPoint(v, pv);
  auto onVertex = PointsPolyData({ { pv[0], pv[1], -0.1 }, { 0.9, 0.9, 0.0 } });
  Parameters q;
  q.Source = onVertex;
  q.Radius = 0.2;
  const RunResult snapped = Run(grid, q);
  Check(Mentions(snapped.Warnings, "only the first"), "SourcePortVertex",
    "no warning about the extra source points");
  q.Source = nullptr;
  q.SourceVertexId = v;
  const RunResult byId = Run(grid, q);
  bool same = snapped.Theta() && byId.Theta() &&
    snapped.Output->GetNumberOfPoints() == byId.Output->GetNumberOfPoints();
  for (vtkIdType i = 0; same && i < byId.Output->GetNumberOfPoints(); ++i)
  {
    const double a = snapped.Theta()->GetValue(i), b = byId.Theta()->GetValue(i);
    const double ra = snapped.Rho()->GetValue(i), rb = byId.Rho()->GetValue(i);
    same = ((std::isnan(a) && std::isnan(b)) || std::abs(a - b) < 1e-12) &&
      ((std::isnan(ra) && std::isnan(rb)) || std::abs(ra - rb) < 1e-12);
  }
  Check(same, "SourcePortVertex", "a source on a vertex differs from SourceVertexId");
}

// Expects an error mentioning `keyword` and an empty output.
void ExpectRejected(const std::string& test, vtkPolyData* mesh, const Parameters& p,
  const std::string& keyword)
{
  const RunResult r = Run(mesh, p);
  Check(Mentions(r.Errors, keyword), test, "no error mentioning '" + keyword + "'");
  Check(r.Empty(), test, "output is not empty");
}

void TestBadInputs(vtkPolyData* grid)
{
  vtkNew<vtkPolyData> empty;
  ExpectRejected("EmptyMesh", empty, Parameters(), "Invalid input mesh");

  Parameters p;
  p.SourceVertexId = -1;
  ExpectRejected("NegativeSourceVertexId", grid, p, "out of range");
  p.SourceVertexId = grid->GetNumberOfPoints();
  ExpectRejected("LargeSourceVertexId", grid, p, "out of range");

  // A point used by no triangle.
  vtkNew<vtkPolyData> extra;
  extra->DeepCopy(grid);
  extra->GetPoints()->InsertNextPoint(3.0, 3.0, 0.0);
  p.SourceVertexId = extra->GetNumberOfPoints() - 1;
  ExpectRejected("UnreferencedSource", extra, p, "not used by any triangle");
  // ... but as an ordinary point it is simply NaN.
  p.SourceVertexId = 0;
  const RunResult r = Run(extra, p);
  Check(r.Errors.empty() && r.Rho() &&
      std::isnan(r.Rho()->GetValue(extra->GetNumberOfPoints() - 1)) && r.Rho()->GetValue(0) == 0,
    "UnreferencedPoint", "an unreferenced point is not NaN");

  for (double radius : { 0.0, -1.0, std::numeric_limits<double>::quiet_NaN() })
  {
    Parameters q;
    q.Radius = radius;
    ExpectRejected("Radius " + std::to_string(radius), grid, q, "Radius must be > 0");
  }
  for (double size : { 0.0, -2.0, std::numeric_limits<double>::infinity() })
  {
    Parameters q;
    q.DecalSize = size;
    ExpectRejected("DecalSize " + std::to_string(size), grid, q, "DecalSize");
  }
  {
    Parameters q;
    q.Reference[1] = std::numeric_limits<double>::quiet_NaN();
    ExpectRejected("NaNReference", grid, q, "not finite");
  }
  {
    Parameters q;
    q.AngleMode = 2;
    ExpectRejected("UnknownAngleMode", grid, q, "AngleMode");
  }
  {
    // A curve of a single point on the surface (zero length): rejected.
    auto curve = PointsPolyData({ { 0.5, 0.5, 0.0 }, { 0.5, 0.5, 0.0 } });
    vtkNew<vtkCellArray> lines;
    const vtkIdType ids[2] = { 0, 1 };
    lines->InsertNextCell(2, ids);
    curve->SetLines(lines);
    Parameters q;
    q.Source = curve;
    ExpectRejected("ZeroLengthCurve", grid, q, "curve");
  }
  {
    auto none = PointsPolyData({});
    Parameters q;
    q.Source = none;
    ExpectRejected("EmptySource", grid, q, "no point");
  }
  {
    auto nan = PointsPolyData({ { std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0 } });
    Parameters q;
    q.Source = nan;
    ExpectRejected("NaNSourcePoint", grid, q, "non-finite");
  }
}

// Quads (triangulated with a warning): the triangulation is converted once while the input is
// unchanged (also through Modified() alone); editing it in place converts it again. Abort: empty
// output.
void TestCacheAndAbort()
{
  const std::string test = "Cache";
  vtkNew<vtkPlaneSource> plane;
  plane->SetResolution(10, 10);
  plane->Update();
  vtkNew<vtkPolyData> quads;
  quads->DeepCopy(plane->GetOutput());

  vtkNew<vtkGeodesicPolarCoordinates> filter;
  vtkNew<MessageRecorder> recorder;
  filter->AddObserver(vtkCommand::ErrorEvent, recorder);
  filter->AddObserver(vtkCommand::WarningEvent, recorder);
  filter->SetInputData(quads);
  filter->SetSourceVertexId(60);
  filter->SetRadius(0.3);
  filter->Update();
  vtkCellArray* first = filter->GetOutput()->GetPolys();
  Check(Mentions(recorder->Warnings, "triangulated"), test, "no triangulation warning");
  Check(filter->GetOutput()->GetNumberOfPolys() == 200, test, "quads not triangulated");
  filter->SetRadius(0.5);
  filter->SetSourceVertexId(40);
  filter->SetReferenceDirection(0.0, 1.0, 0.0);
  filter->Update();
  Check(filter->GetOutput()->GetPolys() == first, test, "mesh converted again");
  Check(filter->GetOutput()->GetPointData()->GetArray("PolarAngle")->GetTuple1(40) == 0.0, test,
    "new source not used");
  // Modified() alone (an upstream filter that ran again with the same mesh): kept; a point moved
  // in place, then Modified() on the data set only: converted again.
  quads->Modified();
  filter->Update();
  Check(filter->GetOutput()->GetPolys() == first, test, "unchanged mesh converted again after Modified()");
  double x[3];
  quads->GetPoints()->GetPoint(60, x);
  x[2] = 0.01;
  quads->GetPoints()->GetData()->SetTuple(60, x); // (no Modified() on the points)
  quads->Modified();
  filter->Update();
  Check(filter->GetOutput()->GetPolys() != first, test, "mesh edited in place not converted again");
  double moved[3];
  filter->GetOutput()->GetPoint(60, moved);
  Check(std::abs(moved[2] - 0.01) < 1e-6, test, "the edited point is not in the output");
  Check(recorder->Errors.empty(), test, "unexpected error");

  std::ostringstream printed;
  filter->Print(printed);
  Check(printed.str().find("AngleMode: 0 (Geodesic direction)") != std::string::npos &&
      printed.str().find("ReferenceDirection: (0, 1, 0)") != std::string::npos,
    "PrintSelf", "missing parameters");

  vtkNew<vtkCallbackCommand> abort;
  abort->SetCallback([](vtkObject* caller, unsigned long, void*, void*) {
    static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
  });
  filter->AddObserver(vtkCommand::ProgressEvent, abort);
  filter->SetRadius(0.4);
  filter->Update();
  Check(filter->GetOutput()->GetNumberOfPoints() == 0, "Abort", "aborted output not empty");
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

// The saddle vertex graph engine (K >= 1): on a plane the refined distances are exact and the
// angles within the 0.1 degree; a negative K is rejected.
// A curve source on the plane: Offset is the signed distance to the segment's line (positive on
// its left, +z up), ArcLength the projection's fraction, DecalCoordinates (u, delta / size + 0.5).
void TestCurveSource(vtkPolyData* grid)
{
  const std::string test = "CurveSource";
  const double a[3] = { 0.2, 0.3, 0.0 }, b[3] = { 0.8, 0.6, 0.0 };
  auto curve = PointsPolyData({ { a[0], a[1], a[2] }, { b[0], b[1], b[2] } });
  vtkNew<vtkCellArray> lines;
  const vtkIdType ids[2] = { 0, 1 };
  lines->InsertNextCell(2, ids);
  curve->SetLines(lines);
  Parameters p;
  p.Source = curve;
  p.Radius = 0.2;
  p.DecalSize = 0.4;
  const RunResult r = Run(grid, p);
  vtkDoubleArray* offset = r.Array("Offset");
  vtkDoubleArray* arc = r.Array("ArcLength");
  Check(r.Errors.empty() && offset && arc && r.Decal(), test, "no Offset/ArcLength output");
  if (!offset || !arc || !r.Decal())
  {
    return;
  }
  const double dx = b[0] - a[0], dy = b[1] - a[1], length = std::hypot(dx, dy);
  double worstOffset = 0, worstArc = 0, worstDecal = 0;
  int beside = 0;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    double x[3];
    grid->GetPoint(i, x);
    const double along = ((x[0] - a[0]) * dx + (x[1] - a[1]) * dy) / (length * length);
    const double side = (dx * (x[1] - a[1]) - dy * (x[0] - a[0])) / length;
    if (std::abs(side) > 0.19 || along < 0.03 || along > 0.97)
    {
      continue;
    }
    ++beside;
    worstOffset = std::max(worstOffset, std::abs(offset->GetValue(i) - side));
    worstArc = std::max(worstArc, std::abs(arc->GetValue(i) - along));
    worstDecal = std::max(worstDecal,
      std::abs(r.Decal()->GetTypedComponent(i, 1) - (offset->GetValue(i) / 0.4 + 0.5)) +
        std::abs(r.Decal()->GetTypedComponent(i, 0) - arc->GetValue(i)));
  }
  Check(beside > 50, test, "too few points beside the segment");
  Check(worstOffset < 1e-3, test, "Offset differs from the signed distance");
  Check(worstArc < 1e-2, test, "ArcLength differs from the projection's fraction");
  Check(worstDecal < 1e-12, test, "DecalCoordinates differ from (u, delta / size + 0.5)");
  std::cout << test << ": " << beside << " points beside the curve, offset error " << worstOffset
            << ", arc length error " << worstArc << "\n";
  Check(!Mentions(r.Warnings, "Curve source"), test, "warning with the default settings");
  // Settings that apply to point sources only are ignored, with a warning, and change nothing.
  p.AngleMode = vtkGeodesicPolarCoordinates::ISO_CURVE_ARC_LENGTH;
  p.Solver = vtkGeodesicPolarCoordinates::SVG_LABEL_CORRECTING;
  p.K = 20;
  const RunResult ignored = Run(grid, p);
  Check(Mentions(ignored.Warnings, "Curve source"), test, "no warning for AngleMode and Solver");
  vtkDoubleArray* offset2 = ignored.Array("Offset");
  bool same = offset2 && offset2->GetNumberOfTuples() == offset->GetNumberOfTuples();
  for (vtkIdType i = 0; same && i < offset->GetNumberOfTuples(); ++i)
  {
    const double u = offset->GetValue(i), v = offset2->GetValue(i);
    same = (std::isnan(u) && std::isnan(v)) || u == v;
  }
  Check(same, test, "AngleMode or K changed a curve source's Offset");
}

// Iso-curve arc length on the plane: the polar angle within the 0.1 degree (inside the
// grid, where the iso-curves are closed loops).
void TestIsoCurveMode(vtkPolyData* grid)
{
  const std::string test = "IsoCurveMode";
  Parameters p;
  p.SourceVertexId = 10 * 21 + 10; // the centre of the unit square
  p.Radius = 0.45;
  p.AngleMode = vtkGeodesicPolarCoordinates::ISO_CURVE_ARC_LENGTH;
  const RunResult iso = Run(grid, p);
  p.AngleMode = vtkGeodesicPolarCoordinates::GEODESIC_DIRECTION;
  const RunResult geodesic = Run(grid, p);
  Check(iso.Errors.empty() && iso.Warnings.empty() && iso.Theta(), test, "errors or warnings");
  if (!iso.Theta() || !geodesic.Theta())
  {
    return;
  }
  double worst = 0;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    if (std::isfinite(geodesic.Rho()->GetValue(i)) && geodesic.Rho()->GetValue(i) > 0.12)
    {
      worst = std::max(worst, AngleDifference(iso.Theta()->GetValue(i), geodesic.Theta()->GetValue(i)));
    }
  }
  Check(worst < 0.1 * Pi / 180, test, "iso-curve angle differs from the polar angle by 0.1 degree or more");
  std::cout << test << ": worst difference " << worst * 180 / Pi << " degree\n";
  // Past the square's boundary the iso-curves are not loops: those points keep the geodesic
  // direction, with a warning.
  p.AngleMode = vtkGeodesicPolarCoordinates::ISO_CURVE_ARC_LENGTH;
  p.Radius = 0.8;
  const RunResult open = Run(grid, p);
  Check(open.Errors.empty() && Mentions(open.Warnings, "not a closed loop") && open.Theta(), test,
    "no warning for iso-curves meeting the boundary");
}

// The graph engines (the saddle vertex graph of K, and the discrete geodesic graph of
// GraphAccuracy) against the exact engine on the plane.
void TestGraphEngine(vtkPolyData* grid, double graphAccuracy)
{
  const std::string test = graphAccuracy > 0.0 ? "DiscreteGeodesicGraphEngine" : "GraphEngine";
  Parameters p;
  p.SourceVertexId = 10 * 21 + 10;
  p.Radius = 0.8;
  p.Solver = graphAccuracy > 0.0 ? vtkGeodesicPolarCoordinates::DGG
                                 : vtkGeodesicPolarCoordinates::SVG_LABEL_CORRECTING;
  p.K = 50;
  p.GraphAccuracy = graphAccuracy;
  const RunResult r = Run(grid, p);
  Check(r.Errors.empty() && r.Rho() && r.Theta(), test, "no output");
  if (!r.Rho() || !r.Theta())
  {
    return;
  }
  double s[3];
  grid->GetPoint(p.SourceVertexId, s);
  double ref[3];
  // theta's zero: the exact engine's first edge, read from an exact run.
  Parameters e = p;
  e.Solver = vtkGeodesicPolarCoordinates::EXACT;
  const RunResult exact = Run(grid, e);
  double worstRho = 0, worstTheta = 0;
  int inside = 0;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    const double rho = r.Rho()->GetValue(i), exactRho = exact.Rho()->GetValue(i);
    Check(std::isnan(rho) == std::isnan(exactRho), test, "inside/outside differs at point " + std::to_string(i));
    if (std::isnan(rho) || exactRho == 0.0)
    {
      continue;
    }
    ++inside;
    grid->GetPoint(i, ref);
    worstRho = std::max(worstRho, std::abs(rho - exactRho) / exactRho);
    worstTheta = std::max(worstTheta, AngleDifference(r.Theta()->GetValue(i), exact.Theta()->GetValue(i)));
  }
  Check(inside > 100, test, "too few points inside the radius");
  Check(worstRho < 1e-9, test, "rho differs from the exact engine's");
  Check(worstTheta < 0.1 * Pi / 180, test, "theta differs from the exact engine's by 0.1 degree or more");
  if (graphAccuracy > 0.0)
  {
    p.GraphAccuracy = 0.5;
    ExpectRejected("GraphAccuracyOutOfRange", grid, p, "accuracy");
    return;
  }
  p.K = 0;
  ExpectRejected("NoK", grid, p, "K must be at least 1");
  p.K = 50;
  p.Solver = 2; // (SVG (Dijkstra): SVG Geodesic Distance's only)
  ExpectRejected("UnknownSolver", grid, p, "Unknown Solver 2");
}

int main(int argc, char* argv[])
{
  vtkNew<vtkPLYReader> reader;
  reader->SetFileName((DataDirectory(argc, argv) + "/planar_grid.ply").c_str());
  reader->Update();
  vtkPolyData* grid = reader->GetOutput();
  if (grid->GetNumberOfPoints() != 441)
  {
    std::cerr << "Could not read " << reader->GetFileName() << "\n";
    return 1;
  }
  TestVertexSource(grid);
  TestSourcePort(grid);
  TestBadInputs(grid);
  TestCacheAndAbort();
  TestGraphEngine(grid, 0.0);
  TestGraphEngine(grid, 1e-2);
  TestIsoCurveMode(grid);
  TestCurveSource(grid);
  if (Failures > 0)
  {
    std::cerr << Failures << " failure(s)\n";
    return 1;
  }
  std::cout << "all passed\n";
  return 0;
}
