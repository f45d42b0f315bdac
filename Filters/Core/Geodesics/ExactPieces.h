// Exact geodesic distance on a surface partitioned over processes (MPI), without any process
// holding the whole surface: the window propagation of ExactGeodesicSolver on each process's
// piece (SurfacePiece, with a band of two rings of faces), each process propagating the windows
// of its own faces and spreading the pseudo-source vertices it owns.
//
// The solve runs by rounds of distance thresholds: in each round every process propagates its
// windows up to the round's threshold (the smallest key over all processes plus a step of the
// surface's size); a window that enters another process's face, and an improved distance of
// another process's vertex, go to that process at the end of each pass, and the passes repeat
// until no process sent anything below the threshold. Window propagation with the vertex
// trimming and "one angle, one split" pruning is exact in any order of processing (every
// distance it compares with is the length of a path on the surface); an owned pseudo-source
// vertex whose distance drops after it spread spreads again. So the distances are the exact
// geodesic distances, equal to a serial solve's up to rounding (the order of the windows, and
// so the rounding of ties, differs). Departure angles come with them (ExactPiecesResult); path
// origins are not computed.
#pragma once

#include "PieceCommunicator.h"
#include "SaddleVertexGraph.h"
#include "Status.h"
#include "SurfacePiece.h"

#include <cstdint>
#include <vector>

namespace gs
{

struct ExactPiecesResult
{
  // Per vertex of the piece's mesh: the distance of every vertex of the process's own faces and
  // every vertex it owns (infinite where unreached or beyond the maximum distance); NaN for the
  // band's other vertices.
  std::vector<double> Distance;
  // Per vertex owned by this process: the departure angle of its path (ExactGeodesicSolver::
  // DepartureAngle's convention, in the frame of the source as its own process's mesh lays it
  // out: a vertex source's fan from that mesh's VertexHalfedge, a face point's first edge of
  // that mesh's face); NaN elsewhere, where unknown, and everywhere when a piece's faces turn
  // the other way from its neighbours' (the angle then no longer carries across). Meaningful
  // for a single source.
  std::vector<double> Departure;
  int Rounds = 0;    // distance thresholds
  int Exchanges = 0; // exchanges of windows and vertex distances over all rounds
  std::int64_t WindowsPropagated = 0; // by this process
  std::int64_t WindowsSent = 0;       // by this process to others
};

// Collective. The exact geodesic distance from the vertices of global ids `sources` (the same
// list on every process) and from `points` (surface points of this process's own faces, in its
// piece's mesh: each process passes those it holds, see SnapToPieces) on the surface whose
// pieces the processes hold; vertices farther than maxDistance (> 0 and finite) are unreached.
// Grows the piece's band to two rings when it is narrower (then `points` must be empty on every
// process: the band's growth renumbers the faces). Fails on every process when there is
// no source or a source id is no vertex of the surface, when any process's piece fails to grow,
// or when the progress callback of any process (called once per round with the fraction of
// this process's vertices reached) returns false (Aborted).
Status ComputeExactOnPieces(SurfacePiece& piece, const std::vector<std::int64_t>& sources,
  double maxDistance, PieceCommunicator& comm, ExactPiecesResult& result,
  const ProgressCallback& progress = nullptr, const std::vector<SurfacePoint>& points = {});

} // namespace gs
