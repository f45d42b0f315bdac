// vtkDistributedSurface: the filters' behaviour under MPI (pvbatch --symmetric, pvserver).
//
// Every algorithm of the suite needs the whole surface (geodesics cross piece boundaries), so a
// filter whose request is one piece of a partition over the processes of the global controller
// gathers the pieces on process 0, runs there, and hands each process back what belongs to it:
//  - GatherSurface: every process sends its piece; process 0 reassembles the surface. Ghost
//    cells (vtkGhostType DUPLICATECELL) are dropped. When every non-empty piece carries global
//    cell ids (GetGlobalIds of the cell data: Redistribute DataSet, Global Point And Cell Ids,
//    D3) the cells are put in global id order (a cell present twice is kept once); when every
//    non-empty piece carries global point ids, points shared by pieces are merged by id and put
//    in id order. The surface is then the serial one, cell for cell and point for point, and the
//    results are the serial results. Without ids the pieces are concatenated in rank order (the
//    mesh builder welds the exactly coincident copies of shared points): the same surface and
//    distances, but vertex and face numbers differ from a serial run, and so may a random
//    distribution's shapes. Each reassembled cell carries its origin (process, cell id).
//  - ScatterSurface: process 0's result on the whole surface goes back as pieces: each process
//    receives the cells that came from its piece (in its order), with their points and every
//    point, cell and field array. Ghost cells are not passed on.
//  - GatherAuxiliary (source points, curves, singularities, strokes: small point sets) appends
//    the processes' pieces on process 0 (identical copies, from a source that every process
//    generated whole, count once); GatherFirstNonEmpty (the tables of MSDT Source) takes
//    the first non-empty piece in rank order.
// All of these are collective: every process of the controller calls them, in the same order,
// whatever its input (a missing or empty input is sent as an empty piece).
//
// Not a vtkObject and not wrapped (a private class of the GeodesicShapes::Filters module).
#ifndef vtkDistributedSurface_h
#define vtkDistributedSurface_h

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <functional>
#include <initializer_list>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;
class vtkInformation;
class vtkInformationVector;
class vtkMultiProcessController;
class vtkPointSet;
class vtkPolyData;

class vtkDistributedSurface
{
public:
  // Names of the cell arrays that record where a reassembled cell came from.
  static const char* OriginProcessArrayName() { return "vtkGSOriginProcess"; }
  static const char* OriginCellArrayName() { return "vtkGSOriginCell"; }

  // The global controller when `outputInformation` requests piece p of P with P the number of
  // its processes (> 1) and p this process's rank; nullptr otherwise (a serial run).
  explicit vtkDistributedSurface(vtkInformation* outputInformation);

  explicit operator bool() const { return this->Controller != nullptr; }
  vtkMultiProcessController* GetController() const { return this->Controller; }
  bool IsRoot() const { return this->Rank == 0; }
  int GetRank() const { return this->Rank; }
  int GetNumberOfProcesses() const { return this->Size; }

  // A piece's own cells: its non-ghost cells with every point and array, ghost arrays removed
  // (what GatherSurface sends and what a filter working on pieces outputs).
  static vtkSmartPointer<vtkPolyData> OwnCells(vtkPolyData* piece);

  // Collective. On process 0 the whole surface (see above); nullptr elsewhere.
  vtkSmartPointer<vtkPolyData> GatherSurface(vtkPolyData* piece) const;

  // Collective. Process 0 passes the result computed on GatherSurface's surface (it may have
  // been triangulated: the origin arrays follow the cells); every process gets its cells in
  // `piece`. A result without origin arrays (an error) gives every process an empty piece.
  void ScatterSurface(vtkPolyData* whole, vtkPolyData* piece) const;

  // Collective: the whole protocol of a filter whose output is its input surface with arrays.
  // Gathers `piece` and each of `auxiliaries` (GatherAuxiliary), calls `execute(whole surface,
  // gathered auxiliaries in the same order, result)` on process 0, and scatters the result into
  // `output` (ScatterSurface).
  using SurfaceExecute = std::function<void(
    vtkPolyData*, const std::vector<vtkSmartPointer<vtkPointSet>>&, vtkPolyData*)>;
  void ExecuteOnWhole(vtkPolyData* piece, const std::vector<vtkPointSet*>& auxiliaries,
    vtkPolyData* output, const SurfaceExecute& execute) const;

  // The RequestData of a mesh filter whose port 0 is the surface and whose other ports are
  // optional auxiliary point sets: fetches them (nullptr when not connected) and returns
  // `execute(surface, auxiliaries in port order, output)` in a serial run; under MPI runs it on
  // the whole surface on process 0 (ExecuteOnWhole) and returns 1. A missing surface or output
  // is an error of `self` (returns 0).
  using FilterExecute =
    std::function<int(vtkPolyData*, const std::vector<vtkPointSet*>&, vtkPolyData*)>;
  static int RequestData(vtkAlgorithm* self, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector, const FilterExecute& execute);

  // Collective. On process 0 the pieces of an optional point set appended in rank order (a
  // single non-empty piece is passed as it is; nullptr when process 0's input is missing, as the
  // input is then not connected); nullptr elsewhere.
  vtkSmartPointer<vtkPointSet> GatherAuxiliary(vtkPointSet* piece) const;

  // Collective. The points of an optional point set as GatherAuxiliary gathers it, on every
  // process (x, y, z of each point in order; none when the input is not connected): true, or
  // false (and `xyz` empty) on every process when it holds line cells (curves).
  bool GatherAuxiliaryPoints(vtkPointSet* piece, std::vector<double>& xyz) const;

  // Collective. An optional point set as GatherAuxiliary gathers it, on every process, as
  // polydata (its points and, for polydata, its line cells; another point set: its points
  // only); nullptr on every process when the input is not connected.
  vtkSmartPointer<vtkPolyData> GatherAuxiliaryEverywhere(vtkPointSet* piece) const;
  // Source points and curves as the pieces take them from such a polydata: the points no line
  // cell uses (x, y, z in order, as a serial run takes them as points) and, when it has line
  // cells, the curves (`all` itself).
  static void SplitPointsAndCurves(
    vtkPolyData* all, std::vector<double>& xyz, vtkSmartPointer<vtkPolyData>& curves);

  // Collective. On process 0 the first piece, in rank order, with at least one point (process
  // 0's own when all are empty); nullptr elsewhere.
  vtkSmartPointer<vtkDataObject> GatherFirstNonEmpty(vtkDataObject* piece) const;

private:
  // Copies the cells `cells` of `input` (in that order, grouped by kind as vtkPolyData stores
  // them: vertices, lines, polygons, strips) with the points they use (in increasing id order)
  // and their point, cell and field data.
  static vtkSmartPointer<vtkPolyData> ExtractCells(vtkPolyData* input, const vtkIdType* cells,
    vtkIdType numberOfCells);

  vtkMultiProcessController* Controller = nullptr;
  int Rank = 0;
  int Size = 1;
};

#endif
