#include "vtkSurfacePieces.h"

#include "vtkDistributedSurface.h"
#include "vtkSurfacePointLocator.h"

#include "SVGGeodesicSolver.h"

#include <vtkAlgorithm.h>
#include <vtkMath.h>
#include <vtkSmartPointer.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkCommunicator.h>
#include <vtkDataArray.h>
#include <vtkGenericCell.h>
#include <vtkMultiProcessController.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace
{
// Message tags of the exchanges.
enum Tags
{
  EXCHANGE_LENGTH = 470311,
  EXCHANGE_BYTES = 470312
};

vtkIdType GlobalId(vtkDataArray* ids, vtkIdType i)
{
  return static_cast<vtkIdType>(ids->GetComponent(i, 0));
}

// The core's progress callback reporting on `self` from `from` to `to`, abortable.
gs::ProgressCallback Progress(vtkAlgorithm* self, double from, double to)
{
  return [self, from, to](double fraction) {
    self->UpdateProgress(from + (to - from) * fraction);
    return !self->CheckAbort();
  };
}

// Whether a core step succeeded; its error reported on `self` after `what` (nothing when it
// was aborted).
bool Reported(vtkAlgorithm* self, const char* what, const gs::Status& status)
{
  if (!status.Ok() && !status.IsAborted())
  {
    vtkErrorWithObjectMacro(self, << what << status.Message() << ".");
  }
  return status.Ok();
}

// What a process lacks to work on its piece in place ("" when nothing).
std::string Lacks(vtkPolyData* piece)
{
  if (!piece || piece->GetNumberOfCells() == 0)
  {
    return ""; // an empty piece takes part with nothing
  }
  if (piece->GetNumberOfStrips() > 0)
  {
    return "triangle strips";
  }
  if ((piece->GetPointData()->GetGlobalIds() != nullptr) !=
    (piece->GetCellData()->GetGlobalIds() != nullptr))
  {
    // (Gathering numbers points by point ids and cells by cell ids, each alone.)
    return "both global point and cell ids, or neither";
  }
  auto it = vtk::TakeSmartPointer(piece->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* pts;
    it->GetCurrentCell(n, pts);
    if (n != 3)
    {
      return "triangles only (polygons of " + std::to_string(n) + " points)";
    }
  }
  return "";
}
} // namespace

// The core's transport over the controller. Exchange: every pair of processes swaps its two
// buffers, the pairs taken in one global order (the lower rank sends first): the earliest pair
// not done always has both processes ready, so blocking sends cannot deadlock.
class vtkSurfacePieces::Communicator : public gs::PieceCommunicator
{
public:
  explicit Communicator(vtkMultiProcessController* controller)
    : Controller(controller)
  {
  }
  int Rank() const override { return Controller->GetLocalProcessId(); }
  int Size() const override { return Controller->GetNumberOfProcesses(); }
  void Exchange(
    const std::vector<gs::ByteBuffer>& outgoing, std::vector<gs::ByteBuffer>& incoming) override
  {
    const int me = Rank(), size = Size();
    incoming.assign(static_cast<std::size_t>(size), {});
    incoming[static_cast<std::size_t>(me)] = outgoing[static_cast<std::size_t>(me)];
    for (int a = 0; a < size; ++a)
    {
      for (int b = a + 1; b < size; ++b)
      {
        if (me != a && me != b)
        {
          continue;
        }
        const int other = me == a ? b : a;
        if (me == a)
        {
          Send(outgoing[static_cast<std::size_t>(other)], other);
          Receive(incoming[static_cast<std::size_t>(other)], other);
        }
        else
        {
          Receive(incoming[static_cast<std::size_t>(other)], other);
          Send(outgoing[static_cast<std::size_t>(other)], other);
        }
      }
    }
  }
  std::int64_t Sum(std::int64_t value) override
  {
    long long in = value, out = 0;
    Controller->AllReduce(&in, &out, 1, vtkCommunicator::SUM_OP);
    return out;
  }
  double Min(double value) override { return Reduce(value, vtkCommunicator::MIN_OP); }
  double Max(double value) override { return Reduce(value, vtkCommunicator::MAX_OP); }

private:
  void Send(const gs::ByteBuffer& bytes, int to)
  {
    vtkIdType length = static_cast<vtkIdType>(bytes.size());
    Controller->Send(&length, 1, to, EXCHANGE_LENGTH);
    if (length > 0)
    {
      Controller->Send(reinterpret_cast<const char*>(bytes.data()), length, to, EXCHANGE_BYTES);
    }
  }
  void Receive(gs::ByteBuffer& bytes, int from)
  {
    vtkIdType length = 0;
    Controller->Receive(&length, 1, from, EXCHANGE_LENGTH);
    bytes.resize(static_cast<std::size_t>(std::max<vtkIdType>(length, 0)));
    if (length > 0)
    {
      Controller->Receive(reinterpret_cast<char*>(bytes.data()), length, from, EXCHANGE_BYTES);
    }
  }
  double Reduce(double value, int operation)
  {
    double out = value;
    Controller->AllReduce(&value, &out, 1, operation);
    return out;
  }

  vtkMultiProcessController* Controller;
};

//------------------------------------------------------------------------------
vtkSurfacePieces::vtkSurfacePieces(vtkMultiProcessController* controller)
  : Comm(new Communicator(controller))
{
}

vtkSurfacePieces::~vtkSurfacePieces() = default;

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkSurfacePieces::OwnCellsInPlace(vtkAlgorithm* self,
  const vtkDistributedSurface& distributed, std::unique_ptr<vtkSurfacePieces>& pieces,
  vtkPolyData* input)
{
  if (!pieces)
  {
    pieces.reset(new vtkSurfacePieces(distributed.GetController()));
  }
  vtkSmartPointer<vtkPolyData> own = vtkDistributedSurface::OwnCells(input);
  std::string why;
  if (pieces->CanUse(own, why))
  {
    return own;
  }
  if (self->GetDebug())
  {
    vtkGenericWarningMacro("Gathering the surface: " << why << ".");
  }
  return nullptr;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::CanUse(vtkPolyData* ownCells, std::string& why)
{
  std::string lacks;
  const int first = gs::FirstMessage(*Comm, Lacks(ownCells), lacks);
  why = first < 0 ? std::string()
                  : "process " + std::to_string(first) + "'s piece lacks " + lacks;
  return first < 0;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::OwnTriangles(
  vtkAlgorithm* self, vtkPolyData* ownCells, gs::PieceTriangles& own)
{
  // This process's triangles (on the piece's points, in cell order).
  const std::size_t np = static_cast<std::size_t>(ownCells->GetNumberOfPoints());
  std::vector<std::array<int, 3>> triangles;
  if (ownCells->GetNumberOfPolys() > 0)
  {
    auto it = vtk::TakeSmartPointer(ownCells->GetPolys()->NewIterator());
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      vtkIdType n;
      const vtkIdType* pts;
      it->GetCurrentCell(n, pts);
      triangles.push_back({ static_cast<int>(pts[0]), static_cast<int>(pts[1]),
        static_cast<int>(pts[2]) });
    }
  }
  // Their ids: the given global ids when every piece with points has them, otherwise the
  // numbering of the gathered surface (as gathering would number them).
  vtkDataArray* pointIds = ownCells->GetPointData()->GetGlobalIds();
  vtkDataArray* cellIds = ownCells->GetCellData()->GetGlobalIds();
  this->GivenIds = Comm->Sum(np > 0 && (!pointIds || !cellIds) ? 1 : 0) == 0;
  std::vector<gs::Vec3> positions(np);
  for (std::size_t i = 0; i < np; ++i)
  {
    double x[3];
    ownCells->GetPoint(static_cast<vtkIdType>(i), x);
    positions[i] = gs::Vec3(x[0], x[1], x[2]);
  }
  gs::GatheredNumbering numbering;
  if (this->GivenIds)
  {
    numbering.PointIds.resize(np);
    for (std::size_t i = 0; i < np; ++i)
    {
      numbering.PointIds[i] = GlobalId(pointIds, static_cast<vtkIdType>(i));
    }
    const vtkIdType firstPoly = ownCells->GetNumberOfVerts() + ownCells->GetNumberOfLines();
    for (std::size_t t = 0; t < triangles.size(); ++t)
    {
      numbering.TriangleIds.push_back(GlobalId(cellIds, firstPoly + static_cast<vtkIdType>(t)));
    }
  }
  else if (!Reported(self, "Numbering the distributed surface: ",
             gs::NumberAsGathered(positions, triangles, *Comm, numbering)))
  {
    return false;
  }
  this->FirstPoint = numbering.FirstPoint;
  // The piece: the points the triangles use, with their ids.
  this->PointIds.assign(np, -1);
  std::vector<int> pointOf(np, -1);
  for (const std::array<int, 3>& corners : triangles)
  {
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k)
    {
      const std::size_t q = static_cast<std::size_t>(corners[static_cast<std::size_t>(k)]);
      if (pointOf[q] < 0)
      {
        pointOf[q] = static_cast<int>(own.Points.size());
        own.Points.push_back(positions[q]);
        own.PointIds.push_back(numbering.PointIds[q]);
        this->PointIds[q] = numbering.PointIds[q];
      }
      t[static_cast<std::size_t>(k)] = pointOf[q];
    }
    own.Triangles.push_back(t);
  }
  own.TriangleIds = std::move(numbering.TriangleIds);
  this->TriangleIds = own.TriangleIds;
  return true;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::UsePiece(
  vtkAlgorithm* self, vtkPolyData* ownCells, vtkMTimeType key, int rings)
{
  if (Comm->Sum(this->HasPiece && key == this->PieceKey ? 0 : 1) == 0)
  {
    return true;
  }
  this->HasPiece = this->HasGraph = false;
  // (The triangles are made in their own scope: what made them is freed before the band.)
  gs::PieceTriangles own;
  if (!this->OwnTriangles(self, ownCells, own))
  {
    return false;
  }
  if (!Reported(
        self, "The distributed surface: ", this->SurfacePieceState.Build(own, rings, *Comm)))
  {
    return false;
  }
  this->HasPiece = true;
  this->PieceKey = key;
  return true;
}

//------------------------------------------------------------------------------
std::vector<std::int64_t> vtkSurfacePieces::SurfaceIds(const std::vector<vtkIdType>& pointIds)
{
  std::vector<std::int64_t> ids;
  for (const vtkIdType id : pointIds)
  {
    const std::int64_t serial = static_cast<std::int64_t>(id);
    ids.push_back(this->GivenIds
        ? this->SurfacePieceState.IdOfRank(serial, *Comm)
        : gs::GatheredPointId(this->PointIds, this->FirstPoint, serial, *Comm));
  }
  return ids;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::UseGraph(vtkAlgorithm* self, vtkPolyData* ownCells, vtkMTimeType key,
  const gs::SaddleVertexGraphOptions& options, double from, double to, bool& built)
{
  built = false;
  if (!this->UsePiece(self, ownCells, key))
  {
    return false;
  }
  const bool same = this->HasGraph && options.Construction == this->Options.Construction &&
    options.K == this->Options.K && options.Accuracy == this->Options.Accuracy;
  if (Comm->Sum(same ? 0 : 1) == 0)
  {
    return true;
  }
  this->HasGraph = false;
  if (!Reported(self, "The distributed surface: ",
        this->GraphState.Build(this->SurfacePieceState, options, *Comm, Progress(self, from, to))))
  {
    this->HasPiece = false; // (its band may have failed to grow: made again next time)
    return false;
  }
  this->HasGraph = true;
  this->Options = options;
  built = true;
  return true;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::Polar(vtkAlgorithm* self, vtkPolyData* ownCells, vtkIdType source,
  const std::vector<gs::Vec3>& points, double radius, const double referenceDirection[3],
  bool isoCurveAngles, std::vector<double>& rho, std::vector<double>& theta,
  gs::PiecePolarCoordinates& chart)
{
  const gs::Vec3 reference(referenceDirection[0], referenceDirection[1], referenceDirection[2]);
  std::vector<gs::SurfacePoint> mine;
  if (!points.empty() && !this->SnapPoints(self, ownCells, { points.front() }, mine))
  {
    return false;
  }
  if (!Reported(self, "Geodesic polar coordinates about the source point: ",
        points.empty()
          ? gs::ComputePolarOnPieces(this->SurfacePieceState, this->SurfaceIds({ source })[0],
              radius, reference, *Comm, chart, isoCurveAngles)
          : gs::ComputePolarOnPieces(this->SurfacePieceState, mine.empty() ? nullptr : &mine[0],
              radius, reference, *Comm, chart, isoCurveAngles)))
  {
    this->HasPiece = this->HasGraph = false; // (its band may have failed to grow)
    return false;
  }
  rho = this->AtPoints(chart.Rho, 0.0);
  theta = this->AtPoints(chart.Theta, 0.0);
  return true;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::PolarCurve(vtkAlgorithm* self, vtkPolyData* ownCells, vtkPolyData* curve,
  double radius, std::vector<double>& rho, std::vector<double>& theta,
  gs::PiecePolarCoordinates& chart)
{
  std::vector<std::vector<gs::PiecePointName>> names;
  if (!this->SnapCurves(self, ownCells, curve, names))
  {
    return false;
  }
  if (names.empty() || names.front().size() < 2)
  {
    vtkErrorWithObjectMacro(self, "The Source curve has fewer than two distinct points on the surface.");
    return false;
  }
  if (!Reported(self, "Geodesic polar coordinates about the source curve: ",
        gs::ComputeCurveCoordinatesOnPieces(
          this->SurfacePieceState, names.front(), radius, *Comm, chart)))
  {
    this->HasPiece = this->HasGraph = false; // (its band may have failed to grow)
    return false;
  }
  rho = this->AtPoints(chart.Rho, 0.0);
  theta = this->AtPoints(chart.Theta, 0.0);
  return true;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::Distances(vtkAlgorithm* self, vtkPolyData* ownCells,
  const std::vector<vtkIdType>& sources, const std::vector<gs::Vec3>& points, vtkPolyData* curves,
  double maxDistance, bool refine, std::vector<double>& perPoint)
{
  std::vector<std::pair<std::int64_t, double>> seeds;
  if (curves)
  {
    // The curves and the points as one-point curves; traced where every process can see them,
    // then sampled and seeded as SVGGeodesicSolver::SolveCurves does.
    std::vector<std::vector<gs::PiecePointName>> names;
    std::vector<gs::SurfacePoint> mine, samples;
    std::vector<gs::PiecePointName> pointNames;
    std::vector<std::vector<gs::CurvePiece>> unused;
    std::vector<gs::CurvePiece> pieces;
    std::int64_t crossed = 0;
    if (!this->SnapCurves(self, ownCells, curves, names) ||
      !this->SnapPoints(self, ownCells, points, mine, nullptr, &pointNames))
    {
      return false;
    }
    for (const gs::PiecePointName& p : pointNames)
    {
      names.push_back({ p });
    }
    if (!this->TraceCurves(self, names, CurveUse::GraphSeeds, samples, unused, pieces, crossed) ||
      !Reported(self, "Source curves: ",
        gs::GraphSeedsFromPoints(this->SurfacePieceState, this->GraphState, {}, samples,
          maxDistance, *Comm, seeds, pieces, crossed)))
    {
      return false;
    }
  }
  else if (points.empty())
  {
    for (const std::int64_t id : this->SurfaceIds(sources))
    {
      seeds.push_back({ id, 0.0 });
    }
  }
  else
  {
    std::vector<gs::SurfacePoint> mine;
    if (!this->SnapPoints(self, ownCells, points, mine) ||
      !Reported(self, "Source points: ",
        gs::GraphSeedsFromPoints(this->SurfacePieceState, this->GraphState, {}, mine,
          maxDistance, *Comm, seeds)))
    {
      return false;
    }
  }
  gs::PieceDistanceSolver solver(this->GraphState);
  if (!Reported(self,
        curves ? "Source curves: " : points.empty() ? "Source vertex ids: " : "Source points: ",
        solver.Solve(seeds, maxDistance, *Comm, refine)))
  {
    return false;
  }
  this->LastRounds = solver.Rounds();
  this->LastRefinementRounds = solver.Refinements();
  std::vector<int> wanted;
  for (const std::int64_t id : this->PointIds)
  {
    if (id >= 0)
    {
      wanted.push_back(this->SurfacePieceState.Vertex(id));
    }
  }
  const std::vector<double> fetched = solver.Fetch(this->SurfacePieceState, wanted, *Comm);
  std::vector<double> perVertex(
    static_cast<std::size_t>(this->SurfacePieceState.Mesh().NumberOfVertices()),
    std::numeric_limits<double>::quiet_NaN());
  for (std::size_t j = 0; j < wanted.size(); ++j)
  {
    perVertex[static_cast<std::size_t>(wanted[j])] = fetched[j];
  }
  perPoint = this->AtPoints(perVertex, maxDistance);
  return true;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::DistancesWithoutGraph(vtkAlgorithm* self, gs::GeodesicSolver solver,
  vtkPolyData* ownCells, vtkMTimeType key, const std::vector<vtkIdType>& sources,
  const std::vector<gs::Vec3>& points, vtkPolyData* curves, double maxDistance,
  std::vector<double>& perPoint)
{
  // Both solves need two rings (made at once when the piece is new; a piece kept from a graph's
  // run may have fewer), before source points name faces of the piece's mesh.
  if (!this->UsePiece(self, ownCells, key, 1))
  {
    return false;
  }
  const int rings = this->SurfacePieceState.Rings();
  if (rings < 1 &&
    !Reported(self, "The distributed surface: ", this->SurfacePieceState.Grow(1 - rings, *Comm)))
  {
    this->HasPiece = this->HasGraph = false; // (a piece that failed to grow is not used again)
    return false;
  }
  const std::vector<std::int64_t> ids = this->SurfaceIds(sources);
  // Curves first: their band's growth renumbers the piece's faces.
  std::vector<gs::SurfacePoint> samples;
  std::vector<std::vector<gs::CurvePiece>> runs;
  std::vector<std::vector<gs::PiecePointName>> names;
  std::vector<gs::CurvePiece> unused;
  std::int64_t crossed = 0;
  const bool exact = solver == gs::GeodesicSolver::Exact;
  if (curves &&
    (!this->SnapCurves(self, ownCells, curves, names) ||
      !this->TraceCurves(self, names, exact ? CurveUse::ExactSamples : CurveUse::Runs, samples,
        runs, unused, crossed)))
  {
    return false;
  }
  std::vector<gs::SurfacePoint> mine;
  if (!this->SnapPoints(self, ownCells, points, mine))
  {
    return false;
  }
  mine.insert(mine.end(), samples.begin(), samples.end());
  gs::Status status;
  std::vector<double> perVertex;
  if (!exact)
  {
    gs::VirtualSourcePiecesResult result;
    status = gs::ComputeVirtualSourcesOnPieces(this->SurfacePieceState, ids, maxDistance, *Comm,
      result, Progress(self, 0.1, 0.95), mine, runs);
    this->LastRounds = result.Rounds;
    this->LastWindows = result.Crossings;
    this->LastWindowsSent = result.FacesSent;
    perVertex = std::move(result.Distance);
  }
  else
  {
    gs::ExactPiecesResult result;
    status = gs::ComputeExactOnPieces(this->SurfacePieceState, ids, maxDistance, *Comm, result,
      Progress(self, 0.1, 0.95), mine);
    this->LastRounds = result.Rounds;
    this->LastWindows = result.WindowsPropagated;
    this->LastWindowsSent = result.WindowsSent;
    perVertex = std::move(result.Distance);
  }
  if (!Reported(self,
        curves ? "Source curves: " : points.empty() ? "Source vertex ids: " : "Source points: ", status))
  {
    this->HasPiece = this->HasGraph = false; // (its band may have failed to grow)
    return false;
  }
  this->LastRefinementRounds = 0;
  perPoint = this->AtPoints(perVertex, maxDistance);
  return true;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::SnapPoints(vtkAlgorithm* self, vtkPolyData* ownCells,
  const std::vector<gs::Vec3>& points, std::vector<gs::SurfacePoint>& mine,
  const std::vector<unsigned char>* anywhere, std::vector<gs::PiecePointName>* everywhere)
{
  mine.clear();
  std::vector<std::pair<std::size_t, gs::SurfacePoint>> held; // (point, its surface point)
  // The closest point of this process's own triangles to each point (distance, triangle, point).
  vtkNew<vtkPolyData> triangles;
  triangles->SetPoints(ownCells->GetPoints());
  triangles->SetPolys(ownCells->GetPolys());
  std::vector<double> distance(points.size(), std::numeric_limits<double>::infinity());
  std::vector<vtkIdType> cell(points.size(), -1);
  std::vector<std::array<double, 3>> closest(points.size());
  vtkNew<vtkStaticCellLocator> locator;
  vtkNew<vtkGenericCell> scratch;
  if (triangles->GetNumberOfPolys() > 0)
  {
    locator->SetDataSet(triangles);
    locator->BuildLocator();
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      const gs::Vec3& p = points[i];
      double x[3] = { p.x, p.y, p.z }, dist2 = 0.0;
      int subId = 0;
      if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z))
      {
        locator->FindClosestPoint(x, closest[i].data(), scratch, cell[i], subId, dist2);
        distance[i] = cell[i] >= 0 ? std::sqrt(dist2) : distance[i];
      }
    }
  }
  // The closest over the processes; the process holding it makes the surface point.
  std::vector<double> smallest;
  const std::vector<int> winner = gs::SmallestOverProcesses(*Comm, distance, smallest);
  const double diagonal = this->SurfacePieceState.LengthScale();
  std::string problem;
  const double reach = vtkSurfacePointLocator::MaximumDistanceFraction * diagonal;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const gs::Vec3& p = points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z) || winner[i] < 0 ||
      (smallest[i] > reach && !(anywhere && (*anywhere)[i])))
    {
      vtkErrorWithObjectMacro(self, "Source point " << i << ": "
          << (winner[i] < 0 ? std::string("non-finite coordinates")
                            : vtkSurfacePointLocator::TooFar(smallest[i],
                                vtkSurfacePointLocator::MaximumDistanceFraction, diagonal))
          << ".");
      return false;
    }
    if (winner[i] != Comm->Rank() || !problem.empty())
    {
      continue;
    }
    // The triangle's global id names the piece's face; its points' global ids its corners.
    triangles->GetCell(cell[i], scratch);
    const gs::SurfacePiece& piece = this->SurfacePieceState;
    const int face = piece.Face(this->TriangleIds[static_cast<std::size_t>(cell[i])]);
    const gs::Result<gs::SurfacePoint> q = face < 0
      ? gs::Result<gs::SurfacePoint>(gs::Status::Error("its triangle is not in the piece"))
      : vtkSurfacePointLocator::OnFace(scratch, closest[i].data(), face, piece.Mesh().Face(face),
          [this, &piece](vtkIdType point) {
            return piece.Vertex(this->PointIds[static_cast<std::size_t>(point)]);
          });
    if (q.Ok())
    {
      mine.push_back(*q);
      held.push_back({ i, *q });
    }
    else
    {
      problem = "Source point " + std::to_string(i) + ": " + q.Message() + ".";
    }
  }
  // (A failure on the process holding a point fails every process.)
  std::string first;
  if (gs::FirstMessage(*Comm, problem, first) >= 0)
  {
    vtkErrorWithObjectMacro(self, << first);
    mine.clear();
    return false;
  }
  if (everywhere)
  {
    // Every point's name, from the process holding it, to every process.
    everywhere->assign(points.size(), gs::PiecePointName());
    std::vector<gs::ByteBuffer> out(static_cast<std::size_t>(Comm->Size())), in;
    for (const auto& [i, q] : held)
    {
      const gs::PiecePointName name(this->SurfacePieceState, q);
      (*everywhere)[i] = name;
      for (gs::ByteBuffer& b : out)
      {
        gs::ByteWriter(b).Put(static_cast<std::int64_t>(i));
        gs::ByteWriter(b).Put(name);
      }
    }
    Comm->Exchange(out, in);
    for (std::size_t q = 0; q < in.size(); ++q)
    {
      gs::ByteReader r(in[q]);
      std::int64_t i = 0;
      gs::PiecePointName name;
      while (static_cast<int>(q) != Comm->Rank() && r.Get(i) && r.Get(name))
      {
        (*everywhere)[static_cast<std::size_t>(i)] = name;
      }
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::SnapCurves(vtkAlgorithm* self, vtkPolyData* ownCells, vtkPolyData* sources,
  std::vector<std::vector<gs::PiecePointName>>& curves)
{
  curves.clear();
  // The samples as vtkSurfacePointLocator::SnapCurve places them, with the whole surface's mean
  // edge length; the polyline's own points within the usual reach, the samples anywhere.
  const double spacing = vtkSurfacePointLocator::CurveSampleSpacing *
    this->SurfacePieceState.MeanEdgeLength(*Comm);
  constexpr vtkIdType MaximumSamplesPerSegment = 1 << 20;
  std::vector<gs::Vec3> xyz;
  std::vector<unsigned char> anywhere;
  std::vector<std::size_t> starts; // each curve's first sample
  vtkIdType npts = 0;
  const vtkIdType* pts = nullptr;
  auto lines = vtk::TakeSmartPointer(sources->GetLines()->NewIterator());
  for (lines->GoToFirstCell(); !lines->IsDoneWithTraversal(); lines->GoToNextCell())
  {
    lines->GetCurrentCell(npts, pts);
    starts.push_back(xyz.size());
    for (vtkIdType i = 0; i < npts; ++i)
    {
      double a[3], b[3];
      sources->GetPoint(pts[i], a);
      xyz.emplace_back(a[0], a[1], a[2]);
      anywhere.push_back(0);
      if (i + 1 == npts)
      {
        break;
      }
      sources->GetPoint(pts[i + 1], b);
      const double length = std::sqrt(vtkMath::Distance2BetweenPoints(a, b));
      const vtkIdType steps = std::isfinite(length)
        ? static_cast<vtkIdType>(std::min<double>(MaximumSamplesPerSegment, std::ceil(length / spacing)))
        : 1;
      for (vtkIdType s = 1; s < steps; ++s)
      {
        const double t = static_cast<double>(s) / static_cast<double>(steps);
        xyz.emplace_back(a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2]));
        anywhere.push_back(1);
      }
    }
  }
  starts.push_back(xyz.size());
  std::vector<gs::SurfacePoint> mine;
  std::vector<gs::PiecePointName> names;
  if (!this->SnapPoints(self, ownCells, xyz, mine, &anywhere, &names))
  {
    return false;
  }
  // Consecutive samples snapped to the same surface point count once, as serially.
  auto same = [](const gs::PiecePointName& a, const gs::PiecePointName& b) {
    return a.Vertex == b.Vertex && a.Face == b.Face && a.Bary == b.Bary;
  };
  for (std::size_t c = 0; c + 1 < starts.size(); ++c)
  {
    std::vector<gs::PiecePointName> curve;
    for (std::size_t i = starts[c]; i < starts[c + 1]; ++i)
    {
      if (curve.empty() || !same(curve.back(), names[i]))
      {
        curve.push_back(names[i]);
      }
    }
    if (!curve.empty())
    {
      curves.push_back(std::move(curve));
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkSurfacePieces::TraceCurves(vtkAlgorithm* self,
  const std::vector<std::vector<gs::PiecePointName>>& curves, CurveUse use,
  std::vector<gs::SurfacePoint>& points, std::vector<std::vector<gs::CurvePiece>>& runs,
  std::vector<gs::CurvePiece>& pieces, std::int64_t& faces)
{
  gs::SurfacePiece& piece = this->SurfacePieceState;
  const double mean = piece.MeanEdgeLength(*Comm);
  // The band grows around the curves' points until no walk enters the fence (faces with a
  // vertex whose other faces the piece lacks): a walk stopped by the band's edge would keep a
  // point alone where the whole surface goes on.
  std::vector<std::int64_t> around;
  for (const auto& curve : curves)
  {
    for (const gs::PiecePointName& p : curve)
    {
      p.AppendVertexIds(around);
    }
  }
  std::vector<gs::SurfacePoint> samples;
  std::vector<std::vector<gs::CurvePiece>> walks; // a walk per curve, or the runs
  std::vector<gs::CurvePiece> all;
  const gs::Status grown = piece.GrowUntilInside(around, *Comm, [&] {
    samples.clear();
    walks.clear();
    for (const auto& names : curves)
    {
      std::vector<gs::SurfacePoint> curve;
      for (const gs::PiecePointName& p : names)
      {
        curve.push_back(p.In(piece));
      }
      if (use != CurveUse::Runs)
      {
        walks.push_back(gs::TraceSurfaceCurve(piece.Mesh(), curve));
      }
      else
      {
        gs::AppendStraightRuns(piece.Mesh(), curve, walks);
        if (curve.size() == 1)
        {
          samples.push_back(curve[0]); // (a one-point curve is a point)
        }
      }
    }
    all.clear();
    std::vector<int> faces;
    for (const auto& walk : walks)
    {
      for (const gs::CurvePiece& step : walk)
      {
        all.push_back(step);
        faces.push_back(step.Face);
      }
    }
    return faces;
  });
  if (!Reported(self, "Source curve: ", grown))
  {
    this->HasPiece = this->HasGraph = false;
    return false;
  }
  if (use != CurveUse::Runs)
  {
    samples = gs::SampleCurvePieces(piece.Mesh(), all,
      (use == CurveUse::ExactSamples ? gs::ExactCurveSampleSpacing
                                     : gs::SVGGeodesicSolver::CurveSeedSpacing) * mean);
  }
  // This process's share: the samples on its own faces (or vertices it owns) and the pieces on
  // its own faces; the runs whole (each process seeds the pieces on its own faces).
  for (const gs::SurfacePoint& s : samples)
  {
    if (s.IsVertex() ? piece.IsOwned(s.Vertex) : piece.IsOwnFace(s.Face))
    {
      points.push_back(s);
    }
  }
  std::vector<std::int64_t> crossed;
  for (const gs::CurvePiece& step : all)
  {
    crossed.push_back(piece.FaceId(step.Face));
    if (piece.IsOwnFace(step.Face))
    {
      pieces.push_back(step);
    }
  }
  std::sort(crossed.begin(), crossed.end());
  faces = std::unique(crossed.begin(), crossed.end()) - crossed.begin();
  if (use == CurveUse::Runs)
  {
    runs = std::move(walks);
  }
  return true;
}

//------------------------------------------------------------------------------
std::vector<double> vtkSurfacePieces::AtPoints(
  const std::vector<double>& perVertex, double maxDistance) const
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> perPoint(this->PointIds.size(), nan);
  for (std::size_t i = 0; i < this->PointIds.size(); ++i)
  {
    const int v = this->PointIds[i] >= 0 ? this->SurfacePieceState.Vertex(this->PointIds[i]) : -1;
    if (v >= 0)
    {
      const double d = perVertex[static_cast<std::size_t>(v)];
      perPoint[i] = std::isfinite(d) && !(maxDistance > 0.0 && d > maxDistance) ? d : nan;
    }
  }
  return perPoint;
}
