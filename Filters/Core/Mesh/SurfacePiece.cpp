#include "SurfacePiece.h"

#include "Memory.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace gs
{

namespace
{
// Sorts `items` and calls visit(item, uses) once per distinct item, in order, with how many
// times it appears (counting edge or spoke uses without a map).
template <class T, class Visit>
void ForEachRun(std::vector<T>& items, Visit&& visit)
{
  std::sort(items.begin(), items.end());
  for (std::size_t i = 0; i < items.size();)
  {
    std::size_t j = i + 1;
    while (j < items.size() && items[j] == items[i])
    {
      ++j;
    }
    visit(items[i], j - i);
    i = j;
  }
}

// Every process fails when one does: the first failing rank's message goes to all (a failed
// Status always has one).
Status Agree(const Status& mine, PieceCommunicator& comm)
{
  std::string message;
  const int first = FirstMessage(comm, mine.Ok() ? std::string() : mine.Message(), message);
  if (first < 0)
  {
    return Status();
  }
  return Status::Error(first == comm.Rank() ? message
                                            : "process " + std::to_string(first) + ": " + message);
}
} // namespace

void SurfacePiece::AddFace(std::int64_t id, const FaceRecord& face)
{
  auto [it, added] = Faces.emplace(id, face);
  if (!added)
  {
    it->second.Owner = std::min(it->second.Owner, face.Owner);
  }
  for (const std::int64_t v : face.V)
  {
    VertexRecord& r = Vertices[v];
    r.Owner = std::min(r.Owner, face.Owner);
  }
}

Status SurfacePiece::Build(const PieceTriangles& own, int rings, PieceCommunicator& comm)
{
  MyRank = comm.Rank();
  Clear();
  std::vector<std::int64_t> frontier;

  Status valid;
  const std::size_t np = own.Points.size(), nt = own.Triangles.size();
  if (own.PointIds.size() != np || own.TriangleIds.size() != nt)
  {
    valid = Status::Error("every point and every triangle needs a global id");
  }
  for (std::size_t t = 0; t < nt && valid.Ok(); ++t)
  {
    for (const int k : own.Triangles[t])
    {
      if (k < 0 || static_cast<std::size_t>(k) >= np)
      {
        valid = Status::Error("triangle " + std::to_string(own.TriangleIds[t]) +
          " uses a point that is not in its piece");
        break;
      }
    }
  }
  // (Room for the own faces and their points and a ring around them: no rehashing as they come.)
  Faces.reserve(nt + nt / 4);
  Vertices.reserve(np + np / 4);
  OwnStar.reserve(3 * nt);
  // Vertices: every point used, by id (a point listed twice under one id must sit in one place).
  const int maxOwner = std::numeric_limits<int>::max();
  for (std::size_t t = 0; t < nt && valid.Ok(); ++t)
  {
    for (const int k : own.Triangles[t])
    {
      const std::int64_t id = own.PointIds[static_cast<std::size_t>(k)];
      const Vec3& p = own.Points[static_cast<std::size_t>(k)];
      auto [it, added] = Vertices.emplace(id, VertexRecord{ p, maxOwner, false });
      if (!added && !(it->second.P.x == p.x && it->second.P.y == p.y && it->second.P.z == p.z))
      {
        valid = Status::Error("point id " + std::to_string(id) + " is used at two positions");
      }
    }
  }
  if (const Status agreed = Agree(valid, comm); !agreed.Ok())
  {
    Vertices.clear();
    return agreed;
  }

  // Own faces; the edges used once among them bound the own region: their vertices have faces
  // on other processes (or on the surface's boundary) and are the first requests.
  // (Each edge once per use, sorted: an edge used once is a run of one.)
  std::vector<std::pair<std::int64_t, std::int64_t>> edgeUses;
  edgeUses.reserve(3 * nt);
  for (std::size_t t = 0; t < nt; ++t)
  {
    FaceRecord face;
    for (int k = 0; k < 3; ++k)
    {
      face.V[static_cast<std::size_t>(k)] =
        own.PointIds[static_cast<std::size_t>(own.Triangles[t][static_cast<std::size_t>(k)])];
    }
    face.Owner = MyRank;
    AddFace(own.TriangleIds[t], face);
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t a = face.V[static_cast<std::size_t>(k)];
      const std::int64_t b = face.V[static_cast<std::size_t>((k + 1) % 3)];
      edgeUses.emplace_back(std::min(a, b), std::max(a, b));
      OwnStar.emplace_back(a, own.TriangleIds[t]);
    }
  }
  SortOwnStar();
  ForEachRun(edgeUses, [&](const std::pair<std::int64_t, std::int64_t>& edge, std::size_t uses) {
    if (uses == 1)
    {
      frontier.push_back(edge.first);
      frontier.push_back(edge.second);
    }
  });
  std::vector<std::pair<std::int64_t, std::int64_t>>().swap(edgeUses);
  std::sort(frontier.begin(), frontier.end());
  frontier.erase(std::unique(frontier.begin(), frontier.end()), frontier.end());
  // The other own vertices are surrounded by own faces: complete already.
  for (auto& [id, r] : Vertices)
  {
    r.Complete = !std::binary_search(frontier.begin(), frontier.end(), id);
  }

  // The whole surface's bounding box, as TriangleMesh computes it.
  Vec3 lo(std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity());
  Vec3 hi = lo * -1.0;
  for (const auto& [id, r] : Vertices)
  {
    lo = Vec3(std::min(lo.x, r.P.x), std::min(lo.y, r.P.y), std::min(lo.z, r.P.z));
    hi = Vec3(std::max(hi.x, r.P.x), std::max(hi.y, r.P.y), std::max(hi.z, r.P.z));
  }
  lo = Vec3(comm.Min(lo.x), comm.Min(lo.y), comm.Min(lo.z));
  hi = Vec3(comm.Max(hi.x), comm.Max(hi.y), comm.Max(hi.z));
  Diagonal = std::isfinite(lo.x) ? Norm(hi - lo) : 0.0;

  GatherRing(Incomplete(), comm); // the faces around the own vertices: their owners are known
  return Grow(rings, comm);
}

std::vector<std::int64_t> SurfacePiece::Incomplete() const
{
  std::vector<std::int64_t> ids;
  for (const auto& [id, r] : Vertices)
  {
    if (!r.Complete)
    {
      ids.push_back(id);
    }
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

std::vector<std::int64_t> SurfacePiece::Pinched() const
{
  // Each face adds the two spokes (v, x) of each of its incomplete vertices v; a spoke used once
  // ends a fan: more than two such ends, more than one fan.
  // (Each spoke once per use, sorted: a spoke used once is a run of one.)
  std::vector<std::pair<std::int64_t, std::int64_t>> spokes;
  for (const auto& [id, face] : Faces)
  {
    for (int k = 0; k < 3; ++k)
    {
      const std::int64_t v = face.V[static_cast<std::size_t>(k)];
      if (!Vertices.at(v).Complete)
      {
        spokes.emplace_back(v, face.V[static_cast<std::size_t>((k + 1) % 3)]);
        spokes.emplace_back(v, face.V[static_cast<std::size_t>((k + 2) % 3)]);
      }
    }
  }
  std::vector<std::int64_t> ids;
  bool first = true;
  std::int64_t current = 0;
  int ends = 0;
  ForEachRun(spokes, [&](const std::pair<std::int64_t, std::int64_t>& spoke, std::size_t uses) {
    if (first || spoke.first != current)
    {
      first = false;
      current = spoke.first;
      ends = 0;
    }
    if (uses == 1 && ++ends == 3)
    {
      ids.push_back(current);
    }
  });
  return ids;
}

Status SurfacePiece::Grow(int rings, PieceCommunicator& comm)
{
  RestoreRecords();
  for (int r = 0; r < rings; ++r)
  {
    GatherRing(Incomplete(), comm);
    ++NumRings;
  }
  return Finish(comm);
}

Status SurfacePiece::GrowTo(int rings, std::size_t points, PieceCommunicator& comm)
{
  if (NumRings >= rings)
  {
    return Status();
  }
  if (comm.Sum(static_cast<std::int64_t>(points)) > 0)
  {
    return Status::Error("source points need a piece with " + std::to_string(rings + 1) +
      " rings of faces (its faces would be renumbered as it grows)");
  }
  return Grow(rings - NumRings, comm);
}

Status SurfacePiece::GrowAround(
  const std::vector<std::int64_t>& around, int rings, PieceCommunicator& comm)
{
  RestoreRecords();
  std::vector<std::int64_t> frontier;
  for (const std::int64_t v : around)
  {
    const auto it = Vertices.find(v);
    if (it == Vertices.end() || !it->second.Complete)
    {
      frontier.push_back(v);
    }
  }
  std::sort(frontier.begin(), frontier.end());
  frontier.erase(std::unique(frontier.begin(), frontier.end()), frontier.end());
  for (int r = 0; r < rings; ++r)
  {
    frontier = GatherRing(frontier, comm);
  }
  return Finish(comm);
}

Status SurfacePiece::Finish(PieceCommunicator& comm)
{
  // Where the band's edge meets itself at a vertex (two fans of faces), the piece would not be
  // a manifold mesh: such vertices get their whole star, until none is left.
  while (true)
  {
    const std::vector<std::int64_t> pinched = Pinched();
    if (comm.Sum(static_cast<std::int64_t>(pinched.size())) == 0)
    {
      break;
    }
    GatherRing(pinched, comm);
  }
  // (The records and the mesh build's temporaries are gone once MakeMesh returns.)
  const Status made = MakeMesh(comm);
  ReturnFreedMemory();
  return made;
}

std::vector<std::int64_t> SurfacePiece::GatherRing(
  const std::vector<std::int64_t>& request, PieceCommunicator& comm)
{
  const std::size_t size = static_cast<std::size_t>(comm.Size());
  std::vector<ByteBuffer> requests(size), asked;
  {
    ByteBuffer mine;
    ByteWriter w(mine);
    for (const std::int64_t v : request)
    {
      w.Put(v);
    }
    for (std::size_t q = 0; q < size; ++q)
    {
      if (static_cast<int>(q) != MyRank)
      {
        requests[q] = mine;
      }
    }
  }
  comm.Exchange(requests, asked);

  // Answer each process with the own faces around the vertices it asked for.
  std::vector<ByteBuffer> answers(size), answered;
  std::vector<std::int64_t> faces;
  for (std::size_t q = 0; q < size; ++q)
  {
    if (static_cast<int>(q) == MyRank)
    {
      continue;
    }
    faces.clear();
    ByteReader r(asked[q]);
    std::int64_t v = 0;
    while (r.Get(v))
    {
      const auto first = std::lower_bound(OwnStar.begin(), OwnStar.end(),
        std::make_pair(v, std::numeric_limits<std::int64_t>::min()));
      for (auto it = first; it != OwnStar.end() && it->first == v; ++it)
      {
        faces.push_back(it->second);
      }
    }
    std::sort(faces.begin(), faces.end());
    faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
    ByteWriter w(answers[q]);
    for (const std::int64_t f : faces)
    {
      const FaceRecord& face = Faces.at(f);
      w.Put(f);
      for (const std::int64_t id : face.V)
      {
        w.Put(id);
        w.Put(Vertices.at(id).P);
      }
    }
  }
  comm.Exchange(answers, answered);

  std::vector<std::int64_t> brought;
  for (std::size_t q = 0; q < size; ++q)
  {
    if (static_cast<int>(q) == MyRank)
    {
      continue;
    }
    ByteReader r(answered[q]);
    std::int64_t f = 0;
    while (r.Get(f))
    {
      FaceRecord face;
      face.Owner = static_cast<int>(q);
      for (std::int64_t& id : face.V)
      {
        Vec3 p;
        r.Get(id);
        r.Get(p);
        if (Vertices.find(id) == Vertices.end())
        {
          Vertices.emplace(id, VertexRecord{ p, std::numeric_limits<int>::max(), false });
          brought.push_back(id);
        }
      }
      AddFace(f, face);
    }
  }
  for (const std::int64_t v : request)
  {
    // (A vertex no process has a face of stays out of the piece.)
    if (const auto it = Vertices.find(v); it != Vertices.end())
    {
      it->second.Complete = true;
    }
  }
  std::sort(brought.begin(), brought.end());
  return brought;
}

Status SurfacePiece::MakeMesh(PieceCommunicator& comm)
{
  FaceIds.clear();
  FaceIds.reserve(Faces.size());
  for (const auto& [id, face] : Faces)
  {
    FaceIds.push_back(id);
  }
  std::sort(FaceIds.begin(), FaceIds.end());
  VertexIds.clear();
  VertexIds.reserve(Vertices.size());
  for (const auto& [id, r] : Vertices)
  {
    VertexIds.push_back(id);
  }
  std::sort(VertexIds.begin(), VertexIds.end());
  std::vector<Vec3> points(VertexIds.size());
  for (std::size_t i = 0; i < VertexIds.size(); ++i)
  {
    points[i] = Vertices.at(VertexIds[i]).P;
  }
  std::vector<std::array<long long, 3>> triangles(FaceIds.size());
  FaceOwners.assign(FaceIds.size(), -1);
  for (std::size_t f = 0; f < FaceIds.size(); ++f)
  {
    const FaceRecord& face = Faces.at(FaceIds[f]);
    for (int k = 0; k < 3; ++k)
    {
      triangles[f][static_cast<std::size_t>(k)] = Vertex(face.V[static_cast<std::size_t>(k)]);
    }
    FaceOwners[f] = face.Owner;
  }

  // A process may hold no face (more processes than pieces): its piece is empty. The surface
  // may not be.
  if (comm.Sum(static_cast<std::int64_t>(FaceIds.size())) == 0)
  {
    Clear();
    return Status::Error("the surface has no triangles");
  }
  // Each complete vertex's owner; then the records are dropped (not resident with the mesh
  // that is made from them, nor with the old one).
  Owners.assign(VertexIds.size(), -1);
  for (std::size_t v = 0; v < VertexIds.size(); ++v)
  {
    const VertexRecord& r = Vertices.at(VertexIds[v]);
    Owners[v] = r.Complete ? r.Owner : -1;
  }
  DropRecords();
  Local = TriangleMesh();
  ReturnFreedMemory();
  Status made;
  Result<MeshBuild> built = triangles.empty() ? Result<MeshBuild>(MeshBuild())
                                              : TriangleMeshBuilder::Build(points, triangles);
  if (!built.Ok())
  {
    made = Status::Error(built.Message());
  }
  else if (built->Mesh.NumberOfVertices() != static_cast<int>(points.size()) ||
    built->NumberOfWeldedPoints > 0)
  {
    made = Status::Error("points of different global ids coincide, or a vertex is pinched "
                         "between faces that share no edge");
  }
  if (const Status agreed = Agree(made, comm); !agreed.Ok())
  {
    Clear();
    return agreed;
  }
  Local = std::move(built->Mesh);
  // The mesh turns a face against its record by swapping its corners 1 and 2.
  Flipped.assign(FaceIds.size(), 0);
  for (int f = 0; f < Local.NumberOfFaces(); ++f)
  {
    Flipped[static_cast<std::size_t>(f)] =
      Local.Face(f)[1] != triangles[static_cast<std::size_t>(f)][1] ? 1 : 0;
  }

  OwnedCount = 0;
  for (const int owner : Owners)
  {
    OwnedCount += owner == MyRank ? 1 : 0;
  }
  FenceFaces.assign(FaceIds.size(), 0);
  for (int f = 0; f < Local.NumberOfFaces(); ++f)
  {
    for (const int v : Local.Face(f))
    {
      if (Owners[static_cast<std::size_t>(v)] < 0)
      {
        FenceFaces[static_cast<std::size_t>(f)] = 1;
      }
    }
  }
  GlobalVertexCount = comm.Sum(OwnedCount);
  return Status();
}

void SurfacePiece::Clear()
{
  DropRecords();
  Local = TriangleMesh();
  VertexIds.clear();
  FaceIds.clear();
  Owners.clear();
  FaceOwners.clear();
  FenceFaces.clear();
  Flipped.clear();
  NumRings = 0;
  OwnedCount = GlobalVertexCount = 0;
}

void SurfacePiece::DropRecords()
{
  // (Swapped with empty containers: clear() would keep their buckets.)
  std::unordered_map<std::int64_t, FaceRecord>().swap(Faces);
  std::unordered_map<std::int64_t, VertexRecord>().swap(Vertices);
  std::vector<std::pair<std::int64_t, std::int64_t>>().swap(OwnStar);
}

void SurfacePiece::SortOwnStar()
{
  std::sort(OwnStar.begin(), OwnStar.end());
  OwnStar.erase(std::unique(OwnStar.begin(), OwnStar.end()), OwnStar.end());
}

void SurfacePiece::RestoreRecords()
{
  if (!Faces.empty() || FaceIds.empty())
  {
    return;
  }
  const int maxOwner = std::numeric_limits<int>::max();
  for (std::size_t v = 0; v < VertexIds.size(); ++v)
  {
    Vertices.emplace(
      VertexIds[v], VertexRecord{ Local.Position(static_cast<int>(v)), maxOwner, Owners[v] >= 0 });
  }
  for (std::size_t f = 0; f < FaceIds.size(); ++f)
  {
    const auto& corners = Local.Face(static_cast<int>(f));
    FaceRecord face;
    for (int k = 0; k < 3; ++k)
    {
      face.V[static_cast<std::size_t>(k)] = VertexIds[static_cast<std::size_t>(corners[k])];
    }
    if (Flipped[f])
    {
      std::swap(face.V[1], face.V[2]);
    }
    face.Owner = FaceOwners[f];
    AddFace(FaceIds[f], face);
    if (face.Owner == MyRank)
    {
      for (const std::int64_t v : face.V)
      {
        OwnStar.emplace_back(v, FaceIds[f]);
      }
    }
  }
  SortOwnStar();
}

void SurfacePiece::AppendIncompleteVertices(
  const std::vector<int>& faces, std::vector<std::int64_t>& out) const
{
  for (const int f : faces)
  {
    for (const int v : Local.Face(f))
    {
      if (!IsComplete(v))
      {
        out.push_back(GlobalId(v));
      }
    }
  }
}

std::int64_t SurfacePiece::IdOfRank(std::int64_t index, PieceCommunicator& comm) const
{
  // Each vertex counted once: by its owner. (Ids are below 2^53: exact as doubles.)
  std::vector<std::int64_t> owned;
  for (std::size_t v = 0; v < VertexIds.size(); ++v)
  {
    if (Owners[v] == MyRank)
    {
      owned.push_back(VertexIds[v]); // (in increasing order)
    }
  }
  const double none = std::numeric_limits<double>::infinity();
  const double lowest = comm.Min(owned.empty() ? none : static_cast<double>(owned.front()));
  const double highest = comm.Max(owned.empty() ? -none : static_cast<double>(owned.back()));
  if (index < 0 || index >= GlobalVertexCount)
  {
    return -1;
  }
  if (lowest == 0.0 && highest == static_cast<double>(GlobalVertexCount - 1))
  {
    return index; // the ids number the vertices
  }
  // The smallest id with more than `index` ids at or below it.
  std::int64_t lo = static_cast<std::int64_t>(lowest), hi = static_cast<std::int64_t>(highest);
  while (lo < hi)
  {
    const std::int64_t mid = lo + (hi - lo) / 2;
    const std::int64_t atOrBelow = comm.Sum(static_cast<std::int64_t>(
      std::upper_bound(owned.begin(), owned.end(), mid) - owned.begin()));
    if (atOrBelow > index)
    {
      hi = mid;
    }
    else
    {
      lo = mid + 1;
    }
  }
  return lo;
}

int SurfacePiece::Face(std::int64_t globalId) const
{
  const auto it = std::lower_bound(FaceIds.begin(), FaceIds.end(), globalId);
  return it != FaceIds.end() && *it == globalId ? static_cast<int>(it - FaceIds.begin()) : -1;
}

int SurfacePiece::Vertex(std::int64_t globalId) const
{
  const auto it = std::lower_bound(VertexIds.begin(), VertexIds.end(), globalId);
  return it != VertexIds.end() && *it == globalId ? static_cast<int>(it - VertexIds.begin()) : -1;
}

SurfacePoint SurfacePiece::LocalPoint(std::int64_t globalFace,
  const std::array<std::int64_t, 3>& corners, const std::array<double, 3>& bary) const
{
  const int f = Face(globalFace);
  if (f < 0)
  {
    return SurfacePoint();
  }
  SurfacePoint q = SurfacePoint::InFace(f, 0.0, 0.0, 0.0);
  for (std::size_t k = 0; k < 3; ++k)
  {
    for (std::size_t c = 0; c < 3; ++c)
    {
      if (GlobalId(Local.Face(f)[c]) == corners[k])
      {
        q.Bary[c] = bary[k];
      }
    }
  }
  return q;
}

PieceTriangles PieceOfMesh(const TriangleMesh& mesh, const std::vector<int>& partOfFace, int part)
{
  PieceTriangles piece;
  std::vector<int> point(static_cast<std::size_t>(mesh.NumberOfVertices()), -1);
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    if (partOfFace[static_cast<std::size_t>(f)] != part)
    {
      continue;
    }
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k)
    {
      const int v = mesh.Face(f)[static_cast<std::size_t>(k)];
      int& local = point[static_cast<std::size_t>(v)];
      if (local < 0)
      {
        local = static_cast<int>(piece.Points.size());
        piece.Points.push_back(mesh.Position(v));
        piece.PointIds.push_back(v);
      }
      t[static_cast<std::size_t>(k)] = local;
    }
    piece.Triangles.push_back(t);
    piece.TriangleIds.push_back(f);
  }
  return piece;
}

std::vector<int> BlockPartition(const TriangleMesh& mesh, int parts, int blocks)
{
  const int nf = mesh.NumberOfFaces();
  std::vector<int> part(static_cast<std::size_t>(nf), 0);
  if (mesh.NumberOfVertices() == 0 || parts <= 1)
  {
    return part;
  }
  const Vec3 &lo = mesh.BoundingBoxMin(), &hi = mesh.BoundingBoxMax();
  const double side = std::max({ hi.x - lo.x, hi.y - lo.y, hi.z - lo.z });
  const double cell = side > 0.0 ? side / std::max(blocks, 1) : 1.0;
  for (int f = 0; f < nf; ++f)
  {
    const auto& t = mesh.Face(f);
    const Vec3 c = (mesh.Position(t[0]) + mesh.Position(t[1]) + mesh.Position(t[2])) / 3.0 - lo;
    const long long i = static_cast<long long>(c.x / cell), j = static_cast<long long>(c.y / cell),
                    k = static_cast<long long>(c.z / cell);
    part[static_cast<std::size_t>(f)] = static_cast<int>((i + j + k) % parts);
  }
  return part;
}

std::vector<int> SlabPartition(const TriangleMesh& mesh, int parts, const Vec3& direction)
{
  const int nf = mesh.NumberOfFaces();
  std::vector<std::pair<double, int>> keys(static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f)
  {
    const auto& t = mesh.Face(f);
    const Vec3 c = (mesh.Position(t[0]) + mesh.Position(t[1]) + mesh.Position(t[2])) / 3.0;
    keys[static_cast<std::size_t>(f)] = { Dot(c, direction), f };
  }
  std::sort(keys.begin(), keys.end());
  std::vector<int> part(static_cast<std::size_t>(nf), 0);
  for (int i = 0; i < nf; ++i)
  {
    part[static_cast<std::size_t>(keys[static_cast<std::size_t>(i)].second)] =
      static_cast<int>(static_cast<long long>(i) * parts / nf);
  }
  return part;
}

} // namespace gs

namespace gs
{

Status SurfacePiece::OwnSources(const std::vector<std::int64_t>& sources,
  const std::vector<SurfacePoint>& points, PieceCommunicator& comm, std::vector<int>& owned,
  std::size_t others) const
{
  owned.clear();
  std::vector<std::int64_t> ids = sources;
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  for (const std::int64_t id : ids)
  {
    const int v = Vertex(id);
    if (v >= 0 && IsOwned(v))
    {
      owned.push_back(v);
    }
  }
  Status valid = Local.CheckPoints(points, "source");
  for (const SurfacePoint& p : points)
  {
    if (valid.Ok() && !(p.IsVertex() ? IsOwned(p.Vertex) : IsOwnFace(p.Face)))
    {
      valid = Status::Error("a source point lies on a face (or is a vertex) of another process");
    }
  }
  std::string problem;
  if (FirstMessage(comm, valid.Ok() ? std::string() : valid.Message(), problem) >= 0)
  {
    return Status::Error(problem);
  }
  const std::int64_t allPoints = comm.Sum(static_cast<std::int64_t>(points.size() + others));
  if (comm.Sum(static_cast<std::int64_t>(owned.size())) != static_cast<std::int64_t>(ids.size()) ||
    ids.size() + static_cast<std::size_t>(allPoints) == 0)
  {
    return Status::Error(ids.empty() && allPoints == 0
        ? "no source given"
        : "a source vertex id is not a point of the surface");
  }
  return Status();
}

PiecePointName::PiecePointName(const SurfacePiece& piece, const SurfacePoint& p)
{
  if (p.IsVertex())
  {
    Vertex = piece.GlobalId(p.Vertex);
    return;
  }
  Face = piece.FaceId(p.Face);
  Bary = p.Bary;
  for (std::size_t k = 0; k < 3; ++k)
  {
    Corners[k] = piece.GlobalId(piece.Mesh().Face(p.Face)[k]);
  }
}

SurfacePoint PiecePointName::In(const SurfacePiece& piece) const
{
  if (Vertex >= 0)
  {
    const int v = piece.Vertex(Vertex);
    return v >= 0 ? SurfacePoint::AtVertex(v) : SurfacePoint::InFace(-1, 1.0, 0.0, 0.0);
  }
  return piece.LocalPoint(Face, Corners, Bary);
}

void PiecePointName::AppendVertexIds(std::vector<std::int64_t>& out) const
{
  if (Vertex >= 0)
  {
    out.push_back(Vertex);
  }
  else
  {
    out.insert(out.end(), Corners.begin(), Corners.end());
  }
}

Status SurfacePiece::GrowUntilInside(std::vector<std::int64_t> around, PieceCommunicator& comm,
  const std::function<std::vector<int>()>& reach)
{
  int rings = 2;
  while (true)
  {
    if (comm.Sum(static_cast<std::int64_t>(around.size())) > 0)
    {
      if (rings > (1 << 12))
      {
        return Status::Error("the band of faces around the computation keeps growing past 4096 rings");
      }
      if (const Status grown = GrowAround(around, rings, comm); !grown.Ok())
      {
        return grown;
      }
      rings *= 2;
    }
    around.clear();
    // (Only the fence's faces have incomplete vertices.)
    AppendIncompleteVertices(reach(), around);
    if (comm.Sum(static_cast<std::int64_t>(around.size())) == 0)
    {
      return Status();
    }
  }
}

double SurfacePiece::MeanEdgeLength(PieceCommunicator& comm) const
{
  double sum = 0.0;
  std::int64_t own = 0;
  for (int f = 0; f < Local.NumberOfFaces(); ++f)
  {
    if (IsOwnFace(f))
    {
      sum += Local.EdgeLength(3 * f) + Local.EdgeLength(3 * f + 1) + Local.EdgeLength(3 * f + 2);
      ++own;
    }
  }
  const std::int64_t faces = comm.Sum(own);
  const double total = SumOverProcesses(comm, sum);
  return faces > 0 ? total / (3.0 * static_cast<double>(faces)) : 0.0;
}

void SurfacePiece::ValuesFromOwners(std::vector<double>& perVertex, PieceCommunicator& comm) const
{
  const int nv = Local.NumberOfVertices();
  std::vector<std::vector<std::int64_t>> asks(static_cast<std::size_t>(comm.Size()));
  std::vector<std::vector<int>> askedFor(asks.size());
  std::vector<unsigned char> asked(static_cast<std::size_t>(nv), 0);
  for (int f = 0; f < Local.NumberOfFaces(); ++f)
  {
    if (!IsOwnFace(f))
    {
      continue;
    }
    for (const int v : Local.Face(f))
    {
      const int owner = Owner(v);
      if (owner >= 0 && owner != comm.Rank() && !asked[static_cast<std::size_t>(v)])
      {
        asked[static_cast<std::size_t>(v)] = 1;
        asks[static_cast<std::size_t>(owner)].push_back(GlobalId(v));
        askedFor[static_cast<std::size_t>(owner)].push_back(v);
      }
    }
  }
  const std::vector<std::vector<double>> answers =
    AskProcesses(comm, asks, [&](int, std::int64_t id) {
      const int v = Vertex(id);
      return v >= 0 && IsOwned(v) ? perVertex[static_cast<std::size_t>(v)]
                                  : std::numeric_limits<double>::infinity();
    });
  for (std::size_t q = 0; q < asks.size(); ++q)
  {
    for (std::size_t i = 0; i < askedFor[q].size() && i < answers[q].size(); ++i)
    {
      perVertex[static_cast<std::size_t>(askedFor[q][i])] = answers[q][i];
    }
  }
}

} // namespace gs
