#include "vtkDistributedSurface.h"

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkDataSet.h>
#include <vtkDataSetAttributes.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <utility>
#include <vector>

namespace
{
// Message tags of the collectives (one per operation: a process never mixes them up).
enum Tags
{
  GATHER_SURFACE = 470301,
  SCATTER_SURFACE = 470302,
  GATHER_AUXILIARY = 470303,
  GATHER_FIRST = 470304
};

// Where a cell of a reassembled polydata comes from.
struct CellSource
{
  int Piece;
  vtkIdType Cell;
};

// vtkPolyData stores vertices, lines, polygons and strips apart, cell ids in that order.
int CellKind(int type)
{
  switch (type)
  {
    case VTK_VERTEX:
    case VTK_POLY_VERTEX:
      return 0;
    case VTK_LINE:
    case VTK_POLY_LINE:
      return 1;
    case VTK_TRIANGLE_STRIP:
      return 3;
    case VTK_EMPTY_CELL:
      return -1;
    default:
      return 2;
  }
}

// Builds a polydata from cells of `pieces` (in the given order, grouped by kind) whose points
// are `points` (new point i is points[i]); pointMap[piece][old point] is the new id. Point and
// cell arrays are those every piece has (global ids included); field data from the first piece.
vtkSmartPointer<vtkPolyData> Assemble(const std::vector<vtkPolyData*>& pieces,
  const std::vector<CellSource>& cells, const std::vector<std::pair<int, vtkIdType>>& points,
  const std::vector<std::vector<vtkIdType>>& pointMap)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  if (pieces.empty())
  {
    return out;
  }
  const int n = static_cast<int>(pieces.size());
  vtkDataSetAttributes::FieldList pointFields(n), cellFields(n);
  for (vtkPolyData* piece : pieces)
  {
    pointFields.IntersectFieldList(piece->GetPointData());
    cellFields.IntersectFieldList(piece->GetCellData());
  }

  vtkNew<vtkPoints> newPoints;
  newPoints->SetDataType(
    pieces[0]->GetPoints() ? pieces[0]->GetPoints()->GetDataType() : VTK_DOUBLE);
  newPoints->SetNumberOfPoints(static_cast<vtkIdType>(points.size()));
  vtkPointData* outPD = out->GetPointData();
  outPD->CopyAllOn();
  pointFields.CopyAllocate(outPD, vtkDataSetAttributes::COPYTUPLE,
    static_cast<vtkIdType>(points.size()), 0);
  for (size_t i = 0; i < points.size(); ++i)
  {
    vtkPolyData* piece = pieces[static_cast<size_t>(points[i].first)];
    const vtkIdType id = static_cast<vtkIdType>(i);
    newPoints->SetPoint(id, piece->GetPoint(points[i].second));
    pointFields.CopyData(points[i].first, piece->GetPointData(), points[i].second, outPD, id);
  }
  out->SetPoints(newPoints);

  std::array<std::vector<CellSource>, 4> byKind;
  for (const CellSource& c : cells)
  {
    const int kind = CellKind(pieces[static_cast<size_t>(c.Piece)]->GetCellType(c.Cell));
    if (kind >= 0)
    {
      byKind[static_cast<size_t>(kind)].push_back(c);
    }
  }
  vtkCellData* outCD = out->GetCellData();
  outCD->CopyAllOn();
  cellFields.CopyAllocate(
    outCD, vtkDataSetAttributes::COPYTUPLE, static_cast<vtkIdType>(cells.size()), 0);
  std::array<vtkSmartPointer<vtkCellArray>, 4> arrays;
  vtkNew<vtkIdList> ids;
  vtkIdType next = 0;
  for (size_t kind = 0; kind < 4; ++kind)
  {
    arrays[kind] = vtkSmartPointer<vtkCellArray>::New();
    for (const CellSource& c : byKind[kind])
    {
      vtkPolyData* piece = pieces[static_cast<size_t>(c.Piece)];
      piece->GetCellPoints(c.Cell, ids);
      const std::vector<vtkIdType>& map = pointMap[static_cast<size_t>(c.Piece)];
      for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      {
        ids->SetId(k, map[static_cast<size_t>(ids->GetId(k))]);
      }
      arrays[kind]->InsertNextCell(ids);
      cellFields.CopyData(c.Piece, piece->GetCellData(), c.Cell, outCD, next++);
    }
  }
  out->SetVerts(arrays[0]);
  out->SetLines(arrays[1]);
  out->SetPolys(arrays[2]);
  out->SetStrips(arrays[3]);
  out->GetFieldData()->ShallowCopy(pieces[0]->GetFieldData());
  return out;
}

// Every cell of `pieces`, piece after piece.
std::vector<CellSource> AllCells(const std::vector<vtkPolyData*>& pieces)
{
  std::vector<CellSource> cells;
  for (size_t j = 0; j < pieces.size(); ++j)
  {
    for (vtkIdType c = 0; c < pieces[j]->GetNumberOfCells(); ++c)
    {
      cells.push_back({ static_cast<int>(j), c });
    }
  }
  return cells;
}

// Every point of `pieces`, piece after piece (shared points repeated), and the point map.
void AllPoints(const std::vector<vtkPolyData*>& pieces,
  std::vector<std::pair<int, vtkIdType>>& points, std::vector<std::vector<vtkIdType>>& map)
{
  points.clear();
  map.assign(pieces.size(), {});
  for (size_t j = 0; j < pieces.size(); ++j)
  {
    for (vtkIdType i = 0; i < pieces[j]->GetNumberOfPoints(); ++i)
    {
      map[j].push_back(static_cast<vtkIdType>(points.size()));
      points.emplace_back(static_cast<int>(j), i);
    }
  }
}

// The non-ghost cells of `piece` with their origin arrays, ghost arrays removed.
vtkSmartPointer<vtkPolyData> PrepareForGather(vtkPolyData* piece, int rank)
{
  auto prepared = vtkSmartPointer<vtkPolyData>::New();
  if (!piece || piece->GetNumberOfPoints() == 0)
  {
    return prepared;
  }
  vtkUnsignedCharArray* ghosts = piece->GetCellGhostArray();
  std::vector<vtkIdType> keep;
  keep.reserve(static_cast<size_t>(piece->GetNumberOfCells()));
  for (vtkIdType c = 0; c < piece->GetNumberOfCells(); ++c)
  {
    if (!ghosts || !(ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL))
    {
      keep.push_back(c);
    }
  }
  // Every point is kept (unused points are part of the serial surface too).
  vtkNew<vtkPolyData> tagged;
  tagged->ShallowCopy(piece);
  vtkNew<vtkIntArray> origin;
  origin->SetName(vtkDistributedSurface::OriginProcessArrayName());
  origin->SetNumberOfTuples(piece->GetNumberOfCells());
  origin->FillValue(rank);
  vtkNew<vtkIdTypeArray> originCell;
  originCell->SetName(vtkDistributedSurface::OriginCellArrayName());
  originCell->SetNumberOfTuples(piece->GetNumberOfCells());
  for (vtkIdType c = 0; c < piece->GetNumberOfCells(); ++c)
  {
    originCell->SetValue(c, c);
  }
  tagged->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  tagged->GetPointData()->RemoveArray(vtkDataSetAttributes::GhostArrayName());
  tagged->GetCellData()->AddArray(origin);
  tagged->GetCellData()->AddArray(originCell);
  std::vector<CellSource> cells;
  cells.reserve(keep.size());
  for (vtkIdType c : keep)
  {
    cells.push_back({ 0, c });
  }
  std::vector<std::pair<int, vtkIdType>> points;
  std::vector<std::vector<vtkIdType>> map;
  AllPoints({ tagged.Get() }, points, map);
  return Assemble({ tagged.Get() }, cells, points, map);
}

// Same number of points and cells, same coordinates.
bool SamePoints(vtkPointSet* a, vtkPointSet* b)
{
  if (a->GetNumberOfPoints() != b->GetNumberOfPoints() ||
    a->GetNumberOfCells() != b->GetNumberOfCells())
  {
    return false;
  }
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double x[3], y[3];
    a->GetPoint(i, x);
    b->GetPoint(i, y);
    if (x[0] != y[0] || x[1] != y[1] || x[2] != y[2])
    {
      return false;
    }
  }
  return true;
}

vtkIdType GlobalId(vtkDataArray* ids, vtkIdType i)
{
  return static_cast<vtkIdType>(ids->GetComponent(i, 0));
}
} // namespace

//------------------------------------------------------------------------------
vtkDistributedSurface::vtkDistributedSurface(vtkInformation* outputInformation)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() < 2 || !outputInformation ||
    !outputInformation->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) ||
    !outputInformation->Has(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER()))
  {
    return;
  }
  const int pieces =
    outputInformation->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES());
  const int piece = outputInformation->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
  if (pieces != controller->GetNumberOfProcesses() || piece != controller->GetLocalProcessId())
  {
    return; // not a partition over the processes (e.g. a streaming request): serial
  }
  this->Controller = controller;
  this->Rank = piece;
  this->Size = pieces;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkDistributedSurface::ExtractCells(
  vtkPolyData* input, const vtkIdType* cells, vtkIdType numberOfCells)
{
  if (!input)
  {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  std::vector<CellSource> list;
  list.reserve(static_cast<size_t>(numberOfCells));
  std::vector<char> used(static_cast<size_t>(input->GetNumberOfPoints()), 0);
  vtkNew<vtkIdList> ids;
  for (vtkIdType i = 0; i < numberOfCells; ++i)
  {
    list.push_back({ 0, cells[i] });
    input->GetCellPoints(cells[i], ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      used[static_cast<size_t>(ids->GetId(k))] = 1;
    }
  }
  std::vector<std::pair<int, vtkIdType>> points;
  std::vector<std::vector<vtkIdType>> map(1, std::vector<vtkIdType>(used.size(), -1));
  for (size_t p = 0; p < used.size(); ++p)
  {
    if (used[p])
    {
      map[0][p] = static_cast<vtkIdType>(points.size());
      points.emplace_back(0, static_cast<vtkIdType>(p));
    }
  }
  return Assemble({ input }, list, points, map);
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkDistributedSurface::OwnCells(vtkPolyData* piece)
{
  vtkUnsignedCharArray* ghosts = piece ? piece->GetCellGhostArray() : nullptr;
  bool duplicates = false;
  for (vtkIdType c = 0; ghosts && c < ghosts->GetNumberOfTuples() && !duplicates; ++c)
  {
    duplicates = (ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL) != 0;
  }
  if (piece && !duplicates)
  {
    // No ghost cell to drop: the piece itself (shallow), without its ghost arrays.
    auto own = vtkSmartPointer<vtkPolyData>::New();
    own->ShallowCopy(piece);
    own->GetCellData()->RemoveArray(vtkDataSetAttributes::GhostArrayName());
    own->GetPointData()->RemoveArray(vtkDataSetAttributes::GhostArrayName());
    return own;
  }
  vtkSmartPointer<vtkPolyData> own = PrepareForGather(piece, 0);
  own->GetCellData()->RemoveArray(OriginProcessArrayName());
  own->GetCellData()->RemoveArray(OriginCellArrayName());
  return own;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkDistributedSurface::GatherSurface(vtkPolyData* piece) const
{
  vtkSmartPointer<vtkPolyData> mine = PrepareForGather(piece, this->Rank);
  if (!this->IsRoot())
  {
    this->Controller->Send(mine, 0, GATHER_SURFACE);
    return nullptr;
  }
  std::vector<vtkSmartPointer<vtkPolyData>> received(static_cast<size_t>(this->Size));
  received[0] = mine;
  for (int r = 1; r < this->Size; ++r)
  {
    vtkSmartPointer<vtkDataObject> object =
      vtkSmartPointer<vtkDataObject>::Take(this->Controller->ReceiveDataObject(r, GATHER_SURFACE));
    received[static_cast<size_t>(r)] = vtkPolyData::SafeDownCast(object);
  }
  std::vector<vtkPolyData*> pieces;
  for (auto& p : received)
  {
    if (p && p->GetNumberOfPoints() > 0)
    {
      pieces.push_back(p);
    }
  }
  if (pieces.empty())
  {
    return vtkSmartPointer<vtkPolyData>::New();
  }
  const int n = static_cast<int>(pieces.size());
  bool cellIds = true, pointIds = true;
  for (vtkPolyData* p : pieces)
  {
    cellIds = cellIds && p->GetCellData()->GetGlobalIds() != nullptr;
    pointIds = pointIds && p->GetPointData()->GetGlobalIds() != nullptr;
  }

  // Cells: in global id order, each id once; otherwise in rank order.
  std::vector<CellSource> cells = AllCells(pieces);
  if (cellIds)
  {
    std::vector<std::pair<vtkIdType, size_t>> keys(cells.size());
    for (size_t i = 0; i < cells.size(); ++i)
    {
      keys[i] = { GlobalId(pieces[static_cast<size_t>(cells[i].Piece)]->GetCellData()->GetGlobalIds(),
                    cells[i].Cell),
        i };
    }
    std::sort(keys.begin(), keys.end());
    std::vector<CellSource> ordered;
    ordered.reserve(cells.size());
    for (size_t i = 0; i < keys.size(); ++i)
    {
      if (i == 0 || keys[i].first != keys[i - 1].first)
      {
        ordered.push_back(cells[keys[i].second]);
      }
    }
    cells.swap(ordered);
  }

  // Points: merged by global id in id order; otherwise every piece's points in rank order.
  std::vector<std::pair<int, vtkIdType>> points;
  std::vector<std::vector<vtkIdType>> map(static_cast<size_t>(n));
  if (pointIds)
  {
    std::vector<std::pair<vtkIdType, std::pair<int, vtkIdType>>> keys;
    for (int j = 0; j < n; ++j)
    {
      vtkPolyData* p = pieces[static_cast<size_t>(j)];
      vtkDataArray* ids = p->GetPointData()->GetGlobalIds();
      map[static_cast<size_t>(j)].assign(static_cast<size_t>(p->GetNumberOfPoints()), -1);
      for (vtkIdType i = 0; i < p->GetNumberOfPoints(); ++i)
      {
        keys.push_back({ GlobalId(ids, i), { j, i } });
      }
    }
    std::sort(keys.begin(), keys.end());
    for (size_t i = 0; i < keys.size(); ++i)
    {
      if (i == 0 || keys[i].first != keys[i - 1].first)
      {
        points.push_back(keys[i].second);
      }
      map[static_cast<size_t>(keys[i].second.first)][static_cast<size_t>(keys[i].second.second)] =
        static_cast<vtkIdType>(points.size()) - 1;
    }
  }
  else
  {
    AllPoints(pieces, points, map);
  }
  return Assemble(pieces, cells, points, map);
}

//------------------------------------------------------------------------------
void vtkDistributedSurface::ScatterSurface(vtkPolyData* whole, vtkPolyData* piece) const
{
  if (!this->IsRoot())
  {
    vtkSmartPointer<vtkDataObject> object = vtkSmartPointer<vtkDataObject>::Take(
      this->Controller->ReceiveDataObject(0, SCATTER_SURFACE));
    vtkPolyData* mine = vtkPolyData::SafeDownCast(object);
    if (piece)
    {
      if (mine)
      {
        piece->ShallowCopy(mine);
      }
      else
      {
        piece->Initialize();
      }
    }
    return;
  }
  vtkDataArray* origin =
    whole ? whole->GetCellData()->GetArray(OriginProcessArrayName()) : nullptr;
  vtkDataArray* originCell =
    whole ? whole->GetCellData()->GetArray(OriginCellArrayName()) : nullptr;
  std::vector<std::vector<std::pair<vtkIdType, vtkIdType>>> cells(static_cast<size_t>(this->Size));
  if (origin && originCell)
  {
    for (vtkIdType c = 0; c < whole->GetNumberOfCells(); ++c)
    {
      const int r = static_cast<int>(origin->GetComponent(c, 0));
      if (r >= 0 && r < this->Size)
      {
        cells[static_cast<size_t>(r)].push_back(
          { static_cast<vtkIdType>(originCell->GetComponent(c, 0)), c });
      }
    }
  }
  for (int r = this->Size - 1; r >= 0; --r)
  {
    vtkSmartPointer<vtkPolyData> part = vtkSmartPointer<vtkPolyData>::New();
    if (origin && originCell)
    {
      auto& list = cells[static_cast<size_t>(r)];
      std::stable_sort(list.begin(), list.end(),
        [](const std::pair<vtkIdType, vtkIdType>& a, const std::pair<vtkIdType, vtkIdType>& b) {
          return a.first < b.first;
        });
      std::vector<vtkIdType> ids(list.size());
      for (size_t i = 0; i < list.size(); ++i)
      {
        ids[i] = list[i].second;
      }
      part = ExtractCells(whole, ids.data(), static_cast<vtkIdType>(ids.size()));
      part->GetCellData()->RemoveArray(OriginProcessArrayName());
      part->GetCellData()->RemoveArray(OriginCellArrayName());
    }
    if (r > 0)
    {
      this->Controller->Send(part, r, SCATTER_SURFACE);
    }
    else if (piece)
    {
      piece->ShallowCopy(part);
    }
  }
}

//------------------------------------------------------------------------------
void vtkDistributedSurface::ExecuteOnWhole(vtkPolyData* piece,
  const std::vector<vtkPointSet*>& auxiliaries, vtkPolyData* output,
  const SurfaceExecute& execute) const
{
  vtkSmartPointer<vtkPolyData> whole = this->GatherSurface(piece);
  std::vector<vtkSmartPointer<vtkPointSet>> gathered;
  for (vtkPointSet* auxiliary : auxiliaries)
  {
    gathered.push_back(this->GatherAuxiliary(auxiliary));
  }
  vtkNew<vtkPolyData> result;
  if (this->IsRoot())
  {
    execute(whole, gathered, result);
  }
  this->ScatterSurface(result, output);
}

//------------------------------------------------------------------------------
int vtkDistributedSurface::RequestData(vtkAlgorithm* self, vtkInformationVector** inputVector,
  vtkInformationVector* outputVector, const FilterExecute& execute)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  std::vector<vtkPointSet*> auxiliaries;
  for (int port = 1; port < self->GetNumberOfInputPorts(); ++port)
  {
    auxiliaries.push_back(inputVector[port]->GetNumberOfInformationObjects() > 0
        ? vtkPointSet::GetData(inputVector[port], 0)
        : nullptr);
  }
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!input || !output)
  {
    vtkErrorWithObjectMacro(self, "Missing input or output mesh.");
    return 0;
  }
  // Under MPI: the whole surface on process 0, the results back to each process's piece.
  const vtkDistributedSurface distributed(outputVector->GetInformationObject(0));
  if (distributed)
  {
    distributed.ExecuteOnWhole(input, auxiliaries, output,
      [&execute](vtkPolyData* whole, const std::vector<vtkSmartPointer<vtkPointSet>>& gathered,
        vtkPolyData* result) {
        std::vector<vtkPointSet*> raw(gathered.begin(), gathered.end());
        execute(whole, raw, result);
      });
    return 1;
  }
  return execute(input, auxiliaries, output);
}

//------------------------------------------------------------------------------
bool vtkDistributedSurface::GatherAuxiliaryPoints(
  vtkPointSet* piece, std::vector<double>& xyz) const
{
  xyz.clear();
  vtkSmartPointer<vtkPointSet> all = this->GatherAuxiliary(piece);
  vtkIdType count = 0; // -1: line cells
  if (this->IsRoot() && all)
  {
    vtkPolyData* poly = vtkPolyData::SafeDownCast(all);
    count = poly && poly->GetNumberOfLines() > 0 ? -1 : all->GetNumberOfPoints();
    for (vtkIdType i = 0; i < count; ++i)
    {
      double x[3];
      all->GetPoint(i, x);
      xyz.insert(xyz.end(), x, x + 3);
    }
  }
  this->Controller->Broadcast(&count, 1, 0);
  if (count > 0)
  {
    xyz.resize(3 * static_cast<std::size_t>(count));
    this->Controller->Broadcast(xyz.data(), 3 * count, 0);
  }
  return count >= 0;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPolyData> vtkDistributedSurface::GatherAuxiliaryEverywhere(vtkPointSet* piece) const
{
  vtkSmartPointer<vtkPointSet> all = this->GatherAuxiliary(piece);
  int connected = this->IsRoot() && all ? 1 : 0;
  this->Controller->Broadcast(&connected, 1, 0);
  if (!connected)
  {
    return nullptr;
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  if (this->IsRoot())
  {
    if (vtkPolyData* p = vtkPolyData::SafeDownCast(all))
    {
      poly->SetPoints(p->GetPoints());
      poly->SetLines(p->GetLines());
    }
    else
    {
      poly->SetPoints(all->GetPoints());
    }
    if (!poly->GetPoints())
    {
      poly->SetPoints(vtkSmartPointer<vtkPoints>::New());
    }
  }
  this->Controller->Broadcast(poly, 0);
  return poly;
}

//------------------------------------------------------------------------------
void vtkDistributedSurface::SplitPointsAndCurves(
  vtkPolyData* all, std::vector<double>& xyz, vtkSmartPointer<vtkPolyData>& curves)
{
  std::vector<unsigned char> onCurve(static_cast<std::size_t>(all->GetNumberOfPoints()), 0);
  if (all->GetLines() && all->GetNumberOfLines() > 0)
  {
    curves = all;
    auto it = vtk::TakeSmartPointer(all->GetLines()->NewIterator());
    vtkIdType npts = 0;
    const vtkIdType* pts = nullptr;
    for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
    {
      it->GetCurrentCell(npts, pts);
      for (vtkIdType i = 0; i < npts; ++i)
      {
        if (pts[i] >= 0 && pts[i] < all->GetNumberOfPoints())
        {
          onCurve[static_cast<std::size_t>(pts[i])] = 1;
        }
      }
    }
  }
  for (vtkIdType i = 0; i < all->GetNumberOfPoints(); ++i)
  {
    if (!onCurve[static_cast<std::size_t>(i)])
    {
      double x[3];
      all->GetPoint(i, x);
      xyz.insert(xyz.end(), x, x + 3);
    }
  }
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkPointSet> vtkDistributedSurface::GatherAuxiliary(vtkPointSet* piece) const
{
  vtkSmartPointer<vtkPointSet> mine = piece;
  if (!mine)
  {
    mine = vtkSmartPointer<vtkPolyData>::New();
  }
  if (!this->IsRoot())
  {
    this->Controller->Send(mine, 0, GATHER_AUXILIARY);
    return nullptr;
  }
  std::vector<vtkSmartPointer<vtkPointSet>> pieces;
  if (mine->GetNumberOfPoints() > 0)
  {
    pieces.push_back(mine);
  }
  for (int r = 1; r < this->Size; ++r)
  {
    vtkSmartPointer<vtkDataObject> object = vtkSmartPointer<vtkDataObject>::Take(
      this->Controller->ReceiveDataObject(r, GATHER_AUXILIARY));
    vtkPointSet* set = vtkPointSet::SafeDownCast(object);
    if (set && set->GetNumberOfPoints() > 0)
    {
      pieces.push_back(set);
    }
  }
  if (!piece)
  {
    return nullptr; // the optional input is not connected
  }
  if (pieces.size() <= 1)
  {
    return pieces.empty() ? mine : pieces[0];
  }
  // A source that every process generated whole (e.g. a programmable source that ignores piece
  // requests) arrives as identical copies: keep one.
  bool replicated = true;
  for (size_t j = 1; j < pieces.size() && replicated; ++j)
  {
    replicated = SamePoints(pieces[0], pieces[j]);
  }
  if (replicated)
  {
    return pieces[0];
  }
  // Several pieces: append them (polydata: all cells; other point sets: the points only, which
  // is all the filters read from them).
  bool allPolyData = true;
  for (auto& p : pieces)
  {
    allPolyData = allPolyData && vtkPolyData::SafeDownCast(p) != nullptr;
  }
  if (allPolyData)
  {
    std::vector<vtkPolyData*> polys;
    for (auto& p : pieces)
    {
      polys.push_back(vtkPolyData::SafeDownCast(p));
    }
    std::vector<std::pair<int, vtkIdType>> points;
    std::vector<std::vector<vtkIdType>> map;
    AllPoints(polys, points, map);
    return Assemble(polys, AllCells(polys), points, map);
  }
  auto all = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (auto& p : pieces)
  {
    for (vtkIdType i = 0; i < p->GetNumberOfPoints(); ++i)
    {
      points->InsertNextPoint(p->GetPoint(i));
    }
  }
  all->SetPoints(points);
  return all;
}

//------------------------------------------------------------------------------
vtkSmartPointer<vtkDataObject> vtkDistributedSurface::GatherFirstNonEmpty(
  vtkDataObject* piece) const
{
  auto count = [](vtkDataObject* object) -> int {
    vtkDataSet* set = vtkDataSet::SafeDownCast(object);
    return set && set->GetNumberOfPoints() > 0 ? 1 : 0;
  };
  const int mine = count(piece);
  std::vector<int> all(static_cast<size_t>(this->Size), 0);
  this->Controller->Gather(&mine, all.data(), 1, 0);
  int source = 0;
  if (this->IsRoot())
  {
    const auto it = std::find(all.begin(), all.end(), 1);
    source = it == all.end() ? 0 : static_cast<int>(it - all.begin());
  }
  this->Controller->Broadcast(&source, 1, 0);
  if (source == 0)
  {
    return this->IsRoot() ? vtkSmartPointer<vtkDataObject>(piece) : nullptr;
  }
  if (this->Rank == source)
  {
    this->Controller->Send(piece, 0, GATHER_FIRST);
    return nullptr;
  }
  if (this->IsRoot())
  {
    return vtkSmartPointer<vtkDataObject>::Take(
      this->Controller->ReceiveDataObject(source, GATHER_FIRST));
  }
  return nullptr;
}
