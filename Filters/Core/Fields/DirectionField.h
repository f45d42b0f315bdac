// N-direction fields on triangle meshes (N = 1: vector field, 2: line field, 4: cross field).
//
// Representation: one angle per face, measured in the face's tangent frame (X = its first edge,
// Y = normal x X); the field is the N directions angle + 2 pi k / N. Faces are related by the
// discrete Levi-Civita connection: crossing an edge rotates the frame by the transport angle that
// unfolds the two faces about their shared edge.
//
// Singularity index of a vertex v: (sum of the field's jumps around v relative to transport
// + angle defect of v) / 2 pi, where the jumps are taken as the smallest rotations modulo 2 pi / N.
// Interior vertices get multiples of 1/N; boundary vertices use the geodesic-curvature defect
// (pi - angle sum) and get real values: the boundary convention is that a boundary loop's indices
// sum to 0 when the field keeps a constant angle to the boundary, and the sum of all indices is the
// Euler characteristic (Poincare-Hopf) whatever the field.
#pragma once

#include "Status.h"
#include "SurfaceCurve.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"
#include "Vector.h"

#include <limits>
#include <memory>
#include <vector>

namespace gs
{

// A hard constraint: the field's direction in `Face` (a tangent vector; its component along the
// face normal is ignored).
struct FaceDirectionConstraint
{
  int Face = -1;
  Vec3 Direction;
};

// A singularity placed by the user: `Index` is a multiple of 1/N. At a boundary vertex it adds to
// the turning of the field relative to the boundary tangent along that vertex's boundary loop (1/4
// at each corner of a rectangle makes the constant, boundary-aligned cross field).
struct VertexSingularity
{
  int Vertex = -1;
  double Index = 0.0;
};

// A streamline of a direction field: straight inside each face (the field is constant per face),
// crossing edges exactly.
struct Streamline
{
  enum StopReason
  {
    ReachedLength,
    ReachedBoundary,
    ReachedSingularity, // entered a face touching a singular vertex, or the field turned abruptly
    Stuck               // degenerate geometry
  };
  std::vector<CurvePiece> Pieces;
  double Length = 0.0;
  SurfacePoint End;
  StopReason Reason = ReachedLength;
};

// Unit vertex normals: the area-weighted mean of the normals of the faces around each vertex
// (the tangent planes of the direction fields' point output).
std::vector<Vec3> AreaWeightedVertexNormals(const TriangleMesh& mesh);

// Per-face directions of an N-direction field given at the vertices (N = 1, 2 or 4): each
// corner's vector is projected onto its vertex's tangent plane (AreaWeightedVertexNormals) and
// carried to the face plane by the smallest rotation taking the vertex normal to the face normal
// (angles between a cross's arms are kept), its angle in the face multiplied by N (its
// length kept as the weight), the three summed and the angle divided by N again; of the N
// equivalent directions the one closest to the first usable corner's is returned, with unit length.
// N = 1 is the plain sum; N = 2 lines up opposite vectors; N = 4 also vectors a quarter turn apart
// (a cross given by any of its arms). Zero where no corner has a finite, nonzero tangent vector or
// where they cancel (a singular face). Fails unless `atVertex` has one vector per vertex and the
// symmetry is 1, 2 or 4.
Result<std::vector<Vec3>> FaceDirectionsFromVertices(
  const TriangleMesh& mesh, const std::vector<Vec3>& atVertex, int symmetry);

// Direction constraints from a stroke drawn on the surface: `curve` is the stroke snapped to the
// surface, `polyline` its own points in space. Every face the stroke's traced path crosses over
// at least `minimumLength` takes the direction of the stroke segment closest to the piece inside
// it, projected onto the face; appended to `constraints` in stroke order.
void AddStrokeConstraints(const TriangleMesh& mesh, const std::vector<SurfacePoint>& curve,
  const std::vector<Vec3>& polyline, double minimumLength,
  std::vector<FaceDirectionConstraint>& constraints);

class DirectionFieldSolver
{
public:
  explicit DirectionFieldSolver(const TriangleMesh& mesh);
  ~DirectionFieldSolver();

  const TriangleMesh& Mesh() const { return Surface; }

  // Tangent frame of a face.
  Vec3 FaceBasisX(int f) const { return BasisX[f]; }
  Vec3 FaceBasisY(int f) const { return BasisY[f]; }
  // Angle of a 3D vector in the frame of face f (projected onto the face plane).
  double AngleInFace(int f, const Vec3& v) const;
  Vec3 DirectionInFace(int f, double angle) const;
  // Levi-Civita transport angle across half-edge h: an angle phi in face(h) becomes
  // phi + TransportAngle(h) in face(twin(h)). 0 at boundary half-edges.
  double TransportAngle(int h) const { return Transport[h]; }

  // Knoppel et al. 2013 globally smoothest N-direction field (the smallest eigenvector of the
  // connection Laplacian), or, with `curvatureAlignment` t > 0, the smoothest field pulled towards
  // the principal curvature directions (N = 2, 4) with weight t (0: ignore curvature; 1: balanced).
  // Hard constraints replace the eigenproblem by the smoothest extension of the constrained faces.
  // The angles per face go to `angles`. The factorization is kept and reused while N and t stay the
  // same and the set of constrained faces does not change.
  Status SolveSmoothest(int n, double curvatureAlignment,
    const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles);

  // Crane, Desbrun, Schroder 2010 trivial connections: the smoothest (least Dirichlet energy)
  // change of the Levi-Civita connection whose holonomy around every vertex gives exactly the
  // prescribed indices (0 elsewhere), around every homology generator (tree-cotree) the multiple
  // of 2 pi / N closest to the Levi-Civita holonomy, and around every boundary loop the turning
  // of the field against the boundary tangent equals the sum of the indices given to the loop's
  // vertices (0 by default: the field turns with the boundary). The field is
  // then transported over a spanning tree of faces. Indices must sum to the Euler characteristic
  // of each connected component (the error names the sum found and the sum required).
  // Constraints (strokes) fix the relative holonomy between consecutive constrained faces (a face
  // constrained twice keeps its first constraint).
  // The factorization is kept while the constrained faces do not change: new singularities or
  // new stroke directions re-solve with it.
  Status SolvePrescribed(int n, const std::vector<VertexSingularity>& singularities,
    const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles);

  // Index (times N, an integer for interior vertices) of every vertex, as a real number.
  std::vector<double> VertexIndices(int n, const std::vector<double>& angles) const;
  // The index of every vertex rounded to a multiple of 1/N for interior vertices (boundary
  // vertices keep their real value).
  std::vector<double> RoundedVertexIndices(int n, const std::vector<double>& angles) const;

  // Follows the field from `start` (a face point, or a vertex: its first face) for a geodesic
  // `length`, leaving along the field direction closest to `initialAngle` (in the start face's
  // frame) and, in every next face, along the direction closest to the incoming one. Stops at the
  // boundary, in faces touching a vertex with non-zero index in `indices` (optional, one per
  // vertex), or where the field turns by more than `maxTurn` radians across an edge (default:
  // 0.9 pi / N).
  Streamline TraceStreamline(int n, const std::vector<double>& angles, const SurfacePoint& start,
    double initialAngle, double length, const std::vector<double>* indices = nullptr,
    double maxTurn = -1.0) const;

  // The same streamline traced in stages: Continue(until) traces it on to the first face exit at
  // or beyond the geodesic length `until` (or to its end), so that a caller can look at its
  // beginning before paying for the rest. The pieces are those of TraceStreamline, bit for bit,
  // however the tracing is staged (a stage never cuts a piece short of its face's exit). The
  // solver, `angles` and `indices` must outlive the tracer.
  class StreamlineTracer
  {
  public:
    StreamlineTracer(const DirectionFieldSolver& solver, int n, const std::vector<double>& angles,
      const SurfacePoint& start, double initialAngle, double length,
      const std::vector<double>* indices = nullptr, double maxTurn = -1.0);
    // Traces on until Line().Length >= until or the line has ended; true while it goes on.
    bool Continue(double until = std::numeric_limits<double>::infinity());
    bool Finished() const { return Done; }
    const Streamline& Line() const { return Traced; }
    Streamline& Line() { return Traced; }

  private:
    bool Singular(int face) const;
    void Finish();
    const DirectionFieldSolver& Solver;
    const std::vector<double>& Angles;
    const std::vector<double>* Indices;
    int Symmetry; // N of the N-direction field
    double MaxTurn;
    Streamline Traced;
    int Face = -1, Entry = -1; // the face traced through, and the half-edge it was entered by
    Vec3 Point{ 0, 0, 0 };     // where the line is (in Face)
    Vec3 Direction{ 0, 0, 0 }; // its unit direction in Face
    double Angle = 0.0;        // that direction's angle in Face's frame (a branch of the field)
    double Remaining = 0.0;    // geodesic length still to trace
    long long StepsLeft = 0;
    bool Done = false;
  };

  // One direction per vertex: the area-weighted average of the N-th powers of the adjacent
  // faces' directions, taken in the vertex's tangent plane (normal: area-weighted face normals),
  // back to a unit vector; zero where they cancel (at singularities).
  std::vector<Vec3> VertexDirections(int n, const std::vector<double>& angles) const;

  // Interior indices rounded to multiples of 1/N plus, for every boundary loop, its turning
  // (the sum of its vertices' indices) rounded to a multiple of 1/N: the Euler characteristic.
  double IndexSum(int n, const std::vector<double>& angles) const;

  // Smoothness energy sum_e w_e |u_g - r_e u_f|^2 / sum_f A_f with u = exp(i N angle).
  double Energy(int n, const std::vector<double>& angles) const;

  // Smallest jump in [-pi/N, pi/N) of an N-direction angle.
  static double WrapSymmetric(double a, int n);

private:
  struct Factorization;
  Status SolvePrescribedUnique(int n, const std::vector<double>& index,
    const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles);
  std::vector<Vec3> VertexNormals() const;
  void ComputeCurvatureTarget(int n, std::vector<double>& re, std::vector<double>& im) const;

  const TriangleMesh& Surface;
  std::vector<Vec3> BasisX, BasisY;
  std::vector<double> Transport;
  std::vector<double> EdgeWeight; // per half-edge (same on both twins)
  std::unique_ptr<Factorization> Cache;
  struct ConnectionFactorization;
  std::unique_ptr<ConnectionFactorization> ConnectionCache;
};

} // namespace gs
