// Exact geodesic distance on several cores: the surface cut into a fixed number of parts, each
// solved by the exact window propagation of its piece (ComputeExactOnPieces, ExactPieces.h) on a
// thread of its own, the pieces exchanging the windows and vertex distances that cross between
// them (ThreadCommunicator). Window propagation is exact in any order of processing, so the
// distances are the exact geodesic distances, equal to a serial solve's up to rounding (the
// order of the windows, and so the rounding of ties, differs: within 1e-12 of the largest
// distance in the tests). The partition depends on the mesh and the number of parts only, so
// the result is the same to the bit whatever the number of cores; the parts run as threads even
// on one core. Departure angles from a single source (so that Geodesic Polar Coordinates solves
// charts over a whole large surface this way too).
#pragma once

#include "Status.h"
#include "SurfacePoint.h"
#include "SurfacePiece.h"
#include "TriangleMesh.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace gs
{
class ThreadHub;
struct ExactPiecesResult;

class ExactSolverInParts
{
public:
  /// The number of parts the surface is cut into (the engine's; a function of nothing else):
  /// four threads, which on two cores are as fast as two (a part waits for the others at each
  /// exchange) and use four cores where there are.
  static constexpr int DefaultParts = 4;
  /// The parts are cubes of the bounding box's longest side over this, dealt out in turn.
  static constexpr int BlocksAlongLongestSide = 8;

  /// The mesh must outlive the solver. The pieces are made at the first solve and kept.
  explicit ExactSolverInParts(const TriangleMesh& mesh, int parts = DefaultParts);
  ~ExactSolverInParts();

  /// Distances from the nearest of the vertex sources; vertices farther than maxDistance (> 0
  /// and finite) are unreached (infinite). Fails (every vertex unreached) for no source or an
  /// invalid one, or when `progress` (called from the calling thread once per round with the
  /// fraction of the first part's vertices reached) returns false (Status::Aborted()).
  Status Solve(const std::vector<int>& sources, double maxDistance = 0.0,
    const std::function<bool(double)>& progress = nullptr);
  /// The same from surface points (vertices and face points; TriangleMesh::CheckPoints).
  Status Solve(const std::vector<SurfacePoint>& sources, double maxDistance = 0.0,
    const std::function<bool(double)>& progress = nullptr);

  double Distance(int v) const { return Dist[static_cast<std::size_t>(v)]; }
  /// After a solve from a single source: the angle at which v's path leaves it, in
  /// ExactGeodesicSolver::DepartureAngle's convention on this mesh (equal to the serial
  /// solver's up to rounding, modulo a full turn about the source: windows carry their angles
  /// between the parts); NaN otherwise, for the source itself and where unreached.
  double DepartureAngle(int v) const { return Departure[static_cast<std::size_t>(v)]; }
  /// Whether the last solve kept departure angles (one source, measured as the mesh does).
  bool AnglesKept() const { return Kept; }
  const std::vector<double>& Distances() const { return Dist; }
  /// Windows propagated by all parts in the last solve, and its rounds.
  std::int64_t WindowsPropagated() const { return Windows; }
  int Rounds() const { return NumRounds; }

private:
  // Each part's piece (made first when `make`) and solve, on the hub's threads; each part's
  // status and result.
  void RunParts(ThreadHub& hub, const std::vector<SurfacePoint>& sources,
    const std::vector<std::int64_t>& vertices, double maxDistance,
    const std::function<bool(double)>& progress, bool make, std::vector<Status>& statuses,
    std::vector<ExactPiecesResult>& results);
  // Whether the part holding source `p` (`piece`) measures departure angles from the edge the
  // mesh measures them from (a vertex's VertexHalfedge, a face's first corner).
  bool SameFrame(const SurfacePoint& p, const SurfacePiece& piece) const;
  // After a solve: the departure angles kept from one source in the mesh's frame, else NaN.
  void KeepDepartures(const std::vector<SurfacePoint>& sources);

  const TriangleMesh& Surface;
  const int Parts;
  std::vector<int> PartOfFace;                       // each face's part
  std::vector<std::unique_ptr<SurfacePiece>> Pieces; // made at the first solve
  std::vector<double> Dist, Departure;
  bool Framed = false; // the single source's part measures angles as the mesh
  bool Kept = false;   // the last solve's departure angles are kept
  std::int64_t Windows = 0;
  int NumRounds = 0;
};

} // namespace gs
