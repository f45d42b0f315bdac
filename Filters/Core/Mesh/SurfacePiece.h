// One process's part of a triangle surface partitioned over processes (MPI), with a band of
// its neighbours' faces around it: what a geodesic computation on the piece needs so that it
// decides as it would on the whole surface, without any process holding the whole surface.
//
// Every face belongs to one process (the one whose input holds it); every vertex to one process,
// the lowest rank among those holding a face of it. Points and faces carry global ids (the same
// point has the same id on every process); the piece's mesh numbers its faces and vertices in
// global id order, as a serial run on the whole surface put together in id order does, so that
// a computation touching only complete vertices visits them in the serial order.
//
// The band grows a ring of faces at a time: each process sends the ids of the vertices on its
// band's edge to every other, which answer with their own faces that touch them. A vertex is
// complete once every face of the surface around it is in the piece; the fence is the piece's
// faces with an incomplete vertex: a solve that enters none of them (ExactGeodesicOptions::Fence)
// saw the surface as it is.
#pragma once

#include "PieceCommunicator.h"
#include "Status.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"
#include "Vector.h"

#include <array>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gs
{

// A process's own faces.
struct PieceTriangles
{
  std::vector<Vec3> Points;
  std::vector<std::int64_t> PointIds; // global ids, one per point
  std::vector<std::array<int, 3>> Triangles; // indices into Points
  std::vector<std::int64_t> TriangleIds;     // global ids, one per triangle
};

class SurfacePiece;

// A surface point named by global ids (a vertex, or a face with its corners and the point's
// weights over them), as every process holding the face can name it in its own piece's mesh
// (whose numbers change as the band grows).
struct PiecePointName
{
  std::int64_t Vertex = -1, Face = -1;
  std::array<std::int64_t, 3> Corners{};
  std::array<double, 3> Bary{};

  PiecePointName() = default;
  PiecePointName(const SurfacePiece& piece, const SurfacePoint& p);
  // The point in `piece`'s mesh (a point of no face, Face -1, when the piece lacks it).
  SurfacePoint In(const SurfacePiece& piece) const;
  // Appends the global ids of the vertex, or of the face's corners.
  void AppendVertexIds(std::vector<std::int64_t>& out) const;
};

class SurfacePiece
{
public:
  // Collective. Takes this process's faces and gathers `rings` rings of faces around them (at
  // least the faces of its own faces' vertices). Fails on every process, with a message, when
  // any process's input is malformed (sizes, a triangle's index out of range, a point used with
  // two positions) or its piece does not make a mesh the way the whole surface would (welded
  // coincident points under different ids, non-manifold pieces, degenerate faces).
  Status Build(const PieceTriangles& own, int rings, PieceCommunicator& comm);
  // Collective: `rings` more rings.
  Status Grow(int rings, PieceCommunicator& comm);
  // Collective. Grows the band, by rings that double (2, 4, ...), around the vertices `around`
  // (global ids; they may differ between processes, or be none) and then around the incomplete
  // vertices of the faces `reach` names, until it names none on any process. `reach` is called
  // on every process once before and once after each growth (which renumbers the piece): the
  // faces of the piece the process's computation goes through, none where it computes
  // nothing; its last call computed on the final piece. Fails on every process when the band
  // fails to grow, or keeps growing past 4096 rings.
  Status GrowUntilInside(std::vector<std::int64_t> around, PieceCommunicator& comm,
    const std::function<std::vector<int>()>& reach);
  // Collective: at least `rings` rings. Fails on every process when the band must grow and a
  // process holds `points` > 0 surface points of its piece (growing renumbers the faces).
  Status GrowTo(int rings, std::size_t points, PieceCommunicator& comm);
  // Collective: `rings` rings of faces around the vertices of `around` that are incomplete or
  // not in the piece yet (global ids; complete ones are ignored, and ids of no vertex stay out):
  // the band grows where a computation needs it, not all along the piece's edge, and may reach
  // parts of the surface far from the piece (a curve source's). `rings` is the same on every
  // process; `around` may differ (or be empty).
  Status GrowAround(const std::vector<std::int64_t>& around, int rings, PieceCommunicator& comm);

  const TriangleMesh& Mesh() const { return Local; }
  int Rank() const { return MyRank; }
  // Rings gathered all around the own faces (GrowAround widens the band in places).
  int Rings() const { return NumRings; }
  std::int64_t GlobalId(int v) const { return VertexIds[static_cast<std::size_t>(v)]; }
  // The rank owning vertex v (-1 when v is incomplete: not every process holding it is known).
  int Owner(int v) const { return Owners[static_cast<std::size_t>(v)]; }
  bool IsOwned(int v) const { return Owners[static_cast<std::size_t>(v)] == MyRank; }
  bool IsComplete(int v) const { return Owners[static_cast<std::size_t>(v)] >= 0; }
  // Whether face f is one of this process's own (not a band face).
  bool IsOwnFace(int f) const { return FaceOwners[static_cast<std::size_t>(f)] == MyRank; }
  // The rank whose input holds face f.
  int FaceOwner(int f) const { return FaceOwners[static_cast<std::size_t>(f)]; }
  std::int64_t FaceId(int f) const { return FaceIds[static_cast<std::size_t>(f)]; }
  // The faces with an incomplete vertex.
  const std::vector<unsigned char>& Fence() const { return FenceFaces; }
  // Appends to `out` the incomplete vertices (global ids) of `faces` (faces of Mesh()): where a
  // solve that entered those fence faces left the piece, for GrowAround.
  void AppendIncompleteVertices(const std::vector<int>& faces, std::vector<std::int64_t>& out) const;
  // The local vertex of a global point id (-1 when it is not in the piece).
  int Vertex(std::int64_t globalId) const;
  // The local face of a global face id (-1 when it is not in the piece).
  int Face(std::int64_t globalId) const;
  // The point of face `globalFace` with barycentric coordinates `bary` over the corners of
  // global ids `corners` (in that order), as a point of the piece's mesh (whose face may order
  // its corners otherwise); a point of no face (Face -1) when the face is not in the piece.
  SurfacePoint LocalPoint(std::int64_t globalFace, const std::array<std::int64_t, 3>& corners,
    const std::array<double, 3>& bary) const;
  // Collective. The vertex sources of a solve on the pieces: checks them as a serial solve
  // would and gives, in `owned`, the vertices of `sources` (global ids, the same list on every
  // process) this process owns, in increasing id order, once each. `points` are this process's
  // surface points (on its own faces, or vertices it owns). Fails on every process, with the
  // first failing process's message, when a point is invalid or another process's, when an id
  // is no vertex of the surface, or when there is no source at all.
  // (`others`: this process's sources of other kinds, curves, which count against "no source".)
  Status OwnSources(const std::vector<std::int64_t>& sources,
    const std::vector<SurfacePoint>& points, PieceCommunicator& comm, std::vector<int>& owned,
    std::size_t others = 0) const;
  // Collective. Sets perVertex (one value per vertex of the piece's mesh) at the vertices of
  // this process's own faces that other processes own to their owners' values (infinite where
  // the owner has none).
  void ValuesFromOwners(std::vector<double>& perVertex, PieceCommunicator& comm) const;
  // Collective. The global id of rank `index` among the surface's vertex ids in increasing order
  // (the vertex a serial run on the surface put together in id order numbers `index`; the id
  // itself when the ids number the vertices 0 to N - 1); -1 when there is no such vertex.
  std::int64_t IdOfRank(std::int64_t index, PieceCommunicator& comm) const;
  // The whole surface's bounding box diagonal (the scale of the solvers' tolerances).
  double LengthScale() const { return Diagonal; }
  // Collective. The whole surface's mean edge length (over every face's three edges, as
  // TriangleMesh::MeanEdgeLength; added in rank order, the same on every process).
  double MeanEdgeLength(PieceCommunicator& comm) const;
  // Vertices owned by this process, and over all processes.
  std::int64_t NumberOfOwnedVertices() const { return OwnedCount; }
  std::int64_t GlobalNumberOfVertices() const { return GlobalVertexCount; }

private:
  struct FaceRecord
  {
    std::array<std::int64_t, 3> V;
    int Owner;
  };
  struct VertexRecord
  {
    Vec3 P;
    int Owner;     // lowest rank of the faces seen around it
    bool Complete; // every face around it seen
  };
  void AddFace(std::int64_t id, const FaceRecord& face);
  // Requests the faces around the vertices `request` (of every process's own faces) and adds
  // them: those vertices are complete, the ones they bring are not. Returns the vertices brought
  // (in id order).
  std::vector<std::int64_t> GatherRing(
    const std::vector<std::int64_t>& request, PieceCommunicator& comm);
  // Completes the pinched vertices (see Grow), then makes the mesh.
  Status Finish(PieceCommunicator& comm);
  // The incomplete vertices, and those of them whose faces in the piece form several fans.
  std::vector<std::int64_t> Incomplete() const;
  std::vector<std::int64_t> Pinched() const;
  // Makes the piece's mesh from the records (collective: the processes agree on failure), then
  // drops the records: between growths the piece keeps its mesh and per-vertex and per-face
  // arrays only (about a third of the memory), from which RestoreRecords makes them again.
  Status MakeMesh(PieceCommunicator& comm);
  void DropRecords();
  void RestoreRecords();
  // An empty piece (after a failure: nothing of the failed piece is used again).
  void Clear();

  int MyRank = 0;
  int NumRings = 0;
  // The records, while the band grows.
  std::unordered_map<std::int64_t, FaceRecord> Faces;
  std::unordered_map<std::int64_t, VertexRecord> Vertices;
  // This process's own faces by global vertex id (to answer requests).
  // (Pairs (vertex, face), sorted: one allocation instead of a list per vertex.)
  std::vector<std::pair<std::int64_t, std::int64_t>> OwnStar;
  // Sorts OwnStar and drops repeated pairs.
  void SortOwnStar();
  TriangleMesh Local;
  std::vector<std::int64_t> VertexIds, FaceIds; // sorted: local numbers follow them
  std::vector<int> Owners, FaceOwners;
  std::vector<unsigned char> FenceFaces;
  std::vector<unsigned char> Flipped; // per face: the mesh swapped its record's corners 1 and 2
  double Diagonal = 0.0;
  std::int64_t OwnedCount = 0, GlobalVertexCount = 0;
};

// The pieces of a whole mesh held in one process (the in-process solves on pieces, the tests):
// the faces whose part is `part` (partOfFace, one entry per face), with the mesh's own vertex
// and face numbers as global ids.
PieceTriangles PieceOfMesh(const TriangleMesh& mesh, const std::vector<int>& partOfFace, int part);
// A partition of the faces into `parts` slabs of equal face counts along `direction`, by the
// faces' centroids (ties by face number): a function of the mesh, `parts` and `direction` only.
std::vector<int> SlabPartition(const TriangleMesh& mesh, int parts, const Vec3& direction);
// A partition of the faces into `parts` parts, each made of the cubes of a grid over the
// bounding box (`blocks` cubes along its longest side) whose index sum i + j + k is the part
// modulo `parts` (by the faces' centroids): every region of the surface meets every part.
std::vector<int> BlockPartition(const TriangleMesh& mesh, int parts, int blocks);

} // namespace gs
