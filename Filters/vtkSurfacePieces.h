// vtkSurfacePieces: geodesic graphs and their distances, exact distances, and geodesic polar
// coordinates, on a surface spread over the processes of the global controller (pvbatch
// --symmetric, pvserver), without gathering it: the core's SurfacePiece, PieceGraph,
// PieceDistanceSolver (Filters/Core/Geodesics/GraphPieces.h), ComputeExactOnPieces
// (Geodesics/ExactPieces.h) and ComputePolarOnPieces (Fields/PolarPieces.h) over
// vtkMultiProcessController. Each process keeps its own cells; it gathers from its neighbours
// only the band of faces its vertices' solves (or the chart) need.
//
// The pieces hold triangles only (vertex and line cells are ignored, as serially); ghost cells
// are dropped. Their global point and cell ids (GetGlobalIds of the point and cell data:
// Redistribute DataSet, Global Point And Cell Ids, D3, a partitioned file written with them)
// number the surface; pieces without them are numbered as gathering them would number them
// (PieceNumbering.h), so that point ids keep their serial meaning either way.
//
// Every member is collective: every process calls it, in the same order.
//
// Not a vtkObject and not wrapped (a private class of the GeodesicShapes::Filters module).
#ifndef vtkSurfacePieces_h
#define vtkSurfacePieces_h

#include "ExactPieces.h"
#include "SurfaceCurve.h"
#include "GeodesicEngine.h"
#include "VirtualSourcePieces.h"
#include "GraphPieces.h"
#include "PieceNumbering.h"
#include "PolarPieces.h"
#include "SaddleVertexGraph.h"
#include "SurfacePiece.h"

#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <memory>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDistributedSurface;
class vtkMultiProcessController;
class vtkPolyData;

class vtkSurfacePieces
{
public:
  explicit vtkSurfacePieces(vtkMultiProcessController* controller);
  ~vtkSurfacePieces();

  // Collective. A filter's route under MPI: its pieces object `pieces` (made on first use over
  // `distributed`'s controller) and `input`'s own cells when every process's piece can be worked
  // on in place; nullptr otherwise (the filter gathers; `self`'s debug output says why).
  static vtkSmartPointer<vtkPolyData> OwnCellsInPlace(vtkAlgorithm* self,
    const vtkDistributedSurface& distributed, std::unique_ptr<vtkSurfacePieces>& pieces,
    vtkPolyData* input);

  // Whether every process's `ownCells` (a piece without ghost cells) can be worked on in place;
  // otherwise `why` says what the first process that cannot lacks.
  bool CanUse(vtkPolyData* ownCells, std::string& why);

  // This process's piece of the surface from `ownCells` (a piece without ghost cells), kept
  // while every process passes the same `key` (the input's modification time); a new piece
  // gathers `rings` rings of faces around its own (SurfacePiece::Build). Errors are reported on
  // `self`; false on every process when one fails.
  bool UsePiece(vtkAlgorithm* self, vtkPolyData* ownCells, vtkMTimeType key, int rings = 0);

  // The band and graph for `ownCells` with `options`, kept while every process passes the same
  // `key` (the input's modification time) and options; built otherwise (progress from `self`,
  // from `from` to `to`, abortable). `built`: whether it was built now. Errors are reported on
  // `self`; false on every process when one fails or aborts.
  bool UseGraph(vtkAlgorithm* self, vtkPolyData* ownCells, vtkMTimeType key,
    const gs::SaddleVertexGraphOptions& options, double from, double to, bool& built);

  // Distances from the points `sources` (serial point ids, see SurfaceIds) or, when `points` is
  // not empty, from `points` in space (the same list on every process, snapped as a serial run
  // snaps them; the graph searched from the exact distances around them, GraphSeedsFromPoints)
  // to every point of `ownCells` (the piece UseGraph was given), refined by geodesic triangle
  // unfolding when `refine`: NaN where unreached, beyond maxDistance (> 0) or not on a
  // triangle. False (error on `self`) on every process when a source id is no point of the
  // surface or a point cannot be snapped.
  // With `curves` (line cells, the same on every process; null: none) the sources are curves,
  // the points joining them as one-point curves, as SVGGeodesicSolver::SolveCurves takes them.
  bool Distances(vtkAlgorithm* self, vtkPolyData* ownCells, const std::vector<vtkIdType>& sources,
    const std::vector<gs::Vec3>& points, vtkPolyData* curves, double maxDistance, bool refine,
    std::vector<double>& perPoint);

  // Distances without a graph from the points `sources` (serial point ids) and from `points` in
  // space (the same list on every process, snapped to the surface as a serial run snaps them)
  // to every point of `ownCells` (the piece of UsePiece, with `key`): exact (window propagation
  // on the pieces, ExactPieces.h) or by virtual sources (VirtualSourcePieces.h) as `solver`
  // says. NaN where unreached, beyond maxDistance (> 0) or not on a triangle. Progress from
  // `self`, abortable. False (error on `self`) on every process when a source id is no point of
  // the surface, a point cannot be snapped, or it aborted.
  // `curves`: line cells (the same on every process; null: none), each a curve source as a
  // serial run takes it (SnapCurves, TraceCurves).
  bool DistancesWithoutGraph(vtkAlgorithm* self, gs::GeodesicSolver solver, vtkPolyData* ownCells,
    vtkMTimeType key, const std::vector<vtkIdType>& sources, const std::vector<gs::Vec3>& points,
    vtkPolyData* curves, double maxDistance, std::vector<double>& perPoint);

  // Geodesic polar coordinates about the point `source` (a serial point id) or, when `points`
  // is not empty, about the first of `points` in space (the same list on every process, snapped
  // as a serial run snaps it: a point of `ownCells`' triangles, the piece UsePiece was given)
  // within `radius` (finite), theta's zero from `referenceDirection` (all zero: the source's
  // first edge), at every point of that piece (NaN outside the chart); `chart` says what the
  // chart's process found (angle sum, a reference direction normal to the surface, its faces).
  // False (error on `self`) on every process when it fails.
  // With `isoCurveAngles`, theta is the iso-curve arc-length angle.
  bool Polar(vtkAlgorithm* self, vtkPolyData* ownCells, vtkIdType source,
    const std::vector<gs::Vec3>& points, double radius, const double referenceDirection[3],
    bool isoCurveAngles, std::vector<double>& rho, std::vector<double>& theta,
    gs::PiecePolarCoordinates& chart);

  // Geodesic curve coordinates (offset in `rho`, normalized arc length in `theta`) about the
  // first line cell of `curve` (the same on every process) within `radius` (finite), at every
  // point of `ownCells` (the piece UsePiece was given; NaN outside): ComputeCurveCoordinatesOnPieces.
  bool PolarCurve(vtkAlgorithm* self, vtkPolyData* ownCells, vtkPolyData* curve, double radius,
    std::vector<double>& rho, std::vector<double>& theta, gs::PiecePolarCoordinates& chart);

  const gs::SurfacePiece& Piece() const { return SurfacePieceState; }
  // Rounds of exchanges the last Distances took: the graph search's and the refinement's.
  int SolveRounds() const { return LastRounds; }
  int RefinementRounds() const { return LastRefinementRounds; }
  // This process's work in the last DistancesWithoutGraph: windows propagated and sent to other
  // processes (exact), or edges crossed and sources sent (virtual sources).
  std::int64_t WindowsPropagated() const { return LastWindows; }
  std::int64_t WindowsSent() const { return LastWindowsSent; }
  const gs::PieceGraph& Graph() const { return GraphState; }

private:
  class Communicator;
  std::unique_ptr<Communicator> Comm;
  gs::SurfacePiece SurfacePieceState;
  gs::PieceGraph GraphState;
  bool HasPiece = false, HasGraph = false;
  vtkMTimeType PieceKey = 0;
  int LastRounds = 0, LastRefinementRounds = 0;
  std::int64_t LastWindows = 0, LastWindowsSent = 0;
  // Per point of the piece's own cells: the value of its vertex in `perVertex` (a vector over the
  // piece's mesh), NaN where it is not finite or beyond maxDistance (> 0).
  std::vector<double> AtPoints(const std::vector<double>& perVertex, double maxDistance) const;
  gs::SaddleVertexGraphOptions Options;
  // Per point of the piece's own cells: its global id, or -1 when no triangle uses it.
  std::vector<std::int64_t> PointIds;
  // Per triangle of the piece's own cells (in cell order): its global id.
  std::vector<std::int64_t> TriangleIds;
  // Collective. `points` snapped to the surface as vtkSurfacePointLocator snaps them serially
  // (the closest point of the surface, within a quarter of its bounding box diagonal): each
  // process finds the closest point of its own triangles, the closest over the processes wins
  // (the lowest rank on a tie). `mine`: the points this process holds, on its piece's mesh.
  // False (error on `self`, naming the point) on every process when one fails. Points flagged
  // in `anywhere` may lie farther (a curve's samples between its own points); `everywhere`
  // (when given) gets every point's name, on every process.
  bool SnapPoints(vtkAlgorithm* self, vtkPolyData* ownCells, const std::vector<gs::Vec3>& points,
    std::vector<gs::SurfacePoint>& mine, const std::vector<unsigned char>* anywhere = nullptr,
    std::vector<gs::PiecePointName>* everywhere = nullptr);
  // Collective. The line cells of `sources` (the same on every process) snapped as
  // vtkSurfacePointLocator::SnapCurve snaps them serially (samples at most a quarter of the
  // whole surface's mean edge apart), each curve's points named by global ids, on every process.
  bool SnapCurves(vtkAlgorithm* self, vtkPolyData* ownCells, vtkPolyData* sources,
    std::vector<std::vector<gs::PiecePointName>>& curves);
  // What a solver takes of a curve source (TraceCurves).
  enum class CurveUse
  {
    ExactSamples, // the exact solver's samples (ExactCurveSampleSpacing)
    Runs,         // the virtual sources' straight runs
    GraphSeeds    // the graph solvers' seeds: samples (CurveSeedSpacing) and traced pieces
  };
  // Collective. The curves traced on every process's piece (its band grown around them until
  // every trace stays inside), as `use` says: samples on this process's own faces (appended to
  // `points`), the straight runs whole (`runs`), the traced pieces on its own faces (`pieces`)
  // and the number of faces the curves cross (`faces`, over all processes).
  bool TraceCurves(vtkAlgorithm* self, const std::vector<std::vector<gs::PiecePointName>>& curves,
    CurveUse use, std::vector<gs::SurfacePoint>& points,
    std::vector<std::vector<gs::CurvePiece>>& runs, std::vector<gs::CurvePiece>& pieces,
    std::int64_t& faces);
  // Whether the pieces carry global ids; otherwise the ids number the gathered surface
  // (PieceNumbering.h), and FirstPoint is the gathered index of this piece's first point.
  bool GivenIds = true;
  std::int64_t FirstPoint = 0;
  // Collective. The global ids of points given as the serial run numbers them (with global ids,
  // the rank of the id among the vertices' ids; without, indices of the gathered surface's
  // points): -1 for a point no triangle uses.
  std::vector<std::int64_t> SurfaceIds(const std::vector<vtkIdType>& pointIds);
  // Collective. This process's triangles of `ownCells` with their ids (given, or numbered as
  // the gathered surface numbers them), into `own`; sets PointIds, GivenIds and FirstPoint.
  // False (error on `self`) on every process when the numbering fails.
  bool OwnTriangles(vtkAlgorithm* self, vtkPolyData* ownCells, gs::PieceTriangles& own);
};

#endif
