#include "SafeDistanceTable.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <limits>
#include <random>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double Empty = 1e300; // sentinel extent of an empty row

bool InCircle(const Circle& c, const Vec2& p)
{
  return Norm(p - c.Centre) <= c.Radius * (1.0 + 1e-12) + 1e-300;
}

Circle CircleFrom2(const Vec2& a, const Vec2& b)
{
  return { (a + b) * 0.5, 0.5 * Norm(a - b) };
}

Circle CircleFrom3(const Vec2& a, const Vec2& b, const Vec2& c)
{
  const Vec2 ab = b - a, ac = c - a;
  const double d = 2.0 * Cross(ab, ac);
  if (std::abs(d) <= 1e-14 * (Dot(ab, ab) + Dot(ac, ac)))
  {
    // Collinear: the circle on the farthest pair.
    Circle best = CircleFrom2(a, b);
    for (const Circle& other : { CircleFrom2(a, c), CircleFrom2(b, c) })
    {
      if (other.Radius > best.Radius)
        best = other;
    }
    return best;
  }
  const double ab2 = Dot(ab, ab), ac2 = Dot(ac, ac);
  const Vec2 centre{ a.x + (ac.y * ab2 - ab.y * ac2) / d, a.y + (ab.x * ac2 - ac.x * ab2) / d };
  return { centre, Norm(centre - a) };
}
} // namespace

//------------------------------------------------------------------------------
Circle SmallestEnclosingCircle(std::vector<Vec2> points)
{
  if (points.empty())
  {
    return {};
  }
  std::mt19937 random(12345u);
  std::shuffle(points.begin(), points.end(), random);
  Circle c{ points[0], 0.0 };
  for (std::size_t i = 1; i < points.size(); ++i)
  {
    if (InCircle(c, points[i]))
      continue;
    c = { points[i], 0.0 };
    for (std::size_t j = 0; j < i; ++j)
    {
      if (InCircle(c, points[j]))
        continue;
      c = CircleFrom2(points[i], points[j]);
      for (std::size_t k = 0; k < j; ++k)
      {
        if (!InCircle(c, points[k]))
          c = CircleFrom3(points[i], points[j], points[k]);
      }
    }
  }
  // Make containment exact whatever the rounding above did.
  for (const Vec2& p : points)
  {
    c.Radius = std::max(c.Radius, Norm(p - c.Centre));
  }
  return c;
}

//------------------------------------------------------------------------------
double SafeDistanceTables::BinWidth() const
{
  return 2.0 * Pi / this->AngleBins;
}

double SafeDistanceTables::Step(int a, int b) const
{
  return (this->Parts[a].Radius + this->Parts[b].Radius) / this->DistanceSteps;
}

int SafeDistanceTables::AngleBin(double alpha, int angleBins)
{
  const double w = 2.0 * Pi / angleBins;
  double bin = std::floor(alpha / w + 0.5);
  bin = std::fmod(bin, static_cast<double>(angleBins));
  if (bin < 0)
    bin += angleBins;
  return std::min(static_cast<int>(bin), angleBins - 1);
}

namespace
{
// Area moments of a region, about `ref`.
struct Moments
{
  double Area = 0, Cx = 0, Cy = 0, Sxx = 0, Syy = 0, Sxy = 0; // central second moments / area
};

Moments EvenOddMoments(const Shape2D& shape, const Vec2& ref)
{
  const std::array<double, 6> i = shape.EvenOddIntegrals(ref);
  Moments m;
  m.Area = i[0];
  if (!(m.Area > 0.0))
    return m;
  const double cx = i[1] / m.Area, cy = i[2] / m.Area;
  m.Cx = cx + ref.x;
  m.Cy = cy + ref.y;
  m.Sxx = i[3] / m.Area - cx * cx;
  m.Syy = i[4] / m.Area - cy * cy;
  m.Sxy = i[5] / m.Area - cx * cy;
  return m;
}

Moments GreenMoments(const Shape2D& shape, const Vec2& ref)
{
  double a = 0, mx = 0, my = 0, ixx = 0, iyy = 0, ixy = 0;
  for (const auto& ring : shape.Rings)
  {
    for (std::size_t k = 0, n = ring.size(); k < n; ++k)
    {
      const Vec2 p = ring[k] - ref, q = ring[(k + 1) % n] - ref;
      const double c = Cross(p, q);
      a += c;
      mx += (p.x + q.x) * c;
      my += (p.y + q.y) * c;
      ixx += (p.x * p.x + p.x * q.x + q.x * q.x) * c;
      iyy += (p.y * p.y + p.y * q.y + q.y * q.y) * c;
      ixy += (p.x * q.y + 2 * p.x * p.y + 2 * q.x * q.y + q.x * p.y) * c;
    }
  }
  Moments m;
  m.Area = 0.5 * a;
  if (m.Area == 0.0)
    return m;
  const double cx = mx / (3.0 * a), cy = my / (3.0 * a);
  m.Cx = cx + ref.x;
  m.Cy = cy + ref.y;
  m.Sxx = ixx / (12.0 * m.Area) - cx * cx;
  m.Syy = iyy / (12.0 * m.Area) - cy * cy;
  m.Sxy = ixy / (24.0 * m.Area) - cx * cy;
  return m;
}

// The region's moments under the even-odd rule: by Green's theorem over the oriented rings when
// they bound it (outer rings counter-clockwise, holes clockwise: their signed area is the
// filled area), else (rings that cross each other or themselves, repeated rings) by slabs.
Moments AreaMoments(const Shape2D& shape, const Vec2& ref, double filledArea)
{
  const double signedArea = shape.Area();
  if (!(std::abs(signedArea - filledArea) <= 1e-9 * filledArea))
  {
    return EvenOddMoments(shape, ref);
  }
  return GreenMoments(shape, ref);
}


// The boundary of the class region within the strip lo <= Dot(p - o, u) <= hi: the ring edges
// clipped to the strip, plus the pieces of the cut lines inside the region (even-odd pairs of
// the ring crossings along each line).
std::vector<Segment2> StripBoundary(
  const Shape2D& shape, const Vec2& o, const Vec2& u, double lo, double hi, bool cutLo, bool cutHi)
{
  const Vec2 v{ -u.y, u.x };
  std::vector<Segment2> edges;
  for (const auto& ring : shape.Rings)
  {
    for (std::size_t k = 0, n = ring.size(); k < n; ++k)
    {
      const Vec2& a = ring[k];
      const Vec2& b = ring[(k + 1) % n];
      const double sa = Dot(a - o, u), sb = Dot(b - o, u);
      double t0 = 0.0, t1 = 1.0;
      if (sa == sb)
      {
        if (sa < lo || sa > hi)
          continue;
      }
      else
      {
        double ta = (lo - sa) / (sb - sa), tb = (hi - sa) / (sb - sa);
        if (ta > tb)
          std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        if (t0 >= t1)
          continue;
      }
      edges.push_back({ a + (b - a) * t0, a + (b - a) * t1 });
    }
  }
  for (int side = 0; side < 2; ++side)
  {
    if (!(side == 0 ? cutLo : cutHi))
      continue;
    const double t = side == 0 ? lo : hi;
    std::vector<double> crossings;
    for (const auto& ring : shape.Rings)
    {
      for (std::size_t k = 0, n = ring.size(); k < n; ++k)
      {
        const Vec2& a = ring[k];
        const Vec2& b = ring[(k + 1) % n];
        const double sa = Dot(a - o, u), sb = Dot(b - o, u);
        if ((sa < t) != (sb < t))
        {
          const Vec2 p = a + (b - a) * ((t - sa) / (sb - sa));
          crossings.push_back(Dot(p - o, v));
        }
      }
    }
    std::sort(crossings.begin(), crossings.end());
    const Vec2 base = o + u * t;
    for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
    {
      edges.push_back({ base + v * crossings[k], base + v * crossings[k + 1] });
    }
  }
  return edges;
}

// Extent profiles of one part over all angle bins: Right/Left[bin * rows + row].
struct Profile
{
  std::vector<double> Right, Left;
  std::vector<int> FirstRow, LastRow; // per bin; FirstRow > LastRow when empty
};

void AddSegment(const Vec2& a, const Vec2& b, double delta, double Y, double h, int rows,
  double* right, double* left, int& firstRow, int& lastRow)
{
  const double ylo = std::min(a.y, b.y) - delta, yhi = std::max(a.y, b.y) + delta;
  const int r0 = std::max(0, static_cast<int>(std::floor((ylo + Y) / h)));
  const int r1 = std::min(rows - 1, static_cast<int>(std::floor((yhi + Y) / h)));
  const double dy = b.y - a.y;
  for (int r = r0; r <= r1; ++r)
  {
    double xmin, xmax;
    if (std::abs(dy) <= 1e-15 * Y)
    {
      xmin = std::min(a.x, b.x);
      xmax = std::max(a.x, b.x);
    }
    else
    {
      // Part of the segment whose y lies in the row widened by delta.
      const double y0 = -Y + r * h - delta, y1 = -Y + (r + 1) * h + delta;
      double t0 = (y0 - a.y) / dy, t1 = (y1 - a.y) / dy;
      if (t0 > t1)
        std::swap(t0, t1);
      t0 = std::max(t0, 0.0);
      t1 = std::min(t1, 1.0);
      if (t0 > t1)
        continue;
      const double x0 = a.x + (b.x - a.x) * t0, x1 = a.x + (b.x - a.x) * t1;
      xmin = std::min(x0, x1);
      xmax = std::max(x0, x1);
    }
    right[r] = std::max(right[r], xmax + delta);
    left[r] = std::min(left[r], xmin - delta);
    firstRow = std::min(firstRow, r);
    lastRow = std::max(lastRow, r);
  }
}
// The options ComputeSafeDistanceParts looks at.
Status CheckAspectRatio(const SafeDistanceOptions& options)
{
  if (!(options.MaximumAspectRatio >= 1.0))
  {
    return Status::Error(
      "MaximumAspectRatio must be at least 1, got " + std::to_string(options.MaximumAspectRatio));
  }
  return Status();
}

// The options ComputeSafeDistanceValues looks at.
Status CheckTableOptions(const SafeDistanceOptions& options)
{
  const int ka = options.AngleBins, kr = options.DistanceSteps;
  if (ka < 1 || ka > 4096)
  {
    return Status::Error("AngleBins must be in [1, 4096], got " + std::to_string(ka));
  }
  // (Steps much finer than the extent profiles' rows add time, not precision: 4096 steps take
  // about a second per pair of parts, 2^20 would take minutes.)
  if (kr < 1 || kr > 4096)
  {
    return Status::Error("DistanceSteps must be in [1, 4096], got " + std::to_string(kr) +
      " (steps finer than the 1024-row extent profiles add time, not precision)");
  }
  if (options.Rows < 2 || options.Rows > 1 << 20 || options.RotationSamples < 0 ||
    options.RotationSamples > 4096)
  {
    return Status::Error("Rows must be in [2, 1048576] and RotationSamples in [0, 4096]");
  }
  return Status();
}
} // namespace

namespace
{
// Every ring point of `input`, in ring order; fails naming the shape when a point is not finite.
Status CollectRingPoints(const SafeDistanceInput& input, std::vector<Vec2>& points)
{
  for (const auto& ring : input.Shape.Rings)
  {
    for (const Vec2& p : ring)
    {
      if (!std::isfinite(p.x) || !std::isfinite(p.y))
      {
        return Status::Error("shape '" + input.Name + "' has non-finite coordinates");
      }
      points.push_back(p);
    }
  }
  return Status();
}

// The rings of `shape` in normalized units: origin at `centre`, divided by `scale`.
void AddNormalizedRings(const Shape2D& shape, const Vec2& centre, double scale, Shape2D& outline)
{
  for (const auto& ring : shape.Rings)
  {
    std::vector<Vec2> r;
    r.reserve(ring.size());
    for (const Vec2& p : ring)
    {
      r.push_back((p - centre) * (1.0 / scale));
    }
    outline.Rings.push_back(std::move(r));
  }
}

// The principal axes of a class's area through its centroid, and the extent of its outline
// along them (long shapes are cut across the major axis, Fig. 7).
struct PrincipalFrame
{
  Vec2 U, V;  // major and minor axes (unit vectors)
  Vec2 Origin; // the area's centroid
  double ULo = 1e300, UHi = -1e300, VLo = 1e300, VHi = -1e300;
};

// The principal frame of `outline`, whose even-odd area is `filledArea`.
PrincipalFrame ComputePrincipalFrame(const Shape2D& outline, double filledArea)
{
  const Moments m = AreaMoments(outline, outline.Rings[0][0], filledArea);
  const double angle = 0.5 * std::atan2(2.0 * m.Sxy, m.Sxx - m.Syy);
  PrincipalFrame frame;
  const Vec2 u{ std::cos(angle), std::sin(angle) }, v{ -u.y, u.x };
  const Vec2 o{ m.Cx, m.Cy };
  frame.U = u;
  frame.V = v;
  frame.Origin = o;
  for (const auto& ring : outline.Rings)
  {
    for (const Vec2& p : ring)
    {
      frame.ULo = std::min(frame.ULo, Dot(p - o, u));
      frame.UHi = std::max(frame.UHi, Dot(p - o, u));
      frame.VLo = std::min(frame.VLo, Dot(p - o, v));
      frame.VHi = std::max(frame.VHi, Dot(p - o, v));
    }
  }
  return frame;
}

// The boundary of part k of `parts` (slices of equal width across the major axis); for a split
// class, also sets the part's axis and bounds.
std::vector<Segment2> PartBoundary(
  const Shape2D& outline, const PrincipalFrame& frame, int k, int parts, SafeDistancePart& part)
{
  const Vec2& o = frame.Origin;
  const Vec2& u = frame.U;
  if (parts == 1)
  {
    return StripBoundary(outline, o, u, -1e300, 1e300, false, false);
  }
  const double ulo = frame.ULo, uhi = frame.UHi;
  const double lo = ulo + (uhi - ulo) * k / parts, hi = ulo + (uhi - ulo) * (k + 1) / parts;
  std::vector<Segment2> edges = StripBoundary(
    outline, o, u, k == 0 ? -1e300 : lo, k == parts - 1 ? 1e300 : hi, k > 0, k < parts - 1);
  part.Axis = u;
  part.From = k == 0 ? -1e300 : lo + Dot(o, u);
  part.To = k == parts - 1 ? 1e300 : hi + Dot(o, u);
  return edges;
}

// Gives `part` its circle (the class circle when the class is not split, else the smallest
// circle around its boundary) and its boundary `edges` relative to that circle's centre.
void SetPartCircle(SafeDistancePart& part, std::vector<Segment2>&& edges, int parts, double classRadius)
{
  std::vector<Vec2> ends;
  for (const Segment2& e : edges)
  {
    ends.push_back(e.A);
    ends.push_back(e.B);
  }
  const Circle circle = parts == 1 ? Circle{ { 0.0, 0.0 }, classRadius }
                                   : SmallestEnclosingCircle(ends);
  part.Centre = circle.Centre;
  part.Radius = circle.Radius;
  for (Segment2& e : edges)
  {
    e.A = e.A - circle.Centre;
    e.B = e.B - circle.Centre;
    part.Radius = std::max({ part.Radius, Norm(e.A), Norm(e.B) });
  }
  part.Edges = std::move(edges);
}

// Cuts class `cls` (id `classId`) into `parts` slices across its major axis and appends the
// non-empty ones to `allParts`, recording their indices in the class.
void AddClassParts(SafeDistanceClass& cls, const PrincipalFrame& frame, int classId, int parts,
  std::vector<SafeDistancePart>& allParts)
{
  for (int k = 0; k < parts; ++k)
  {
    SafeDistancePart part;
    part.ClassId = classId;
    part.Index = static_cast<int>(cls.Parts.size());
    std::vector<Segment2> edges = PartBoundary(cls.Outline, frame, k, parts, part);
    if (edges.empty())
      continue;
    SetPartCircle(part, std::move(edges), parts, cls.Radius);
    cls.Parts.push_back(static_cast<int>(allParts.size()));
    allParts.push_back(std::move(part));
  }
}

// Appends class `classId` made from `input` to `tables`: its circle, normalized outline,
// principal axes and parts. The first class sets the tables' scale.
Status AddClass(const SafeDistanceInput& input, int classId, const SafeDistanceOptions& options,
  SafeDistanceTables& tables)
{
  const Shape2D& shape = input.Shape;
  std::vector<Vec2> points;
  if (Status finite = CollectRingPoints(input, points); !finite.Ok())
  {
    return finite;
  }
  const double filled = points.size() < 3 ? 0.0 : shape.FilledArea();
  if (!(filled > 0.0))
  {
    return Status::Error("shape '" + input.Name +
      "' is empty: its rings enclose no area under the even-odd rule");
  }
  SafeDistanceClass cls;
  cls.Name = input.Name;
  cls.SourceCircle = SmallestEnclosingCircle(points);
  if (classId == 0)
  {
    tables.Scale = cls.SourceCircle.Radius;
  }
  cls.Radius = cls.SourceCircle.Radius / tables.Scale;
  AddNormalizedRings(shape, cls.SourceCircle.Centre, tables.Scale, cls.Outline);
  const double scale2 = 1.0 / (tables.Scale * tables.Scale);
  const PrincipalFrame frame = ComputePrincipalFrame(cls.Outline, filled * scale2);
  cls.MajorAxis = frame.U;
  cls.AspectRatio = (frame.UHi - frame.ULo) / std::max(frame.VHi - frame.VLo, 1e-300);
  int parts = 1;
  if (cls.AspectRatio > options.MaximumAspectRatio)
  {
    parts = static_cast<int>(std::ceil(cls.AspectRatio / options.MaximumAspectRatio));
  }
  AddClassParts(cls, frame, classId, parts, tables.Parts);
  tables.Classes.push_back(std::move(cls));
  return Status();
}
} // namespace

//------------------------------------------------------------------------------
Result<SafeDistanceTables> ComputeSafeDistanceParts(
  const std::vector<SafeDistanceInput>& shapes, const SafeDistanceOptions& options)
{
  if (shapes.empty())
  {
    return Status::Error("no shape");
  }
  if (Status aspect = CheckAspectRatio(options); !aspect.Ok())
  {
    return aspect;
  }
  SafeDistanceTables tables;
  // Classes: circles, normalization, moments, parts.
  for (std::size_t c = 0; c < shapes.size(); ++c)
  {
    if (Status added = AddClass(shapes[c], static_cast<int>(c), options, tables); !added.Ok())
    {
      return added;
    }
  }
  return tables;
}

//------------------------------------------------------------------------------
Status CheckSafeDistanceTableSize(int parts, int angleBins)
{
  const double bytes =
    static_cast<double>(parts) * parts * angleBins * angleBins * sizeof(double);
  if (bytes <= MaximumSafeDistanceTableBytes)
  {
    return Status();
  }
  return Status::Error(std::to_string(parts) + " parts at " + std::to_string(angleBins) +
    " angle bins need " + std::to_string(static_cast<long long>(bytes / 1e6)) +
    " MB of tables (limit " +
    std::to_string(static_cast<long long>(MaximumSafeDistanceTableBytes / 1e6)) +
    " MB): use fewer shapes, parts or AngleBins");
}

//------------------------------------------------------------------------------
Status CheckSafeDistanceOptions(const SafeDistanceOptions& options)
{
  if (Status table = CheckTableOptions(options); !table.Ok())
  {
    return table;
  }
  return CheckAspectRatio(options);
}

namespace
{
// Whether the computation goes on: no callback, or the callback says so at fraction `value`.
bool ReportProgress(const std::function<bool(double)>& progress, double value)
{
  return !progress || progress(value);
}

// The row grid of the extent profiles and the rotation sampling of their angle bins.
struct ProfileGrid
{
  int AngleBins = 1;       // ka
  int RotationSamples = 1; // s: rotations sampled per bin
  double BinWidth = 0.0;   // w
  double Dilation = 0.0;   // widening of the segments that covers the rotations between samples
  int Rows = 2;
  double Y = 0.0;   // the rows cover [-Y, Y]
  double H = 0.0;   // row height
  double Eps = 0.0; // rounding of rotations
  bool Conservative = true;
};

// Sets the table settings of `tables` from `options` (the rotation samples: as asked, or
// enough for the distance steps in conservative mode, 1 otherwise) and empties its values.
void SetTableSettings(SafeDistanceTables& tables, const SafeDistanceOptions& options)
{
  const int ka = options.AngleBins, kr = options.DistanceSteps;
  tables.AngleBins = ka;
  tables.DistanceSteps = kr;
  tables.Conservative = options.Conservative;
  tables.RotationSamples = !options.Conservative
    ? 1
    : (options.RotationSamples > 0
          ? options.RotationSamples
          : std::max(1, static_cast<int>(std::ceil(8.0 * Pi * kr / ka - 1e-9))));
  tables.Values.clear();
}

// The profile grid for the parts of `tables`: rows over the largest part radius plus the
// rotation dilation.
ProfileGrid MakeProfileGrid(const SafeDistanceTables& tables, const SafeDistanceOptions& options)
{
  ProfileGrid grid;
  grid.AngleBins = options.AngleBins;
  grid.RotationSamples = tables.RotationSamples;
  grid.Conservative = options.Conservative;
  grid.BinWidth = 2.0 * Pi / grid.AngleBins;
  grid.Dilation =
    options.Conservative ? 2.0 * std::sin(grid.BinWidth / (4.0 * grid.RotationSamples)) : 0.0;
  double maxRadius = 0.0;
  for (const auto& part : tables.Parts)
  {
    maxRadius = std::max(maxRadius, part.Radius);
  }
  grid.Rows = options.Rows;
  grid.Y = maxRadius * (1.0 + grid.Dilation) * (1.0 + 1e-9) + 1e-12;
  grid.H = 2.0 * grid.Y / grid.Rows;
  grid.Eps = options.Conservative ? 1e-12 * maxRadius : 0.0;
  return grid;
}

// The extent profile of `part` at angle bin `bin`, over its rotation samples, into the bin's
// rows `right` and `left` and its first and last occupied rows.
void ProfileBin(const SafeDistancePart& part, const ProfileGrid& grid, int bin, double* right,
  double* left, int& first, int& last)
{
  const int s = grid.RotationSamples;
  const double w = grid.BinWidth;
  for (int k = 0; k < s; ++k)
  {
    const double theta = grid.Conservative ? bin * w + ((k + 0.5) / s - 0.5) * w : bin * w;
    const double cs = std::cos(theta), sn = std::sin(theta);
    for (const Segment2& e : part.Edges)
    {
      const Vec2 a{ cs * e.A.x - sn * e.A.y, sn * e.A.x + cs * e.A.y };
      const Vec2 b{ cs * e.B.x - sn * e.B.y, sn * e.B.x + cs * e.B.y };
      const double delta = grid.Dilation * std::max(Norm(e.A), Norm(e.B)) + grid.Eps;
      AddSegment(a, b, delta, grid.Y, grid.H, grid.Rows, right, left, first, last);
    }
  }
}

// Extent profiles of every part at every angle bin, on one row grid over [-Y, Y] (one
// parallel job per part and bin). Sets `aborted` when the progress callback says stop.
std::vector<Profile> ComputeProfiles(const SafeDistanceTables& tables, const ProfileGrid& grid,
  const std::function<bool(double)>& progress, std::atomic<bool>& aborted)
{
  const int P = tables.NumberOfParts();
  const int ka = grid.AngleBins, rows = grid.Rows;
  std::vector<Profile> profiles(P);
  for (auto& p : profiles)
  {
    p.Right.assign(static_cast<std::size_t>(ka) * rows, -Empty);
    p.Left.assign(static_cast<std::size_t>(ka) * rows, Empty);
    p.FirstRow.assign(ka, rows);
    p.LastRow.assign(ka, -1);
  }
  const long long profileJobs = static_cast<long long>(P) * ka;
#pragma omp parallel for schedule(dynamic, 1)
  for (long long job = 0; job < profileJobs; ++job)
  {
    if (aborted.load(std::memory_order_relaxed))
      continue;
    const int pi = static_cast<int>(job / ka), bin = static_cast<int>(job % ka);
    Profile& prof = profiles[pi];
    double* right = &prof.Right[static_cast<std::size_t>(bin) * rows];
    double* left = &prof.Left[static_cast<std::size_t>(bin) * rows];
    int first = rows, last = -1;
    ProfileBin(tables.Parts[pi], grid, bin, right, left, first, last);
    prof.FirstRow[bin] = first;
    prof.LastRow[bin] = last;
#ifdef _OPENMP
    if (omp_get_thread_num() == 0)
#endif
    {
      if (!ReportProgress(progress, 0.05 + 0.25 * static_cast<double>(job) / profileJobs))
        aborted = true;
    }
  }
  return profiles;
}

// Row j of the table of parts (a, b) into `out` (ka entries): per bin i of A, the largest
// right extent of A minus left extent of B over their common rows, rounded up to the step grid
// and capped at maxD.
void FillTableRow(const Profile& A, const Profile& B, int j, int ka, int rows, double maxD,
  double step, double* out)
{
  const double* left = &B.Left[static_cast<std::size_t>(j) * rows];
  for (int i = 0; i < ka; ++i)
  {
    const double* right = &A.Right[static_cast<std::size_t>(i) * rows];
    const int r0 = std::max(A.FirstRow[i], B.FirstRow[j]);
    const int r1 = std::min(A.LastRow[i], B.LastRow[j]);
    double D = 0.0;
    for (int r = r0; r <= r1; ++r)
    {
      D = std::max(D, right[r] - left[r]);
    }
    out[i] = std::min(std::ceil(D / step) * step, maxD);
  }
}

// The tables: D = max over rows of (right extent of A - left extent of B), rounded up to the
// step grid and capped at r_a + r_b (the circles cannot overlap beyond). One parallel job per
// table row (profiles of `rows` rows per bin); sets `aborted` when the progress callback says
// stop.
void ComputeTables(SafeDistanceTables& tables, const std::vector<Profile>& profiles, int rows,
  const std::function<bool(double)>& progress, std::atomic<bool>& aborted)
{
  const int P = tables.NumberOfParts();
  const int ka = tables.AngleBins, kr = tables.DistanceSteps;
  const std::size_t tableSize = static_cast<std::size_t>(ka) * ka;
  tables.Values.assign(static_cast<std::size_t>(P) * P * tableSize, 0.0);
  const long long tableJobs = static_cast<long long>(P) * P * ka; // one job per table row j
#pragma omp parallel for schedule(dynamic, 4)
  for (long long job = 0; job < tableJobs; ++job)
  {
    if (aborted.load(std::memory_order_relaxed))
      continue;
    const int pair = static_cast<int>(job / ka), j = static_cast<int>(job % ka);
    const int a = pair / P, b = pair % P;
    const double maxD = tables.Parts[a].Radius + tables.Parts[b].Radius;
    const double step = maxD / kr;
    double* out = &tables.Values[pair * tableSize + static_cast<std::size_t>(j) * ka];
    FillTableRow(profiles[a], profiles[b], j, ka, rows, maxD, step, out);
#ifdef _OPENMP
    if (omp_get_thread_num() == 0)
#endif
    {
      if (!ReportProgress(progress, 0.3 + 0.7 * static_cast<double>(job) / tableJobs))
        aborted = true;
    }
  }
}
} // namespace

//------------------------------------------------------------------------------
Result<SafeDistanceTables> ComputeSafeDistanceValues(SafeDistanceTables parts,
  const SafeDistanceOptions& options, const std::function<bool(double)>& progress)
{
  const int ka = options.AngleBins;
  if (parts.Parts.empty())
  {
    return Status::Error("no shape");
  }
  if (Status table = CheckTableOptions(options); !table.Ok())
  {
    return table;
  }
  if (Status size = CheckSafeDistanceTableSize(parts.NumberOfParts(), ka); !size.Ok())
  {
    return size;
  }
  if (!ReportProgress(progress, 0.05))
  {
    return Status::Aborted();
  }

  SafeDistanceTables tables = std::move(parts);
  SetTableSettings(tables, options);
  const ProfileGrid grid = MakeProfileGrid(tables, options);
  std::atomic<bool> aborted(false);
  const std::vector<Profile> profiles = ComputeProfiles(tables, grid, progress, aborted);
  if (aborted)
  {
    return Status::Aborted();
  }
  ComputeTables(tables, profiles, grid.Rows, progress, aborted);
  if (aborted)
  {
    return Status::Aborted();
  }
  ReportProgress(progress, 1.0);
  return tables;
}

//------------------------------------------------------------------------------
Result<SafeDistanceTables> ComputeSafeDistanceTables(const std::vector<SafeDistanceInput>& shapes,
  const SafeDistanceOptions& options, const std::function<bool(double)>& progress)
{
  Result<SafeDistanceTables> parts = ComputeSafeDistanceParts(shapes, options);
  if (!parts.Ok())
  {
    return parts;
  }
  return ComputeSafeDistanceValues(std::move(*parts), options, progress);
}

} // namespace gs
