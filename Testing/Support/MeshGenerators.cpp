#include "MeshGenerators.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <utility>

namespace gs
{

namespace
{
constexpr double Pi = 3.14159265358979323846;

// Adds the two triangles of quad (a, b, c, d), counter-clockwise, split along a-c or b-d.
void AddQuad(TriangleSoup& s, long long a, long long b, long long c, long long d, bool alternate)
{
  if (alternate)
  {
    s.Triangles.push_back({ a, b, d });
    s.Triangles.push_back({ b, c, d });
  }
  else
  {
    s.Triangles.push_back({ a, b, c });
    s.Triangles.push_back({ a, c, d });
  }
}
} // namespace

TriangleSoup MakePlanarGrid(int nx, int ny, double sizeX, double sizeY)
{
  TriangleSoup s;
  for (int j = 0; j <= ny; ++j)
  {
    for (int i = 0; i <= nx; ++i)
    {
      s.Points.emplace_back(sizeX * i / nx, sizeY * j / ny, 0.0);
    }
  }
  auto id = [&](int i, int j) { return static_cast<long long>(j) * (nx + 1) + i; };
  for (int j = 0; j < ny; ++j)
  {
    for (int i = 0; i < nx; ++i)
    {
      AddQuad(s, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 1);
    }
  }
  return s;
}

TriangleSoup MakeIrregularPlanarGrid(int n, double side, double jitter, bool randomDiagonals, unsigned seed)
{
  TriangleSoup s = MakePlanarGrid(n, n, side, side);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> move(-jitter * side / n, jitter * side / n);
  for (Vec3& p : s.Points)
  {
    if (p.x > 1e-9 && p.y > 1e-9 && p.x < side - 1e-9 && p.y < side - 1e-9)
    {
      p.x += move(rng);
      p.y += move(rng);
    }
  }
  if (randomDiagonals)
  {
    std::bernoulli_distribution flip(0.5);
    s.Triangles.clear();
    for (long long y = 0; y < n; ++y)
    {
      for (long long x = 0; x < n; ++x)
      {
        const long long a = y * (n + 1) + x, b = a + 1, c = a + n + 1, d = c + 1;
        if (flip(rng))
        {
          s.Triangles.push_back({ a, b, d });
          s.Triangles.push_back({ a, d, c });
        }
        else
        {
          s.Triangles.push_back({ a, b, c });
          s.Triangles.push_back({ b, d, c });
        }
      }
    }
  }
  return s;
}

TriangleSoup MakeLShape(int n)
{
  TriangleSoup s;
  const int m = 2 * n;
  std::map<std::pair<int, int>, long long> ids;
  auto id = [&](int i, int j) {
    auto it = ids.find({ i, j });
    if (it != ids.end())
    {
      return it->second;
    }
    const long long k = static_cast<long long>(s.Points.size());
    s.Points.emplace_back(static_cast<double>(i) / n, static_cast<double>(j) / n, 0.0);
    ids[{ i, j }] = k;
    return k;
  };
  for (int j = 0; j < m; ++j)
  {
    for (int i = 0; i < m; ++i)
    {
      if (i >= n && j >= n)
      {
        continue; // the removed upper-right square
      }
      AddQuad(s, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 1);
    }
  }
  return s;
}

TriangleSoup MakeCone(double halfAngle, double slant, int rings, int sectors)
{
  TriangleSoup s;
  const double height = slant * std::cos(halfAngle);
  s.Points.emplace_back(0.0, 0.0, height); // apex
  for (int i = 1; i <= rings; ++i)
  {
    const double r = slant * i / rings;
    for (int j = 0; j < sectors; ++j)
    {
      const double a = 2.0 * Pi * j / sectors;
      const double rho = r * std::sin(halfAngle);
      s.Points.emplace_back(rho * std::cos(a), rho * std::sin(a), height - r * std::cos(halfAngle));
    }
  }
  auto id = [&](int i, int j) { return 1 + static_cast<long long>(i - 1) * sectors + (j % sectors); };
  for (int j = 0; j < sectors; ++j)
  {
    s.Triangles.push_back({ 0, id(1, j + 1), id(1, j) });
  }
  for (int i = 1; i < rings; ++i)
  {
    for (int j = 0; j < sectors; ++j)
    {
      AddQuad(s, id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j), (i + j) % 2 == 1);
    }
  }
  return s;
}

TriangleSoup MakeCylinder(double radius, double height, int sectors, int rings)
{
  TriangleSoup s;
  for (int i = 0; i <= rings; ++i)
  {
    for (int j = 0; j < sectors; ++j)
    {
      const double a = 2.0 * Pi * j / sectors;
      s.Points.emplace_back(radius * std::cos(a), radius * std::sin(a), height * i / rings);
    }
  }
  auto id = [&](int i, int j) { return static_cast<long long>(i) * sectors + (j % sectors); };
  for (int i = 0; i < rings; ++i)
  {
    for (int j = 0; j < sectors; ++j)
    {
      AddQuad(s, id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j), (i + j) % 2 == 1);
    }
  }
  return s;
}

TriangleSoup MakeIcosphere(double radius, int level)
{
  TriangleSoup s;
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  const double base[12][3] = { { -1, t, 0 }, { 1, t, 0 }, { -1, -t, 0 }, { 1, -t, 0 },
    { 0, -1, t }, { 0, 1, t }, { 0, -1, -t }, { 0, 1, -t }, { t, 0, -1 }, { t, 0, 1 },
    { -t, 0, -1 }, { -t, 0, 1 } };
  for (const auto& p : base)
  {
    Vec3 v(p[0], p[1], p[2]);
    s.Points.push_back(v / Norm(v));
  }
  s.Triangles = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 },
    { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 },
    { 3, 4, 2 }, { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 },
    { 6, 2, 10 }, { 8, 6, 7 }, { 9, 8, 1 } };
  for (int l = 0; l < level; ++l)
  {
    std::map<std::pair<long long, long long>, long long> mid;
    auto midpoint = [&](long long a, long long b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end())
      {
        return it->second;
      }
      Vec3 m = (s.Points[a] + s.Points[b]) * 0.5;
      const long long k = static_cast<long long>(s.Points.size());
      s.Points.push_back(m / Norm(m));
      mid[key] = k;
      return k;
    };
    std::vector<std::array<long long, 3>> next;
    next.reserve(4 * s.Triangles.size());
    for (const auto& tri : s.Triangles)
    {
      const long long a = midpoint(tri[0], tri[1]);
      const long long b = midpoint(tri[1], tri[2]);
      const long long c = midpoint(tri[2], tri[0]);
      next.push_back({ tri[0], a, c });
      next.push_back({ tri[1], b, a });
      next.push_back({ tri[2], c, b });
      next.push_back({ a, b, c });
    }
    s.Triangles = std::move(next);
  }
  for (Vec3& p : s.Points)
  {
    p = p * radius;
  }
  return s;
}

TriangleSoup MakeTorus(double majorRadius, double minorRadius, int n, int m)
{
  TriangleSoup s;
  for (int i = 0; i < n; ++i)
  {
    const double u = 2.0 * Pi * i / n;
    for (int j = 0; j < m; ++j)
    {
      const double v = 2.0 * Pi * j / m;
      const double r = majorRadius + minorRadius * std::cos(v);
      s.Points.emplace_back(r * std::cos(u), r * std::sin(u), minorRadius * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return static_cast<long long>(i % n) * m + (j % m); };
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < m; ++j)
    {
      AddQuad(s, id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), (i + j) % 2 == 1);
    }
  }
  return s;
}

std::vector<Vec2> MakeStarPolygon(int points, double outer, double inner)
{
  const double pi = std::acos(-1.0);
  std::vector<Vec2> ring;
  for (int k = 0; k < 2 * points; ++k)
  {
    const double a = pi / 2 + pi * k / points;
    const double r = k % 2 == 0 ? outer : inner;
    ring.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  return ring;
}

TriangleSoup SubdivideAtMidpoints(const TriangleSoup& soup)
{
  TriangleSoup out;
  out.Points = soup.Points;
  std::map<std::pair<long long, long long>, long long> middle;
  auto midpoint = [&](long long a, long long b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    auto it = middle.find(key);
    if (it != middle.end())
    {
      return it->second;
    }
    out.Points.push_back((soup.Points[a] + soup.Points[b]) * 0.5);
    return middle[key] = static_cast<long long>(out.Points.size()) - 1;
  };
  for (const auto& t : soup.Triangles)
  {
    const long long ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    out.Triangles.push_back({ t[0], ab, ca });
    out.Triangles.push_back({ ab, t[1], bc });
    out.Triangles.push_back({ ca, bc, t[2] });
    out.Triangles.push_back({ ab, bc, ca });
  }
  return out;
}

} // namespace gs
