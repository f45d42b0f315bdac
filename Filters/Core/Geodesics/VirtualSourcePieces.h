// Virtual source propagation (VirtualSourceSolver) on a surface partitioned over processes
// (MPI), without any process holding the whole surface: each process runs the propagation of
// its own faces on its piece (SurfacePiece, with a band of two rings of faces).
//
// The solve runs by rounds of distance thresholds: in each round every process processes its
// queue up to the round's threshold (the smallest bucket left anywhere plus a step of 1/64 of
// the surface's size), then the processes exchange what left them: the source given to a face
// of another process (in that face's frame, as the crossing computed it), and the distance of
// a vertex of another process at which paths may bend (a saddle or reflex boundary vertex),
// whose owner seeds the faces around it. The propagation is label correcting: a face improved
// late crosses its edges again, in any order. At the end each vertex takes the smallest
// distance any process's crossings gave it.
//
// The serial solve's buckets, tolerance and horizon are kept (from the whole surface's mean and
// longest edge), and crossings are computed from the same face records, so a face ends with
// the serial solve's source wherever the order of processing does not decide between sources
// of nearly equal key. Where it does, a vertex ends with another of the distances the method
// gives it: on flat and developable meshes (where it is exact) the serial distances to
// rounding; on curved ones distances as accurate against the exact solver as the serial ones,
// but a little different, by partition (Docs/FILTERS.md, "Under MPI", gives the differences
// measured).
#pragma once

#include "PieceCommunicator.h"
#include "SaddleVertexGraph.h"
#include "Status.h"
#include "SurfaceCurve.h"
#include "SurfacePiece.h"

#include <cstdint>
#include <vector>

namespace gs
{

struct VirtualSourcePiecesResult
{
  // Per vertex of the piece's mesh: the distance of every vertex of the process's own faces and
  // every vertex it owns (infinite where unreached or beyond the maximum distance); NaN for the
  // band's other vertices.
  std::vector<double> Distance;
  int Rounds = 0;    // distance thresholds
  int Exchanges = 0; // exchanges of sources and vertex distances
  std::int64_t Crossings = 0; // edges crossed by this process
  std::int64_t FacesSent = 0; // sources sent by this process to others' faces
};

// Collective. The virtual-source distance from the vertices of global ids `sources` (the same
// list on every process) and from `points` (surface points of this process's own faces, in its
// piece's mesh) on the surface whose pieces the processes hold; vertices farther than
// maxDistance (> 0 and finite) are unreached. Grows the piece's band to two rings when it is
// narrower (then `points` must be empty on every process: the band's growth renumbers the
// faces). Fails on every process as ComputeExactOnPieces does (no source, an id that is no
// vertex, a band that fails to grow, Aborted by the progress callback of any process).
// `runs`: curve sources as VirtualSourceSolver::Solve takes them, each whole on every process
// that holds one of its faces (in its piece's mesh); each process seeds the pieces on its own
// faces.
Status ComputeVirtualSourcesOnPieces(SurfacePiece& piece, const std::vector<std::int64_t>& sources,
  double maxDistance, PieceCommunicator& comm, VirtualSourcePiecesResult& result,
  const ProgressCallback& progress = nullptr, const std::vector<SurfacePoint>& points = {},
  const std::vector<std::vector<CurvePiece>>& runs = {});

} // namespace gs
