#include "ShapeDistributor.h"

#include "DirectionField.h"
#include "GeodesicPolarCoordinates.h"
#include "GeodesicShooting.h"
#include "Hash.h"
#include "OverlapCheck.h"
#include "SaddleVertexGraph.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double TwoPi = 2.0 * Pi;

std::uint64_t Mix(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// Counter-based generator: the stream of (seed, kind, round, index) is independent of threads.
struct Random
{
  std::uint64_t State;
  Random(std::uint64_t seed, std::uint64_t kind, std::uint64_t round, std::uint64_t index)
    : State(Mix(Mix(Mix(seed ^ Mix(kind)) ^ round) ^ index))
  {
  }
  double Uniform()
  {
    State = Mix(State);
    return static_cast<double>(State >> 11) * (1.0 / 9007199254740992.0);
  }
};

int ThreadCount(int requested)
{
#ifdef _OPENMP
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

int ThreadId()
{
#ifdef _OPENMP
  return omp_get_thread_num();
#else
  return 0;
#endif
}

struct ChartEntry
{
  int V;
  float X, Y;
};

// Log-map coordinates of the vertices about one part centre (x axis: the part's axis), sorted by
// vertex.
struct Chart
{
  std::vector<ChartEntry> Entries;
  // Sum of |angle defect| of the chart's vertices over the chart's area: the density of
  // absolute discrete Gaussian curvature around the centre.
  float Roughness = 0.0f;
  const ChartEntry* Find(int v) const
  {
    auto it = std::lower_bound(Entries.begin(), Entries.end(), v,
      [](const ChartEntry& e, int value) { return e.V < value; });
    return it != Entries.end() && it->V == v ? &*it : nullptr;
  }
};

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
  // Outside: the distance to the nearest edge.
  auto segment = [&x](const Vec3& p, const Vec3& q) {
    const Vec3 pq = q - p;
    const double l2 = Dot(pq, pq);
    const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, Dot(x - p, pq) / l2)) : 0.0;
    return Norm(p + pq * t - x);
  };
  return std::min(segment(a, b), std::min(segment(b, c), segment(c, a)));
}

void SortUnique(std::vector<int>& v)
{
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}
} // namespace

struct ShapeDistributor::Impl
{
  const TriangleMesh& M;
  const SaddleVertexGraph* G;

  SafeDistanceTables T;
  ShapeDistributionOptions O;
  bool CircleMode = false;
  std::vector<Vec3> FaceDirection; // unit, in the face plane; zero: none
  std::vector<double> Density;     // per vertex (empty: 1)
  std::vector<double> FaceCdf;     // cumulative face weights (live faces only)
  std::vector<double> FaceWeight;  // area / f^2 (0: no density)
  std::vector<double> AllCdf;      // cumulative face weights of all faces (probes)
  std::vector<char> Dead;          // faces where no candidate can fit any more
  int DeadSinceCdf = 0;            // faces killed since FaceCdf was built
  std::vector<double> KillRadius;  // per (part, class) (normalized): see KillFaces
  std::vector<double> KillReach;   // per class (normalized): see KillFaces
  std::vector<char> DeadFor;       // per (class, face): no candidate of that class fits there
  int NumberOfClasses = 0;
  double MaxFaceDensity = 1.0;
  double MaxEdge = 0.0;
  double ChartMargin = 0.0; // beyond the largest safe distance: two mean edge lengths
  std::vector<double> Defect; // per vertex: |2 pi - angle sum| (interior vertices)
  double RMax = 0.0; // largest part radius (class radius in Circumcircle mode), normalized
  std::vector<double> ClassCdf;
  std::vector<double> ClassExtentMin, ClassExtentMax; // outline extent along the major axis
  // Per class: its silhouette for point queries, and the clearance of its centre (the distance
  // from the class origin, the point a candidate is centred at, to the outline; -1 when the
  // origin is outside the silhouette). See CentreCovered.
  std::vector<ClassRegion> Regions;
  std::vector<double> Clearance;
  double MaxClearance = 0.0; // the regions' reach for Within
  // Greedy: per single-part class, the densest lattice of copies turned alike that the tables
  // admit (six neighbour vectors in the shape's frame, normalized units); empty: none.
  std::vector<std::vector<Vec2>> ClassLattice;
  void ComputeLattices();
  // The densest lattice for part p (see ComputeLattices); empty when the search finds none.
  std::vector<Vec2> PartLattice(int p) const;
  // Lattices found in earlier runs, by a hash of what they depend on (the part's radius and
  // its own table): a re-run with the same tables (a new seed, say) skips the search (35-160
  // ms for 4 classes at 64-128 angle bins).
  std::map<std::uint64_t, std::vector<Vec2>> LatticeCache;

  std::unique_ptr<DirectionFieldSolver> Field;
  std::vector<double> FieldAngles;
  std::vector<std::unique_ptr<GeodesicPolarCoordinates>> Engines;

  struct Record
  {
    PlacedShape S;
    std::vector<Chart> Charts; // one per part (empty before the chart step)
    bool Valid = false;
    bool Rejected = false;
    // Prepared in parallel for the commit (see PrepareCommit).
    bool Prepared = false;
    std::vector<int> Cover, Centres;
    std::vector<std::pair<int, int>> Kills; // (class, face)
    // The outline as drawn (Outline, OutlineSpacing), once the tables accept the shape.
    std::vector<OutlinePiece> Drawn;
    bool HasDrawn = false;
    // Long shapes: the inverse of the drawing map (for the drawn check against long neighbours).
    std::shared_ptr<const CurveGrid> Frame;
  };
  // The shape model (one map for outlines, decals and the drawn check; see the public Map,
  // Outline, ClassPoint).
  MappedPoint MapShape(const PlacedShape& s, const Vec2& p) const;
  std::vector<OutlinePiece> OutlineOf(const PlacedShape& s, double spacing) const;
  bool ClassPointOf(const Record& r, const SurfacePoint& x, Vec2& p) const;
  // A surface point in a chart (divided by `unit`): a vertex's entry, or a face point's corners
  // interpolated; false when a corner is not in the chart.
  bool ChartPoint(const Chart& chart, const SurfacePoint& x, double unit, Vec2& p) const;
  // Between outline points: half a mean edge (what the filter draws).
  double OutlineSpacing() const { return 0.5 * M.MeanEdgeLength(); }

  std::vector<Record> Accepted;
  std::vector<PlacedShape> Placed;
  std::vector<std::vector<int>> CoverIndex;  // vertex -> accepted shapes whose chart holds it
  std::vector<std::vector<int>> CentreIndex; // vertex -> accepted shapes with a part centre in a face of it

  Impl(const TriangleMesh& mesh, const SaddleVertexGraph* graph)
    : M(mesh)
    , G(graph)
  {
  }

  double PartRadius(int part) const
  {
    return CircleMode ? T.Classes[part].Radius : T.Parts[part].Radius;
  }

  double SafeDistance(int a, int b, double alphaA, double alphaB) const
  {
    if (CircleMode)
    {
      return T.Classes[a].Radius + T.Classes[b].Radius;
    }
    return T.Lookup(a, b, alphaA, alphaB);
  }

  double ChartRadius(const PlacedShape& s, const PlacedPart& p) const
  {
    return (PartRadius(p.Part) + RMax) * O.ShapeSize * s.Scale * (1.0 + O.SafetyMargin) +
      ChartMargin;
  }

  double DensityAt(const SurfacePoint& p) const
  {
    if (Density.empty())
    {
      return 1.0;
    }
    const auto& f = M.Face(p.Face);
    return p.Bary[0] * Density[f[0]] + p.Bary[1] * Density[f[1]] + p.Bary[2] * Density[f[2]];
  }

  // Point at arc length u along curve pieces (clamped), with the unit tangent there.
  static bool PointOnCurve(const TriangleMesh& m, const std::vector<CurvePiece>& curve, double u,
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

  // From curve point (face, x) with tangent t: `across` to the left (negative: right) along the
  // perpendicular geodesic. Returns the end and the transported tangent.
  bool Across(int face, const Vec3& x, const Vec3& t, double across, SurfacePoint& end,
    Vec3& endTangent, bool* boundary = nullptr) const
  {
    end = SurfacePoint::InFace(face, 0, 0, 0);
    end.Bary = M.ClampedBarycentric(face, x);
    endTangent = t;
    if (std::abs(across) <= 0.0)
    {
      return true;
    }
    const double side = across > 0.0 ? 1.0 : -1.0;
    const double angle = TangentAngle(M, end, t);
    if (!std::isfinite(angle))
    {
      return false;
    }
    const GeodesicShot shot = ShootGeodesic(M, end, angle + side * 0.5 * Pi, std::abs(across));
    if (boundary)
    {
      *boundary = shot.ReachedBoundary;
    }
    end = shot.End;
    Vec3 dir = Unit(RotateTangent(t, M.FaceNormal(face), side * 0.5 * Pi));
    for (auto it = shot.Pieces.rbegin(); it != shot.Pieces.rend(); ++it)
    {
      if (Norm(it->B - it->A) > 0.0)
      {
        dir = Unit(it->B - it->A);
        break;
      }
    }
    const Vec3 n = M.FaceNormal(end.Face);
    endTangent = Unit(RotateTangent(dir, n, -side * 0.5 * Pi));
    return true;
  }

  // The map of a long shape (the one its outline and its parts use): class point p -> the point
  // at arc length CurveCentre + <p, m> scale along its curve, then <p, perp> scale across it
  // along the perpendicular geodesic (m: the class's major axis), sampled on a grid of (along,
  // across) nodes finer than an edge (one geodesic shot per column and side), covering the
  // silhouette's extent and two mean edges more. CurveGrid::Locate inverts it.
  CurveGrid BuildCurveGrid(const PlacedShape& s, const SafeDistanceClass& c) const
  {
    CurveGrid grid;
    grid.Mesh = &M;
    const double scale = O.ShapeSize * s.Scale;
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
    const double margin = std::min(2.0 * M.MeanEdgeLength(), c.Radius * scale);
    const double h0 = std::min(M.MeanEdgeLength(), c.Radius * scale / 12.0);
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
      int face = -1;
      Vec3 x, tangent;
      SurfacePoint foot;
      if (u >= 0.0 && u <= length)
      {
        if (!PointOnCurve(M, s.Curve, u, face, x, tangent))
        {
          continue;
        }
        foot = SurfacePoint::InFace(face, 0, 0, 0);
        foot.Bary = M.ClampedBarycentric(face, x);
      }
      else
      {
        // Beyond an end: the geodesic continuing the curve's end.
        const bool after = u > length;
        if (!PointOnCurve(M, s.Curve, after ? length : 0.0, face, x, tangent))
        {
          continue;
        }
        SurfacePoint end = SurfacePoint::InFace(face, 0, 0, 0);
        end.Bary = M.ClampedBarycentric(face, x);
        const double angle = TangentAngle(M, end, after ? tangent : tangent * -1.0);
        if (!std::isfinite(angle))
        {
          continue;
        }
        const double beyond = after ? u - length : -u;
        const GeodesicShot shot = ShootGeodesic(M, end, angle, beyond);
        if (shot.ReachedBoundary || shot.Pieces.empty())
        {
          continue;
        }
        foot = shot.End;
        Vec3 dir = after ? tangent : tangent * -1.0;
        for (auto it = shot.Pieces.rbegin(); it != shot.Pieces.rend(); ++it)
        {
          if (Norm(it->B - it->A) > 0.0)
          {
            dir = Unit(it->B - it->A);
            break;
          }
        }
        tangent = after ? dir : dir * -1.0;
        face = foot.Face;
      }
      const double a = (u - s.CurveCentre) / scale;
      const int centreRow = half;
      CurveGrid::Node& mid = nodes[static_cast<std::size_t>(i) * rows + centreRow];
      mid.Valid = true;
      mid.At = foot;
      mid.X = M.Interpolate(foot.Face, foot.Bary);
      mid.P = m * a;
      const double angle = TangentAngle(M, foot, tangent);
      if (!std::isfinite(angle))
      {
        continue;
      }
      for (const double side : { 1.0, -1.0 })
      {
        const GeodesicShot shot = ShootGeodesic(M, foot, angle + side * 0.5 * Pi, across + margin);
        for (int j = 1; j <= half; ++j)
        {
          CurveGrid::Node& node = nodes[static_cast<std::size_t>(i) * rows + centreRow + (side > 0.0 ? j : -j)];
          if (!walk(shot, db * j * (1.0 - 1e-12), node.At, M))
          {
            break;
          }
          node.Valid = true;
          node.X = M.Interpolate(node.At.Face, node.At.Bary);
          node.P = m * a + perp * (side * db * j / scale);
        }
      }
    }
    return grid;
  }

  // The class points (normalized) of the vertices near a long shape: the vertices of the grid
  // nodes' faces and their neighbours, each located from a node of that face. Appends
  // (vertex, class point) pairs.
  void CurveShapeVertices(const CurveGrid& grid, std::vector<std::pair<int, Vec2>>& local) const
  {
    const std::vector<CurveGrid::Node>& nodes = grid.Nodes;
    // The vertices of the nodes' faces and their neighbours, each with a node to start from;
    // the nearest node by descent over the grid (the map is smooth at the grid's scale).
    // (Each vertex once: marks per thread, stamped per call.)
    thread_local std::vector<unsigned> mark;
    thread_local unsigned stamp = 0;
    if (mark.size() != static_cast<std::size_t>(M.NumberOfVertices()) || stamp == ~0u)
    {
      mark.assign(M.NumberOfVertices(), 0u);
      stamp = 0;
    }
    ++stamp;
    std::vector<std::pair<int, int>> seeds; // (vertex, node)
    for (int k = 0; k < static_cast<int>(nodes.size()); ++k)
    {
      if (nodes[k].Valid)
      {
        for (int v : M.Face(nodes[k].At.Face))
        {
          if (mark[v] != stamp)
          {
            mark[v] = stamp;
            seeds.emplace_back(v, k);
          }
        }
      }
    }
    for (std::size_t k = 0, n = seeds.size(); k < n; ++k)
    {
      for (int he : M.OutgoingHalfedges(seeds[k].first))
      {
        for (int w : M.Face(he / 3))
        {
          if (mark[w] != stamp)
          {
            mark[w] = stamp;
            seeds.emplace_back(w, seeds[k].second);
          }
        }
      }
    }
    local.reserve(local.size() + seeds.size());
    for (const auto& seed : seeds)
    {
      const int v = seed.first;
      Vec2 point;
      if (grid.Locate(M.Position(v), seed.second, point, nullptr))
      {
        local.emplace_back(v, point);
      }
    }
  }


  // Builds a candidate's geometry at `centre` (a face point) for class `cls`: the direction,
  // the curve of a long class and the parts. False when it does not fit (curve too short).
  // `prefer` (optional): of the field's N directions in the face, take the one closest to it
  // (greedy fronts keep neighbours turned alike in cross fields); otherwise the face's own.
  bool MakeShape(const SurfacePoint& centre, int cls, Random& rng, PlacedShape& s,
    const Vec3* prefer = nullptr) const
  {
    s = PlacedShape();
    s.ClassId = cls;
    s.Centre = centre;
    s.Scale = DensityAt(centre);
    if (!(s.Scale > 0.0) || !std::isfinite(s.Scale))
    {
      return false;
    }
    const int f = centre.Face;
    s.Position = M.Interpolate(f, centre.Bary);
    s.Normal = M.FaceNormal(f);
    Vec3 dir = FaceDirection[f];
    const double spin = rng.Uniform();
    if (!(Norm(dir) > 0.0))
    {
      const auto& v = M.Face(f);
      dir = RotateTangent(Unit(M.Position(v[1]) - M.Position(v[0])), s.Normal, TwoPi * spin);
    }
    else if (prefer && O.Symmetry > 1)
    {
      Vec3 best = dir;
      double bestDot = -2.0;
      for (int k = 0; k < O.Symmetry; ++k)
      {
        const Vec3 candidate = RotateTangent(dir, s.Normal, TwoPi * k / O.Symmetry);
        const double d = Dot(candidate, *prefer);
        if (d > bestDot)
        {
          bestDot = d;
          best = candidate;
        }
      }
      dir = Unit(best);
    }
    const SafeDistanceClass& c = T.Classes[cls];
    const double scale = O.ShapeSize * s.Scale;
    if (c.Parts.size() <= 1)
    {
      s.Direction = dir;
    }
    else
    {
      // The major axis follows the field: trace the streamline both ways.
      const double phiM = std::atan2(c.MajorAxis.y, c.MajorAxis.x);
      s.Direction = Unit(RotateTangent(dir, s.Normal, -phiM));
      const int n = O.Symmetry == 1 ? 2 : O.Symmetry;
      const double a0 = Field->AngleInFace(f, dir);
      const double forward = ClassExtentMax[cls] * scale, backward = -ClassExtentMin[cls] * scale;
      const Streamline ahead = Field->TraceStreamline(n, FieldAngles, centre, a0, forward);
      const Streamline behind = Field->TraceStreamline(n, FieldAngles, centre, a0 + Pi, backward);
      if (ahead.Length < forward * (1.0 - 1e-9) || behind.Length < backward * (1.0 - 1e-9))
      {
        return false;
      }
      for (auto it = behind.Pieces.rbegin(); it != behind.Pieces.rend(); ++it)
      {
        s.Curve.push_back(CurvePiece{ it->Face, it->B, it->A });
      }
      s.Curve.insert(s.Curve.end(), ahead.Pieces.begin(), ahead.Pieces.end());
      s.CurveCentre = behind.Length;
    }
    if (CircleMode || c.Parts.size() <= 1)
    {
      PlacedPart p;
      p.Part = CircleMode ? cls : c.Parts[0];
      p.Centre = centre;
      p.Position = s.Position;
      p.Axis = s.Direction;
      s.Parts.push_back(p);
      return true;
    }
    const double phiM = std::atan2(c.MajorAxis.y, c.MajorAxis.x);
    for (int part : c.Parts)
    {
      const Vec2& pc = T.Parts[part].Centre;
      const double along = Dot(pc, c.MajorAxis) * scale;
      const double across = Cross(c.MajorAxis, pc) * scale;
      int face = -1;
      Vec3 x, tangent;
      if (!PointOnCurve(M, s.Curve, s.CurveCentre + along, face, x, tangent))
      {
        return false;
      }
      PlacedPart p;
      p.Part = part;
      Vec3 endTangent;
      bool boundary = false;
      if (!Across(face, x, tangent, across, p.Centre, endTangent, &boundary) || boundary)
      {
        return false;
      }
      p.Position = M.Interpolate(p.Centre.Face, p.Centre.Bary);
      p.Axis = Unit(RotateTangent(endTangent, M.FaceNormal(p.Centre.Face), -phiM));
      s.Parts.push_back(p);
    }
    return true;
  }

  SurfacePoint RandomPoint(Random& rng, bool live = true) const
  {
    const std::vector<double>& cdf = live ? FaceCdf : AllCdf;
    const double u = rng.Uniform() * cdf.back();
    int f = static_cast<int>(std::upper_bound(cdf.begin(), cdf.end(), u) - cdf.begin());
    f = std::min(f, M.NumberOfFaces() - 1);
    while (f > 0 && cdf[f] == cdf[f - 1])
    {
      --f; // never a zero-weight face
    }
    double a = rng.Uniform(), b = rng.Uniform();
    if (a + b > 1.0)
    {
      a = 1.0 - a;
      b = 1.0 - b;
    }
    return SurfacePoint::InFace(f, 1.0 - a - b, a, b);
  }

  int RandomClass(Random& rng) const
  {
    const double u = rng.Uniform() * ClassCdf.back();
    int k = static_cast<int>(std::upper_bound(ClassCdf.begin(), ClassCdf.end(), u) - ClassCdf.begin());
    k = std::min(k, static_cast<int>(ClassCdf.size()) - 1);
    while (k > 0 && ClassCdf[k] == ClassCdf[k - 1])
    {
      --k;
    }
    return k;
  }

  void ComputeCharts(Record& r, GeodesicPolarCoordinates& engine) const
  {
    r.Charts.assign(r.S.Parts.size(), Chart());
    for (std::size_t k = 0; k < r.S.Parts.size(); ++k)
    {
      const PlacedPart& p = r.S.Parts[k];
      const double reference = TangentAngle(M, p.Centre, p.Axis);
      if (!std::isfinite(reference) ||
        !engine.Compute(p.Centre, ChartRadius(r.S, p), reference))
      {
        continue; // an empty chart: this part is evaluated from the other side only
      }
      Chart& c = r.Charts[k];
      c.Entries.reserve(engine.Inside().size());
      for (int v : engine.Inside())
      {
        const double rho = engine.Rho(v), theta = engine.Theta(v);
        c.Entries.push_back(ChartEntry{ v, static_cast<float>(rho * std::cos(theta)),
          static_cast<float>(rho * std::sin(theta)) });
      }
      std::sort(c.Entries.begin(), c.Entries.end(),
        [](const ChartEntry& a, const ChartEntry& b) { return a.V < b.V; });
      double defects = 0.0;
      for (const ChartEntry& e : c.Entries)
      {
        defects += Defect[e.V];
      }
      const double radius = ChartRadius(r.S, p);
      c.Roughness = static_cast<float>(defects / (Pi * radius * radius));
    }
  }

  // Does shape Y conflict with shape X, judged in X's charts?
  bool ConflictInCharts(const Record& X, const Record& Y) const
  {
    const double fmax = std::max(X.S.Scale, Y.S.Scale);
    const double unit = O.ShapeSize * fmax * (1.0 + O.SafetyMargin);
    for (std::size_t i = 0; i < X.S.Parts.size() && i < X.Charts.size(); ++i)
    {
      const Chart& chart = X.Charts[i];
      const int pa = X.S.Parts[i].Part;
      for (const PlacedPart& py : Y.S.Parts)
      {
        const int g = py.Centre.Face;
        const auto& corners = M.Face(g);
        const ChartEntry* e[3];
        bool all = true;
        for (int k = 0; k < 3 && all; ++k)
        {
          e[k] = chart.Find(corners[k]);
          all = e[k] != nullptr;
        }
        if (!all)
        {
          // A corner beyond the chart radius R: Y's centre is at least R minus the face's
          // longest edge away (a point of a triangle is within its longest edge of every corner). Farther than any safe distance: no conflict; otherwise (a face
          // with edges longer than the chart margin) judged conservatively.
          double longest = 0.0;
          for (int k = 0; k < 3; ++k)
          {
            longest = std::max(longest, Norm(M.Position(corners[(k + 1) % 3]) - M.Position(corners[k])));
          }
          if (ChartRadius(X.S, X.S.Parts[i]) - longest >= (PartRadius(pa) + PartRadius(py.Part)) * unit)
          {
            continue;
          }
          return true;
        }
        Vec2 P[3];
        for (int k = 0; k < 3; ++k)
        {
          P[k] = Vec2{ e[k]->X, e[k]->Y };
        }
        const Vec2 q = P[0] * py.Centre.Bary[0] + P[1] * py.Centre.Bary[1] + P[2] * py.Centre.Bary[2];
        const double d = Norm(q);
        if (d >= (PartRadius(pa) + PartRadius(py.Part)) * unit)
        {
          continue;
        }
        if (CircleMode)
        {
          return true;
        }
        // Angles: A's axis is the chart's x axis; the arrival direction at Y's centre is the
        // chart's radial direction pulled back into face g.
        const double alphaA = d > 0.0 ? -std::atan2(q.y, q.x) : 0.0;
        const Vec3 x0 = M.Position(corners[0]);
        const Vec3 e1 = M.Position(corners[1]) - x0, e2 = M.Position(corners[2]) - x0;
        const Vec2 E1 = P[1] - P[0], E2 = P[2] - P[0];
        const double det = Cross(E1, E2);
        Vec3 t;
        if (d > 0.0 && std::abs(det) > 1e-12 * (Dot(E1, E1) + Dot(E2, E2)))
        {
          const Vec2 u = q * (1.0 / d);
          const double a = Cross(u, E2) / det, b = Cross(E1, u) / det;
          t = e1 * a + e2 * b;
        }
        else
        {
          t = py.Position - X.S.Parts[i].Position;
        }
        // Intrinsic distortion of the chart at Y's centre: the tables need rigid planar copies.
        const double stretch = std::max({ std::abs(Norm(E1) / Norm(e1) - 1.0),
          std::abs(Norm(E2) / Norm(e2) - 1.0), std::abs(Norm(E2 - E1) / Norm(e2 - e1) - 1.0) });
        if (!(stretch <= O.DistortionLimit))
        {
          return true; // d < r_A + r_B: the circumcircles overlap
        }
        const Vec3 n = M.FaceNormal(g);
        t = t - n * Dot(n, t);
        double alphaB = 0.0;
        if (Norm(t) > 0.0)
        {
          alphaB = std::atan2(Dot(n, Cross(t, py.Axis)), Dot(t, py.Axis));
        }
        // Holonomy: Y's outline, drawn by Y's own exponential map, is turned in X's chart by at
        // most the absolute curvature enclosed by X, Y and the outline point (area at most
        // (d + r_Y) r_Y / 2): a displacement of up to that angle times r_Y.
        const double rY = PartRadius(py.Part) * unit;
        const double turn = O.HolonomyMargin * chart.Roughness * 0.5 * (d + rY) * rY;
        if (d < SafeDistance(pa, py.Part, alphaA, alphaB) * unit + turn * rY)
        {
          return true;
        }
      }
    }
    return false;
  }

  // Chart vertices of a record (all parts), sorted, unique.
  static std::vector<int> ChartVertices(const Record& r)
  {
    std::vector<int> vs;
    for (const Chart& c : r.Charts)
    {
      for (const ChartEntry& e : c.Entries)
      {
        vs.push_back(e.V);
      }
    }
    SortUnique(vs);
    return vs;
  }

  std::vector<int> CentreCorners(const Record& r) const
  {
    std::vector<int> vs;
    for (const PlacedPart& p : r.S.Parts)
    {
      for (int v : M.Face(p.Centre.Face))
      {
        vs.push_back(v);
      }
    }
    SortUnique(vs);
    return vs;
  }

  // A candidate of class `cls` centred at `centre` (density factor `scale`) certainly overlaps
  // an accepted shape: its centre, inside its own silhouette with clearance rho (see
  // Clearance), lies within 0.9 rho of an accepted part's silhouette, read in that part's chart
  // within the part's circle (a 2% margin for the chart). The full check would reject it too
  // (the tables keep silhouettes apart); this one needs no curve, so long candidates skip
  // tracing their streamlines where the surface is taken.
  bool CentreCovered(const SurfacePoint& centre, int cls, double scale, std::vector<int>& scratch) const
  {
    if (CircleMode || Clearance[cls] < 0.0)
    {
      return false;
    }
    const auto& corners = M.Face(centre.Face);
    scratch.clear();
    for (int v : corners)
    {
      scratch.insert(scratch.end(), CoverIndex[v].begin(), CoverIndex[v].end());
    }
    SortUnique(scratch);
    const Vec3 position = M.Interpolate(centre.Face, centre.Bary);
    for (int x : scratch)
    {
      const Record& X = Accepted[x];
      const double unit = O.ShapeSize * X.S.Scale;
      const ClassRegion& region = Regions[X.S.ClassId];
      for (std::size_t i = 0; i < X.S.Parts.size() && i < X.Charts.size(); ++i)
      {
        const int pa = X.S.Parts[i].Part;
        if (Norm(X.S.Parts[i].Position - position) > PartRadius(pa) * unit)
        {
          continue; // beyond the part's circle (the geodesic distance is never shorter)
        }
        const double margin = 0.02 * PartRadius(pa);
        const double dilation = 0.9 * Clearance[cls] * scale / X.S.Scale - margin;
        Vec2 q;
        if (!ChartPoint(X.Charts[i], centre, unit, q))
        {
          continue;
        }
        if (Norm(q) > PartRadius(pa))
        {
          continue;
        }
        const Vec2 p = T.Parts[pa].Centre + q;
        if (dilation >= 0.0 ? region.Within(p, std::min(dilation, MaxClearance)) : region.DeeplyInside(p, -dilation))
        {
          return true;
        }
      }
    }
    return false;
  }

  // The drawn check, after the tables accepted the candidate (its charts computed): its outline
  // as drawn (kept in the record) against every accepted neighbour's, as VerifyOverlaps judges
  // them: a conflict when one reaches into the other's silhouette deeper than a quarter of
  // VerifyOverlaps' tolerance (0.125% of the smaller circumradius), read in the chart of the
  // short one of the two (two long shapes: the tables alone). The tables assume rigid planar
  // copies; this catches where the drawn shapes are not (a long shape's part bending with its
  // curve, a chart that is no isometry across the neighbour's circle).
  bool DrawnConflict(Record& c, std::vector<int>& scratch) const
  {
    if (CircleMode || !O.DrawnCheck)
    {
      return false;
    }
    if (!c.HasDrawn)
    {
      c.Drawn = OutlineOf(c.S, OutlineSpacing());
      c.HasDrawn = true;
    }
    if (!c.S.Curve.empty() && !c.Frame)
    {
      std::shared_ptr<CurveGrid> frame = std::make_shared<CurveGrid>(BuildCurveGrid(c.S, T.Classes[c.S.ClassId]));
      frame->Index();
      c.Frame = frame;
    }
    scratch.clear();
    for (int v : CentreCorners(c))
    {
      scratch.insert(scratch.end(), CoverIndex[v].begin(), CoverIndex[v].end());
    }
    for (const Chart& chart : c.Charts)
    {
      for (const ChartEntry& e : chart.Entries)
      {
        scratch.insert(scratch.end(), CentreIndex[e.V].begin(), CentreIndex[e.V].end());
      }
    }
    SortUnique(scratch);
    const bool shortC = c.S.Curve.empty() && !c.Charts.empty() && !c.Charts[0].Entries.empty();
    const double unitC = O.ShapeSize * c.S.Scale;
    const double radiusC = T.Classes[c.S.ClassId].Radius * unitC;
    for (int x : scratch)
    {
      const Record& X = Accepted[x];
      const double unitX = O.ShapeSize * X.S.Scale;
      const double radiusX = T.Classes[X.S.ClassId].Radius * unitX;
      if (Norm(X.S.Position - c.S.Position) >= radiusX + radiusC)
      {
        continue; // the geodesic distance is never shorter
      }
      const bool shortX = X.S.Curve.empty() && !X.Charts.empty() && !X.Charts[0].Entries.empty();
      const double depth = 0.00125 * std::min(radiusX, radiusC);
      // (Outline points farther in space than sqrt(2) circumradii from a shape's centre are
      // outside it: its outline is drawn along paths of length |along| + |across| at most.)
      auto near = [this](const Record& R, double radius) {
        const Vec3 centre = R.S.Position;
        const double reach = 1.4143 * radius + M.MeanEdgeLength();
        return [this, centre, reach](const SurfacePoint& q) {
          return Norm((q.IsVertex() ? M.Position(q.Vertex) : M.Interpolate(q.Face, q.Bary)) - centre) <= reach;
        };
      };
      const auto nearX = near(X, radiusX), nearC = near(c, radiusC);
      if (shortX &&
        OutlineEnters(Regions[X.S.ClassId], c.Drawn,
          [this, &X](const SurfacePoint& q, Vec2& p) { return ClassPointOf(X, q, p); }, depth / unitX))
      {
        return true;
      }
      int hint = -1;
      if (!shortX && X.Frame && !shortC &&
        OutlineEnters(Regions[X.S.ClassId], c.Drawn,
          [&X, &nearX, &hint](const SurfacePoint& q, Vec2& p) { return nearX(q) && X.Frame->ClassPoint(q, p, &hint); },
          depth / unitX))
      {
        return true;
      }
      if (shortC && X.HasDrawn &&
        OutlineEnters(Regions[c.S.ClassId], X.Drawn,
          [this, &c](const SurfacePoint& q, Vec2& p) { return ClassPointOf(c, q, p); }, depth / unitC))
      {
        return true;
      }
      hint = -1;
      if (!shortC && c.Frame && !shortX && X.HasDrawn &&
        OutlineEnters(Regions[c.S.ClassId], X.Drawn,
          [&c, &nearC, &hint](const SurfacePoint& q, Vec2& p) { return nearC(q) && c.Frame->ClassPoint(q, p, &hint); },
          depth / unitC))
      {
        return true;
      }
    }
    return false;
  }

  // Checks against accepted shapes whose charts judge the pair (f_X >= f_C: the older decides
  // ties). Needs no chart of the candidate.
  bool CheapConflict(const Record& c, std::vector<int>& scratch) const
  {
    scratch.clear();
    for (int v : CentreCorners(c))
    {
      scratch.insert(scratch.end(), CoverIndex[v].begin(), CoverIndex[v].end());
    }
    SortUnique(scratch);
    for (int x : scratch)
    {
      const Record& X = Accepted[x];
      if (X.S.Scale >= c.S.Scale && ConflictInCharts(X, c))
      {
        return true;
      }
    }
    return false;
  }

  // Checks against accepted shapes with a smaller density factor, in the candidate's charts.
  // KeepInside: a boundary vertex within a part's circle (plus half the longest edge).
  bool TouchesBoundary(const Record& c) const
  {
    for (std::size_t k = 0; k < c.Charts.size() && k < c.S.Parts.size(); ++k)
    {
      const double reach = PartRadius(c.S.Parts[k].Part) * O.ShapeSize * c.S.Scale + 0.5 * MaxEdge;
      const float r2 = static_cast<float>(reach * reach);
      for (const ChartEntry& e : c.Charts[k].Entries)
      {
        if (e.X * e.X + e.Y * e.Y < r2 && M.IsBoundaryVertex(e.V))
        {
          return true;
        }
      }
    }
    return false;
  }

  bool FullConflict(const Record& c, std::vector<int>& scratch) const
  {
    if (O.KeepInside && TouchesBoundary(c))
    {
      return true;
    }
    scratch.clear();
    for (int v : ChartVertices(c))
    {
      scratch.insert(scratch.end(), CentreIndex[v].begin(), CentreIndex[v].end());
    }
    SortUnique(scratch);
    for (int y : scratch)
    {
      const Record& Y = Accepted[y];
      if (Y.S.Scale < c.S.Scale && ConflictInCharts(c, Y))
      {
        return true;
      }
    }
    return false;
  }

  // Rebuilds the sampling distribution over the faces still alive.
  void BuildCdf()
  {
    const int nf = M.NumberOfFaces();
    FaceCdf.assign(nf, 0.0);
    double total = 0.0;
    for (int f = 0; f < nf; ++f)
    {
      total += Dead[f] ? 0.0 : FaceWeight[f];
      FaceCdf[f] = total;
    }
    DeadSinceCdf = 0;
  }

  bool AnyLiveFace() const { return FaceCdf.back() > 0.0; }

  // Faces where no candidate can fit any more: every candidate centred in them conflicts with
  // part k of the new shape, because its distance from that part's centre is below the smallest
  // safe distance against any part of any class, less the class's reach (its part centres'
  // offsets from its sample). Sampling skips them: the run is the same dart throwing, without
  // the candidates that would certainly fail.
  // The (class, face) pairs the shape kills (see above), whatever is dead already. `mark` is a
  // per-vertex scratch array of zeros (left as found).
  void CollectKills(const Record& r, std::vector<char>& mark, std::vector<int>& marked,
    std::vector<std::pair<int, int>>& kills) const
  {
    kills.clear();
    const int nc = NumberOfClasses;
    for (std::size_t k = 0; k < r.Charts.size() && k < r.S.Parts.size(); ++k)
    {
      const Chart& chart = r.Charts[k];
      for (int c = 0; c < nc; ++c)
      {
        const double radius = KillRadius[static_cast<std::size_t>(r.S.Parts[k].Part) * nc + c] *
            O.ShapeSize * r.S.Scale - KillReach[c] * O.ShapeSize * MaxFaceDensity;
        if (!(radius > 0.0))
        {
          continue;
        }
        const float r2 = static_cast<float>(radius * radius);
        marked.clear();
        for (const ChartEntry& e : chart.Entries)
        {
          if (e.X * e.X + e.Y * e.Y < r2)
          {
            mark[e.V] = 1;
            marked.push_back(e.V);
          }
        }
        for (int v : marked)
        {
          const int start = M.VertexHalfedge(v);
          int h = start;
          do
          {
            const int f = h / 3;
            const auto& t = M.Face(f);
            // Each face once: from its smallest marked corner.
            if (mark[t[0]] && mark[t[1]] && mark[t[2]] && v == std::min({ t[0], t[1], t[2] }))
            {
              kills.emplace_back(c, f);
            }
            h = M.RotateCCW(h);
          } while (h >= 0 && h != start);
        }
        for (int v : marked)
        {
          mark[v] = 0;
        }
      }
    }
  }

  void KillFaces(const Record& r)
  {
    std::vector<std::pair<int, int>> own;
    if (!r.Prepared)
    {
      CollectKills(r, Marks[0], Marked, own); // (serial: the first thread's scratch)
    }
    const int nc = NumberOfClasses;
    for (const auto& cf : r.Prepared ? r.Kills : own)
    {
      const int c = cf.first, f = cf.second;
      char& dead = DeadFor[static_cast<std::size_t>(c) * M.NumberOfFaces() + f];
      if (dead)
      {
        continue;
      }
      dead = 1;
      Killed.emplace_back(c, f);
      bool all = true;
      for (int o = 0; o < nc && all; ++o)
      {
        all = !(ClassCdf[o] > (o > 0 ? ClassCdf[o - 1] : 0.0)) ||
          DeadFor[static_cast<std::size_t>(o) * M.NumberOfFaces() + f];
      }
      if (all && !Dead[f])
      {
        Dead[f] = 1;
        Killed.emplace_back(-1, f);
        ++DeadSinceCdf;
      }
    }
  }

  // The commit's own work that needs no shared state, done in parallel before it.
  void PrepareCommit(Record& r, std::vector<char>& mark, std::vector<int>& marked) const
  {
    r.Cover = ChartVertices(r);
    r.Centres = CentreCorners(r);
    CollectKills(r, mark, marked, r.Kills);
    r.Prepared = true;
  }
  bool DeadForClass(int c, int f) const
  {
    return DeadFor[static_cast<std::size_t>(c) * M.NumberOfFaces() + f] != 0;
  }
  std::vector<std::vector<char>> Marks; // per thread, per vertex, all 0 between uses
  std::vector<int> Marked;

  // Takes back the last committed shape (index entries, killed faces) and returns it.
  Record Uncommit()
  {
    const int id = static_cast<int>(Accepted.size()) - 1;
    Record r = std::move(Accepted.back());
    Accepted.pop_back();
    Placed.pop_back();
    for (int v : ChartVertices(r))
    {
      if (!CoverIndex[v].empty() && CoverIndex[v].back() == id)
      {
        CoverIndex[v].pop_back();
      }
    }
    for (int v : CentreCorners(r))
    {
      if (!CentreIndex[v].empty() && CentreIndex[v].back() == id)
      {
        CentreIndex[v].pop_back();
      }
    }
    for (std::size_t k = KilledBy[id]; k < Killed.size(); ++k)
    {
      if (Killed[k].first < 0)
      {
        Dead[Killed[k].second] = 0;
      }
      else
      {
        DeadFor[static_cast<std::size_t>(Killed[k].first) * M.NumberOfFaces() + Killed[k].second] = 0;
      }
    }
    Killed.resize(KilledBy[id]);
    KilledBy.pop_back();
    DeadSinceCdf += 1;
    return r;
  }
  std::vector<std::pair<int, int>> Killed; // (class or -1 for all, face) killed, in order
  std::vector<std::size_t> KilledBy; // per accepted shape: its first entry in Killed

  void Commit(Record&& r)
  {
    KilledBy.push_back(Killed.size());
    KillFaces(r);
    const int id = static_cast<int>(Accepted.size());
    for (int v : r.Prepared ? r.Cover : ChartVertices(r))
    {
      CoverIndex[v].push_back(id);
    }
    for (int v : r.Prepared ? r.Centres : CentreCorners(r))
    {
      CentreIndex[v].push_back(id);
    }
    r.Cover.clear();
    r.Cover.shrink_to_fit();
    r.Centres.clear();
    r.Kills.clear();
    r.Kills.shrink_to_fit();
    r.Prepared = false;
    Placed.push_back(r.S);
    Accepted.push_back(std::move(r));
  }

  GeodesicPolarCoordinates& Engine()
  {
    return *Engines[ThreadId()];
  }
  GeodesicPolarCoordinates& Engine0() { return *Engines[0]; } // outside parallel regions

  void EnsureEngines(int threads)
  {
    const int nv = M.NumberOfVertices();
    if (static_cast<int>(Marks.size()) < threads)
    {
      Marks.resize(threads);
    }
    for (auto& m : Marks)
    {
      if (static_cast<int>(m.size()) != nv)
      {
        m.assign(nv, 0);
      }
    }
    const int have = static_cast<int>(Engines.size());
    if (have >= threads)
    {
      return;
    }
    Engines.resize(threads);
#pragma omp parallel for schedule(static, 1) num_threads(threads)
    for (int t = have; t < threads; ++t)
    {
      Engines[t].reset(new GeodesicPolarCoordinates(M, G));
    }
  }

  std::string Prepare(const SafeDistanceTables& tables, const std::vector<Vec3>& faceDirections,
    const std::vector<double>& vertexDensity, const ShapeDistributionOptions& options);
  void Generate(std::vector<Record>& batch, int round) const;
  // Greedy: candidate centres around accepted shape `parentId`, touching it and one of its
  // neighbours (or, alone, in GreedyDirections directions), the new shape assumed turned like
  // the parent. Key: distance from the first shape (fronts fill outwards).
  struct Proposal
  {
    SurfacePoint Centre;
    int Class = 0;
    double Key = 0.0;
    Vec3 Prefer; // the parent's field direction
  };
  std::vector<Proposal> Propose(int parentId, int round, int slot) const;
};

std::string ShapeDistributor::Impl::Prepare(const SafeDistanceTables& tables,
  const std::vector<Vec3>& faceDirections, const std::vector<double>& vertexDensity,
  const ShapeDistributionOptions& options)
{
  T = tables;
  O = options;
  CircleMode = O.Mode == DistributionMode::CircumcirclePoissonDisk;
  const int nf = M.NumberOfFaces(), nv = M.NumberOfVertices();
  if (nf == 0)
  {
    return "the mesh has no faces";
  }
  if (T.Classes.empty() || T.Parts.empty())
  {
    return "the tables hold no shape class";
  }
  const std::size_t ka = static_cast<std::size_t>(std::max(T.AngleBins, 0));
  if (T.AngleBins < 1 || T.Values.size() != T.Parts.size() * T.Parts.size() * ka * ka)
  {
    return "the tables are inconsistent (" + std::to_string(T.Values.size()) +
      " values for " + std::to_string(T.Parts.size()) + " parts and " +
      std::to_string(T.AngleBins) + " angle bins)";
  }
  for (const SafeDistanceClass& c : T.Classes)
  {
    if (c.Parts.empty() || !(c.Radius > 0.0) || !std::isfinite(c.Radius))
    {
      return "class '" + c.Name + "' has no part or no valid radius";
    }
  }
  for (double v : T.Values)
  {
    if (!std::isfinite(v) || v < 0.0)
    {
      return "the tables hold a negative or non-finite safe distance";
    }
  }
  if (!(O.ShapeSize > 0.0) || !std::isfinite(O.ShapeSize))
  {
    return "ShapeSize must be a positive finite number (it is " + std::to_string(O.ShapeSize) + ")";
  }
  if (O.ShapeSize * 1e7 < M.MeanEdgeLength())
  {
    return "ShapeSize " + std::to_string(O.ShapeSize) +
      " is absurdly small for this mesh (mean edge length " + std::to_string(M.MeanEdgeLength()) +
      "): it would take more than 1e14 shapes";
  }
  if (O.Symmetry != 1 && O.Symmetry != 2 && O.Symmetry != 4)
  {
    return "the direction field's symmetry must be 1, 2 or 4 (it is " + std::to_string(O.Symmetry) + ")";
  }
  if (O.MaximumShapes < 0 || O.MaximalFailures < 0 || O.GreedyDirections < 1 ||
    O.GreedyDirections > 1024 || !(O.SafetyMargin >= 0.0) || O.SafetyMargin > 10.0 ||
    !(O.DistortionLimit >= 0.0) || !(O.HolonomyMargin >= 0.0) || O.HolonomyMargin > 100.0)
  {
    return "invalid MaximumShapes, MaximalFailures, GreedyDirections (1..1024), SafetyMargin "
           "(0..10), DistortionLimit (>= 0) or HolonomyMargin (0..100)";
  }
  ComputeLattices();
  // Class weights.
  std::vector<double> w = O.ClassWeights;
  if (w.empty())
  {
    w.assign(T.Classes.size(), 1.0);
  }
  if (w.size() != T.Classes.size())
  {
    return "ClassWeights has " + std::to_string(w.size()) + " values for " +
      std::to_string(T.Classes.size()) + " classes";
  }
  ClassCdf.clear();
  double sum = 0.0;
  for (double x : w)
  {
    if (!(x >= 0.0) || !std::isfinite(x))
    {
      return "ClassWeights must be non-negative finite numbers";
    }
    sum += x;
    ClassCdf.push_back(sum);
  }
  if (!(sum > 0.0))
  {
    return "ClassWeights are all zero";
  }
  // Directions.
  if (static_cast<int>(faceDirections.size()) != nf)
  {
    return "one direction per face is needed (" + std::to_string(faceDirections.size()) +
      " given for " + std::to_string(nf) + " faces)";
  }
  FaceDirection.assign(nf, Vec3{ 0, 0, 0 });
#pragma omp parallel for schedule(static) num_threads(ThreadCount(O.NumberOfThreads))
  for (int f = 0; f < nf; ++f)
  {
    const Vec3& d = faceDirections[f];
    if (!IsFinite(d))
    {
      continue;
    }
    const Vec3 n = M.FaceNormal(f);
    const Vec3 t = d - n * Dot(n, d);
    if (Norm(t) > 1e-12 * Norm(d) && Norm(t) > 0.0)
    {
      FaceDirection[f] = Unit(t);
    }
  }
  // Density and the face weights.
  if (!vertexDensity.empty() && static_cast<int>(vertexDensity.size()) != nv)
  {
    return "one density factor per vertex is needed (" + std::to_string(vertexDensity.size()) +
      " given for " + std::to_string(nv) + " vertices)";
  }
  Density = vertexDensity;
  FaceWeight.assign(nf, 0.0);
  AllCdf.assign(nf, 0.0);
  MaxFaceDensity = 0.0;
  double total = 0.0;
  double minimumScale = std::numeric_limits<double>::infinity();
  for (int f = 0; f < nf; ++f)
  {
    double fm = 1.0;
    bool ok = true;
    if (!Density.empty())
    {
      fm = 0.0;
      for (int v : M.Face(f))
      {
        ok = ok && Density[v] > 0.0 && std::isfinite(Density[v]);
        fm += Density[v] / 3.0;
      }
    }
    if (ok)
    {
      FaceWeight[f] = M.FaceArea(f) / (fm * fm);
      total += FaceWeight[f];
      minimumScale = std::min(minimumScale, fm);
      for (int v : M.Face(f))
      {
        MaxFaceDensity = std::max(MaxFaceDensity, Density.empty() ? 1.0 : Density[v]);
      }
    }
    AllCdf[f] = total;
  }
  Dead.assign(nf, 0);
  NumberOfClasses = static_cast<int>(T.Classes.size());
  DeadFor.assign(static_cast<std::size_t>(NumberOfClasses) * nf, 0);
  Killed.clear();
  KilledBy.clear();
  BuildCdf();
  if (!(total > 0.0))
  {
    return "no face has a positive density factor at all its corners";
  }
  double area = 0.0;
  for (int f = 0; f < nf; ++f)
  {
    area += M.FaceArea(f);
  }
  {
    double smallest = std::numeric_limits<double>::infinity();
    for (const SafeDistanceClass& c : T.Classes)
    {
      smallest = std::min(smallest, c.Radius);
    }
    const double r = O.ShapeSize * minimumScale * smallest;
    if (area / (r * r) > 1e9)
    {
      return "ShapeSize (times the smallest density factor) is too small for this mesh: more than "
             "1e9 shapes would fit";
    }
  }
  MaxEdge = 0.0;
  {
    double longest = 0.0;
#pragma omp parallel for schedule(static) reduction(max : longest) num_threads(ThreadCount(O.NumberOfThreads))
    for (int h = 0; h < M.NumberOfHalfedges(); ++h)
    {
      longest = std::max(longest, M.EdgeLength(h));
    }
    MaxEdge = longest;
  }
  ChartMargin = 2.0 * M.MeanEdgeLength();
  if (static_cast<int>(Defect.size()) != nv)
  {
    Defect.assign(nv, 0.0);
    for (int v = 0; v < nv; ++v)
    {
      Defect[v] = M.IsBoundaryVertex(v) ? 0.0 : std::abs(TwoPi - M.TotalAngle(v));
    }
  }
  RMax = 0.0;
  if (CircleMode)
  {
    for (const SafeDistanceClass& c : T.Classes)
    {
      RMax = std::max(RMax, c.Radius);
    }
  }
  else
  {
    for (const SafeDistancePart& p : T.Parts)
    {
      RMax = std::max(RMax, p.Radius);
    }
  }
  // Dead faces: per (part, class), the smallest safe distance of the part against any part of
  // the class (2% less, for the charts' approximations); per class, its reach.
  {
    const int np = CircleMode ? static_cast<int>(T.Classes.size()) : T.NumberOfParts();
    const int nc = static_cast<int>(T.Classes.size());
    KillRadius.assign(static_cast<std::size_t>(np) * nc, std::numeric_limits<double>::infinity());
    KillReach.assign(nc, 0.0);
    const std::size_t ka = static_cast<std::size_t>(T.AngleBins);
    for (int x = 0; x < np; ++x)
    {
      for (int c = 0; c < nc; ++c)
      {
        double& kill = KillRadius[static_cast<std::size_t>(x) * nc + c];
        if (CircleMode)
        {
          kill = T.Classes[x].Radius + T.Classes[c].Radius;
        }
        else
        {
          for (int pc : T.Classes[c].Parts)
          {
            const double* table = &T.Values[(static_cast<std::size_t>(x) * T.Parts.size() + pc) * ka * ka];
            kill = std::min(kill, *std::min_element(table, table + ka * ka));
          }
        }
        kill *= 0.98;
      }
    }
    for (int c = 0; c < nc && !CircleMode; ++c)
    {
      if (T.Classes[c].Parts.size() <= 1)
      {
        continue;
      }
      for (int pc : T.Classes[c].Parts)
      {
        const Vec2& q = T.Parts[pc].Centre;
        KillReach[c] = std::max(KillReach[c],
          std::abs(Dot(q, T.Classes[c].MajorAxis)) + std::abs(Cross(T.Classes[c].MajorAxis, q)));
      }
    }
  }
  // Long classes: their extent along the major axis, and the field's angles for streamlines.
  ClassExtentMin.assign(T.Classes.size(), 0.0);
  ClassExtentMax.assign(T.Classes.size(), 0.0);
  bool anyLong = false;
  for (std::size_t k = 0; k < T.Classes.size(); ++k)
  {
    const SafeDistanceClass& c = T.Classes[k];
    if (c.Parts.size() <= 1)
    {
      continue;
    }
    anyLong = true;
    double lo = 0.0, hi = 0.0;
    for (const auto& ring : c.Outline.Rings)
    {
      for (const Vec2& p : ring)
      {
        lo = std::min(lo, Dot(p, c.MajorAxis));
        hi = std::max(hi, Dot(p, c.MajorAxis));
      }
    }
    for (int part : c.Parts)
    {
      const double a = Dot(T.Parts[part].Centre, c.MajorAxis);
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
    ClassExtentMin[k] = lo;
    ClassExtentMax[k] = hi;
  }
  Regions.clear();
  Clearance.assign(T.Classes.size(), -1.0);
  {
    double largest = 0.0;
    std::vector<double> clearance(T.Classes.size(), -1.0);
    for (std::size_t k = 0; k < T.Classes.size(); ++k)
    {
      const SafeDistanceClass& c = T.Classes[k];
      ClassRegion probe(c.Outline.Rings, c.Radius, 0.0);
      if (probe.Inside(Vec2{ 0.0, 0.0 }))
      {
        double d = std::numeric_limits<double>::infinity();
        for (const auto& ring : c.Outline.Rings)
        {
          for (std::size_t i = 0, n = ring.size(); i < n; ++i)
          {
            const Vec2 a = ring[i], ab = ring[(i + 1) % n] - ring[i];
            const double l2 = Dot(ab, ab);
            const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, -Dot(a, ab) / l2)) : 0.0;
            d = std::min(d, Norm(a + ab * t));
          }
        }
        clearance[k] = d;
        largest = std::max(largest, d);
      }
    }
    for (const SafeDistanceClass& c : T.Classes)
    {
      Regions.emplace_back(c.Outline.Rings, c.Radius, std::max(largest, 0.01 * c.Radius));
    }
    Clearance = clearance;
    MaxClearance = largest;
  }
  if (anyLong)
  {
    if (!Field)
    {
      Field.reset(new DirectionFieldSolver(M));
    }
    FieldAngles.assign(nf, 0.0);
    for (int f = 0; f < nf; ++f)
    {
      FieldAngles[f] = Norm(FaceDirection[f]) > 0.0 ? Field->AngleInFace(f, FaceDirection[f]) : 0.0;
    }
  }
  Accepted.clear();
  Placed.clear();
  CoverIndex.assign(nv, {});
  CentreIndex.assign(nv, {});
  return std::string();
}

void ShapeDistributor::Impl::Generate(std::vector<Record>& batch, int round) const
{
  const int n = static_cast<int>(batch.size());
#pragma omp parallel num_threads(ThreadCount(O.NumberOfThreads))
  {
    std::vector<int> scratch;
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < n; ++i)
    {
      Random rng(O.Seed, 1, static_cast<std::uint64_t>(round), static_cast<std::uint64_t>(i));
      const int cls = RandomClass(rng);
      const SurfacePoint centre = RandomPoint(rng);
      // A class that certainly cannot fit in this face, or (long classes, whose shapes cost a
      // streamline) at this centre: no need to build the shape.
      batch[i].Valid = !DeadForClass(cls, centre.Face) &&
        !(T.Classes[cls].Parts.size() > 1 && CentreCovered(centre, cls, DensityAt(centre), scratch)) &&
        MakeShape(centre, cls, rng, batch[i].S);
    }
  }
}

void ShapeDistributor::Impl::ComputeLattices()
{
  // For copies of one part turned alike, the tables give the smallest admissible offset in
  // each direction beta (of the line from one centre to the other, in the shape's frame):
  // D(beta) = max(T(-beta, -beta), T(-beta - pi, -beta - pi)) (the pair seen from either
  // shape). A lattice {i u + j v} is admissible when every lattice vector w is at least
  // D(angle(w)) long; the densest one has basis vectors on the boundary |w| = D: searched over
  // pairs of boundary samples, smallest cell area first. Greedy then proposes the lattice
  // neighbours of each placed shape, so that a cluster grows as one crystal instead of grains
  // of two-contact growth that leave gaps where they meet.
  ClassLattice.assign(T.Classes.size(), {});
  if (O.Mode != DistributionMode::Greedy || CircleMode)
  {
    return;
  }
  for (std::size_t c = 0; c < T.Classes.size(); ++c)
  {
    if (T.Classes[c].Parts.size() != 1)
    {
      continue;
    }
    const int p = T.Classes[c].Parts[0];
    Hasher h;
    h.AddValue(T.AngleBins);
    h.AddValue(T.Parts[p].Radius);
    const std::size_t ka = static_cast<std::size_t>(T.AngleBins);
    const std::size_t pair = static_cast<std::size_t>(p) * T.Parts.size() + p;
    h.Add(T.Values.data() + pair * ka * ka, ka * ka * sizeof(double));
    auto it = LatticeCache.find(h.H);
    if (it == LatticeCache.end())
    {
      if (LatticeCache.size() >= 64)
      {
        LatticeCache.clear();
      }
      it = LatticeCache.emplace(h.H, PartLattice(p)).first;
    }
    ClassLattice[c] = it->second;
  }
}

std::vector<Vec2> ShapeDistributor::Impl::PartLattice(int p) const
{
  // (Within 2e-3 rad of beta too: a lattice vector on a bin boundary must not depend on the
  // last bits of the angle the conflict check will compute.)
  auto D = [&](double beta) {
    double d = 0.0;
    for (const double b : { beta - 2e-3, beta, beta + 2e-3 })
    {
      d = std::max({ d, T.Lookup(p, p, -b, -b), T.Lookup(p, p, -b - Pi, -b - Pi) });
    }
    return d;
  };
  const double cap = 2.0 * T.Parts[p].Radius; // no table value exceeds r_A + r_B
  auto admissible = [&](const Vec2& u, const Vec2& v, int range) {
    for (int i = -range; i <= range; ++i)
    {
      for (int j = 0; j <= range; ++j)
      {
        if (j == 0 && i <= 0)
        {
          continue; // w and -w: one of them, and not 0
        }
        const Vec2 w = u * i + v * j;
        const double len = Norm(w);
        if (len < cap && len < D(std::atan2(w.y, w.x)) * (1.0 - 1e-12))
        {
          return false;
        }
      }
    }
    return true;
  };
  // Boundary samples: four per angle bin, 256 to 512 (the search is quadratic in them).
  const int n = std::min(512, std::max(256, 4 * T.AngleBins));
  std::vector<Vec2> boundary(n);
  for (int k = 0; k < n; ++k)
  {
    const double beta = Pi * (k + 0.5) / n; // half a turn: -w is in the lattice too
    boundary[k] = Vec2{ std::cos(beta), std::sin(beta) } * (D(beta) * (1.0 + 1e-9));
  }
  double bestArea = std::numeric_limits<double>::infinity();
  Vec2 bu, bv;
  for (int a = 0; a < n; ++a)
  {
    for (int b = 0; b < n; ++b)
    {
      // v anywhere in the open half turn after u (as v or -v).
      for (const double sign : { 1.0, -1.0 })
      {
        const Vec2 u = boundary[a], v = boundary[b] * sign;
        const double area = Cross(u, v);
        if (!(area > 1e-12 * cap * cap) || area >= bestArea || !admissible(u, v, 4))
        {
          continue;
        }
        bestArea = area;
        bu = u;
        bv = v;
      }
    }
  }
  if (!(bestArea < std::numeric_limits<double>::infinity()) || !admissible(bu, bv, 8))
  {
    return {};
  }
  const Vec2 w = Norm(bu - bv) < Norm(bu + bv) ? bu - bv : bu + bv;
  return { bu, bv, w, bu * -1.0, bv * -1.0, w * -1.0 };
}

std::vector<ShapeDistributor::Impl::Proposal> ShapeDistributor::Impl::Propose(
  int parentId, int round, int slot) const
{
  std::vector<Proposal> out;
  const Record& A = Accepted[parentId];
  Random rng(O.Seed, 2, static_cast<std::uint64_t>(round), static_cast<std::uint64_t>(slot));
  const int cls = RandomClass(rng);
  const SafeDistanceClass& ac = T.Classes[A.S.ClassId];
  const SafeDistanceClass& cc = T.Classes[cls];
  const double unit = O.ShapeSize * A.S.Scale * (1.0 + O.SafetyMargin);
  const double a0 = TangentAngle(M, A.S.Centre, A.S.Direction);
  if (!std::isfinite(a0))
  {
    return out;
  }
  const bool tabled = !CircleMode && ac.Parts.size() == 1 && cc.Parts.size() == 1;
  const int pa = CircleMode ? A.S.ClassId : ac.Parts[0];
  const int pc = CircleMode ? cls : cc.Parts[0];
  // Safe distance of the new shape (turned like A) in direction beta from A (A's frame).
  auto reach = [&](double beta) {
    return tabled ? T.Lookup(pa, pc, -beta, -beta) * unit
                  : (CircleMode ? 1.0 : 0.75) * (ac.Radius + cc.Radius) * unit;
  };
  // Neighbours in A's chart: their centre and axis, as seen from A.
  struct Near
  {
    Vec2 Q;
    double Axis;
    int Part;
    double Unit;
  };
  std::vector<Near> near;
  if (tabled || CircleMode)
  {
    std::vector<int> ids;
    if (!A.Charts.empty())
    {
      for (const ChartEntry& e : A.Charts[0].Entries)
      {
        ids.insert(ids.end(), CentreIndex[e.V].begin(), CentreIndex[e.V].end());
      }
    }
    SortUnique(ids);
    for (int id : ids)
    {
      if (id == parentId)
      {
        continue;
      }
      const Record& B = Accepted[id];
      if (B.S.Parts.size() != 1)
      {
        continue;
      }
      const PlacedPart& pb = B.S.Parts[0];
      const auto& corners = M.Face(pb.Centre.Face);
      const ChartEntry* e[3];
      bool all = true;
      for (int k = 0; k < 3 && all; ++k)
      {
        e[k] = A.Charts[0].Find(corners[k]);
        all = e[k] != nullptr;
      }
      if (!all)
      {
        continue;
      }
      Vec2 P[3];
      for (int k = 0; k < 3; ++k)
      {
        P[k] = Vec2{ e[k]->X, e[k]->Y };
      }
      Near b;
      b.Q = P[0] * pb.Centre.Bary[0] + P[1] * pb.Centre.Bary[1] + P[2] * pb.Centre.Bary[2];
      // B's axis carried into the chart by the face's affine map.
      const Vec3 x0 = M.Position(corners[0]);
      const Vec3 e1 = M.Position(corners[1]) - x0, e2 = M.Position(corners[2]) - x0;
      const double g11 = Dot(e1, e1), g12 = Dot(e1, e2), g22 = Dot(e2, e2);
      const double det = g11 * g22 - g12 * g12;
      if (!(det > 0.0))
      {
        continue;
      }
      const double r1 = Dot(pb.Axis, e1), r2 = Dot(pb.Axis, e2);
      const double u = (g22 * r1 - g12 * r2) / det, v = (g11 * r2 - g12 * r1) / det;
      const Vec2 axis = (P[1] - P[0]) * u + (P[2] - P[0]) * v;
      b.Axis = std::atan2(axis.y, axis.x);
      b.Part = pb.Part;
      b.Unit = O.ShapeSize * std::max(B.S.Scale, A.S.Scale) * (1.0 + O.SafetyMargin);
      if (Norm(b.Q) < (PartRadius(pa) + 2.0 * PartRadius(pc) + PartRadius(b.Part)) * b.Unit)
      {
        near.push_back(b);
      }
    }
  }
  // Clearance of a new shape at P (turned like A) from neighbour b: > 0 when free.
  auto clearance = [&](const Vec2& P, const Near& b) {
    const Vec2 w = P - b.Q;
    const double dist = Norm(w), line = std::atan2(w.y, w.x);
    const double safe = CircleMode ? (PartRadius(b.Part) + PartRadius(pc)) : T.Lookup(b.Part, pc, b.Axis - line, -line);
    return dist - safe * b.Unit;
  };
  auto at = [&](double beta) { return Vec2{ std::cos(beta), std::sin(beta) } * reach(beta); };
  auto freeOfAll = [&](double beta) {
    const Vec2 P = at(beta);
    for (const Near& b : near)
    {
      if (clearance(P, b) < 0.0)
      {
        return false;
      }
    }
    return true;
  };
  // lengths: the lattice vectors' lengths; empty: each proposal lies on A's contact curve
  // (reach(beta)).
  std::vector<double> betas, lengths;
  if (cls == A.S.ClassId && !ClassLattice[cls].empty())
  {
    // The lattice neighbours of A that no placed neighbour already rules out.
    for (const Vec2& w : ClassLattice[cls])
    {
      const Vec2 P = w * unit;
      bool free = true;
      for (const Near& b : near)
      {
        free = free && clearance(P, b) >= -1e-9 * unit;
      }
      if (free)
      {
        betas.push_back(std::atan2(w.y, w.x));
        lengths.push_back(Norm(w) * unit);
      }
    }
  }
  else if (near.empty())
  {
    const double offset = rng.Uniform();
    for (int j = 0; j < O.GreedyDirections; ++j)
    {
      betas.push_back(TwoPi * (j + offset) / O.GreedyDirections);
    }
  }
  else
  {
    // Touching A and a neighbour: where the clearance from that neighbour changes sign along
    // A's contact curve (the side with clearance >= 0, refined by bisection).
    const int samples = 4 * O.GreedyDirections;
    for (const Near& b : near)
    {
      double previous = clearance(at(0.0), b);
      for (int j = 1; j <= samples; ++j)
      {
        const double beta = TwoPi * j / samples;
        const double now = clearance(at(beta), b);
        if ((previous < 0.0) != (now < 0.0))
        {
          double lo = TwoPi * (j - 1) / samples, hi = beta; // lo: the previous sample
          const bool loFree = previous >= 0.0;
          for (int it = 0; it < 20; ++it)
          {
            const double mid = 0.5 * (lo + hi);
            const bool midFree = clearance(at(mid), b) >= 0.0;
            (midFree == loFree ? lo : hi) = mid;
          }
          const double free = loFree ? lo : hi;
          if (freeOfAll(free))
          {
            betas.push_back(free);
          }
        }
        previous = now;
      }
    }
  }
  for (std::size_t k = 0; k < betas.size(); ++k)
  {
    const double beta = betas[k];
    const double d = (k < lengths.size() ? lengths[k] : reach(beta)) * (1.0 + 1e-6) + 1e-9 * MaxEdge;
    const GeodesicShot shot = ShootGeodesic(M, A.S.Centre, a0 + beta, d);
    if (shot.ReachedBoundary || shot.End.Face < 0 || !(FaceWeight[shot.End.Face] > 0.0) ||
      DeadForClass(cls, shot.End.Face))
    {
      continue; // off the surface or in a region without density
    }
    Proposal p;
    p.Centre = shot.End;
    p.Class = cls;
    p.Prefer = FaceDirection[A.S.Centre.Face];
    if (O.Symmetry > 1)
    {
      // The parent's own choice among the N directions (its class axis for short shapes).
      p.Prefer = ac.Parts.size() <= 1 ? A.S.Direction : p.Prefer;
    }
    p.Key = Norm(M.Interpolate(p.Centre.Face, p.Centre.Bary) - Accepted[0].S.Position);
    out.push_back(p);
  }
  return out;
}

bool ShapeDistributor::Impl::ClassPointOf(const Record& r, const SurfacePoint& x, Vec2& p) const
{
  if (!r.S.Curve.empty() || r.Charts.empty() || r.Charts[0].Entries.empty())
  {
    return false;
  }
  return ChartPoint(r.Charts[0], x, O.ShapeSize * r.S.Scale, p);
}

bool ShapeDistributor::Impl::ChartPoint(const Chart& chart, const SurfacePoint& x, double unit, Vec2& p) const
{
  const double inverse = 1.0 / unit;
  if (x.IsVertex())
  {
    const ChartEntry* e = chart.Find(x.Vertex);
    if (!e)
    {
      return false;
    }
    p = Vec2{ e->X * inverse, e->Y * inverse };
    return true;
  }
  if (x.Face < 0 || x.Face >= M.NumberOfFaces())
  {
    return false;
  }
  const auto& corners = M.Face(x.Face);
  Vec2 q{ 0.0, 0.0 };
  for (int k = 0; k < 3; ++k)
  {
    const ChartEntry* e = chart.Find(corners[k]);
    if (!e)
    {
      return false;
    }
    q = q + Vec2{ e->X, e->Y } * x.Bary[k];
  }
  p = q * inverse;
  return true;
}

MappedPoint ShapeDistributor::Impl::MapShape(const PlacedShape& s, const Vec2& p) const
{
  const Impl& I = *this;
  const SafeDistanceClass& c = I.T.Classes[s.ClassId];
  const double scale = I.O.ShapeSize * s.Scale;
  MappedPoint m;
  if (s.Curve.empty())
  {
    const double rho = Norm(p) * scale;
    if (rho <= 0.0)
    {
      m.End = s.Centre;
      return m;
    }
    const double a = TangentAngle(I.M, s.Centre, s.Direction);
    const GeodesicShot shot = ShootGeodesic(I.M, s.Centre, a + std::atan2(p.y, p.x), rho);
    m.End = shot.End;
    m.Reached = !shot.ReachedBoundary;
    m.Reach = m.Reached ? 1.0 : std::min(1.0, shot.Length / rho);
    return m;
  }
  int face = -1;
  Vec3 x, tangent;
  Impl::PointOnCurve(I.M, s.Curve, s.CurveCentre + Dot(p, c.MajorAxis) * scale, face, x, tangent);
  Vec3 endTangent;
  bool boundary = false;
  if (!I.Across(face, x, tangent, Cross(c.MajorAxis, p) * scale, m.End, endTangent, &boundary))
  {
    m.End = SurfacePoint::InFace(face, 0, 0, 0);
    m.End.Bary = I.M.ClampedBarycentric(face, x);
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
  const SafeDistanceClass& c = I.T.Classes[s.ClassId];
  const double unit = I.O.ShapeSize * s.Scale;
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
  double best = distance2(Nodes[nearest].X);
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
        const double d = distance2(Nodes[i1 * Rows + j1].X);
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
  for (int ci = ni - 1; ci <= ni; ++ci)
  {
    for (int cj = nj - 1; cj <= nj; ++cj)
    {
      if (ci < 0 || cj < 0 || ci + 1 >= Columns || cj + 1 >= Rows)
      {
        continue;
      }
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
        const double d = TriangleDistance(A.X, B.X, C.X, X, lambda);
        if (d < bestDistance)
        {
          bestDistance = d;
          p = A.P * lambda[0] + B.P * lambda[1] + C.P * lambda[2];
        }
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
      lo = Vec3{ std::min(lo.x, n.X.x), std::min(lo.y, n.X.y), std::min(lo.z, n.X.z) };
      hi = Vec3{ std::max(hi.x, n.X.x), std::max(hi.y, n.X.y), std::max(hi.z, n.X.z) };
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
      ++CellStart[cellOf(n.X) + 1];
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
      CellNodes[fill[cellOf(Nodes[k].X)]++] = k;
    }
  }
}

bool CurveGrid::ClassPoint(const SurfacePoint& x, Vec2& p, int* hint) const
{
  if (!Mesh || CellStart.empty())
  {
    return false;
  }
  const Vec3 X = x.IsVertex() ? Mesh->Position(x.Vertex) : Mesh->Interpolate(x.Face, x.Bary);
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
          const Vec3 d = Nodes[CellNodes[q]].X - X;
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

double ShapeDistributor::OutlineSpacing() const
{
  return P->OutlineSpacing();
}

std::shared_ptr<const CurveGrid> ShapeDistributor::Frame(int shape) const
{
  const Impl& I = *P;
  const PlacedShape& s = I.Placed.at(shape);
  if (s.Curve.empty())
  {
    return nullptr;
  }
  if (I.Accepted.at(shape).Frame)
  {
    return I.Accepted.at(shape).Frame;
  }
  auto grid = std::make_shared<CurveGrid>(I.BuildCurveGrid(s, I.T.Classes[s.ClassId]));
  grid->Index();
  return grid;
}

double ShapeDistributor::ExpectedCount(const TriangleMesh& mesh, const SafeDistanceTables& tables,
  const std::vector<double>& vertexDensity, double shapeSize)
{
  if (tables.Classes.empty() || !(shapeSize > 0.0))
  {
    return 0.0;
  }
  double radius = 0.0;
  for (const SafeDistanceClass& c : tables.Classes)
  {
    radius += c.Radius / static_cast<double>(tables.Classes.size());
  }
  double weight = 0.0;
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    double factor = 1.0;
    if (vertexDensity.size() == static_cast<std::size_t>(mesh.NumberOfVertices()))
    {
      const auto& c = mesh.Face(f);
      factor = std::min({ vertexDensity[c[0]], vertexDensity[c[1]], vertexDensity[c[2]] });
    }
    if (factor > 0.0 && std::isfinite(factor))
    {
      weight += mesh.FaceArea(f) / (factor * factor);
    }
  }
  const double r = shapeSize * radius;
  return 0.5 * weight / (Pi * r * r);
}

ShapeDistributor::ShapeDistributor(const TriangleMesh& mesh, const SaddleVertexGraph* graph)
  : P(new Impl(mesh, graph && graph->NumberOfVertices() == mesh.NumberOfVertices() ? graph : nullptr))
{
}

ShapeDistributor::~ShapeDistributor() = default;

const std::vector<PlacedShape>& ShapeDistributor::Shapes() const
{
  return P->Placed;
}

const TriangleMesh& ShapeDistributor::Mesh() const
{
  return P->M;
}

const SafeDistanceTables& ShapeDistributor::Tables() const
{
  return P->T;
}

const ShapeDistributionOptions& ShapeDistributor::Options() const
{
  return P->O;
}

bool ShapeDistributor::ClassPoint(int shape, const SurfacePoint& x, Vec2& p) const
{
  return P->ClassPointOf(P->Accepted.at(shape), x, p);
}

ShapeDistributionResult ShapeDistributor::Run(const SafeDistanceTables& tables,
  const std::vector<Vec3>& faceDirections, const std::vector<double>& vertexDensity,
  const ShapeDistributionOptions& options, const std::function<bool(double)>& progress)
{
  const auto start = std::chrono::steady_clock::now();
  ShapeDistributionResult result;
  Impl& I = *P;
  result.Error = I.Prepare(tables, faceDirections, vertexDensity, options);
  if (!result.Error.empty())
  {
    I.Accepted.clear();
    I.Placed.clear();
    return result;
  }
  const ShapeDistributionOptions& O = I.O;
  const int threads = ThreadCount(O.NumberOfThreads);
  I.EnsureEngines(threads);
  result.Statistics.PrepareSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const long long failuresToStop = O.MaximalFailures > 0 ? O.MaximalFailures : 10000;
  const bool greedyMode = O.Mode == DistributionMode::Greedy;
  std::vector<int> front;
  bool seedsGrow = true;          // Greedy: random rounds plant one seed each
  long long seeds = 0, grownSinceSeed = 0;
  long long consecutive = 0;
  int randomRounds = 0;
  bool stop = false;
  double reported = 0.0;
  ShapeDistributionStatistics& stats = result.Statistics;
  for (int round = 0; !stop; ++round)
  {
    const bool greedy = greedyMode && !front.empty();
    const bool seeding = greedyMode && !greedy && seedsGrow;
    auto clock = std::chrono::steady_clock::now();
    auto lap = [&clock](double& into) {
      const auto now = std::chrono::steady_clock::now();
      into += std::chrono::duration<double>(now - clock).count();
      clock = now;
    };
    std::vector<Impl::Record> batch;
    int n;
    if (greedy)
    {
      // Proposals of every front shape, nearest to the first shape first.
      std::vector<std::vector<Impl::Proposal>> proposals(front.size());
#pragma omp parallel for schedule(dynamic, 4) num_threads(threads)
      for (int k = 0; k < static_cast<int>(front.size()); ++k)
      {
        proposals[k] = I.Propose(front[k], round, k);
      }
      std::vector<Impl::Proposal> all;
      for (const auto& p : proposals)
      {
        all.insert(all.end(), p.begin(), p.end());
      }
      std::stable_sort(all.begin(), all.end(),
        [](const Impl::Proposal& a, const Impl::Proposal& b) { return a.Key < b.Key; });
      n = static_cast<int>(all.size());
      batch.resize(n);
#pragma omp parallel for schedule(dynamic, 16) num_threads(threads)
      for (int i = 0; i < n; ++i)
      {
        Random rng(O.Seed, 4, static_cast<std::uint64_t>(round), static_cast<std::uint64_t>(i));
        batch[i].Valid = I.MakeShape(all[i].Centre, all[i].Class, rng, batch[i].S, &all[i].Prefer);
      }
    }
    else
    {
      if (I.DeadSinceCdf > 0)
      {
        I.BuildCdf();
      }
      if (!I.AnyLiveFace())
      {
        stats.Maximal = true; // no face left where a shape could fit
        break;
      }
      // Up to 4096: little work past the last failure. Greedy seeds one shape per round.
      n = seeding ? (randomRounds == 0 ? 1 : 256) : 256 << std::min(randomRounds, 4);
      ++randomRounds;
      batch.resize(n);
      I.Generate(batch, round);
    }
    lap(stats.GenerateSeconds);
    stats.Candidates += n;
    long long charts = 0;
    double chartSeconds = 0.0;
    // (a) Cheap checks against the shapes of previous rounds (no chart needed).
#pragma omp parallel num_threads(threads)
    {
      std::vector<int> scratch;
#pragma omp for schedule(dynamic, 64)
      for (int i = 0; i < n; ++i)
      {
        Impl::Record& r = batch[i];
        r.Rejected = !r.Valid || I.CheapConflict(r, scratch);
      }
    }
    // (b) Survivors that may conflict with each other: parts closer in space than the sum of
    // their circumradii (the geodesic distance is never shorter). Each keeps its
    // higher-priority neighbours.
    std::vector<int> survivors;
    for (int i = 0; i < n; ++i)
    {
      if (!batch[i].Rejected)
      {
        survivors.push_back(i);
      }
    }
    std::vector<std::vector<int>> above(n);
    {
      const double cell = 2.0 * I.RMax * O.ShapeSize * I.MaxFaceDensity * (1.0 + O.SafetyMargin);
      auto key = [cell](const Vec3& x) {
        return std::array<long long, 3>{ static_cast<long long>(std::floor(x.x / cell)),
          static_cast<long long>(std::floor(x.y / cell)), static_cast<long long>(std::floor(x.z / cell)) };
      };
      std::vector<std::pair<std::array<long long, 3>, int>> grid; // (cell, candidate)
      for (int i : survivors)
      {
        for (const PlacedPart& p : batch[i].S.Parts)
        {
          grid.emplace_back(key(p.Position), i);
        }
      }
      std::sort(grid.begin(), grid.end());
      grid.erase(std::unique(grid.begin(), grid.end()), grid.end());
#pragma omp parallel for schedule(dynamic, 64) num_threads(threads)
      for (std::size_t k = 0; k < survivors.size(); ++k)
      {
        const int i = survivors[k];
        const Impl::Record& r = batch[i];
        std::vector<int>& list = above[i];
        for (const PlacedPart& p : r.S.Parts)
        {
          const std::array<long long, 3> c = key(p.Position);
          for (long long dx = -1; dx <= 1; ++dx)
            for (long long dy = -1; dy <= 1; ++dy)
              for (long long dz = -1; dz <= 1; ++dz)
              {
                const std::array<long long, 3> q{ c[0] + dx, c[1] + dy, c[2] + dz };
                auto it = std::lower_bound(grid.begin(), grid.end(), std::make_pair(q, -1));
                for (; it != grid.end() && it->first == q && it->second < i; ++it)
                {
                  const Impl::Record& o = batch[it->second];
                  const double unit = O.ShapeSize * std::max(r.S.Scale, o.S.Scale) * (1.0 + O.SafetyMargin);
                  for (const PlacedPart& op : o.S.Parts)
                  {
                    if (Norm(op.Position - p.Position) <=
                      (I.PartRadius(p.Part) + I.PartRadius(op.Part)) * unit * (1.0 + 1e-9))
                    {
                      list.push_back(it->second);
                      break;
                    }
                  }
                }
              }
        }
        SortUnique(list);
      }
    }
    // (c) Waves: a survivor is decided once all its higher-priority neighbours are; it is then
    // checked against every accepted shape (those of this round included) and, if free, gets
    // its charts and is accepted. Candidates of one wave are never neighbours, so this is
    // sequential dart throwing in priority order, with charts only for accepted shapes (and
    // the rare ones a smaller neighbour rejects).
    const int roundStart = static_cast<int>(I.Accepted.size());
    std::vector<char> state(n, 2); // 0 undecided, 1 accepted, 2 rejected
    for (int i : survivors)
    {
      state[i] = 0;
    }
    std::vector<int> acceptedAs(n, -1); // id in I.Accepted
    std::vector<int> undecided = survivors, ready, waiting;
    if (seeding)
    {
      // Greedy seeds one shape per random round: the first survivor that fits, in order.
      std::vector<int> scratch;
      for (int i : survivors)
      {
        Impl::Record& r = batch[i];
        I.ComputeCharts(r, I.Engine0());
        ++charts;
        if (I.FullConflict(r, scratch) || I.DrawnConflict(r, scratch))
        {
          state[i] = 2;
          continue;
        }
        state[i] = 1;
        acceptedAs[i] = static_cast<int>(I.Accepted.size());
        I.Commit(std::move(r));
        break;
      }
      for (int i : survivors)
      {
        state[i] = state[i] == 0 ? 2 : state[i]; // after the seed: beyond the cut below
      }
      undecided.clear();
    }
    while (!undecided.empty())
    {
      ready.clear();
      waiting.clear();
      for (int i : undecided)
      {
        bool free = true;
        for (int j : above[i])
        {
          free = free && state[j] != 0;
        }
        (free ? ready : waiting).push_back(i);
      }
      const int nr = static_cast<int>(ready.size());
#pragma omp parallel num_threads(threads) reduction(+ : charts, chartSeconds)
      {
        std::vector<int> scratch, marked;
        // One candidate at a time: a chart costs about 0.6 ms, and waves are often short (a
        // chunk of 4 left one thread idle for up to 3 charts).
#pragma omp for schedule(dynamic, 1)
        for (int k = 0; k < nr; ++k)
        {
          Impl::Record& r = batch[ready[k]];
          bool recheck = false;
          for (int j : above[ready[k]])
          {
            recheck = recheck || state[j] == 1;
          }
          if (recheck && I.CheapConflict(r, scratch))
          {
            r.Rejected = true;
            continue;
          }
          const auto chartStart = std::chrono::steady_clock::now();
          I.ComputeCharts(r, I.Engine());
          chartSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - chartStart).count();
          ++charts;
          if (I.FullConflict(r, scratch) || I.DrawnConflict(r, scratch))
          {
            r.Rejected = true;
            r.Charts.clear();
            continue;
          }
          I.PrepareCommit(r, I.Marks[ThreadId()], marked);
        }
      }
      for (int i : ready) // priority order
      {
        if (batch[i].Rejected)
        {
          state[i] = 2;
          continue;
        }
        state[i] = 1;
        acceptedAs[i] = static_cast<int>(I.Accepted.size());
        I.Commit(std::move(batch[i]));
      }
      undecided.swap(waiting);
    }
    stats.Charts += charts;
    stats.ChartCpuSeconds += chartSeconds;
    lap(stats.CheckSeconds);
    // (d) Priority order: consecutive failures and MaximumShapes may end the run inside the
    // round; shapes after that point are taken back.
    int cut = n;
    int total = roundStart;
    for (int i = 0; i < n; ++i)
    {
      if (state[i] != 1)
      {
        ++consecutive;
        if (consecutive >= failuresToStop && !greedy)
        {
          stop = true;
          stats.Maximal = true;
          cut = i + 1;
          break;
        }
        continue;
      }
      consecutive = 0;
      ++total;
      if (O.MaximumShapes > 0 && total >= O.MaximumShapes)
      {
        stop = true;
        cut = i + 1;
        break;
      }
      if (seeding)
      {
        cut = i + 1; // Greedy: one random seed, then its front grows
        break;
      }
    }
    bool takeBack = false;
    for (int i = cut; i < n; ++i)
    {
      takeBack = takeBack || state[i] == 1;
    }
    std::vector<int> nextFront;
    if (takeBack)
    {
      std::vector<std::pair<int, Impl::Record>> kept; // (priority, record)
      while (static_cast<int>(I.Accepted.size()) > roundStart)
      {
        const int id = static_cast<int>(I.Accepted.size()) - 1;
        int i = 0;
        while (acceptedAs[i] != id)
        {
          ++i;
        }
        Impl::Record r = I.Uncommit();
        if (i < cut)
        {
          kept.emplace_back(i, std::move(r));
        }
      }
      std::sort(kept.begin(), kept.end(),
        [](const std::pair<int, Impl::Record>& a, const std::pair<int, Impl::Record>& b) { return a.first < b.first; });
      for (auto& k : kept)
      {
        I.Commit(std::move(k.second));
      }
    }
    for (int id = roundStart; id < static_cast<int>(I.Accepted.size()); ++id)
    {
      nextFront.push_back(id);
    }
    if (greedyMode)
    {
      // A seed whose front cannot grow at all: the gaps left hold single shapes, which plain
      // dart throwing fills (one seed per round would cost a whole round per gap).
      if (greedy)
      {
        grownSinceSeed += static_cast<long long>(nextFront.size());
      }
      else if (seeding)
      {
        if (seeds > 0 && grownSinceSeed == 0)
        {
          seedsGrow = false;
        }
        ++seeds;
        grownSinceSeed = 0;
      }
      front.swap(nextFront);
    }
    lap(stats.RoundSeconds);
    stats.Rounds = round + 1;
    double fraction = static_cast<double>(consecutive) / static_cast<double>(failuresToStop);
    if (O.MaximumShapes > 0)
    {
      fraction = std::max(fraction, static_cast<double>(I.Accepted.size()) / O.MaximumShapes);
    }
    reported = std::max(reported, std::min(0.99, fraction));
    if (progress && !progress(reported))
    {
      result.Error = "aborted";
      I.Accepted.clear();
      I.Placed.clear();
      return result;
    }
  }
  stats.ConsecutiveFailures = consecutive;
  stats.Seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.Shapes = I.Placed;
  result.Ok = true;
  if (progress)
  {
    progress(1.0);
  }
  return result;
}

double ShapeDistributor::ProbeFitFraction(int probes, std::uint64_t seed)
{
  Impl& I = *P;
  if (probes <= 0 || I.AllCdf.empty())
  {
    return 0.0;
  }
  const int threads = ThreadCount(I.O.NumberOfThreads);
  I.EnsureEngines(threads);
  long long fits = 0;
#pragma omp parallel num_threads(threads) reduction(+ : fits)
  {
    std::vector<int> scratch;
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < probes; ++i)
    {
      Random rng(seed, 3, 0, static_cast<std::uint64_t>(i));
      Impl::Record r;
      const int cls = I.RandomClass(rng);
      const SurfacePoint centre = I.RandomPoint(rng, false);
      if (!I.MakeShape(centre, cls, rng, r.S) || I.CheapConflict(r, scratch))
      {
        continue;
      }
      I.ComputeCharts(r, I.Engine());
      if (!I.FullConflict(r, scratch) && !I.DrawnConflict(r, scratch))
      {
        ++fits;
      }
    }
  }
  return static_cast<double>(fits) / probes;
}

SurfacePoint ShapeDistributor::MapToSurface(int shape, const Vec2& p) const
{
  return Map(shape, p).End;
}

MappedPoint ShapeDistributor::Map(int shape, const Vec2& p) const
{
  return P->MapShape(P->Placed.at(shape), p);
}

std::vector<OutlinePiece> ShapeDistributor::Outline(int shape, double spacing) const
{
  const Impl::Record& r = P->Accepted.at(shape);
  if (r.HasDrawn && spacing == P->OutlineSpacing())
  {
    return r.Drawn; // drawn when the shape was checked
  }
  return P->OutlineOf(P->Placed.at(shape), spacing);
}

namespace
{
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
} // namespace

bool ShapeDecal::TextureCoordinate(const SurfacePoint& p, Vec2& uv) const
{
  if (p.Face < 0)
  {
    return false;
  }
  for (std::size_t k = 0; k < Faces.size(); ++k)
  {
    if (Faces[k] != p.Face)
    {
      continue;
    }
    // p's barycentric coordinates in the triangle: solve in the first two face coordinates.
    const auto& B = Corners[k];
    const double ax = B[0][0] - B[2][0], bx = B[1][0] - B[2][0], ay = B[0][1] - B[2][1],
                 by = B[1][1] - B[2][1];
    const double det = ax * by - bx * ay;
    if (det == 0.0)
    {
      continue;
    }
    const double px = p.Bary[0] - B[2][0], py = p.Bary[1] - B[2][1];
    const double l0 = (px * by - bx * py) / det, l1 = (ax * py - px * ay) / det, l2 = 1.0 - l0 - l1;
    const double eps = -1e-9;
    if (l0 >= eps && l1 >= eps && l2 >= eps)
    {
      const auto& U = TextureCoordinates[k];
      uv = U[0] * l0 + U[1] * l1 + U[2] * l2;
      return true;
    }
  }
  return false;
}

ShapeDecal ShapeDistributor::Decal(int shape, double tolerance) const
{
  const Impl& I = *P;
  ShapeDecal decal;
  const PlacedShape& s = I.Placed.at(shape);
  const SafeDistanceClass& c = I.T.Classes[s.ClassId];
  const double scale = I.O.ShapeSize * s.Scale;
  const double reach = c.Radius * scale + I.MaxEdge;
  // Class-frame coordinates (normalized) of the vertices near the shape.
  std::vector<std::pair<int, Vec2>> local;
  std::shared_ptr<const CurveGrid> grid;
  if (s.Curve.empty())
  {
    const Impl::Record& r = I.Accepted.at(shape);
    if (r.Charts.empty())
    {
      return decal;
    }
    for (const ChartEntry& e : r.Charts[0].Entries)
    {
      const Vec2 q{ e.X, e.Y };
      if (Norm(q) <= reach)
      {
        local.emplace_back(e.V, q * (1.0 / scale));
      }
    }
  }
  else
  {
    grid = Frame(shape); // the grid the drawn check built (indexed), or a new one
    if (!grid)
    {
      return decal;
    }
    I.CurveShapeVertices(*grid, local);
  }
  std::sort(local.begin(), local.end(),
    [](const std::pair<int, Vec2>& a, const std::pair<int, Vec2>& b) { return a.first < b.first; });
  auto find = [&](int v) -> const Vec2* {
    auto it = std::lower_bound(local.begin(), local.end(), v,
      [](const std::pair<int, Vec2>& e, int value) { return e.first < value; });
    return it != local.end() && it->first == v ? &it->second : nullptr;
  };
  const auto toTexture = [&c](const Vec2& q) {
    return Vec2{ 0.5 * (q.x / c.Radius + 1.0), 0.5 * (q.y / c.Radius + 1.0) };
  };
  // The texels that draw: the silhouette's bounding box (2% of the circumradius around it, for
  // texture filtering) within the class square. Faces whose texture triangle misses it would
  // draw only transparent texels: not in the decal.
  Vec2 lo{ 1.0, 1.0 }, hi{ 0.0, 0.0 };
  for (const auto& ring : c.Outline.Rings)
  {
    for (const Vec2& p : ring)
    {
      const Vec2 u = toTexture(p);
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
  int hint = -1, firstValid = -1;
  if (grid)
  {
    for (int k = 0; k < static_cast<int>(grid->Nodes.size()) && firstValid < 0; ++k)
    {
      firstValid = grid->Nodes[k].Valid ? k : -1;
    }
  }
  // The shape's map at a point of face f: on the grid, or beyond it its affine extension (what
  // the corners' values are, CurveShapeVertices).
  const auto classAt = [&](int f, const std::array<double, 3>& b, Vec2& q) {
    // (Not from the previous point's node: where the map folds, at a kink of the curve, the
    // globally nearest node decides the sheet, the same for every point.)
    if (grid->ClassPoint(SurfacePoint::InFace(f, b[0], b[1], b[2]), q))
    {
      return true;
    }
    if (hint < 0)
    {
      hint = firstValid;
    }
    return grid->Locate(I.M.Interpolate(f, b), hint, q, nullptr, &hint);
  };
  // Faces checked for splitting: a long shape's faces wider than its grid's step (on smaller
  // faces the grid, affine per grid triangle, knows the map no better than the face's corners).
  const double tolUV = tolerance > 0.0 ? 0.5 * tolerance : 0.0; // texture units per circumradius
  const auto splits = [&](int f) {
    if (!grid || !(tolUV > 0.0))
    {
      return false;
    }
    const auto& v = I.M.Face(f);
    const double longest = std::max({ Norm(I.M.Position(v[1]) - I.M.Position(v[0])),
      Norm(I.M.Position(v[2]) - I.M.Position(v[1])), Norm(I.M.Position(v[0]) - I.M.Position(v[2])) });
    return longest > grid->Step;
  };
  // Faces with all corners known, near the shape (each face visited once, from its corner of
  // smallest index), whose texture triangle meets the class square.
  std::vector<int> faces;
  for (const auto& e : local)
  {
    for (int h : I.M.OutgoingHalfedges(e.first))
    {
      const auto& corners = I.M.Face(h / 3);
      if (e.first == std::min(corners[0], std::min(corners[1], corners[2])))
      {
        faces.push_back(h / 3);
      }
    }
  }
  std::sort(faces.begin(), faces.end());
  std::vector<std::pair<int, std::array<Vec2, 3>>> whole;
  std::unordered_map<int, Vec2> cornerValues; // vertices of faces to split, on the grid
  double orientation = 0.0; // the map's sense: the area-weighted sign of the texture triangles
  for (int f : faces)
  {
    std::array<Vec2, 3> uv;
    bool all = true;
    for (int k = 0; k < 3 && all; ++k)
    {
      const int v = I.M.Face(f)[k];
      const Vec2* q = find(v);
      all = q != nullptr;
      if (all)
      {
        // (The corners of a face to split are read like the points inside it, on the grid where
        // it reaches: where the map folds the grid decides the sheet, the same for all.)
        Vec2 value = *q;
        if (splits(f))
        {
          auto known = cornerValues.find(v);
          if (known == cornerValues.end())
          {
            Vec2 onGrid;
            known = cornerValues.emplace(v, grid->ClassPoint(SurfacePoint::AtVertex(v), onGrid) ? onGrid : *q).first;
          }
          value = known->second;
        }
        uv[k] = toTexture(value);
      }
    }
    if (all && MeetsBox(uv, lo, hi))
    {
      whole.emplace_back(f, uv);
      orientation += SignedArea(uv);
    }
  }
  // Each face's texture map is affine; where the true map departs from it by more than the
  // tolerance at an edge midpoint (a long shape's map along its curve, read on its grid), the
  // triangle is split in four, to depth 5 (1024 pieces per face). A piece whose texture
  // triangle is turned over (the map folds there) or stretched far beyond its size on the
  // surface (a jump across a seam of the map) is dropped.
  const int maxDepth = 5;
  const double sense = orientation >= 0.0 ? 1.0 : -1.0;
  const double unit = 2.0 * c.Radius * scale; // world length of one texture unit
  struct Piece
  {
    std::array<std::array<double, 3>, 3> B;
    std::array<Vec2, 3> U;
    int Depth;
  };
  std::vector<Piece> stack;
  std::unordered_map<std::uint64_t, std::pair<bool, Vec2>> midpoints; // face edges' midpoints
  for (const auto& entry : whole)
  {
    const int f = entry.first;
    const auto& corners = I.M.Face(f);
    const Vec3 X[3] = { I.M.Position(corners[0]), I.M.Position(corners[1]), I.M.Position(corners[2]) };
    const bool split = splits(f);
    stack.clear();
    stack.push_back(Piece{ { { { 1.0, 0.0, 0.0 }, { 0.0, 1.0, 0.0 }, { 0.0, 0.0, 1.0 } } }, entry.second, 0 });
    while (!stack.empty())
    {
      const Piece t = stack.back();
      stack.pop_back();
      if (!MeetsBox(t.U, lo, hi))
      {
        continue;
      }
      auto at = [&X](const std::array<double, 3>& b) { return X[0] * b[0] + X[1] * b[1] + X[2] * b[2]; };
      if (split)
      {
        std::array<std::array<double, 3>, 3> mid;
        std::array<Vec2, 3> trueUV;
        double error = 0.0;
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
          const auto known = t.Depth == 0 ? midpoints.find(edge) : midpoints.end();
          Vec2 q;
          bool found = false;
          if (known != midpoints.end())
          {
            found = known->second.first;
            q = known->second.second;
          }
          else
          {
            found = classAt(f, mid[k], q);
            if (t.Depth == 0)
            {
              midpoints.emplace(edge, std::make_pair(found, q));
            }
          }
          if (found)
          {
            trueUV[k] = toTexture(q);
            error = std::max(error, Norm(trueUV[k] - linear));
          }
          else
          {
            trueUV[k] = linear;
          }
        }
        // Finest: depth 5, or pieces as small as half the grid's step (it cannot tell more).
        const double size = std::max({ Norm(at(t.B[1]) - at(t.B[0])), Norm(at(t.B[2]) - at(t.B[1])),
          Norm(at(t.B[0]) - at(t.B[2])) });
        if (error > tolUV && (t.Depth == maxDepth || size <= 0.5 * grid->Step))
        {
          if (error > 5.0 * tolUV)
          {
            continue; // still not affine at the finest: the map folds or jumps here
          }
        }
        else if (error > tolUV)
        {
          // Corners 0, 1, 2 and midpoints m01, m12, m20.
          stack.push_back(Piece{ { { t.B[0], mid[0], mid[2] } }, { { t.U[0], trueUV[0], trueUV[2] } }, t.Depth + 1 });
          stack.push_back(Piece{ { { mid[0], t.B[1], mid[1] } }, { { trueUV[0], t.U[1], trueUV[1] } }, t.Depth + 1 });
          stack.push_back(Piece{ { { mid[2], mid[1], t.B[2] } }, { { trueUV[2], trueUV[1], t.U[2] } }, t.Depth + 1 });
          stack.push_back(Piece{ { { mid[0], mid[1], mid[2] } }, { { trueUV[0], trueUV[1], trueUV[2] } }, t.Depth + 1 });
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
        const double inTexture = Norm(t.U[(k + 1) % 3] - t.U[k]) * unit;
        torn = inTexture > 4.0 * onSurface + 0.05 * unit;
      }
      if (torn)
      {
        continue;
      }
      decal.Faces.push_back(f);
      decal.Corners.push_back(t.B);
      decal.TextureCoordinates.push_back(t.U);
    }
  }
  return decal;
}

} // namespace gs
