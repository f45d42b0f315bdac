// The shape model: a placed shape is its map class point -> surface point (a short shape's
// exponential map about its centre; a long shape's curve map: arc length along its streamline,
// then across along the perpendicular geodesic). Outlines are the class outline pushed forward;
// CurveGrid samples a long shape's map and inverts it near the shape.
#include "ShapeDistributorImpl.h"
#include "ShapeMap.h"

#include "GeodesicShooting.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace gs
{
using namespace distribution;

namespace
{
// Distance from x to triangle abc, and the barycentric coordinates of x's projection onto
// the triangle's plane (not clamped: the affine extension outside). Infinite when degenerate.
double TriangleDistance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& x, double lambda[3])
{
  const Vec3 e0 = b - a, e1 = c - a, n = Cross(e0, e1);
  const double area2 = Dot(n, n);
  if (!(area2 > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  const Vec3 w = x - a;
  lambda[1] = Dot(Cross(w, e1), n) / area2;
  lambda[2] = Dot(Cross(e0, w), n) / area2;
  lambda[0] = 1.0 - lambda[1] - lambda[2];
  if (lambda[0] >= 0.0 && lambda[1] >= 0.0 && lambda[2] >= 0.0)
  {
    return std::abs(Dot(w, n)) / std::sqrt(area2);
  }
  // Outside: the distance to the nearest edge. (One square root of the smallest square: the
  // same value as the smallest of three roots, the root being monotonic and correctly rounded.)
  auto segment2 = [&x](const Vec3& p, const Vec3& q) {
    const Vec3 pq = q - p;
    const double l2 = Dot(pq, pq);
    const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, Dot(x - p, pq) / l2)) : 0.0;
    const Vec3 d = p + pq * t - x;
    return Dot(d, d);
  };
  return std::sqrt(std::min(segment2(a, b), std::min(segment2(b, c), segment2(c, a))));
}
} // namespace

bool ShapeDistributor::Impl::PointOnCurve(const TriangleMesh& m, const std::vector<CurvePiece>& curve, double u,
  int& face, Vec3& x, Vec3& tangent)
{
  double walked = 0.0;
  const CurvePiece* last = nullptr;
  for (const CurvePiece& piece : curve)
  {
    const double len = Norm(piece.B - piece.A);
    if (len <= 0.0)
    {
      continue;
    }
    last = &piece;
    if (walked + len >= u)
    {
      const double t = std::max(0.0, (u - walked) / len);
      face = piece.Face;
      x = piece.A + (piece.B - piece.A) * t;
      tangent = (piece.B - piece.A) * (1.0 / len);
      return true;
    }
    walked += len;
  }
  if (!last)
  {
    return false;
  }
  (void)m;
  face = last->Face;
  x = last->B;
  tangent = Unit(last->B - last->A);
  return true;
}

bool ShapeDistributor::Impl::Across(int face, const Vec3& x, const Vec3& t, double across, SurfacePoint& end,
  Vec3& endTangent, bool* boundary) const
{
  end = SurfacePoint::InFace(face, 0, 0, 0);
  end.Bary = Mesh.ClampedBarycentric(face, x);
  endTangent = t;
  if (std::abs(across) <= 0.0)
  {
    return true;
  }
  const double side = across > 0.0 ? 1.0 : -1.0;
  const double angle = TangentAngle(Mesh, end, t);
  if (!std::isfinite(angle))
  {
    return false;
  }
  const GeodesicShot shot = ShootGeodesic(Mesh, end, angle + side * 0.5 * Pi, std::abs(across));
  if (boundary)
  {
    *boundary = shot.ReachedBoundary;
  }
  end = shot.End;
  Vec3 dir = Unit(RotateTangent(t, Mesh.FaceNormal(face), side * 0.5 * Pi));
  for (auto it = shot.Pieces.rbegin(); it != shot.Pieces.rend(); ++it)
  {
    if (Norm(it->B - it->A) > 0.0)
    {
      dir = Unit(it->B - it->A);
      break;
    }
  }
  const Vec3 n = Mesh.FaceNormal(end.Face);
  endTangent = Unit(RotateTangent(dir, n, -side * 0.5 * Pi));
  return true;
}

MappedPoint ShapeDistributor::Impl::MapShape(const PlacedShape& s, const Vec2& p) const
{
  const Impl& I = *this;
  const SafeDistanceClass& c = I.Tables.Classes[s.ClassId];
  const double scale = I.Options.ShapeSize * s.Scale;
  MappedPoint m;
  if (s.Curve.empty())
  {
    const double rho = Norm(p) * scale;
    if (rho <= 0.0)
    {
      m.End = s.Centre;
      return m;
    }
    const double a = TangentAngle(I.Mesh, s.Centre, s.Direction);
    const GeodesicShot shot = ShootGeodesic(I.Mesh, s.Centre, a + std::atan2(p.y, p.x), rho);
    m.End = shot.End;
    m.Reached = !shot.ReachedBoundary;
    m.Reach = m.Reached ? 1.0 : std::min(1.0, shot.Length / rho);
    return m;
  }
  int face = -1;
  Vec3 x, tangent;
  Impl::PointOnCurve(
    I.Mesh, s.Curve, s.CurveCentre + Dot(p, c.MajorAxis) * scale, face, x, tangent);
  Vec3 endTangent;
  bool boundary = false;
  if (!I.Across(face, x, tangent, Cross(c.MajorAxis, p) * scale, m.End, endTangent, &boundary))
  {
    m.End = SurfacePoint::InFace(face, 0, 0, 0);
    m.End.Bary = I.Mesh.ClampedBarycentric(face, x);
    m.Reached = false;
    m.Reach = 0.0;
  }
  else if (boundary)
  {
    m.Reached = false;
    m.Reach = 0.0;
  }
  return m;
}

std::vector<OutlinePiece> ShapeDistributor::Impl::OutlineOf(const PlacedShape& s, double spacing) const
{
  const Impl& I = *this;
  const SafeDistanceClass& c = I.Tables.Classes[s.ClassId];
  const double unit = I.Options.ShapeSize * s.Scale;
  if (!(spacing > 0.0) || !(unit > 0.0))
  {
    return {};
  }
  // No more samples than 1000 per unit of the class radius on an edge.
  const double normalized = std::max(spacing / unit, 1e-3 * c.Radius);
  const auto map = [this, &s](const Vec2& p) { return MapShape(s, p); };
  if (s.Curve.empty())
  {
    return DrawRadialOutline(c.Outline.Rings, normalized, c.Radius, map);
  }
  return DrawOutlinePieces(c.Outline.Rings, normalized, map);
}

bool ShapeDistributor::Impl::CurveGridFoot(
  const PlacedShape& s, double u, double length, SurfacePoint& foot, Vec3& tangent) const
{
  int face = -1;
  Vec3 x;
  // A column within rounding of an end is on the curve (it lands on an end whenever the class is
  // exactly as long as its circle's diameter and the margin is the radius: a "beyond" geodesic a
  // few 1e-17 long took its direction from rounding noise and turned the column, folding the
  // grid).
  const double snap = 1e-9 * std::max(length, Mesh.MeanEdgeLength());
  if (u >= -snap && u <= length + snap)
  {
    u = std::min(length, std::max(0.0, u));
    if (!PointOnCurve(Mesh, s.Curve, u, face, x, tangent))
    {
      return false;
    }
    foot = SurfacePoint::InFace(face, 0, 0, 0);
    foot.Bary = Mesh.ClampedBarycentric(face, x);
  }
  else
  {
    // Beyond an end: the geodesic continuing the curve's end.
    const bool after = u > length;
    if (!PointOnCurve(Mesh, s.Curve, after ? length : 0.0, face, x, tangent))
    {
      return false;
    }
    SurfacePoint end = SurfacePoint::InFace(face, 0, 0, 0);
    end.Bary = Mesh.ClampedBarycentric(face, x);
    const double angle = TangentAngle(Mesh, end, after ? tangent : tangent * -1.0);
    if (!std::isfinite(angle))
    {
      return false;
    }
    const double beyond = after ? u - length : -u;
    const GeodesicShot shot = ShootGeodesic(Mesh, end, angle, beyond);
    if (shot.ReachedBoundary || shot.Pieces.empty())
    {
      return false;
    }
    foot = shot.End;
    Vec3 dir = after ? tangent : tangent * -1.0;
    for (auto it = shot.Pieces.rbegin(); it != shot.Pieces.rend(); ++it)
    {
      if (Norm(it->B - it->A) > 1e-9 * Mesh.MeanEdgeLength()) // (never a rounding-length piece)
      {
        dir = Unit(it->B - it->A);
        break;
      }
    }
    tangent = after ? dir : dir * -1.0;
  }
  return true;
}

CurveGrid ShapeDistributor::Impl::BuildCurveGrid(const PlacedShape& s, const SafeDistanceClass& c) const
{
  CurveGrid grid;
  grid.Mesh = &Mesh;
  const double scale = Options.ShapeSize * s.Scale;
  double length = 0.0;
  for (const CurvePiece& piece : s.Curve)
  {
    length += Norm(piece.B - piece.A);
  }
  double across = 0.0;
  for (const auto& ring : c.Outline.Rings)
  {
    for (const Vec2& p : ring)
    {
      across = std::max(across, std::abs(Cross(c.MajorAxis, p)));
    }
  }
  across *= scale;
  if (!(length > 0.0) || !(scale > 0.0))
  {
    return grid;
  }
  // Margin beyond the silhouette's extent (two mean edges): a face with a corner in the shape
  // has its others within about an edge; a longer edge reaches into the affine extension.
  const double margin = std::min(2.0 * Mesh.MeanEdgeLength(), c.Radius * scale);
  const double h0 = std::min(Mesh.MeanEdgeLength(), c.Radius * scale / 12.0);
  const int columns = std::max(2, std::min(1024, static_cast<int>(std::ceil((length + 2.0 * margin) / h0)) + 1));
  const int half = std::max(1, std::min(256, static_cast<int>(std::ceil((across + margin) / h0))));
  const int rows = 2 * half + 1;
  const double du = (length + 2.0 * margin) / (columns - 1), db = (across + margin) / half;
  const Vec2 m = c.MajorAxis, perp{ -c.MajorAxis.y, c.MajorAxis.x };
  grid.Columns = columns;
  grid.Rows = rows;
  grid.Step = std::max(du, db);
  grid.Nodes.assign(static_cast<std::size_t>(columns) * rows, CurveGrid::Node());
  std::vector<CurveGrid::Node>& nodes = grid.Nodes;
  auto walk = [](const GeodesicShot& shot, double d, SurfacePoint& at, const TriangleMesh& mesh) {
    double walked = 0.0;
    for (const CurvePiece& piece : shot.Pieces)
    {
      const double len = Norm(piece.B - piece.A);
      if (walked + len >= d && len > 0.0)
      {
        at = SurfacePoint::InFace(piece.Face, 0, 0, 0);
        at.Bary = mesh.ClampedBarycentric(piece.Face, piece.A + (piece.B - piece.A) * ((d - walked) / len));
        return true;
      }
      walked += len;
    }
    return false;
  };
  for (int i = 0; i < columns; ++i)
  {
    const double u = -margin + du * i;
    SurfacePoint foot;
    Vec3 tangent;
    if (!CurveGridFoot(s, u, length, foot, tangent))
    {
      continue;
    }
    const double a = (u - s.CurveCentre) / scale;
    const int centreRow = half;
    CurveGrid::Node& mid = nodes[static_cast<std::size_t>(i) * rows + centreRow];
    mid.Valid = true;
    mid.At = foot;
    mid.Position = Mesh.Interpolate(foot.Face, foot.Bary);
    mid.ClassPoint = m * a;
    const double angle = TangentAngle(Mesh, foot, tangent);
    if (!std::isfinite(angle))
    {
      continue;
    }
    for (const double side : { 1.0, -1.0 })
    {
      const GeodesicShot shot = ShootGeodesic(Mesh, foot, angle + side * 0.5 * Pi, across + margin);
      for (int j = 1; j <= half; ++j)
      {
        CurveGrid::Node& node = nodes[static_cast<std::size_t>(i) * rows + centreRow + (side > 0.0 ? j : -j)];
        if (!walk(shot, db * j * (1.0 - 1e-12), node.At, Mesh))
        {
          break;
        }
        node.Valid = true;
        node.Position = Mesh.Interpolate(node.At.Face, node.At.Bary);
        node.ClassPoint = m * a + perp * (side * db * j / scale);
      }
    }
  }
  return grid;
}

void ShapeDistributor::Impl::CurveShapeVertices(const CurveGrid& grid, std::vector<std::pair<int, Vec2>>& local,
  std::vector<int>* far) const
{
  // The vertices the shape is drawn on, each from its node: the nearest node by descent over
  // the grid (the map is smooth at the grid's scale).
  const std::vector<std::pair<int, int>> seeds = grid.Vertices(); // (vertex, node)
  local.reserve(local.size() + seeds.size());
  for (const auto& seed : seeds)
  {
    const int v = seed.first;
    Vec2 point;
    double distance = 0.0;
    if (grid.Locate(Mesh.Position(v), seed.second, point, &distance))
    {
      local.emplace_back(v, point);
      if (far && distance > 0.5 * grid.Step)
      {
        far->push_back(v);
      }
    }
  }
}

std::shared_ptr<const CurveGrid> ShapeDistributor::Impl::FrameOf(int shape) const
{
  const PlacedShape& s = Accepted.Placed.at(shape);
  if (s.Curve.empty())
  {
    return nullptr;
  }
  if (Accepted.Records.at(shape).Frame)
  {
    return Accepted.Records.at(shape).Frame;
  }
  auto grid = std::make_shared<CurveGrid>(BuildCurveGrid(s, Tables.Classes[s.ClassId]));
  grid->Index();
  return grid;
}

bool CurveGrid::Locate(const Vec3& X, int start, Vec2& p, double* distance, int* nearestNode) const
{
  if (start < 0 || start >= static_cast<int>(Nodes.size()) || !Nodes[start].Valid)
  {
    return false;
  }
  int nearest = start;
  auto distance2 = [&X](const Vec3& y) {
    const Vec3 d = y - X;
    return Dot(d, d);
  };
  double best = distance2(Nodes[nearest].Position);
  for (bool moved = true; moved;)
  {
    moved = false;
    const int i0 = nearest / Rows, j0 = nearest % Rows;
    for (int di = -1; di <= 1; ++di)
    {
      for (int dj = -1; dj <= 1; ++dj)
      {
        const int i1 = i0 + di, j1 = j0 + dj;
        if (i1 < 0 || j1 < 0 || i1 >= Columns || j1 >= Rows || !Nodes[i1 * Rows + j1].Valid)
        {
          continue;
        }
        const double d = distance2(Nodes[i1 * Rows + j1].Position);
        if (d < best)
        {
          best = d;
          nearest = i1 * Rows + j1;
          moved = true;
        }
      }
    }
  }
  // The grid triangles around the nearest node: the nearest of them, its affine map.
  if (nearestNode)
  {
    *nearestNode = nearest;
  }
  const int ni = nearest / Rows, nj = nearest % Rows;
  double bestDistance = std::numeric_limits<double>::infinity();
  auto cell = [&](int ci, int cj) {
    const int q00 = ci * Rows + cj, q10 = (ci + 1) * Rows + cj, q11 = (ci + 1) * Rows + cj + 1,
              q01 = ci * Rows + cj + 1;
    for (const std::array<int, 3>& t : { std::array<int, 3>{ q00, q10, q11 }, std::array<int, 3>{ q00, q11, q01 } })
    {
      const Node &A = Nodes[t[0]], &B = Nodes[t[1]], &C = Nodes[t[2]];
      if (!A.Valid || !B.Valid || !C.Valid)
      {
        continue;
      }
      double lambda[3] = { 0.0, 0.0, 0.0 };
      const double d = TriangleDistance(A.Position, B.Position, C.Position, X, lambda);
      if (d < bestDistance)
      {
        bestDistance = d;
        p = A.ClassPoint * lambda[0] + B.ClassPoint * lambda[1] + C.ClassPoint * lambda[2];
      }
    }
  };
  for (int ci = ni - 1; ci <= ni; ++ci)
  {
    for (int cj = nj - 1; cj <= nj; ++cj)
    {
      if (ci >= 0 && cj >= 0 && ci + 1 < Columns && cj + 1 < Rows)
      {
        cell(ci, cj);
      }
    }
  }
  // A nearest node on a ragged border (its shots stopped short: the grid's corners on a bent
  // curve) may have no whole grid triangle about it: the nearest triangle of the whole grid
  // then. (Before, the point had no class point: a face corner far from the shape, on a mesh
  // whose faces are larger than the shape, was left out and its faces with it, and the decal
  // left a strip of the outline undrawn: mannequin-devil at ShapeSize 0.6%, 35 points.)
  if (!std::isfinite(bestDistance))
  {
    for (int ci = 0; ci + 1 < Columns; ++ci)
    {
      for (int cj = 0; cj + 1 < Rows; ++cj)
      {
        cell(ci, cj);
      }
    }
  }
  if (distance)
  {
    *distance = bestDistance;
  }
  return std::isfinite(bestDistance);
}

void CurveGrid::Index()
{
  CellSize = std::max(2.0 * Step, 1e-300);
  CellStart.clear();
  CellNodes.clear();
  Vec3 lo{ 1e300, 1e300, 1e300 }, hi{ -1e300, -1e300, -1e300 };
  bool any = false;
  for (const Node& n : Nodes)
  {
    if (n.Valid)
    {
      any = true;
      lo = Vec3{ std::min(lo.x, n.Position.x), std::min(lo.y, n.Position.y),
        std::min(lo.z, n.Position.z) };
      hi = Vec3{ std::max(hi.x, n.Position.x), std::max(hi.y, n.Position.y),
        std::max(hi.z, n.Position.z) };
    }
  }
  if (!any)
  {
    Dims = { { 0, 0, 0 } };
    return;
  }
  const double extent = std::max({ hi.x - lo.x, hi.y - lo.y, hi.z - lo.z });
  CellSize = std::max(CellSize, extent / 100.0); // at most 101^3 cells
  Origin = lo;
  for (int k = 0; k < 3; ++k)
  {
    const double e = k == 0 ? hi.x - lo.x : k == 1 ? hi.y - lo.y : hi.z - lo.z;
    Dims[k] = static_cast<int>(std::floor(e / CellSize)) + 1;
  }
  const std::size_t cells = static_cast<std::size_t>(Dims[0]) * Dims[1] * Dims[2];
  CellStart.assign(cells + 1, 0);
  auto cellOf = [this](const Vec3& x) {
    const int i = std::min(Dims[0] - 1, static_cast<int>((x.x - Origin.x) / CellSize));
    const int j = std::min(Dims[1] - 1, static_cast<int>((x.y - Origin.y) / CellSize));
    const int k = std::min(Dims[2] - 1, static_cast<int>((x.z - Origin.z) / CellSize));
    return (static_cast<std::size_t>(k) * Dims[1] + j) * Dims[0] + i;
  };
  for (const Node& n : Nodes)
  {
    if (n.Valid)
    {
      ++CellStart[cellOf(n.Position) + 1];
    }
  }
  for (std::size_t c = 0; c < cells; ++c)
  {
    CellStart[c + 1] += CellStart[c];
  }
  CellNodes.assign(CellStart[cells], 0);
  std::vector<int> fill(CellStart.begin(), CellStart.end() - 1);
  for (int k = 0; k < static_cast<int>(Nodes.size()); ++k)
  {
    if (Nodes[k].Valid)
    {
      CellNodes[fill[cellOf(Nodes[k].Position)]++] = k;
    }
  }
}

std::vector<std::pair<int, int>> CurveGrid::Vertices() const
{
  std::vector<std::pair<int, int>> seeds; // (vertex, node)
  if (!Mesh)
  {
    return seeds;
  }
  // (Each vertex once: marks per thread, stamped per call.)
  thread_local VertexStamps marks;
  marks.Begin(static_cast<std::size_t>(Mesh->NumberOfVertices()));
  for (int k = 0; k < static_cast<int>(Nodes.size()); ++k)
  {
    if (Nodes[k].Valid)
    {
      for (int v : Mesh->Face(Nodes[k].At.Face))
      {
        if (marks.Mark(v))
        {
          seeds.emplace_back(v, k);
        }
      }
    }
  }
  for (std::size_t k = 0, n = seeds.size(); k < n; ++k)
  {
    const int node = seeds[k].second;
    Mesh->ForEachOutgoingHalfedge(seeds[k].first, [&](int he) {
      for (int w : Mesh->Face(he / 3))
      {
        if (marks.Mark(w))
        {
          seeds.emplace_back(w, node);
        }
      }
    });
  }
  return seeds;
}

bool CurveGrid::ClassPoint(const SurfacePoint& x, Vec2& p, int* hint) const
{
  if (!Mesh || CellStart.empty())
  {
    return false;
  }
  const Vec3 X = Mesh->Position(x);
  if (hint && *hint >= 0 && *hint < static_cast<int>(Nodes.size()))
  {
    // From the previous point's node: the descent finds the nearest node when it is near.
    double distance = 0.0;
    if (Locate(X, *hint, p, &distance, hint) && distance <= 0.5 * Step)
    {
      return true;
    }
  }
  const int ci = static_cast<int>(std::floor((X.x - Origin.x) / CellSize));
  const int cj = static_cast<int>(std::floor((X.y - Origin.y) / CellSize));
  const int ck = static_cast<int>(std::floor((X.z - Origin.z) / CellSize));
  if (ci < -1 || cj < -1 || ck < -1 || ci > Dims[0] || cj > Dims[1] || ck > Dims[2])
  {
    return false; // farther than a cell from every node
  }
  int start = -1;
  double best = std::numeric_limits<double>::infinity();
  for (int k = std::max(0, ck - 1); k <= std::min(Dims[2] - 1, ck + 1); ++k)
    for (int j = std::max(0, cj - 1); j <= std::min(Dims[1] - 1, cj + 1); ++j)
      for (int i = std::max(0, ci - 1); i <= std::min(Dims[0] - 1, ci + 1); ++i)
      {
        const std::size_t c = (static_cast<std::size_t>(k) * Dims[1] + j) * Dims[0] + i;
        for (int q = CellStart[c]; q < CellStart[c + 1]; ++q)
        {
          const Vec3 d = Nodes[CellNodes[q]].Position - X;
          const double d2 = Dot(d, d);
          if (d2 < best)
          {
            best = d2;
            start = CellNodes[q];
          }
        }
      }
  double distance = 0.0;
  const bool found = start >= 0 && Locate(X, start, p, &distance, hint) && distance <= 0.5 * Step;
  if (hint && !found)
  {
    *hint = -1;
  }
  return found;
}

} // namespace gs
