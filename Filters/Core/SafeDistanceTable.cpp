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
    const Shape2D& shape = shapes[c].Shape;
    std::vector<Vec2> points;
    for (const auto& ring : shape.Rings)
    {
      for (const Vec2& p : ring)
      {
        if (!std::isfinite(p.x) || !std::isfinite(p.y))
        {
          return Status::Error("shape '" + shapes[c].Name + "' has non-finite coordinates");
        }
        points.push_back(p);
      }
    }
    const double filled = points.size() < 3 ? 0.0 : shape.FilledArea();
    if (!(filled > 0.0))
    {
      return Status::Error("shape '" + shapes[c].Name +
        "' is empty: its rings enclose no area under the even-odd rule");
    }
    SafeDistanceClass cls;
    cls.Name = shapes[c].Name;
    cls.SourceCircle = SmallestEnclosingCircle(points);
    if (c == 0)
    {
      tables.Scale = cls.SourceCircle.Radius;
    }
    cls.Radius = cls.SourceCircle.Radius / tables.Scale;
    for (const auto& ring : shape.Rings)
    {
      std::vector<Vec2> r;
      r.reserve(ring.size());
      for (const Vec2& p : ring)
      {
        r.push_back((p - cls.SourceCircle.Centre) * (1.0 / tables.Scale));
      }
      cls.Outline.Rings.push_back(std::move(r));
    }
    // Principal axes of the area (Fig. 7: long shapes are cut across the major axis).
    const double scale2 = 1.0 / (tables.Scale * tables.Scale);
    const Moments m = AreaMoments(cls.Outline, cls.Outline.Rings[0][0], filled * scale2);
    const double angle = 0.5 * std::atan2(2.0 * m.Sxy, m.Sxx - m.Syy);
    const Vec2 u{ std::cos(angle), std::sin(angle) }, v{ -u.y, u.x };
    const Vec2 o{ m.Cx, m.Cy };
    double ulo = 1e300, uhi = -1e300, vlo = 1e300, vhi = -1e300;
    for (const auto& ring : cls.Outline.Rings)
    {
      for (const Vec2& p : ring)
      {
        ulo = std::min(ulo, Dot(p - o, u));
        uhi = std::max(uhi, Dot(p - o, u));
        vlo = std::min(vlo, Dot(p - o, v));
        vhi = std::max(vhi, Dot(p - o, v));
      }
    }
    cls.MajorAxis = u;
    cls.AspectRatio = (uhi - ulo) / std::max(vhi - vlo, 1e-300);
    int parts = 1;
    if (cls.AspectRatio > options.MaximumAspectRatio)
    {
      parts = static_cast<int>(std::ceil(cls.AspectRatio / options.MaximumAspectRatio));
    }
    const int classId = static_cast<int>(c);
    for (int k = 0; k < parts; ++k)
    {
      SafeDistancePart part;
      part.ClassId = classId;
      part.Index = static_cast<int>(cls.Parts.size());
      std::vector<Segment2> edges;
      if (parts == 1)
      {
        edges = StripBoundary(cls.Outline, o, u, -1e300, 1e300, false, false);
      }
      else
      {
        const double lo = ulo + (uhi - ulo) * k / parts, hi = ulo + (uhi - ulo) * (k + 1) / parts;
        edges = StripBoundary(cls.Outline, o, u, k == 0 ? -1e300 : lo,
          k == parts - 1 ? 1e300 : hi, k > 0, k < parts - 1);
        part.Axis = u;
        part.From = k == 0 ? -1e300 : lo + Dot(o, u);
        part.To = k == parts - 1 ? 1e300 : hi + Dot(o, u);
      }
      if (edges.empty())
        continue;
      std::vector<Vec2> ends;
      for (const Segment2& e : edges)
      {
        ends.push_back(e.A);
        ends.push_back(e.B);
      }
      const Circle circle = parts == 1 ? Circle{ { 0.0, 0.0 }, cls.Radius }
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
      cls.Parts.push_back(static_cast<int>(tables.Parts.size()));
      tables.Parts.push_back(std::move(part));
    }
    tables.Classes.push_back(std::move(cls));
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

//------------------------------------------------------------------------------
Result<SafeDistanceTables> ComputeSafeDistanceValues(SafeDistanceTables parts,
  const SafeDistanceOptions& options, const std::function<bool(double)>& progress)
{
  const int ka = options.AngleBins, kr = options.DistanceSteps;
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
  auto report = [&](double value) { return !progress || progress(value); };
  if (!report(0.05))
  {
    return Status::Aborted();
  }

  SafeDistanceTables tables = std::move(parts);
  tables.AngleBins = ka;
  tables.DistanceSteps = kr;
  tables.Conservative = options.Conservative;
  tables.RotationSamples = !options.Conservative
    ? 1
    : (options.RotationSamples > 0
          ? options.RotationSamples
          : std::max(1, static_cast<int>(std::ceil(8.0 * Pi * kr / ka - 1e-9))));
  tables.Values.clear();

  // 2. Extent profiles of every part at every angle bin, on one row grid over [-Y, Y].
  const int P = tables.NumberOfParts();
  const int s = tables.RotationSamples;
  const double w = 2.0 * Pi / ka;
  const double dilation = options.Conservative ? 2.0 * std::sin(w / (4.0 * s)) : 0.0;
  double maxRadius = 0.0;
  for (const auto& part : tables.Parts)
  {
    maxRadius = std::max(maxRadius, part.Radius);
  }
  const int rows = options.Rows;
  const double Y = maxRadius * (1.0 + dilation) * (1.0 + 1e-9) + 1e-12;
  const double h = 2.0 * Y / rows;
  const double eps = options.Conservative ? 1e-12 * maxRadius : 0.0; // rounding of rotations
  std::vector<Profile> profiles(P);
  for (auto& p : profiles)
  {
    p.Right.assign(static_cast<std::size_t>(ka) * rows, -Empty);
    p.Left.assign(static_cast<std::size_t>(ka) * rows, Empty);
    p.FirstRow.assign(ka, rows);
    p.LastRow.assign(ka, -1);
  }
  std::atomic<bool> aborted(false);
  const long long profileJobs = static_cast<long long>(P) * ka;
#pragma omp parallel for schedule(dynamic, 1)
  for (long long job = 0; job < profileJobs; ++job)
  {
    if (aborted.load(std::memory_order_relaxed))
      continue;
    const int pi = static_cast<int>(job / ka), bin = static_cast<int>(job % ka);
    const SafeDistancePart& part = tables.Parts[pi];
    Profile& prof = profiles[pi];
    double* right = &prof.Right[static_cast<std::size_t>(bin) * rows];
    double* left = &prof.Left[static_cast<std::size_t>(bin) * rows];
    int first = rows, last = -1;
    for (int k = 0; k < s; ++k)
    {
      const double theta =
        options.Conservative ? bin * w + ((k + 0.5) / s - 0.5) * w : bin * w;
      const double cs = std::cos(theta), sn = std::sin(theta);
      for (const Segment2& e : part.Edges)
      {
        const Vec2 a{ cs * e.A.x - sn * e.A.y, sn * e.A.x + cs * e.A.y };
        const Vec2 b{ cs * e.B.x - sn * e.B.y, sn * e.B.x + cs * e.B.y };
        const double delta = dilation * std::max(Norm(e.A), Norm(e.B)) + eps;
        AddSegment(a, b, delta, Y, h, rows, right, left, first, last);
      }
    }
    prof.FirstRow[bin] = first;
    prof.LastRow[bin] = last;
#ifdef _OPENMP
    if (omp_get_thread_num() == 0)
#endif
    {
      if (!report(0.05 + 0.25 * static_cast<double>(job) / profileJobs))
        aborted = true;
    }
  }
  if (aborted)
  {
    return Status::Aborted();
  }

  // 3. Tables: D = max over rows of (right extent of A - left extent of B), rounded up to the
  //    step grid and capped at r_a + r_b (the circles cannot overlap beyond).
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
    const Profile& A = profiles[a];
    const Profile& B = profiles[b];
    const double maxD = tables.Parts[a].Radius + tables.Parts[b].Radius;
    const double step = maxD / kr;
    const double* left = &B.Left[static_cast<std::size_t>(j) * rows];
    double* out = &tables.Values[pair * tableSize + static_cast<std::size_t>(j) * ka];
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
#ifdef _OPENMP
    if (omp_get_thread_num() == 0)
#endif
    {
      if (!report(0.3 + 0.7 * static_cast<double>(job) / tableJobs))
        aborted = true;
    }
  }
  if (aborted)
  {
    return Status::Aborted();
  }
  report(1.0);
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
