// vtkSurfacePieces: geodesic graphs and their distances on a surface spread over the processes
// of the global controller (pvbatch --symmetric, pvserver), without gathering it: the core's
// SurfacePiece, PieceGraph and PieceDistanceSolver (Filters/Core/Geodesics/GraphPieces.h) over
// vtkMultiProcessController. Each process keeps its own cells; it gathers from its neighbours
// only the band of faces its vertices' solves need.
//
// The pieces must carry global point and cell ids (GetGlobalIds of the point and cell data:
// Redistribute DataSet, Global Point And Cell Ids, D3, a partitioned file written with them) and
// hold triangles only (vertex and line cells are ignored, as serially). Ghost cells are dropped.
//
// Every member is collective: every process calls it, in the same order.
//
// Not a vtkObject and not wrapped (a private class of the GeodesicShapes::Filters module).
#ifndef vtkSurfacePieces_h
#define vtkSurfacePieces_h

#include "GraphPieces.h"
#include "SaddleVertexGraph.h"
#include "SurfacePiece.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <memory>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkMultiProcessController;
class vtkPolyData;

class vtkSurfacePieces
{
public:
  explicit vtkSurfacePieces(vtkMultiProcessController* controller);
  ~vtkSurfacePieces();

  // Whether every process's `ownCells` (a piece without ghost cells) can be worked on in place;
  // otherwise `why` says what the first process that cannot lacks.
  bool CanUse(vtkPolyData* ownCells, std::string& why);

  // The band and graph for `ownCells` with `options`, kept while every process passes the same
  // `key` (the input's modification time) and options; built otherwise (progress from `self`,
  // from `from` to `to`, abortable). `built`: whether it was built now. Errors are reported on
  // `self`; false on every process when one fails or aborts.
  bool UseGraph(vtkAlgorithm* self, vtkPolyData* ownCells, vtkMTimeType key,
    const gs::SaddleVertexGraphOptions& options, double from, double to, bool& built);

  // Distances from the points of global ids `sources` to every point of `ownCells` (the piece
  // UseGraph was given), refined by geodesic triangle unfolding when `refine`: NaN where
  // unreached, beyond maxDistance (> 0) or not on a triangle. False (error on `self`) on every
  // process when a source id is no point of the surface.
  bool Distances(vtkAlgorithm* self, const std::vector<vtkIdType>& sources, double maxDistance,
    bool refine, std::vector<double>& perPoint);

  const gs::SurfacePiece& Piece() const { return SurfacePieceState; }
  // Rounds of exchanges the last Distances took: the graph search's and the refinement's.
  int SolveRounds() const { return LastRounds; }
  int RefinementRounds() const { return LastRefinementRounds; }
  const gs::PieceGraph& Graph() const { return GraphState; }

private:
  class Communicator;
  std::unique_ptr<Communicator> Comm;
  gs::SurfacePiece SurfacePieceState;
  gs::PieceGraph GraphState;
  bool HasGraph = false;
  int LastRounds = 0, LastRefinementRounds = 0;
  vtkMTimeType Key = 0;
  gs::SaddleVertexGraphOptions Options;
  std::vector<int> PointVertex; // per point of the piece's own cells: its piece vertex or -1
};

#endif
