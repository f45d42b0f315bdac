// The direction field solver: set-up, fields at vertices, indices and energy; stroke
// constraints and per-face directions from vertex vectors.
#include "DirectionFieldImpl.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace gs
{

DirectionFieldSolver::DirectionFieldSolver(const TriangleMesh& mesh)
  : Surface(mesh)
{
  const int nf = Surface.NumberOfFaces();
  BasisX.resize(nf);
  BasisY.resize(nf);
#pragma omp parallel for schedule(static)
  for (int f = 0; f < nf; ++f)
  {
    const Vec3 n = Surface.FaceNormal(f);
    Vec3 x = Surface.Position(Surface.Destination(3 * f)) - Surface.Position(Surface.Origin(3 * f));
    const double l = Norm(x);
    x = l > 0 ? x / l : Vec3(1, 0, 0);
    BasisX[f] = x;
    BasisY[f] = Cross(n, x);
  }
  Transport.assign(Surface.NumberOfHalfedges(), 0.0);
  EdgeWeight.assign(Surface.NumberOfHalfedges(), 0.0);
#pragma omp parallel for schedule(static)
  for (int h = 0; h < Surface.NumberOfHalfedges(); ++h)
  {
    const int t = Surface.Twin(h);
    if (t < 0)
    {
      continue;
    }
    const Vec3 e = Surface.Position(Surface.Destination(h)) - Surface.Position(Surface.Origin(h));
    const int f = TriangleMesh::FaceOf(h), g = TriangleMesh::FaceOf(t);
    // e has angle a_f in f and a_g in g: phi in f is (phi - a_f) from e, hence a_g + phi - a_f.
    Transport[h] = WrapPi(AngleInFace(g, e) - AngleInFace(f, e));
    const double areas = Surface.FaceArea(f) + Surface.FaceArea(g);
    const double l = Surface.EdgeLength(h);
    // Primal edge length over the distance between the two barycentres across it.
    EdgeWeight[h] = areas > 0 ? 3.0 * l * l / (2.0 * areas) : 0.0;
  }
}

DirectionFieldSolver::~DirectionFieldSolver() = default;

double DirectionFieldSolver::AngleInFace(int f, const Vec3& v) const
{
  return std::atan2(Dot(v, BasisY[f]), Dot(v, BasisX[f]));
}

Vec3 DirectionFieldSolver::DirectionInFace(int f, double angle) const
{
  return BasisX[f] * std::cos(angle) + BasisY[f] * std::sin(angle);
}

std::vector<Vec3> AreaWeightedVertexNormals(const TriangleMesh& mesh)
{
  std::vector<Vec3> vn(mesh.NumberOfVertices(), Vec3(0, 0, 0));
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    const Vec3 fn = mesh.FaceNormal(f) * mesh.FaceArea(f);
    for (int c = 0; c < 3; ++c)
    {
      vn[mesh.Face(f)[c]] += fn;
    }
  }
  for (Vec3& v : vn)
  {
    const double l = Norm(v);
    v = l > 0 ? v / l : v;
  }
  return vn;
}

void AddStrokeConstraints(const TriangleMesh& mesh, const std::vector<SurfacePoint>& curve,
  const std::vector<Vec3>& polyline, double minimumLength,
  std::vector<FaceDirectionConstraint>& constraints)
{
  // The stroke's own segments in space: each crossed face takes the direction of the segment
  // closest to the piece inside it, projected onto the face (the traced pieces bend where the
  // path is re-aimed near vertices; their direction is not used).
  auto segmentDirection = [&](const Vec3& m) {
    double best = std::numeric_limits<double>::infinity();
    Vec3 direction(0, 0, 0);
    for (size_t k = 0; k + 1 < polyline.size(); ++k)
    {
      const Vec3 a = polyline[k], ab = polyline[k + 1] - polyline[k];
      const double l2 = Dot(ab, ab);
      if (!(l2 > 0))
      {
        continue;
      }
      const double t = std::min(1.0, std::max(0.0, Dot(m - a, ab) / l2));
      const double d = Norm(a + ab * t - m);
      if (d < best)
      {
        best = d;
        direction = ab;
      }
    }
    return direction;
  };
  // Faces crossed over less than minimumLength are not constrained (a stroke through a vertex
  // grazes the faces around it).
  std::vector<std::pair<int, double>> crossed; // face, length inside, in stroke order
  std::vector<Vec3> middles;
  for (const CurvePiece& piece : TraceSurfaceCurve(mesh, curve))
  {
    const double l = Norm(piece.B - piece.A);
    if (!crossed.empty() && crossed.back().first == piece.Face)
    {
      crossed.back().second += l;
      continue;
    }
    crossed.emplace_back(piece.Face, l);
    middles.push_back((piece.A + piece.B) * 0.5);
  }
  for (size_t k = 0; k < crossed.size(); ++k)
  {
    if (crossed[k].second < minimumLength)
    {
      continue;
    }
    const Vec3 d = segmentDirection(middles[k]);
    const Vec3 normal = mesh.FaceNormal(crossed[k].first);
    const Vec3 tangent = d - normal * Dot(d, normal);
    if (Norm(tangent) > 1e-9 * Norm(d))
    {
      constraints.push_back({ crossed[k].first, tangent });
    }
  }
}

Result<std::vector<Vec3>> FaceDirectionsFromVertices(
  const TriangleMesh& mesh, const std::vector<Vec3>& atVertex, int symmetry)
{
  if (Status valid = CheckSymmetry(symmetry); !valid.Ok())
  {
    return valid;
  }
  if (atVertex.size() != static_cast<std::size_t>(mesh.NumberOfVertices()))
  {
    return Status::Error("the direction field at the vertices needs one vector per vertex: " +
      std::to_string(atVertex.size()) + " given for " + std::to_string(mesh.NumberOfVertices()) +
      " vertices");
  }
  const int nf = mesh.NumberOfFaces();
  const int n = symmetry;
  std::vector<Vec3> out(nf, Vec3{ 0, 0, 0 });
  const std::vector<Vec3> vertexNormals = AreaWeightedVertexNormals(mesh);
  // (Each face on its own: on several threads for large meshes, the same result.)
#pragma omp parallel for schedule(static) if (nf > 20000)
  for (int f = 0; f < nf; ++f)
  {
    const auto& c = mesh.Face(f);
    const Vec3 normal = mesh.FaceNormal(f);
    const Vec3 x = Unit(mesh.Position(c[1]) - mesh.Position(c[0]));
    const Vec3 y = Cross(normal, x);
    double re = 0.0, im = 0.0, reference = 0.0, weight = 0.0;
    bool haveReference = false;
    for (int k = 0; k < 3; ++k)
    {
      Vec3 v = atVertex[c[k]];
      if (!IsFinite(v))
      {
        continue;
      }
      // Into the vertex's tangent plane, then turned into the face's (Rodrigues' formula for
      // the rotation about vn x normal by their angle; plain projection where they are opposed).
      const Vec3& vn = vertexNormals[c[k]];
      const double cosine = Dot(vn, normal);
      if (cosine > -0.9)
      {
        v = v - vn * Dot(vn, v);
        const Vec3 axis = Cross(vn, normal);
        v = v * cosine + Cross(axis, v) + axis * (Dot(axis, v) / (1.0 + cosine));
      }
      const double a = Dot(v, x), b = Dot(v, y);
      const double length = std::hypot(a, b);
      if (!(length > 0.0))
      {
        continue;
      }
      const double angle = std::atan2(b, a);
      if (!haveReference)
      {
        reference = angle;
        haveReference = true;
      }
      weight += length;
      re += length * std::cos(n * angle);
      im += length * std::sin(n * angle);
    }
    const double magnitude = std::hypot(re, im);
    if (!haveReference || !(magnitude > 1e-9 * weight))
    {
      continue;
    }
    // The N directions angle + 2 pi k / N: the one closest to the first corner's vector.
    const double angle = std::atan2(im, re) / n;
    const double step = 2.0 * Pi / n;
    const double k = std::round((reference - angle) / step);
    const double chosen = angle + k * step;
    out[f] = x * std::cos(chosen) + y * std::sin(chosen);
  }
  return out;
}

double DirectionFieldSolver::WrapSymmetric(double a, int n)
{
  const double period = TwoPi / n;
  a = std::fmod(a + 0.5 * period, period);
  if (a < 0)
  {
    a += period;
  }
  return a - 0.5 * period;
}

std::vector<Vec3> DirectionFieldSolver::VertexNormals() const
{
  return AreaWeightedVertexNormals(Surface);
}

std::vector<Vec3> DirectionFieldSolver::VertexDirections(int n, const std::vector<double>& angles) const
{
  const int nv = Surface.NumberOfVertices();
  const std::vector<Vec3> normals = VertexNormals();
  std::vector<Vec3> directions(nv, Vec3(0, 0, 0));
  for (int v = 0; v < nv; ++v)
  {
    const Vec3 normal = normals[v];
    if (!(Norm(normal) > 0))
    {
      continue;
    }
    const std::vector<int> out = Surface.OutgoingHalfedges(v);
    Vec3 x = Surface.Position(Surface.Destination(out[0])) - Surface.Position(v);
    x = x - normal * Dot(x, normal);
    const double lx = Norm(x);
    if (!(lx > 0))
    {
      continue;
    }
    x = x / lx;
    const Vec3 y = Cross(normal, x);
    double re = 0.0, im = 0.0, area = 0.0;
    for (int h : out)
    {
      const int f = TriangleMesh::FaceOf(h);
      const Vec3 d = DirectionInFace(f, angles[f]);
      const double a = std::atan2(Dot(d, y), Dot(d, x));
      re += Surface.FaceArea(f) * std::cos(n * a);
      im += Surface.FaceArea(f) * std::sin(n * a);
      area += Surface.FaceArea(f);
    }
    if (std::hypot(re, im) > 1e-9 * area)
    {
      const double a = std::atan2(im, re) / n;
      directions[v] = x * std::cos(a) + y * std::sin(a);
    }
  }
  return directions;
}

double DirectionFieldSolver::IndexSum(int n, const std::vector<double>& angles) const
{
  const std::vector<double> raw = VertexIndices(n, angles);
  double sum = 0.0;
  for (int v = 0; v < Surface.NumberOfVertices(); ++v)
  {
    if (!Surface.IsBoundaryVertex(v))
    {
      sum += std::round(raw[v] * n) / n;
    }
  }
  for (const auto& loop : Surface.BoundaryLoops())
  {
    double turning = 0.0;
    for (int v : loop)
    {
      turning += raw[v];
    }
    sum += std::round(turning * n) / n;
  }
  return sum;
}

void DirectionFieldSolver::ComputeCurvatureTarget(
  int n, std::vector<double>& re, std::vector<double>& im) const
{
  const int nf = Surface.NumberOfFaces();
  const std::vector<Vec3> vn = VertexNormals();
  re.assign(nf, 0.0);
  im.assign(nf, 0.0);
  double total = 0.0, area = 0.0;
  for (int f = 0; f < nf; ++f)
  {
    // Least-squares shape operator S (2x2 symmetric) in the face frame: S e = dn on every edge.
    Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (int c = 0; c < 3; ++c)
    {
      const int h = 3 * f + c;
      const Vec3 e = Surface.Position(Surface.Destination(h)) - Surface.Position(Surface.Origin(h));
      const Vec3 dn = vn[Surface.Destination(h)] - vn[Surface.Origin(h)];
      const double ex = Dot(e, BasisX[f]), ey = Dot(e, BasisY[f]);
      const double dx = Dot(dn, BasisX[f]), dy = Dot(dn, BasisY[f]);
      // rows: (ex, ey, 0) . (s11, s12, s22) = dx ; (0, ex, ey) . s = dy
      const Eigen::Vector3d r1(ex, ey, 0), r2(0, ex, ey);
      a += r1 * r1.transpose() + r2 * r2.transpose();
      b += r1 * dx + r2 * dy;
    }
    const Eigen::Vector3d s = a.ldlt().solve(b);
    if (!s.allFinite())
    {
      continue;
    }
    // exp(2 i phi) scaled by the anisotropy |k1 - k2|.
    double x = s[0] - s[2], y = 2.0 * s[1];
    if (n == 4)
    {
      const double mag = std::hypot(x, y);
      const double x2 = x * x - y * y, y2 = 2.0 * x * y;
      x = mag > 0 ? x2 / mag : 0.0;
      y = mag > 0 ? y2 / mag : 0.0;
    }
    re[f] = x;
    im[f] = y;
    total += std::hypot(x, y) * Surface.FaceArea(f);
    area += Surface.FaceArea(f);
  }
  const double mean = area > 0 ? total / area : 0.0;
  if (mean > 0)
  {
    for (int f = 0; f < nf; ++f)
    {
      re[f] /= mean;
      im[f] /= mean;
    }
  }
}

std::vector<double> DirectionFieldSolver::VertexIndices(int n, const std::vector<double>& angles) const
{
  const int nv = Surface.NumberOfVertices();
  std::vector<double> index(nv, 0.0);
  for (int v = 0; v < nv; ++v)
  {
    const std::vector<int> out = Surface.OutgoingHalfedges(v);
    double jumps = 0.0;
    for (int h : out)
    {
      const int p = TriangleMesh::Prev(h); // crossing p goes to the next face counter-clockwise
      const int t = Surface.Twin(p);
      if (t < 0)
      {
        continue;
      }
      const int f = TriangleMesh::FaceOf(h), g = TriangleMesh::FaceOf(t);
      jumps += WrapSymmetric(angles[g] - (angles[f] + Transport[p]), n);
    }
    const double defect = (Surface.IsBoundaryVertex(v) ? Pi : TwoPi) - Surface.TotalAngle(v);
    index[v] = (jumps + defect) / TwoPi;
  }
  return index;
}

std::vector<double> DirectionFieldSolver::RoundedVertexIndices(
  int n, const std::vector<double>& angles) const
{
  std::vector<double> index = VertexIndices(n, angles);
  for (int v = 0; v < Surface.NumberOfVertices(); ++v)
  {
    if (!Surface.IsBoundaryVertex(v))
    {
      index[v] = std::round(index[v] * n) / n;
    }
  }
  return index;
}

double DirectionFieldSolver::Energy(int n, const std::vector<double>& angles) const
{
  double e = 0.0, a = 0.0;
  for (int h = 0; h < Surface.NumberOfHalfedges(); ++h)
  {
    const int t = Surface.Twin(h);
    if (t < h)
    {
      continue;
    }
    const int f = TriangleMesh::FaceOf(h), g = TriangleMesh::FaceOf(t);
    const double d = n * (angles[g] - angles[f] - Transport[h]);
    e += EdgeWeight[h] * 2.0 * (1.0 - std::cos(d));
  }
  for (int f = 0; f < Surface.NumberOfFaces(); ++f)
  {
    a += Surface.FaceArea(f);
  }
  return a > 0 ? e / a : 0.0;
}

} // namespace gs
