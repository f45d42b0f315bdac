// The one triangle-mesh structure shared by every GeodesicShapes algorithm.
//
// Corner table / implicit half-edges: face f owns half-edges 3f, 3f+1, 3f+2; half-edge 3f+k runs
// from corner k of f to corner k+1 (mod 3). Faces are oriented consistently (counter-clockwise
// about the outward normal), so the twin of a half-edge runs the other way in the neighbour face.
// Only vertices referenced by a face exist in the mesh; the builder keeps the map from the caller's
// point ids (after welding coincident points) to mesh vertices. Face i is always the caller's
// triangle i; a triangle re-oriented to match its neighbours has its corners 1 and 2 swapped.
// Algorithms that keep a reference to a mesh (solvers) must not outlive it.
#pragma once

#include "Status.h"
#include "SurfacePoint.h"
#include "Vector.h"

#include <array>
#include <string>
#include <vector>

namespace gs
{

class TriangleMesh
{
public:
  int NumberOfVertices() const { return static_cast<int>(Positions.size()); }
  int NumberOfFaces() const { return static_cast<int>(Faces.size()); }
  int NumberOfHalfedges() const { return 3 * NumberOfFaces(); }
  int NumberOfEdges() const { return NumEdges; }

  const Vec3& Position(int v) const { return Positions[v]; }
  // A surface point's position: its vertex's, or interpolated in its face.
  Vec3 Position(const SurfacePoint& p) const
  {
    return p.IsVertex() ? Positions[p.Vertex] : Interpolate(p.Face, p.Bary);
  }
  const std::vector<Vec3>& GetPositions() const { return Positions; }
  const std::array<int, 3>& Face(int f) const { return Faces[f]; }

  // Half-edge navigation (all O(1)).
  static int FaceOf(int h) { return h / 3; }
  static int Next(int h) { return h - h % 3 + (h % 3 + 1) % 3; }
  static int Prev(int h) { return h - h % 3 + (h % 3 + 2) % 3; }
  int Origin(int h) const { return Faces[h / 3][h % 3]; }
  int Destination(int h) const { return Faces[h / 3][(h % 3 + 1) % 3]; }
  // The vertex of face(h) opposite to half-edge h.
  int Opposite(int h) const { return Faces[h / 3][(h % 3 + 2) % 3]; }
  // Twin half-edge in the neighbouring face, or -1 on the boundary.
  int Twin(int h) const { return Twins[h]; }
  bool IsBoundaryHalfedge(int h) const { return Twins[h] < 0; }
  double EdgeLength(int h) const { return Lengths[h]; }
  // Interior angle of face(h) at Origin(h).
  double CornerAngle(int h) const { return Angles[h]; }

  // An outgoing half-edge of v. For a boundary vertex it is the boundary half-edge leaving v, so
  // that rotating counter-clockwise from it visits every face around v.
  int VertexHalfedge(int v) const { return OutHalfedge[v]; }
  // The outgoing half-edges of v in counter-clockwise order.
  std::vector<int> OutgoingHalfedges(int v) const;
  // The same, visited in the same order without building a vector (for loops run per vertex
  // of a shape's region, where the allocation cost more than the visit).
  template <class Visit>
  void ForEachOutgoingHalfedge(int v, Visit&& visit) const
  {
    const int start = OutHalfedge[v];
    int h = start;
    do
    {
      visit(h);
      h = RotateCCW(h);
    } while (h >= 0 && h != start);
  }
  // Counter-clockwise rotation about Origin(h): the next outgoing half-edge, or -1 at the boundary.
  int RotateCCW(int h) const
  {
    const int t = Twins[Prev(h)];
    return t;
  }
  // Clockwise rotation about Origin(h), or -1 at the boundary.
  int RotateCW(int h) const
  {
    const int t = Twins[h];
    return t < 0 ? -1 : Next(t);
  }

  double TotalAngle(int v) const { return VertexAngleSum[v]; }
  bool IsBoundaryVertex(int v) const { return BoundaryVertex[v] != 0; }
  // Interior vertex whose total angle exceeds 2 pi (hyperbolic, negative Gaussian curvature).
  bool IsSaddleVertex(int v) const { return SaddleVertex[v] != 0; }
  // The vertices a shortest path may pass through (pseudo-sources of window propagation):
  // saddles, and boundary vertices whose angle exceeds pi. A path through any other vertex can
  // be shortened; a straight path grazing a flat (angle pi) boundary vertex needs no
  // pseudo-source.
  bool IsPseudoSourceVertex(int v) const { return PseudoSource[v] != 0; }
  double FaceArea(int f) const { return Areas[f]; }
  Vec3 FaceNormal(int f) const; // unit (computed once)
  // Average edge length (a length scale for tolerances).
  double MeanEdgeLength() const { return MeanEdge; }
  double LongestEdgeLength() const { return LongestEdge; }
  double BoundingBoxDiagonal() const { return BoxDiagonal; }
  // Corners of the axis-aligned bounding box of the positions.
  const Vec3& BoundingBoxMin() const { return BoxMin; }
  const Vec3& BoundingBoxMax() const { return BoxMax; }

  // Boundary loops as vertex cycles following the boundary half-edges' direction.
  const std::vector<std::vector<int>>& BoundaryLoops() const { return Loops; }
  int NumberOfComponents() const { return NumComponents; }
  int FaceComponent(int f) const { return FaceComponentIds[f]; }
  int VertexComponent(int v) const { return FaceComponentIds[OutHalfedge[v] / 3]; }
  // V - E + F over the whole mesh.
  int EulerCharacteristic() const { return NumberOfVertices() - NumEdges + NumberOfFaces(); }
  // Sum over connected components of the genus g_c = (2 - chi_c - b_c) / 2.
  int Genus() const { return TotalGenus; }

  // Surface point helpers.
  Vec3 Interpolate(int f, const std::array<double, 3>& bary) const;
  // The inverse of Interpolate for a point lying in face f up to rounding: its barycentric
  // coordinates, clamped to the face and normalized to sum 1.
  std::array<double, 3> ClampedBarycentric(int f, const Vec3& x) const;
  // Ok when p is a point of this mesh: an existing vertex, or an existing face with finite
  // barycentric coordinates, none below -1e-6, summing to 1 within 1e-6; otherwise an error
  // saying what is wrong with it.
  Status CheckPoint(const SurfacePoint& p) const;
  // Ok when each of `points` is a point of this mesh; otherwise an error on the first that is
  // not: "<name> <index> is invalid: <what CheckPoint says>".
  Status CheckPoints(const std::vector<SurfacePoint>& points, const std::string& name) const;

private:
  friend class TriangleMeshBuilder;
  void ComputeDerivedData(); // the four below, in order
  void ComputeGeometry();
  void ComputeVertexKinds();
  void ComputeBoundaryLoops();
  void ComputeComponents();

  std::vector<Vec3> Positions;
  std::vector<std::array<int, 3>> Faces;
  std::vector<int> Twins;
  std::vector<double> Lengths;
  std::vector<double> Angles;
  std::vector<double> Areas;
  std::vector<Vec3> Normals; // unit face normals
  std::vector<int> OutHalfedge;
  std::vector<double> VertexAngleSum;
  std::vector<unsigned char> BoundaryVertex;
  std::vector<unsigned char> SaddleVertex;
  std::vector<unsigned char> PseudoSource;
  std::vector<std::vector<int>> Loops;
  std::vector<int> FaceComponentIds;
  int NumComponents = 0;
  int NumEdges = 0;
  int TotalGenus = 0;
  double MeanEdge = 0.0, LongestEdge = 0.0;
  double BoxDiagonal = 0.0;
  Vec3 BoxMin, BoxMax;
};

// A mesh built from caller data.
struct MeshBuild
{
  std::vector<std::string> Warnings; // e.g. faces re-oriented
  TriangleMesh Mesh;
  // For every input point: the mesh vertex it became (after welding), or -1 when no triangle
  // references it.
  std::vector<int> PointToVertex;
  // For every mesh vertex: one input point that maps to it.
  std::vector<int> VertexToPoint;
  int NumberOfWeldedPoints = 0; // input points merged into an earlier coincident point
};

class TriangleMeshBuilder
{
public:
  // Build from input points and triangles (indices into points). Points with exactly equal
  // coordinates are welded. Fails, with a message, on: no triangles, out-of-range indices,
  // non-finite coordinates of a referenced point, degenerate (repeated index or zero-area)
  // triangles, duplicate triangles, non-manifold edges or vertices, non-orientable components.
  // Inconsistently oriented faces are flipped (a warning says how many). Coordinates beyond
  // 1e100 and meshes whose largest bounding box side is below MinimumExtent are refused (areas
  // and squared lengths would overflow or underflow): "rescale the mesh".
  static constexpr double MinimumExtent = 1e-50;
  static Result<MeshBuild> Build(
    const std::vector<Vec3>& points, const std::vector<std::array<long long, 3>>& triangles);

private:
  using Triangles = std::vector<std::array<long long, 3>>;
  // The steps of Build, in order (TriangleMesh.cpp says what each does); each failure is the
  // message Build returns.
  static Status WeldPoints(const std::vector<Vec3>& points, const Triangles& triangles, MeshBuild& r);
  static Status SetFaces(const Triangles& triangles, MeshBuild& r);
  static Status CheckDuplicates(const TriangleMesh& m);
  static Status PairEdges(const MeshBuild& r, std::vector<int>& partner);
  static Status Orient(const std::vector<int>& partner, MeshBuild& r, std::vector<signed char>& flip);
  static void SetTwins(
    const std::vector<int>& partner, const std::vector<signed char>& flip, TriangleMesh& m);
  static std::vector<int> SetOutgoingHalfedges(TriangleMesh& m, std::vector<int>& degree);
  static Status SplitPinches(const Triangles& triangles, std::size_t np,
    const std::vector<signed char>& flip, const std::vector<int>& pinched,
    const std::vector<int>& degree, MeshBuild& r);
};

} // namespace gs
