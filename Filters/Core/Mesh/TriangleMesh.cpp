#include "TriangleMesh.h"

#include "PositionKey.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <numeric>
#include <sstream>

namespace gs
{

namespace
{
constexpr double Pi = 3.14159265358979323846;

// Angle between vectors a and b, robust for tiny and near-degenerate angles.
double AngleBetween(const Vec3& a, const Vec3& b)
{
  return std::atan2(Norm(Cross(a, b)), Dot(a, b));
}

// The first point seen at each position (exact coordinates, -0 equal to +0): open addressing
// over point indices, linear probing, no allocation per entry (a node-based map spent most of a
// large mesh's build allocating).
class PointWelder
{
public:
  explicit PointWelder(const std::vector<Vec3>& points)
    : Points(points)
  {
    std::size_t size = 16;
    while (size < 2 * points.size())
    {
      size *= 2;
    }
    Slots.assign(size, -1);
    Mask = size - 1;
  }
  // The first point inserted at p's position, p itself when it is the first.
  int Insert(int p)
  {
    const Vec3& x = Points[p];
    for (std::size_t i = PositionKey::Of(x).Hash() & Mask;; i = (i + 1) & Mask)
    {
      const int q = Slots[i];
      if (q < 0)
      {
        Slots[i] = p;
        return p;
      }
      const Vec3& y = Points[q];
      if (x.x == y.x && x.y == y.y && x.z == y.z)
      {
        return q;
      }
    }
  }

private:
  const std::vector<Vec3>& Points;
  std::vector<int> Slots;
  std::size_t Mask = 0;
};

// Items bucketed by a vertex (a counting sort), then each bucket sorted by its entries: the order
// of a sort by (vertex, entry) without sorting all the items. `item(i)`: item i's (vertex,
// entry).
template <class Entry>
struct VertexBuckets
{
  std::vector<int> Start;     // per vertex, into Entries (nv + 1)
  std::vector<Entry> Entries; // by vertex, each bucket sorted
};
template <class Entry, class Item>
VertexBuckets<Entry> BucketByVertex(std::size_t n, int nv, const Item& item)
{
  VertexBuckets<Entry> b;
  b.Start.assign(static_cast<std::size_t>(nv) + 1, 0);
  for (std::size_t i = 0; i < n; ++i)
  {
    ++b.Start[static_cast<std::size_t>(item(i).first) + 1];
  }
  for (int v = 0; v < nv; ++v)
  {
    b.Start[v + 1] += b.Start[v];
  }
  b.Entries.resize(n);
  std::vector<int> fill(b.Start.begin(), b.Start.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto it = item(i);
    b.Entries[fill[it.first]++] = it.second;
  }
  for (int v = 0; v < nv; ++v)
  {
    std::sort(b.Entries.begin() + b.Start[v], b.Entries.begin() + b.Start[v + 1]);
  }
  return b;
}

// The half-edges of `faces` grouped by undirected edge, in the order of (smaller vertex, larger
// vertex, half-edge): entries (larger vertex, half-edge) by smaller vertex.
VertexBuckets<std::pair<int, int>> GroupEdges(const std::vector<std::array<int, 3>>& faces, int nv)
{
  return BucketByVertex<std::pair<int, int>>(3 * faces.size(), nv, [&faces](std::size_t h) {
    const auto& t = faces[h / 3];
    const int a = t[h % 3], b = t[(h % 3 + 1) % 3];
    return std::make_pair(std::min(a, b), std::make_pair(std::max(a, b), static_cast<int>(h)));
  });
}

std::string FaceLabel(std::size_t i)
{
  std::ostringstream s;
  s << "triangle " << i;
  return s.str();
}
} // namespace

std::vector<int> TriangleMesh::OutgoingHalfedges(int v) const
{
  std::vector<int> out;
  ForEachOutgoingHalfedge(v, [&out](int h) { out.push_back(h); });
  return out;
}

Vec3 TriangleMesh::FaceNormal(int f) const
{
  return Normals[f];
}

Vec3 TriangleMesh::Interpolate(int f, const std::array<double, 3>& b) const
{
  const auto& t = Faces[f];
  return Positions[t[0]] * b[0] + Positions[t[1]] * b[1] + Positions[t[2]] * b[2];
}

std::array<double, 3> TriangleMesh::ClampedBarycentric(int f, const Vec3& x) const
{
  const auto& t = Faces[f];
  const Vec3 P0 = Positions[t[0]], P1 = Positions[t[1]], P2 = Positions[t[2]];
  const Vec3 n = Cross(P1 - P0, P2 - P0);
  const double n2 = Dot(n, n);
  const double u0 = Dot(Cross(P1 - x, P2 - x), n) / n2;
  const double u1 = Dot(Cross(P2 - x, P0 - x), n) / n2;
  const double w0 = std::max(0.0, u0), w1 = std::max(0.0, u1), w2 = std::max(0.0, 1.0 - u0 - u1);
  const double sum = w0 + w1 + w2;
  return { { w0 / sum, w1 / sum, w2 / sum } };
}

Status TriangleMesh::CheckPoint(const SurfacePoint& p) const
{
  if (p.IsVertex())
  {
    if (p.Vertex >= NumberOfVertices())
    {
      return Status::Error("vertex " + std::to_string(p.Vertex) + " does not exist (the mesh has " +
        std::to_string(NumberOfVertices()) + " vertices)");
    }
    return Status();
  }
  if (p.Face < 0 || p.Face >= NumberOfFaces())
  {
    return Status::Error("face " + std::to_string(p.Face) + " does not exist (the mesh has " +
      std::to_string(NumberOfFaces()) + " faces)");
  }
  const double sum = p.Bary[0] + p.Bary[1] + p.Bary[2];
  const bool finite = std::isfinite(sum);
  const bool unit = finite && std::abs(sum - 1.0) <= 1e-6;
  if (unit && p.Bary[0] >= -1e-6 && p.Bary[1] >= -1e-6 && p.Bary[2] >= -1e-6)
  {
    return Status();
  }
  std::ostringstream msg;
  msg << "the barycentric coordinates (" << p.Bary[0] << ", " << p.Bary[1] << ", " << p.Bary[2]
      << ") in face " << p.Face;
  if (!finite)
  {
    msg << " are not finite";
  }
  else if (!unit)
  {
    msg << " sum to " << sum << ", not 1";
  }
  else
  {
    msg << " are not all >= 0";
  }
  return Status::Error(msg.str());
}

Status TriangleMesh::CheckPoints(
  const std::vector<SurfacePoint>& points, const std::string& name) const
{
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (const Status valid = CheckPoint(points[i]); !valid.Ok())
    {
      return Status::Error(name + " " + std::to_string(i) + " is invalid: " + valid.Message());
    }
  }
  return Status();
}

void TriangleMesh::ComputeDerivedData()
{
  ComputeGeometry();
  ComputeVertexKinds();
  ComputeBoundaryLoops();
  ComputeComponents();
}

// Edge lengths, corner angles, face areas and normals, the mean and longest edge, the bounding
// box.
void TriangleMesh::ComputeGeometry()
{
  const int nf = NumberOfFaces();
  Lengths.assign(3 * nf, 0.0);
  Angles.assign(3 * nf, 0.0);
  Areas.assign(nf, 0.0);
  Normals.assign(nf, Vec3(0, 0, 0));
#pragma omp parallel for schedule(static) if (nf > 20000)
  for (int f = 0; f < nf; ++f)
  {
    const auto& t = Faces[f];
    for (int k = 0; k < 3; ++k)
    {
      const Vec3& a = Positions[t[k]];
      const Vec3& b = Positions[t[(k + 1) % 3]];
      const Vec3& c = Positions[t[(k + 2) % 3]];
      Lengths[3 * f + k] = Norm(b - a);
      Angles[3 * f + k] = AngleBetween(b - a, c - a);
    }
    const Vec3 n = Cross(Positions[t[1]] - Positions[t[0]], Positions[t[2]] - Positions[t[0]]);
    Areas[f] = 0.5 * Norm(n);
    Normals[f] = Areas[f] > 0 ? n / (2.0 * Areas[f]) : Vec3(0, 0, 0);
  }
  double sum = 0.0; // (in order: the same mean whatever the number of threads)
  LongestEdge = 0.0;
  for (const double l : Lengths)
  {
    sum += l;
    LongestEdge = std::max(LongestEdge, l);
  }
  MeanEdge = nf > 0 ? sum / (3.0 * nf) : 0.0;

  Vec3 lo = Positions.empty() ? Vec3() : Positions[0], hi = lo;
  for (const Vec3& p : Positions)
  {
    lo = Vec3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
    hi = Vec3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
  }
  BoxMin = lo;
  BoxMax = hi;
  BoxDiagonal = Norm(hi - lo);
}

// Angle sums; boundary, saddle and pseudo-source vertices.
void TriangleMesh::ComputeVertexKinds()
{
  const int nf = NumberOfFaces();
  const int nv = NumberOfVertices();
  VertexAngleSum.assign(nv, 0.0);
  for (int h = 0; h < 3 * nf; ++h)
  {
    VertexAngleSum[Origin(h)] += Angles[h];
  }
  BoundaryVertex.assign(nv, 0);
  SaddleVertex.assign(nv, 0);
  PseudoSource.assign(nv, 0);
  for (int v = 0; v < nv; ++v)
  {
    BoundaryVertex[v] = Twins[OutHalfedge[v]] < 0 ? 1 : 0;
    // A small tolerance keeps flat vertices of planar meshes (angle sum 2 pi up to rounding)
    // from being taken as saddles.
    SaddleVertex[v] = (!BoundaryVertex[v] && VertexAngleSum[v] > 2.0 * Pi + 1e-10) ? 1 : 0;
    PseudoSource[v] =
      (SaddleVertex[v] || (BoundaryVertex[v] && VertexAngleSum[v] > Pi + 1e-10)) ? 1 : 0;
  }
}

void TriangleMesh::ComputeBoundaryLoops()
{
  const int nf = NumberOfFaces();
  // Boundary loops: follow boundary half-edges. The boundary half-edge leaving Destination(h)
  // after boundary half-edge h is found by rotating clockwise about Destination(h).
  Loops.clear();
  std::vector<unsigned char> visited(3 * nf, 0);
  for (int h0 = 0; h0 < 3 * nf; ++h0)
  {
    if (Twins[h0] >= 0 || visited[h0])
    {
      continue;
    }
    std::vector<int> loop;
    int h = h0;
    while (!visited[h])
    {
      visited[h] = 1;
      loop.push_back(Origin(h));
      // Next boundary half-edge: the one leaving Destination(h).
      h = OutHalfedge[Destination(h)];
    }
    Loops.push_back(std::move(loop));
  }
}

// Connected components over face adjacency, the edge count and the genus.
void TriangleMesh::ComputeComponents()
{
  const int nf = NumberOfFaces();
  const int nv = NumberOfVertices();
  // Connected components over face adjacency.
  FaceComponentIds.assign(nf, -1);
  NumComponents = 0;
  std::vector<int> stack;
  for (int f0 = 0; f0 < nf; ++f0)
  {
    if (FaceComponentIds[f0] >= 0)
    {
      continue;
    }
    const int c = NumComponents++;
    FaceComponentIds[f0] = c;
    stack.push_back(f0);
    while (!stack.empty())
    {
      const int f = stack.back();
      stack.pop_back();
      for (int k = 0; k < 3; ++k)
      {
        const int t = Twins[3 * f + k];
        if (t >= 0 && FaceComponentIds[t / 3] < 0)
        {
          FaceComponentIds[t / 3] = c;
          stack.push_back(t / 3);
        }
      }
    }
  }

  // Edge count: every interior edge has two half-edges, a boundary edge one.
  int boundaryHalfedges = 0;
  for (int h = 0; h < 3 * nf; ++h)
  {
    boundaryHalfedges += Twins[h] < 0 ? 1 : 0;
  }
  NumEdges = (3 * nf - boundaryHalfedges) / 2 + boundaryHalfedges;

  // Genus per component: chi_c = V_c - E_c + F_c = 2 - 2 g_c - b_c.
  std::vector<long long> vc(NumComponents, 0), ec2(NumComponents, 0), fc(NumComponents, 0),
    bc(NumComponents, 0);
  for (int v = 0; v < nv; ++v)
  {
    vc[VertexComponent(v)]++;
  }
  for (int f = 0; f < nf; ++f)
  {
    fc[FaceComponentIds[f]]++;
    for (int k = 0; k < 3; ++k)
    {
      // Count twice each edge: interior half-edges once each, boundary half-edges twice.
      ec2[FaceComponentIds[f]] += Twins[3 * f + k] < 0 ? 2 : 1;
    }
  }
  for (const auto& loop : Loops)
  {
    bc[VertexComponent(loop[0])]++;
  }
  TotalGenus = 0;
  for (int c = 0; c < NumComponents; ++c)
  {
    const long long chi = vc[c] - ec2[c] / 2 + fc[c];
    TotalGenus += static_cast<int>((2 - chi - bc[c]) / 2);
  }
}

Result<MeshBuild> TriangleMeshBuilder::Build(
  const std::vector<Vec3>& points, const std::vector<std::array<long long, 3>>& triangles)
{
  MeshBuild r;
  if (triangles.empty())
  {
    return Status::Error("the input has no triangles");
  }
  if (points.size() > static_cast<std::size_t>(0x3fffffff) ||
    triangles.size() > static_cast<std::size_t>(0x2aaaaaaa))
  {
    return Status::Error("the input is too large (more than 2^30 points or 7e8 triangles)");
  }
  if (Status s = WeldPoints(points, triangles, r); !s.Ok())
  {
    return s;
  }
  if (Status s = SetFaces(triangles, r); !s.Ok())
  {
    return s;
  }
  if (Status s = CheckDuplicates(r.Mesh); !s.Ok())
  {
    return s;
  }
  std::vector<int> partner;
  if (Status s = PairEdges(r, partner); !s.Ok())
  {
    return s;
  }
  std::vector<signed char> flip;
  if (Status s = Orient(partner, r, flip); !s.Ok())
  {
    return s;
  }
  SetTwins(partner, flip, r.Mesh);
  std::vector<int> degree;
  const std::vector<int> pinched = SetOutgoingHalfedges(r.Mesh, degree);
  if (!pinched.empty())
  {
    if (Status s = SplitPinches(triangles, points.size(), flip, pinched, degree, r); !s.Ok())
    {
      return s;
    }
  }
  r.Mesh.ComputeDerivedData();
  return r;
}

// 1. Indices and coordinates of the referenced points checked; exactly coincident points welded;
// the mesh's vertices: the representatives, in input order.
Status TriangleMeshBuilder::WeldPoints(
  const std::vector<Vec3>& points, const Triangles& triangles, MeshBuild& r)
{
  const std::size_t np = points.size();
  r.PointToVertex.assign(np, -1);
  std::vector<int> weldTarget(np, -1); // input point -> representative input point
  PointWelder firstAt(points);
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const long long p = triangles[i][k];
      if (p < 0 || static_cast<std::size_t>(p) >= np)
      {
        return Status::Error(
          FaceLabel(i) + " refers to point " + std::to_string(p) + ", which does not exist");
      }
      if (weldTarget[p] >= 0)
      {
        continue;
      }
      if (!IsFinite(points[p]))
      {
        return Status::Error("point " + std::to_string(p) + " (used by " + FaceLabel(i) +
          ") has a NaN or infinite coordinate");
      }
      if (std::max({ std::abs(points[p].x), std::abs(points[p].y), std::abs(points[p].z) }) > 1e100)
      {
        return Status::Error("point " + std::to_string(p) + " (used by " + FaceLabel(i) +
          ") has a coordinate beyond 1e100: rescale the mesh");
      }
      weldTarget[p] = firstAt.Insert(static_cast<int>(p));
      if (weldTarget[p] != p)
      {
        r.NumberOfWeldedPoints++;
      }
    }
  }
  // Mesh vertices: representatives, in input order.
  TriangleMesh& m = r.Mesh;
  for (std::size_t p = 0; p < np; ++p)
  {
    if (weldTarget[p] == static_cast<int>(p))
    {
      r.PointToVertex[p] = static_cast<int>(m.Positions.size());
      r.VertexToPoint.push_back(static_cast<int>(p));
      m.Positions.push_back(points[p]);
    }
  }
  for (std::size_t p = 0; p < np; ++p)
  {
    if (weldTarget[p] >= 0)
    {
      r.PointToVertex[p] = r.PointToVertex[weldTarget[p]];
    }
  }
  return Status();
}

// 2. The faces, on the mesh's vertices; degenerate triangles refused.
Status TriangleMeshBuilder::SetFaces(const Triangles& triangles, MeshBuild& r)
{
  TriangleMesh& m = r.Mesh;
  m.Faces.resize(triangles.size());
  double scale = 0.0;
  Vec3 lo = m.Positions.empty() ? Vec3() : m.Positions[0], hi = lo;
  for (const Vec3& p : m.Positions)
  {
    scale = std::max({ scale, std::abs(p.x), std::abs(p.y), std::abs(p.z) });
    lo = Vec3(std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z));
    hi = Vec3(std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z));
  }
  // Areas and squared lengths of a mesh much smaller than this underflow (at 1e-80 a solve is
  // silently wrong, at 1e-200 every triangle has zero area): an error that says what to do,
  // like the 1e100 bound above.
  const double extent = std::max({ hi.x - lo.x, hi.y - lo.y, hi.z - lo.z });
  if (!m.Positions.empty() && extent < MinimumExtent)
  {
    std::ostringstream message;
    message << "the mesh is too small for double precision (its largest bounding box side is "
            << extent << ", below " << MinimumExtent << "): rescale the mesh";
    return Status::Error(message.str());
  }
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    auto& t = m.Faces[i];
    for (int k = 0; k < 3; ++k)
    {
      t[k] = r.PointToVertex[triangles[i][k]];
    }
    if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0])
    {
      return Status::Error(FaceLabel(i) +
        " is degenerate: it uses the same point twice (after welding coincident points)");
    }
    const Vec3 e1 = m.Positions[t[1]] - m.Positions[t[0]];
    const Vec3 e2 = m.Positions[t[2]] - m.Positions[t[0]];
    const Vec3 e3 = m.Positions[t[2]] - m.Positions[t[1]];
    const double twiceArea = Norm(Cross(e1, e2));
    const double longest = std::max({ Norm(e1), Norm(e2), Norm(e3) });
    // Zero area relative to its own size (a collinear or needle-thin triangle), or below what
    // double precision can resolve at this coordinate magnitude.
    if (!(twiceArea > 1e-12 * longest * longest) || !(longest > 1e-13 * scale))
    {
      return Status::Error(FaceLabel(i) + " is degenerate (zero area)");
    }
  }
  return Status();
}

// Duplicate triangles (the same three corners) refused.
Status TriangleMeshBuilder::CheckDuplicates(const TriangleMesh& m)
{
  const int nv = m.NumberOfVertices();
  // Faces in the order of (their sorted corners, index), bucketed by the smallest corner:
  // a duplicate follows its twin.
  std::vector<std::array<int, 3>> corners(m.Faces.size());
  for (std::size_t i = 0; i < m.Faces.size(); ++i)
  {
    corners[i] = m.Faces[i];
    std::sort(corners[i].begin(), corners[i].end());
  }
  const auto sorted = BucketByVertex<std::pair<std::pair<int, int>, int>>(
    m.Faces.size(), nv, [&corners](std::size_t i) {
      const auto& c = corners[i];
      return std::make_pair(c[0], std::make_pair(std::make_pair(c[1], c[2]), static_cast<int>(i)));
    });
  for (int v = 0; v < nv; ++v)
  {
    for (int i = sorted.Start[v] + 1; i < sorted.Start[v + 1]; ++i)
    {
      if (sorted.Entries[i].first == sorted.Entries[i - 1].first)
      {
        return Status::Error(FaceLabel(sorted.Entries[i].second) + " duplicates " +
          FaceLabel(sorted.Entries[i - 1].second));
      }
    }
  }
  return Status();
}

// 3. Undirected edge adjacency: at most two faces per edge; partner[h], the other half-edge of
// h's edge (-1 on the boundary).
Status TriangleMeshBuilder::PairEdges(const MeshBuild& r, std::vector<int>& partner)
{
  const TriangleMesh& m = r.Mesh;
  const int nv = m.NumberOfVertices();
  partner.assign(3 * static_cast<std::size_t>(m.NumberOfFaces()), -1);
  const auto groups = GroupEdges(m.Faces, nv);
  const auto& uses = groups.Entries;
  for (int v = 0; v < nv; ++v)
  {
    // (An edge's half-edges are consecutive in its smaller vertex's bucket.)
    for (int i = groups.Start[v]; i < groups.Start[v + 1];)
    {
      int j = i;
      while (j < groups.Start[v + 1] && uses[j].first == uses[i].first)
      {
        ++j;
      }
      if (j - i > 2)
      {
        const int a = m.Origin(uses[i].second), b = m.Destination(uses[i].second);
        return Status::Error("non-manifold edge between points " +
          std::to_string(r.VertexToPoint[a]) + " and " + std::to_string(r.VertexToPoint[b]) +
          ": it is shared by " + std::to_string(j - i) + " triangles");
      }
      if (j - i == 2)
      {
        partner[uses[i].second] = uses[i + 1].second;
        partner[uses[i + 1].second] = uses[i].second;
      }
      i = j;
    }
  }
  return Status();
}

// 4. Consistent orientation: faces flipped (flip[f] = 1: corners 1 and 2 swapped) by
// breadth-first search over each component, keeping its majority orientation.
Status TriangleMeshBuilder::Orient(
  const std::vector<int>& partner, MeshBuild& r, std::vector<signed char>& flip)
{
  TriangleMesh& m = r.Mesh;
  const int nf = m.NumberOfFaces();
  flip.assign(nf, -1);
  int flipped = 0;
  for (int f0 = 0; f0 < nf; ++f0)
  {
    if (flip[f0] >= 0)
    {
      continue;
    }
    flip[f0] = 0;
    std::vector<int> queue{ f0 };
    std::vector<int> comp;
    for (std::size_t qi = 0; qi < queue.size(); ++qi)
    {
      const int f = queue[qi];
      comp.push_back(f);
      for (int k = 0; k < 3; ++k)
      {
        const int h = 3 * f + k;
        const int t = partner[h];
        if (t < 0)
        {
          continue;
        }
        // Same direction in both faces means opposite orientations.
        const bool sameDir = m.Origin(h) == m.Origin(t);
        const signed char want = static_cast<signed char>(flip[f] ^ (sameDir ? 1 : 0));
        if (flip[t / 3] < 0)
        {
          flip[t / 3] = want;
          queue.push_back(t / 3);
        }
        else if (flip[t / 3] != want)
        {
          return Status::Error("the surface is not orientable (a Moebius-like strip contains " +
            FaceLabel(f) + ")");
        }
      }
    }
    // Keep the majority orientation of the component.
    int nflip = 0;
    for (int f : comp)
    {
      nflip += flip[f];
    }
    if (2 * nflip > static_cast<int>(comp.size()))
    {
      for (int f : comp)
      {
        flip[f] = static_cast<signed char>(1 - flip[f]);
      }
    }
  }
  for (int f = 0; f < nf; ++f)
  {
    if (flip[f])
    {
      std::swap(m.Faces[f][1], m.Faces[f][2]);
      ++flipped;
    }
  }
  if (flipped > 0)
  {
    r.Warnings.push_back(std::to_string(flipped) +
      " triangles were re-oriented to match their neighbours (inconsistent orientation)");
  }
  return Status();
}

// 5. Twins.
void TriangleMeshBuilder::SetTwins(
  const std::vector<int>& partner, const std::vector<signed char>& flip, TriangleMesh& m)
{
  const int nf = m.NumberOfFaces();
  // The partners of step 3 after the flips. Swapping corners 1 and 2 of a face turns
  // its half-edge k into half-edge 2 - k, reversed (a -> b, b -> c, c -> a become c -> a, b -> c
  // reversed, a -> b reversed); the pairs stay.
  m.Twins.assign(3 * nf, -1);
  auto moved = [&flip](int h) { return flip[h / 3] ? h - h % 3 + 2 - h % 3 : h; };
  for (int h = 0; h < 3 * nf; ++h)
  {
    if (partner[h] >= 0)
    {
      m.Twins[moved(h)] = moved(partner[h]);
    }
  }
}

// 6. The outgoing half-edge of each vertex (the boundary one if any) and its degree; the
// vertices whose faces form more than one fan (pinched).
std::vector<int> TriangleMeshBuilder::SetOutgoingHalfedges(TriangleMesh& m, std::vector<int>& degree)
{
  const int nf = m.NumberOfFaces();
  const int nv = m.NumberOfVertices();
  m.OutHalfedge.assign(nv, -1);
  degree.assign(nv, 0);
  for (int h = 0; h < 3 * nf; ++h)
  {
    const int v = m.Origin(h);
    degree[v]++;
    if (m.OutHalfedge[v] < 0 || m.Twins[h] < 0)
    {
      m.OutHalfedge[v] = h;
    }
  }
  // A vertex whose triangles form several fans (a pinch) is split into one vertex per fan. Where
  // the pinch exists only because coincident points were welded (a mesh whose holes touch at a
  // point, stored with separate copies), this restores the input's topology; where one input
  // point itself joins several fans, the input is non-manifold and is rejected below.
  std::vector<int> pinched;
  for (int v = 0; v < nv; ++v)
  {
    int count = 0;
    const int start = m.OutHalfedge[v];
    int h = start;
    do
    {
      ++count;
      h = m.RotateCCW(h);
    } while (h >= 0 && h != start && count <= degree[v]);
    if (count != degree[v])
    {
      pinched.push_back(v);
    }
  }
  return pinched;
}

// Pinched vertices split into one vertex per fan; an input point in more than one fan refused.
Status TriangleMeshBuilder::SplitPinches(const Triangles& triangles, std::size_t np,
  const std::vector<signed char>& flip, const std::vector<int>& pinched,
  const std::vector<int>& degree, MeshBuild& r)
{
  TriangleMesh& m = r.Mesh;
  const int nf = m.NumberOfFaces();
  const int nv = m.NumberOfVertices();
  std::vector<int> slot(nv, -1);
  for (std::size_t i = 0; i < pinched.size(); ++i)
  {
    slot[pinched[i]] = static_cast<int>(i);
  }
  std::vector<std::vector<int>> outgoing(pinched.size());
  for (int h = 0; h < 3 * nf; ++h)
  {
    if (slot[m.Origin(h)] >= 0)
    {
      outgoing[slot[m.Origin(h)]].push_back(h);
    }
  }
  std::vector<unsigned char> assigned(3 * nf, 0);
  for (std::size_t i = 0; i < pinched.size(); ++i)
  {
    const int v = pinched[i];
    bool first = true;
    for (int h0 : outgoing[i])
    {
      if (assigned[h0])
      {
        continue;
      }
      // Go to the clockwise end of h0's fan, then collect it counter-clockwise.
      int start = h0;
      for (int guard = 0; guard < degree[v]; ++guard)
      {
        const int cw = m.RotateCW(start);
        if (cw < 0 || cw == h0)
        {
          break;
        }
        start = cw;
      }
      int target = v;
      if (!first)
      {
        target = static_cast<int>(m.Positions.size());
        m.Positions.push_back(m.Positions[v]);
        r.VertexToPoint.push_back(r.VertexToPoint[v]);
        m.OutHalfedge.push_back(start);
      }
      else
      {
        m.OutHalfedge[v] = start;
      }
      first = false;
      int h = start;
      do
      {
        assigned[h] = 1;
        m.Faces[h / 3][h % 3] = target;
        h = m.RotateCCW(h);
      } while (h >= 0 && h != start && !assigned[h]);
    }
  }
  // Each input point must lie in a single fan.
  std::vector<int> seen(np, -1);
  for (std::size_t i = 0; i < triangles.size(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int corner = flip[i] ? (3 - k) % 3 : k; // flipped faces swapped corners 1 and 2
      const long long p = triangles[i][k];
      const int v = m.Faces[i][corner];
      if (seen[p] >= 0 && seen[p] != v)
      {
        return Status::Error("non-manifold vertex at point " + std::to_string(p) +
          ": its triangles form more than one fan");
      }
      seen[p] = v;
    }
  }
  for (std::size_t p = 0; p < np; ++p)
  {
    r.PointToVertex[p] = seen[p];
  }
  for (int v = 0; v < m.NumberOfVertices(); ++v)
  {
    r.VertexToPoint[v] = -1;
  }
  for (std::size_t p = np; p-- > 0;)
  {
    if (seen[p] >= 0)
    {
      r.VertexToPoint[seen[p]] = static_cast<int>(p);
    }
  }
  r.Warnings.push_back(std::to_string(m.NumberOfVertices() - nv) +
    " coincident points were kept apart: welding them would pinch separate fans of triangles");
  return Status();
}

} // namespace gs
