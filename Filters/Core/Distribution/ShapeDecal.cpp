// Decals: the faces a shape covers with texture coordinates (the inverse of its map: a short
// shape's polar chart, a long shape's CurveGrid), split where the map is not affine over a face.
#include "ShapeDecal.h"
#include "ShapeDistributorImpl.h"

#include "KeyedValues.h"

#include "GeodesicShooting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace gs
{
using namespace distribution;

namespace
{
// A short shape's face is laid out rigidly by its polar coordinates when the squares of its
// edges in the chart are within this fraction of their lengths' squares (a length within 0.5%).
constexpr double RigidStretch = 0.01;

// Whether triangle t (texture coordinates) meets the box [lo, hi] (separating axes).
bool MeetsBox(const std::array<Vec2, 3>& t, const Vec2& lo, const Vec2& hi)
{
  const double minX = std::min({ t[0].x, t[1].x, t[2].x }), maxX = std::max({ t[0].x, t[1].x, t[2].x });
  const double minY = std::min({ t[0].y, t[1].y, t[2].y }), maxY = std::max({ t[0].y, t[1].y, t[2].y });
  if (maxX < lo.x || minX > hi.x || maxY < lo.y || minY > hi.y)
  {
    return false;
  }
  const Vec2 box[4] = { lo, { hi.x, lo.y }, hi, { lo.x, hi.y } };
  for (int k = 0; k < 3; ++k)
  {
    const Vec2 a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
    const Vec2 axis{ -(b.y - a.y), b.x - a.x };
    const double side = Dot(axis, c - a);
    bool allOut = true;
    for (const Vec2& q : box)
    {
      allOut = allOut && Dot(axis, q - a) * side < 0.0;
    }
    if (allOut && side != 0.0)
    {
      return false;
    }
  }
  return true;
}

double SignedArea(const std::array<Vec2, 3>& t)
{
  return 0.5 * Cross(t[1] - t[0], t[2] - t[0]);
}

// A decal triangle clipped to the texture square [0, 1]^2: the renderer interpolates the texture
// coordinates linearly over the triangle, as the barycentric coordinates, so the part of it
// that draws texels of the square is the polygon clipped in texture space, its corners'
// barycentric coordinates interpolated alike (Sutherland-Hodgman, one side at a time), then
// fanned into triangles. A texture that repeats, a renderer that clamps, an exporter: none then
// draws anything outside the silhouette's square. Triangles inside the square are kept as they
// are; `emit` receives each piece (corners in the triangle's order, so its sense is kept).
template <class Emit>
void ClipToTextureSquare(
  const std::array<std::array<double, 3>, 3>& bary, const std::array<Vec2, 3>& uv, Emit&& emit)
{
  bool inside = true;
  for (const Vec2& u : uv)
  {
    inside = inside && u.x >= 0.0 && u.x <= 1.0 && u.y >= 0.0 && u.y <= 1.0;
  }
  if (inside)
  {
    emit(bary, uv);
    return;
  }
  struct Corner
  {
    std::array<double, 3> B;
    Vec2 U;
  };
  std::vector<Corner> polygon = { { bary[0], uv[0] }, { bary[1], uv[1] }, { bary[2], uv[2] } };
  std::vector<Corner> next;
  // Sides: u >= 0, u <= 1, v >= 0, v <= 1 (distance inside: positive).
  for (int side = 0; side < 4 && !polygon.empty(); ++side)
  {
    auto inside = [side](const Vec2& u) {
      switch (side)
      {
        case 0:
          return u.x;
        case 1:
          return 1.0 - u.x;
        case 2:
          return u.y;
        default:
          return 1.0 - u.y;
      }
    };
    next.clear();
    for (std::size_t k = 0, n = polygon.size(); k < n; ++k)
    {
      const Corner& a = polygon[k];
      const Corner& b = polygon[(k + 1) % n];
      const double da = inside(a.U), db = inside(b.U);
      if (da >= 0.0)
      {
        next.push_back(a);
      }
      if ((da >= 0.0) != (db >= 0.0))
      {
        const double t = da / (da - db);
        Corner c;
        for (int i = 0; i < 3; ++i)
        {
          c.B[i] = a.B[i] + t * (b.B[i] - a.B[i]);
        }
        c.U = a.U + (b.U - a.U) * t;
        // (Exactly on the side: rounding may leave it a hair outside.)
        if (side < 2)
          c.U.x = side == 0 ? 0.0 : 1.0;
        else
          c.U.y = side == 2 ? 0.0 : 1.0;
        next.push_back(c);
      }
    }
    polygon.swap(next);
  }
  for (std::size_t k = 1; k + 1 < polygon.size(); ++k)
  {
    const std::array<Vec2, 3> u{ { polygon[0].U, polygon[k].U, polygon[k + 1].U } };
    if (SignedArea(u) == 0.0)
    {
      continue; // (a sliver along a side of the square)
    }
    emit(std::array<std::array<double, 3>, 3>{ { polygon[0].B, polygon[k].B, polygon[k + 1].B } }, u);
  }
}

// The sense in which a long shape's grid lays its class frame on the surface (+1 or -1; 0 when
// it cannot tell): at the node of the centre row nearest the shape's centre (class point 0)
// whose four neighbours along and across are valid, the sign of the face normal against the
// cross product of the grid's steps along (class x) and across (class y).
double GridSense(const TriangleMesh& mesh, const CurveGrid& grid)
{
  const int rows = grid.Rows, centreRow = rows / 2;
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  auto node = [&](int i, int j) -> const CurveGrid::Node& { return grid.Nodes[static_cast<std::size_t>(i) * rows + j]; };
  for (int i = 1; i + 1 < grid.Columns; ++i)
  {
    if (centreRow < 1 || centreRow + 1 >= rows || !node(i, centreRow).Valid || !node(i - 1, centreRow).Valid ||
      !node(i + 1, centreRow).Valid || !node(i, centreRow - 1).Valid || !node(i, centreRow + 1).Valid)
    {
      continue;
    }
    const double d = Norm(node(i, centreRow).ClassPoint);
    if (d < bestDistance)
    {
      bestDistance = d;
      best = i;
    }
  }
  if (best < 0 || node(best, centreRow).At.Face < 0)
  {
    return 0.0;
  }
  const Vec3 along = node(best + 1, centreRow).Position - node(best - 1, centreRow).Position;
  const Vec3 across = node(best, centreRow + 1).Position - node(best, centreRow - 1).Position;
  // (Class y grows with the row: the frame's x and y, along and across, in that order.)
  const double alongY = node(best + 1, centreRow).ClassPoint.y - node(best - 1, centreRow).ClassPoint.y;
  const double acrossY = node(best, centreRow + 1).ClassPoint.y - node(best, centreRow - 1).ClassPoint.y;
  const double alongX = node(best + 1, centreRow).ClassPoint.x - node(best - 1, centreRow).ClassPoint.x;
  const double acrossX = node(best, centreRow + 1).ClassPoint.x - node(best, centreRow - 1).ClassPoint.x;
  const double classSense = alongX * acrossY - alongY * acrossX; // the steps' sense in the class frame
  const double surfaceSense = Dot(mesh.FaceNormal(node(best, centreRow).At.Face), Cross(along, across));
  const double sense = classSense * surfaceSense;
  return sense > 0.0 ? 1.0 : (sense < 0.0 ? -1.0 : 0.0);
}

// The barycentric coordinates l, in a piece of a face with barycentric corners B, of the point
// of that face with barycentric coordinates `bary` (solved in the first two face coordinates);
// whether the piece holds it (to 1e-9). False for a degenerate piece.
bool InPiece(const std::array<std::array<double, 3>, 3>& B, const std::array<double, 3>& bary, double l[3])
{
  const double ax = B[0][0] - B[2][0], bx = B[1][0] - B[2][0], ay = B[0][1] - B[2][1],
               by = B[1][1] - B[2][1];
  const double det = ax * by - bx * ay;
  if (det == 0.0)
  {
    return false;
  }
  const double px = bary[0] - B[2][0], py = bary[1] - B[2][1];
  l[0] = (px * by - bx * py) / det;
  l[1] = (ax * py - px * ay) / det;
  l[2] = 1.0 - l[0] - l[1];
  const double eps = -1e-9;
  return l[0] >= eps && l[1] >= eps && l[2] >= eps;
}
} // namespace

bool ShapeDecal::TextureCoordinateIn(std::size_t k, const std::array<double, 3>& bary, Vec2& uv) const
{
  double l[3];
  if (!InPiece(Corners[k], bary, l))
  {
    return false;
  }
  const auto& U = TextureCoordinates[k];
  uv = U[0] * l[0] + U[1] * l[1] + U[2] * l[2];
  return true;
}

bool ShapeDecal::TextureCoordinate(const SurfacePoint& p, Vec2& uv) const
{
  if (p.Face < 0)
  {
    return false;
  }
  for (std::size_t k = 0; k < Faces.size(); ++k)
  {
    if (Faces[k] == p.Face && TextureCoordinateIn(k, p.Bary, uv))
    {
      return true;
    }
  }
  return false;
}

namespace
{
// The texels of class c that draw: the silhouette's bounding box, 2% of the circumradius around
// it (for texture filtering), within the class square (texture coordinates).
void TexelBox(const SafeDistanceClass& c, Vec2& lo, Vec2& hi)
{
  lo = Vec2{ 1.0, 1.0 };
  hi = Vec2{ 0.0, 0.0 };
  for (const auto& ring : c.Outline.Rings)
  {
    for (const Vec2& p : ring)
    {
      const Vec2 u = DecalTextureCoordinate(p, c.Radius);
      lo = Vec2{ std::min(lo.x, u.x), std::min(lo.y, u.y) };
      hi = Vec2{ std::max(hi.x, u.x), std::max(hi.y, u.y) };
    }
  }
  lo = Vec2{ std::max(0.0, lo.x - 0.01), std::max(0.0, lo.y - 0.01) };
  hi = Vec2{ std::min(1.0, hi.x + 0.01), std::min(1.0, hi.y + 0.01) };
  if (!(lo.x <= hi.x && lo.y <= hi.y))
  {
    lo = Vec2{ 0.0, 0.0 };
    hi = Vec2{ 1.0, 1.0 };
  }
}

// How far from the centre (class units, circumradius r) the texel box [lo, hi] reaches: its
// farthest corner.
double TexelBoxReach(const Vec2& lo, const Vec2& hi, double r)
{
  double reach = 0.0;
  for (const Vec2& u : { lo, hi, Vec2{ lo.x, hi.y }, Vec2{ hi.x, lo.y } })
  {
    reach = std::max(reach, Norm(DecalClassPoint(u, r)));
  }
  return reach;
}
// The state of one decal as it is built: the class points of the vertices near the shape, the
// texels that draw, the long shape's grid and the values read on it once per vertex and edge.
struct DecalBuilder
{
  const TriangleMesh& Mesh;
  const SafeDistanceClass& ShapeClass;
  std::shared_ptr<const CurveGrid> Grid; // long shapes
  // Short shapes: the exact polar coordinates of the centre, and the world units per class unit.
  const GeodesicPolarCoordinates* Exact = nullptr;
  double ExactUnit = 1.0;
  FacePolarCoordinates ExactFace; // Exact over the face last read (a face's pieces read many)
  double TolUV = 0.0;                    // texture units per circumradius
  std::vector<std::pair<int, Vec2>> Local; // (vertex, class point), sorted by vertex
  Vec2 Lo, Hi;                           // the texels that draw (TexelBox)
  int Hint = -1, FirstValid = -1;
  // Long shapes: the grid nodes whose class points lie in the texels that draw, by face (face,
  // barycentric coordinates), sorted. A piece of a face holding one meets the shape, whatever its
  // corners' values say: on a face larger than the shape, its corners lie beyond the grid, and
  // their class points, extended from the grid's border, can all fall on one side of the
  // silhouette (armadillo at ShapeSize 0.6%: a gull's wing tip inside a face whose corners read
  // 2.5-3.3 radii away, its texture triangle outside the silhouette's box: 32 outline points
  // undrawn).
  std::vector<std::pair<int, std::array<double, 3>>> BoxNodes;
  // Short shapes: the world units per class unit, for ChartFaceHolds
  // (0: long shapes, no test).
  double ChartUnit = 0.0;
  // Short shapes: the face holding the centre (-1: a vertex centre, or a long shape). Its
  // texture triangle is the centre's face laid out exactly, so its orientation is the decal's.
  int CentreFace = -1;
  KeyedValues<Vec2> CornerValues; // vertices of faces to split, on the grid
  // The map read at a point: found, and beyond the map's reach inside the silhouette.
  struct Reading
  {
    bool Found = false;
    bool Ghost = false;
    Vec2 Point;
  };
  KeyedValues<Reading> Midpoints; // face edges' midpoints
  // A short shape's map at the midpoints of the pieces of the face being added: they fall on
  // the barycentric coordinates (i, j, k) / 2^MaxDepth exactly, and two pieces share each
  // inner edge (read once). Valid where the stamp is the face's.
  static constexpr int MaxDepth = 5;
  static constexpr int GridSide = (1 << MaxDepth) + 1;
  std::vector<Reading> PieceMidpoints;
  std::vector<unsigned> PieceStamps;
  unsigned FaceStamp = 0;
  // The slot of barycentric point b on that grid (-1: not on it).
  static int GridSlot(const std::array<double, 3>& b)
  {
    const double i = b[1] * (1 << MaxDepth), j = b[2] * (1 << MaxDepth);
    if (!(i >= 0.0 && j >= 0.0 && i < GridSide && j < GridSide) || std::floor(i) != i || std::floor(j) != j)
    {
      return -1;
    }
    return static_cast<int>(i) * GridSide + static_cast<int>(j);
  }
  // Long shapes: where the grid does not reach (its shots stopped at the mesh boundary, or a
  // nearby sheet of the surface), the affine extension of its border (what the vertices beyond
  // it are given, CurveShapeVertices) can carry the silhouette across a hole; such points are
  // ghosts, and the decal does not draw them. The silhouette for that test, the vertices
  // farther than half a grid step from the grid (sorted), and their ghost states as found.
  const ClassRegion* Region = nullptr;
  std::vector<int> Far;
  KeyedValues<char> VertexGhosts;

  DecalBuilder(const TriangleMesh& mesh, const SafeDistanceClass& c, double tolerance)
    : Mesh(mesh)
    , ShapeClass(c)
    , TolUV(tolerance > 0.0 ? 0.5 * tolerance : 0.0)
  {
    TexelBox(ShapeClass, Lo, Hi);
  }

  // Vertex v's class point (null: not near the shape), through the thread's vertex-indexed
  // table that Start fills (a binary search per face corner was a quarter of the decals' own
  // time).
  const Vec2* Find(int v) const
  {
    return Slots.Stamps.Marked(v) ? &Local[Slots.Index[v]].second : nullptr;
  }
  struct SlotTable
  {
    VertexStamps Stamps; // marked: Index holds the vertex's place in Local
    std::vector<int> Index;
  };
  static SlotTable& ThreadSlots()
  {
    thread_local SlotTable table;
    return table;
  }
  SlotTable& Slots = ThreadSlots();

  Vec2 ToTexture(const Vec2& q) const
  {
    return DecalTextureCoordinate(q, ShapeClass.Radius);
  }

  // Sorts and indexes the vertices. (The texels that draw, Lo and Hi, are set at construction:
  // faces whose texture triangle misses them would draw only transparent texels, not in the
  // decal.)
  void Start()
  {
    std::sort(Local.begin(), Local.end(),
      [](const std::pair<int, Vec2>& a, const std::pair<int, Vec2>& b) { return a.first < b.first; });
    const std::size_t nv = static_cast<std::size_t>(Mesh.NumberOfVertices());
    Slots.Stamps.Begin(nv);
    Slots.Index.resize(nv);
    for (std::size_t i = 0; i < Local.size(); ++i)
    {
      if (Slots.Stamps.Mark(Local[i].first)) // (the first of equal vertices, as a search finds)
      {
        Slots.Index[Local[i].first] = static_cast<int>(i);
      }
    }
    if (Grid)
    {
      for (int k = 0; k < static_cast<int>(Grid->Nodes.size()) && FirstValid < 0; ++k)
      {
        FirstValid = Grid->Nodes[k].Valid ? k : -1;
      }
      for (const CurveGrid::Node& node : Grid->Nodes)
      {
        const Vec2 u = ToTexture(node.ClassPoint);
        if (node.Valid && node.At.Face >= 0 && u.x >= Lo.x && u.x <= Hi.x && u.y >= Lo.y && u.y <= Hi.y)
        {
          BoxNodes.emplace_back(node.At.Face, node.At.Bary);
        }
      }
      std::sort(BoxNodes.begin(), BoxNodes.end());
    }
  }

  // The barycentric corners of a whole face.
  static constexpr std::array<std::array<double, 3>, 3> WholeFace{ { { { 1.0, 0.0, 0.0 } }, { { 0.0, 1.0, 0.0 } },
    { { 0.0, 0.0, 1.0 } } } };
  // Whether the piece of face f with barycentric corners B holds a node of BoxNodes.
  bool HoldsBoxNode(int f, const std::array<std::array<double, 3>, 3>& B) const
  {
    const std::array<double, 3> first{ { -1e300, -1e300, -1e300 } };
    for (auto it = std::lower_bound(BoxNodes.begin(), BoxNodes.end(), std::make_pair(f, first));
         it != BoxNodes.end() && it->first == f; ++it)
    {
      double l[3];
      if (InPiece(B, it->second, l))
      {
        return true;
      }
    }
    return false;
  }

  // A class point beyond the grid's reach that the silhouette (dilated by 1% of the radius, for
  // texture filtering) holds: a ghost.
  bool InSilhouette(const Vec2& q) const { return Region->Within(q, 0.01 * ShapeClass.Radius); }

  // The shape's map at a point of face f: on the grid, or beyond it its affine extension (what
  // the corners' values are, CurveShapeVertices); `ghost`: beyond the grid's reach, inside the
  // silhouette.
  bool ClassAt(int f, const std::array<double, 3>& b, Vec2& q, bool& ghost)
  {
    ghost = false;
    if (Exact)
    {
      if (ExactFace.Face() != f)
      {
        ExactFace = Exact->OnFace(f);
      }
      if (!ExactFace.LogMapAt(b, q))
      {
        return false;
      }
      q = q * (1.0 / ExactUnit);
      return true;
    }
    // (Not from the previous point's node: where the map folds, at a kink of the curve, the
    // globally nearest node decides the sheet, the same for every point.)
    if (Grid->ClassPoint(SurfacePoint::InFace(f, b[0], b[1], b[2]), q))
    {
      return true;
    }
    if (Hint < 0)
    {
      Hint = FirstValid;
    }
    const bool found = Grid->Locate(Mesh.Interpolate(f, b), Hint, q, nullptr, &Hint);
    ghost = found && Region && InSilhouette(q);
    return found;
  }

  // Is vertex v (near the shape) a ghost? Only vertices farther than half a grid step from the
  // grid can be (their class point located from their node, the affine extension); the grid's
  // own search then decides.
  bool VertexGhost(int v)
  {
    if (!Grid || !Region || !std::binary_search(Far.begin(), Far.end(), v) || !InSilhouette(*Find(v)))
    {
      return false;
    }
    if (const char* known = VertexGhosts.Find(static_cast<std::uint64_t>(v)))
    {
      return *known != 0;
    }
    Vec2 onGrid;
    const bool ghost = !Grid->ClassPoint(SurfacePoint::AtVertex(v), onGrid);
    VertexGhosts.Insert(static_cast<std::uint64_t>(v), ghost ? 1 : 0);
    return ghost;
  }

  // Faces checked for splitting: a long shape's faces wider than its grid's step (on smaller
  // faces the grid, affine per grid triangle, knows the map no better than the face's corners);
  // a short shape's faces that its polar coordinates do not lay out rigidly (the corners' class
  // points not as far apart as the corners: a face behind a saddle vertex or as large as its
  // distance from the centre, where the log map is not affine).
  bool Splits(int f) const
  {
    if (!(TolUV > 0.0))
    {
      return false;
    }
    if (Exact)
    {
      const auto& v = Mesh.Face(f);
      const Vec2 *a = Find(v[0]), *b = Find(v[1]), *c = Find(v[2]);
      if (!a || !b || !c)
      {
        return false;
      }
      const Vec2 chart[3] = { *a, *b, *c };
      for (int k = 0; k < 3; ++k)
      {
        const Vec2 e = (chart[(k + 1) % 3] - chart[k]) * ExactUnit;
        const double inChart = Dot(e, e), edge = Mesh.EdgeLength(3 * f + k);
        if (std::abs(inChart - edge * edge) > RigidStretch * edge * edge)
        {
          return true;
        }
      }
      return false;
    }
    if (!Grid)
    {
      return false;
    }
    const auto& v = Mesh.Face(f);
    const double longest = std::max({ Norm(Mesh.Position(v[1]) - Mesh.Position(v[0])),
      Norm(Mesh.Position(v[2]) - Mesh.Position(v[1])),
      Norm(Mesh.Position(v[0]) - Mesh.Position(v[2])) });
    return longest > Grid->Step;
  }

  // Faces with all corners known, near the shape (each face visited once, from its corner of
  // smallest index), whose texture triangle meets the class square or that hold a node of
  // BoxNodes; `orientation`: the map's sense, the area-weighted sign of the texture triangles
  // (a short shape's centre face decides; a long shape's grid does, GridSense).
  std::vector<std::pair<int, std::array<Vec2, 3>>> WholeFaces(double& orientation);

  // Face f (texture triangle uv) into the decal, split where the map is not affine.
  void AddFace(int f, const std::array<Vec2, 3>& uv, double sense, double unit, ShapeDecal& decal);

  // A piece of a face (barycentric corners B, texture corners U) as the subdivision sees it.
  struct Piece
  {
    std::array<std::array<double, 3>, 3> B;
    std::array<Vec2, 3> U;
    int Depth;
    std::array<bool, 3> Ghost; // per corner
  };
  std::vector<Piece> Stack; // AddFace's (kept across faces)
  // The departures of the map from the affine map at a piece's edge midpoints (zero where the
  // map is not known); Above: whether the largest is above a bound.
  struct Departures
  {
    std::array<Vec2, 3> At;
    bool Above(double bound) const
    {
      return NormExceeds(At[0], bound) || NormExceeds(At[1], bound) || NormExceeds(At[2], bound);
    }
  };
  // The map at the piece's edge midpoints (mid, trueUV; linear where it is not known; ghost) and
  // its departures from the affine map there.
  Departures MidpointError(int f, const Piece& t, std::array<std::array<double, 3>, 3>& mid,
    std::array<Vec2, 3>& trueUV, std::array<bool, 3>& ghost);
};

std::vector<std::pair<int, std::array<Vec2, 3>>> DecalBuilder::WholeFaces(double& orientation)
{
  std::vector<int> faces;
  for (const auto& e : Local)
  {
    Mesh.ForEachOutgoingHalfedge(e.first, [&](int h) {
      const auto& corners = Mesh.Face(h / 3);
      if (e.first == std::min(corners[0], std::min(corners[1], corners[2])))
      {
        faces.push_back(h / 3);
      }
    });
  }
  std::sort(faces.begin(), faces.end());
  std::vector<std::pair<int, std::array<Vec2, 3>>> whole;
  orientation = 0.0;
  double centreOrientation = 0.0;
  for (int f : faces)
  {
    std::array<Vec2, 3> uv;
    bool all = true;
    for (int k = 0; k < 3 && all; ++k)
    {
      const int v = Mesh.Face(f)[k];
      const Vec2* q = Find(v);
      all = q != nullptr;
      if (all)
      {
        // (The corners of a face to split are read like the points inside it, on the grid where
        // it reaches: where the map folds the grid decides the sheet, the same for all.)
        Vec2 value = *q;
        if (Grid && Splits(f))
        {
          const Vec2* known = CornerValues.Find(static_cast<std::uint64_t>(v));
          if (!known)
          {
            Vec2 onGrid;
            known = &CornerValues.Insert(
              static_cast<std::uint64_t>(v), Grid->ClassPoint(SurfacePoint::AtVertex(v), onGrid) ? onGrid : *q);
          }
          value = *known;
        }
        uv[k] = ToTexture(value);
      }
    }
    if (all && ChartUnit > 0.0)
    {
      // A face across the chart's cut locus spans the chart: it draws nothing.
      const auto& v = Mesh.Face(f);
      const Vec2 c[3] = { *Find(v[0]), *Find(v[1]), *Find(v[2]) };
      all = ChartFaceHolds(Mesh, f, c, ChartUnit);
    }
    if (all && f == CentreFace)
    {
      centreOrientation = SignedArea(uv);
    }
    if (all && (MeetsBox(uv, Lo, Hi) || (Grid && HoldsBoxNode(f, WholeFace))))
    {
      whole.emplace_back(f, uv);
      orientation += SignedArea(uv);
    }
  }
  // (The faces' votes weigh by texture area: where a face much larger than the shape lies across
  // the chart's cut locus undetected, its mirrored triangle outvoted the rest, and the pieces
  // that draw the shape were dropped as folded: turbine at ShapeSize 1.5%, 3 stars drawn by 1-2
  // stray triangles. The centre's face decides when there is one.)
  if (centreOrientation != 0.0)
  {
    orientation = centreOrientation;
  }
  return whole;
}

DecalBuilder::Departures DecalBuilder::MidpointError(int f, const Piece& t,
  std::array<std::array<double, 3>, 3>& mid, std::array<Vec2, 3>& trueUV, std::array<bool, 3>& ghost)
{
  const auto& corners = Mesh.Face(f);
  Departures error;
  for (int k = 0; k < 3; ++k)
  {
    const auto& a = t.B[k];
    const auto& b = t.B[(k + 1) % 3];
    mid[k] = { 0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2]) };
    const Vec2 linear = (t.U[k] + t.U[(k + 1) % 3]) * 0.5;
    // (A face's edge midpoints are shared with the neighbour across: read once.)
    const std::uint64_t edge = t.Depth == 0
      ? (static_cast<std::uint64_t>(std::min(corners[k], corners[(k + 1) % 3])) << 32) |
        static_cast<std::uint32_t>(std::max(corners[k], corners[(k + 1) % 3]))
      : 0;
    const int slot = t.Depth > 0 && Exact ? GridSlot(mid[k]) : -1;
    const Reading* known = t.Depth == 0 ? Midpoints.Find(edge)
      : slot >= 0 && PieceStamps[slot] == FaceStamp ? &PieceMidpoints[slot]
                                                   : nullptr;
    Vec2 q;
    bool found = false;
    if (known)
    {
      found = known->Found;
      ghost[k] = known->Ghost;
      q = known->Point;
    }
    else
    {
      bool g = false;
      found = ClassAt(f, mid[k], q, g);
      ghost[k] = g;
      if (t.Depth == 0)
      {
        Midpoints.Insert(edge, Reading{ found, g, q });
      }
      else if (slot >= 0)
      {
        PieceMidpoints[slot] = Reading{ found, g, q };
        PieceStamps[slot] = FaceStamp;
      }
    }
    if (found)
    {
      trueUV[k] = ToTexture(q);
      error.At[k] = trueUV[k] - linear;
    }
    else
    {
      trueUV[k] = linear;
    }
  }
  return error;
}

// Each face's texture map is affine; where the true map departs from it by more than the
// tolerance at an edge midpoint (a long shape's map along its curve, read on its grid), the
// triangle is split in four, to depth 5 (1024 pieces per face). A piece whose texture triangle
// is turned over (the map folds there) or stretched far beyond its size on the surface (a jump
// across a seam of the map) is dropped. A long shape's face with a ghost corner or midpoint
// (beyond the grid's reach, inside the silhouette) is split to the finest pieces, and those
// whose centre is a ghost are dropped: the shape is drawn where its map reaches.
void DecalBuilder::AddFace(int f, const std::array<Vec2, 3>& uv, double sense, double unit, ShapeDecal& decal)
{
  if (PieceStamps.empty())
  {
    PieceMidpoints.resize(GridSide * GridSide);
    PieceStamps.assign(GridSide * GridSide, 0u);
  }
  ++FaceStamp;
  const auto& corners = Mesh.Face(f);
  const Vec3 X[3] = { Mesh.Position(corners[0]), Mesh.Position(corners[1]),
    Mesh.Position(corners[2]) };
  const std::array<bool, 3> cornerGhost{ { VertexGhost(corners[0]), VertexGhost(corners[1]), VertexGhost(corners[2]) } };
  const bool split = Splits(f) || cornerGhost[0] || cornerGhost[1] || cornerGhost[2];
  std::vector<Piece>& stack = Stack;
  stack.clear();
  stack.push_back(Piece{ WholeFace, uv, 0, cornerGhost });
  while (!stack.empty())
  {
    const Piece t = stack.back();
    stack.pop_back();
    // (A piece holding a node of the silhouette's box meets the shape: its corners' values may
    // be extended from far beyond the grid. It is split to the finest pieces or until its
    // texture triangle, from the map read at its midpoints, meets the box.)
    const bool meets = MeetsBox(t.U, Lo, Hi);
    const bool holds = !meets && Grid && HoldsBoxNode(f, t.B);
    if (!meets && !holds)
    {
      continue;
    }
    auto at = [&X](const std::array<double, 3>& b) { return X[0] * b[0] + X[1] * b[1] + X[2] * b[2]; };
    if (split)
    {
      std::array<std::array<double, 3>, 3> mid;
      std::array<Vec2, 3> trueUV;
      std::array<bool, 3> midGhost{ { false, false, false } };
      const Departures error = MidpointError(f, t, mid, trueUV, midGhost);
      // Finest: depth 5, or pieces as small as half the grid's step (it cannot tell more).
      const double size = std::max({ Norm(at(t.B[1]) - at(t.B[0])), Norm(at(t.B[2]) - at(t.B[1])),
        Norm(at(t.B[0]) - at(t.B[2])) });
      const bool finest = t.Depth == MaxDepth || (Grid && size <= 0.5 * Grid->Step);
      // Corners 0, 1, 2 and midpoints m01, m12, m20, each with its ghost state.
      auto splitInFour = [&]() {
        stack.push_back(Piece{ { { t.B[0], mid[0], mid[2] } }, { { t.U[0], trueUV[0], trueUV[2] } }, t.Depth + 1,
          { { t.Ghost[0], midGhost[0], midGhost[2] } } });
        stack.push_back(Piece{ { { mid[0], t.B[1], mid[1] } }, { { trueUV[0], t.U[1], trueUV[1] } }, t.Depth + 1,
          { { midGhost[0], t.Ghost[1], midGhost[1] } } });
        stack.push_back(Piece{ { { mid[2], mid[1], t.B[2] } }, { { trueUV[2], trueUV[1], t.U[2] } }, t.Depth + 1,
          { { midGhost[2], midGhost[1], t.Ghost[2] } } });
        stack.push_back(Piece{ { { mid[0], mid[1], mid[2] } }, { { trueUV[0], trueUV[1], trueUV[2] } }, t.Depth + 1,
          { { midGhost[0], midGhost[1], midGhost[2] } } });
      };
      if (holds && !finest)
      {
        splitInFour();
        continue;
      }
      if (t.Ghost[0] || t.Ghost[1] || t.Ghost[2] || midGhost[0] || midGhost[1] || midGhost[2])
      {
        if (!finest)
        {
          splitInFour();
          continue;
        }
        const std::array<double, 3> centre{ { (t.B[0][0] + t.B[1][0] + t.B[2][0]) / 3.0,
          (t.B[0][1] + t.B[1][1] + t.B[2][1]) / 3.0, (t.B[0][2] + t.B[1][2] + t.B[2][2]) / 3.0 } };
        Vec2 q;
        bool ghost = false;
        if (ClassAt(f, centre, q, ghost) && ghost)
        {
          continue; // beyond the map's reach
        }
      }
      // (Tolerance 0: no split for the map's bends; a face is split only for its ghosts.)
      if (TolUV > 0.0 && error.Above(TolUV) && finest)
      {
        if (error.Above(5.0 * TolUV))
        {
          continue; // still not affine at the finest: the map folds or jumps here
        }
      }
      else if (TolUV > 0.0 && error.Above(TolUV))
      {
        splitInFour(); // (no ghost here: pieces with one were split above)
        continue;
      }
    }
    // Folded or torn: dropped.
    if (SignedArea(t.U) * sense < 0.0)
    {
      continue;
    }
    bool torn = false;
    for (int k = 0; k < 3 && !torn; ++k)
    {
      const double onSurface = Norm(at(t.B[(k + 1) % 3]) - at(t.B[k]));
      torn = NormExceeds(t.U[(k + 1) % 3] - t.U[k], 4.0 * onSurface + 0.05 * unit, unit);
    }
    if (torn)
    {
      continue;
    }
    ClipToTextureSquare(t.B, t.U,
      [&decal, f](const std::array<std::array<double, 3>, 3>& b, const std::array<Vec2, 3>& u) {
        decal.Faces.push_back(f);
        decal.Corners.push_back(b);
        decal.TextureCoordinates.push_back(u);
      });
  }
}
} // namespace

ShapeDecal ShapeDistributor::Impl::DecalOf(int shape, double tolerance) const
{
  ShapeDecal decal;
  const PlacedShape& s = Accepted.Placed.at(shape);
  const SafeDistanceClass& c = Tables.Classes[s.ClassId];
  const double scale = Options.ShapeSize * s.Scale;
  DecalBuilder b(Mesh, c, tolerance);
  // Class-frame coordinates (normalized) of the vertices near the shape.
  ExactEngineLease exact(*this); // (taken from the pool only for a short shape)
  if (s.Curve.empty())
  {
    // The exact polar coordinates of the centre (the inverse of the geodesic shots that draw the
    // outline), not the placement's chart: its graph's departure angles can be off by degrees
    // behind saddles, which would draw the shape where it is not. The chart covers the faces
    // that meet the disc the texel box reaches (ComputeCoveringDisc: a margin of each face's own
    // edges, not the mesh's longest edge everywhere).
    GeodesicPolarCoordinates& engine = exact.Take();
    const double reference = TangentAngle(Mesh, s.Centre, s.Direction);
    if (!std::isfinite(reference) ||
      !engine.ComputeCoveringDisc(s.Centre, TexelBoxReach(b.Lo, b.Hi, c.Radius) * scale, reference)
         .Ok())
    {
      return decal;
    }
    b.Exact = &engine;
    b.ExactUnit = scale;
    // The decal's vertices: those within the circumradius plus the mesh's longest edge.
    const double reach = c.Radius * scale + Measures.MaxEdge;
    for (int v : engine.Inside())
    {
      if (!(engine.Rho(v) <= reach))
      {
        break; // (Inside is by increasing rho)
      }
      Vec2 q;
      engine.LogMapAt(SurfacePoint::AtVertex(v), q);
      b.Local.emplace_back(v, q * (1.0 / scale));
    }
    b.ChartUnit = scale;
    b.CentreFace = s.Centre.IsVertex() ? -1 : s.Centre.Face;
  }
  else
  {
    b.Grid = FrameOf(shape); // the grid the drawn check built (indexed), or a new one
    if (!b.Grid)
    {
      return decal;
    }
    CurveShapeVertices(*b.Grid, b.Local, &b.Far);
    std::sort(b.Far.begin(), b.Far.end());
    b.Region = &Silhouettes.Regions[s.ClassId];
  }
  b.Start();
  double orientation = 0.0;
  const std::vector<std::pair<int, std::array<Vec2, 3>>> whole = b.WholeFaces(orientation);
  double sense = orientation >= 0.0 ? 1.0 : -1.0;
  // (A long shape's faces vote like a short shape's without a centre face: on turbine at
  // ShapeSize 1.5%, faces far larger than the shape, their corners' class points extended
  // beyond the grid, outvoted the rest for 44 of 7000 long decals, whose drawing pieces were
  // then dropped as folded: fish drawn by 0 to 8 triangles. The grid's own sense decides.)
  if (b.Grid)
  {
    const double gridSense = GridSense(Mesh, *b.Grid);
    sense = gridSense != 0.0 ? gridSense : sense;
  }
  const double unit = 2.0 * c.Radius * scale; // world length of one texture unit
  for (const auto& entry : whole)
  {
    b.AddFace(entry.first, entry.second, sense, unit, decal);
  }
  return decal;
}

ShapeDecal ShapeDistributor::Decal(int shape, double tolerance) const
{
  // A place-keyed run keeps each shape's decal: an edit's run keeps the shapes it did not
  // reach, and their decals with them.
  const Impl::Record& r = Internal->Accepted.Records.at(shape);
  if (r.Decal && r.DecalTolerance == tolerance)
  {
    return *r.Decal;
  }
  ShapeDecal decal = Internal->DecalOf(shape, tolerance);
  if (Internal->Pool.Active)
  {
    r.Decal = std::make_shared<const ShapeDecal>(decal);
    r.DecalTolerance = tolerance;
  }
  return decal;
}

} // namespace gs
