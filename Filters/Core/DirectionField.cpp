#include "DirectionField.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>

namespace gs
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double TwoPi = 2.0 * Pi;

Status CheckSymmetry(int n)
{
  if (n != 1 && n != 2 && n != 4)
  {
    return Status::Error(
      "Symmetry must be 1 (vector field), 2 (line field) or 4 (cross field); it is " +
      std::to_string(n));
  }
  return Status();
}

double WrapPi(double a)
{
  a = std::fmod(a + Pi, TwoPi);
  if (a < 0)
  {
    a += TwoPi;
  }
  return a - Pi;
}
} // namespace

struct DirectionFieldSolver::Factorization
{
  int Symmetry = 0;
  double Alignment = -1.0;
  std::vector<int> Constrained; // sorted constrained faces
  std::vector<int> FreeIndex;   // face -> row block among free faces, -1 if constrained
  Eigen::SparseMatrix<double> System; // full 2F x 2F system matrix (B in the comments)
  Eigen::SparseMatrix<double> Bfc; // free rows x constrained columns
  Eigen::SparseMatrix<double> Bff; // free rows x free columns (the factorized matrix)
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> Solver;

  // The smallest eigenvector of (Bff, M), M the face areas of `surface` (Rayleigh-Ritz).
  Eigen::VectorXd SmallestEigenvector(const TriangleMesh& surface, int nf) const;
};

struct DirectionFieldSolver::ConnectionFactorization
{
  std::vector<int> ConstrainedFaces; // key: the constrained faces in the order given
  std::vector<int> EdgeOf;           // half-edge -> interior edge index, -1 on the boundary
  std::vector<int> ParentHalfedge;   // dual tree: half-edge of the parent face crossing into f
  std::vector<int> Depth;
  std::vector<int> Order;            // faces in breadth-first order (roots first per component)
  std::vector<std::vector<int>> RowVertices; // interior vertex or boundary loop rows
  std::vector<std::vector<int>> Cycles; // homology generators (crossed half-edges)
  std::vector<std::vector<int>> Paths;  // between consecutive constrained faces
  std::vector<std::pair<int, int>> PathEnds; // constraint indices joined by each path
  Eigen::VectorXd InverseWeight;
  // Per row (RowVertices, then Cycles, then Paths): the edges its holonomy crosses.
  Eigen::SparseMatrix<double> Holonomy;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> Solver;
  std::vector<double> ComponentEuler;
};

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

Eigen::VectorXd DirectionFieldSolver::Factorization::SmallestEigenvector(
  const TriangleMesh& surface, int nf) const
{
  // Rayleigh-Ritz accelerated inverse iteration: the subspace spanned by the iterates
  // (M-orthonormalised) is searched for the smallest Ritz pair of (B, M), and the next iterate is
  // B^-1 M (Ritz vector): a Krylov space of B^-1 M. Converges in a few tens of solves where plain
  // inverse iteration stalls on small spectral gaps. Deterministic start.
  const int size = 2 * nf;
  Eigen::VectorXd mass(size);
  double area = 0.0;
  for (int f = 0; f < nf; ++f)
  {
    mass[2 * f] = mass[2 * f + 1] = surface.FaceArea(f);
    area += surface.FaceArea(f);
  }
  std::mt19937 rng(12345u);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i)
  {
    v[i] = uni(rng);
  }
  std::vector<Eigen::VectorXd> basis, image;
  Eigen::VectorXd ritz = v;
  double previous = -1.0;
  const int maxBasis = 40;
  for (int it = 0; it < maxBasis; ++it)
  {
    // M-orthonormalise v against the basis (twice, for stability). What is left is compared
    // with v's own M-norm: v's scale follows the mesh's (areas), never an absolute threshold.
    const double before = std::sqrt(v.dot(mass.cwiseProduct(v)));
    for (int pass = 0; pass < 2; ++pass)
    {
      for (const Eigen::VectorXd& b : basis)
      {
        v -= b * b.dot(mass.cwiseProduct(v));
      }
    }
    const double norm = std::sqrt(v.dot(mass.cwiseProduct(v)));
    if (!(norm > 1e-12 * before) || !std::isfinite(norm))
    {
      break; // the space is invariant: the Ritz vector is exact
    }
    basis.push_back(v / norm);
    image.push_back(Bff * basis.back());
    const int k = static_cast<int>(basis.size());
    Eigen::MatrixXd h(k, k);
    for (int i = 0; i < k; ++i)
    {
      for (int j = 0; j < k; ++j)
      {
        h(i, j) = basis[i].dot(image[j]);
      }
    }
    h = 0.5 * (h + h.transpose()).eval();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(h);
    const Eigen::VectorXd y = eig.eigenvectors().col(0);
    const double value = eig.eigenvalues()[0];
    ritz.setZero();
    for (int i = 0; i < k; ++i)
    {
      ritz += basis[i] * y[i];
    }
    if (it > 1 && std::abs(value - previous) <= 1e-10 * std::abs(value))
    {
      break;
    }
    previous = value;
    v = Solver.solve(mass.cwiseProduct(ritz));
    if (!v.allFinite())
    {
      break;
    }
  }
  const double norm = std::sqrt(ritz.dot(mass.cwiseProduct(ritz)));
  return norm > 0 ? Eigen::VectorXd(ritz * std::sqrt(area) / norm) : ritz;
}

Status DirectionFieldSolver::SolveSmoothest(int n, double alignment,
  const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles)
{
  const int nf = Surface.NumberOfFaces();
  if (Status symmetry = CheckSymmetry(n); !symmetry.Ok())
  {
    return symmetry;
  }
  if (!(alignment >= 0.0) || !std::isfinite(alignment))
  {
    return Status::Error(
      "CurvatureAlignment must be finite and >= 0 (it is " + std::to_string(alignment) + ")");
  }
  if (n == 1)
  {
    alignment = 0.0; // principal directions are lines: no vector (N = 1) target
  }
  if (nf == 0)
  {
    return Status::Error("empty mesh");
  }
  // Constrained faces and their values exp(i N angle); repeated faces average their constraints.
  std::vector<double> cre(nf, 0.0), cim(nf, 0.0);
  std::vector<char> isConstrained(nf, 0);
  for (const FaceDirectionConstraint& c : constraints)
  {
    if (c.Face < 0 || c.Face >= nf || !IsFinite(c.Direction))
    {
      return Status::Error("invalid direction constraint (face " + std::to_string(c.Face) + ")");
    }
    const double a = AngleInFace(c.Face, c.Direction);
    const double x = Dot(c.Direction, BasisX[c.Face]), y = Dot(c.Direction, BasisY[c.Face]);
    if (std::hypot(x, y) <= 0.0)
    {
      return Status::Error("direction constraint normal to its face " + std::to_string(c.Face));
    }
    cre[c.Face] += std::cos(n * a);
    cim[c.Face] += std::sin(n * a);
    isConstrained[c.Face] = 1;
  }
  std::vector<int> constrained;
  for (int f = 0; f < nf; ++f)
  {
    if (isConstrained[f])
    {
      const double l = std::hypot(cre[f], cim[f]);
      if (l < 1e-12)
      {
        return Status::Error("contradictory direction constraints in face " + std::to_string(f));
      }
      cre[f] /= l;
      cim[f] /= l;
      constrained.push_back(f);
    }
  }

  double sumW = 0.0, sumA = 0.0;
  for (int h = 0; h < Surface.NumberOfHalfedges(); ++h)
  {
    sumW += EdgeWeight[h];
  }
  for (int f = 0; f < nf; ++f)
  {
    sumA += Surface.FaceArea(f);
  }
  const double sigma = sumA > 0 ? sumW / sumA : 1.0; // energy / area scale
  const double eps = 1e-10 * sigma;

  if (!Cache || Cache->Symmetry != n || Cache->Alignment != alignment ||
    Cache->Constrained != constrained)
  {
    Cache = std::make_unique<Factorization>();
    Cache->Symmetry = n;
    Cache->Alignment = alignment;
    Cache->Constrained = constrained;
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(8 * Surface.NumberOfHalfedges() + 2 * nf);
    for (int h = 0; h < Surface.NumberOfHalfedges(); ++h)
    {
      const int t = Surface.Twin(h);
      if (t < h)
      {
        continue; // boundary or already seen from its twin
      }
      const int f = TriangleMesh::FaceOf(h), g = TriangleMesh::FaceOf(t);
      const double w = EdgeWeight[h];
      const double c = std::cos(n * Transport[h]), s = std::sin(n * Transport[h]);
      // w |u_g - R u_f|^2, R = [[c, -s], [s, c]].
      for (int k = 0; k < 2; ++k)
      {
        trip.emplace_back(2 * f + k, 2 * f + k, w);
        trip.emplace_back(2 * g + k, 2 * g + k, w);
      }
      const double r[2][2] = { { c, -s }, { s, c } };
      for (int i = 0; i < 2; ++i)
      {
        for (int j = 0; j < 2; ++j)
        {
          trip.emplace_back(2 * g + i, 2 * f + j, -w * r[i][j]);
          trip.emplace_back(2 * f + j, 2 * g + i, -w * r[i][j]);
        }
      }
    }
    for (int f = 0; f < nf; ++f)
    {
      const double d = (alignment * sigma + eps) * Surface.FaceArea(f);
      trip.emplace_back(2 * f, 2 * f, d);
      trip.emplace_back(2 * f + 1, 2 * f + 1, d);
    }
    Cache->System.resize(2 * nf, 2 * nf);
    Cache->System.setFromTriplets(trip.begin(), trip.end());
    Cache->FreeIndex.assign(nf, -1);
    int nfree = 0;
    for (int f = 0; f < nf; ++f)
    {
      if (!isConstrained[f])
      {
        Cache->FreeIndex[f] = nfree++;
      }
    }
    // Restrict to free rows / columns.
    std::vector<Eigen::Triplet<double>> ff, fc;
    std::vector<int> conIndex(nf, -1);
    for (size_t i = 0; i < constrained.size(); ++i)
    {
      conIndex[constrained[i]] = static_cast<int>(i);
    }
    for (int k = 0; k < Cache->System.outerSize(); ++k)
    {
      for (Eigen::SparseMatrix<double>::InnerIterator it(Cache->System, k); it; ++it)
      {
        const int rf = static_cast<int>(it.row()) / 2, cf = static_cast<int>(it.col()) / 2;
        const int rr = static_cast<int>(it.row()) % 2, cc = static_cast<int>(it.col()) % 2;
        if (Cache->FreeIndex[rf] < 0)
        {
          continue;
        }
        const int row = 2 * Cache->FreeIndex[rf] + rr;
        if (Cache->FreeIndex[cf] >= 0)
        {
          ff.emplace_back(row, 2 * Cache->FreeIndex[cf] + cc, it.value());
        }
        else
        {
          fc.emplace_back(row, 2 * conIndex[cf] + cc, it.value());
        }
      }
    }
    Eigen::SparseMatrix<double> bff(2 * nfree, 2 * nfree);
    bff.setFromTriplets(ff.begin(), ff.end());
    Cache->Bfc.resize(2 * nfree, 2 * static_cast<int>(constrained.size()));
    Cache->Bfc.setFromTriplets(fc.begin(), fc.end());
    if (nfree > 0)
    {
      Cache->Solver.compute(bff);
      Cache->Bff = bff;
    }
    if (nfree > 0 && Cache->Solver.info() != Eigen::Success)
    {
      Cache.reset();
      return Status::Error("factorization of the connection Laplacian failed");
    }
  }

  const std::vector<int>& freeIndex = Cache->FreeIndex;
  const int nfree = static_cast<int>(freeIndex.size() - constrained.size());
  Eigen::VectorXd rhsFixed = Eigen::VectorXd::Zero(2 * nfree);
  if (!constrained.empty())
  {
    Eigen::VectorXd uc(2 * constrained.size());
    for (size_t i = 0; i < constrained.size(); ++i)
    {
      uc[2 * i] = cre[constrained[i]];
      uc[2 * i + 1] = cim[constrained[i]];
    }
    rhsFixed -= Cache->Bfc * uc;
  }
  if (alignment > 0)
  {
    std::vector<double> qre, qim;
    ComputeCurvatureTarget(n, qre, qim);
    for (int f = 0; f < nf; ++f)
    {
      if (freeIndex[f] >= 0)
      {
        rhsFixed[2 * freeIndex[f]] += alignment * sigma * Surface.FaceArea(f) * qre[f];
        rhsFixed[2 * freeIndex[f] + 1] += alignment * sigma * Surface.FaceArea(f) * qim[f];
      }
    }
  }
  // Components with neither constraints nor alignment: inverse iteration for the smallest
  // eigenvector (Knoppel et al.), normalised per component.
  const int ncomp = std::max(1, Surface.NumberOfComponents());
  std::vector<char> compFree(ncomp, alignment > 0 ? 0 : 1);
  for (int f : constrained)
  {
    compFree[Surface.FaceComponent(f)] = 0;
  }
  const bool iterate = std::find(compFree.begin(), compFree.end(), 1) != compFree.end();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(2 * nfree);
  if (nfree > 0)
  {
    if (!iterate)
    {
      u = Cache->Solver.solve(rhsFixed);
    }
    else if (ncomp == 1 && constrained.empty() && alignment == 0.0)
    {
      u = Cache->SmallestEigenvector(Surface, nf);
    }
    else
    {
      std::mt19937 rng(12345u);
      std::uniform_real_distribution<double> uni(-1.0, 1.0);
      for (int i = 0; i < 2 * nfree; ++i)
      {
        u[i] = uni(rng);
      }
      std::vector<double> norm(ncomp), compArea(ncomp, 0.0);
      for (int f = 0; f < nf; ++f)
      {
        compArea[Surface.FaceComponent(f)] += Surface.FaceArea(f);
      }
      // Normalised to an area-weighted mean |u|^2 of 1. Stops when the Rayleigh quotient (the
      // field's smoothness energy) is stable to 1e-6 relative, or after 60 iterations: with a
      // small spectral gap (near-symmetric meshes) inverse iteration converges slowly, while
      // the energy is within a few percent of the optimum after a few iterations.
      double previousQuotient = -1.0;
      for (int it = 0; it < 60; ++it)
      {
        Eigen::VectorXd rhs = rhsFixed;
        for (int f = 0; f < nf; ++f)
        {
          const int i = freeIndex[f];
          if (i >= 0 && compFree[Surface.FaceComponent(f)])
          {
            rhs[2 * i] += Surface.FaceArea(f) * u[2 * i];
            rhs[2 * i + 1] += Surface.FaceArea(f) * u[2 * i + 1];
          }
        }
        Eigen::VectorXd next = Cache->Solver.solve(rhs);
        double uu = 0.0, un = 0.0;
        for (int f = 0; f < nf; ++f)
        {
          const int i = freeIndex[f];
          if (i >= 0 && compFree[Surface.FaceComponent(f)])
          {
            uu += Surface.FaceArea(f) * (u[2 * i] * u[2 * i] + u[2 * i + 1] * u[2 * i + 1]);
            un += Surface.FaceArea(f) * (u[2 * i] * next[2 * i] + u[2 * i + 1] * next[2 * i + 1]);
          }
        }
        const double quotient = un != 0.0 ? uu / un : 0.0; // ~ smallest eigenvalue of B
        std::fill(norm.begin(), norm.end(), 0.0);
        for (int f = 0; f < nf; ++f)
        {
          const int i = freeIndex[f];
          if (i >= 0)
          {
            norm[Surface.FaceComponent(f)] +=
              Surface.FaceArea(f) * (next[2 * i] * next[2 * i] + next[2 * i + 1] * next[2 * i + 1]);
          }
        }
        for (int f = 0; f < nf; ++f)
        {
          const int i = freeIndex[f];
          const int c = Surface.FaceComponent(f);
          if (i >= 0 && compFree[c] && norm[c] > 0)
          {
            const double s = std::sqrt(compArea[c] / norm[c]);
            next[2 * i] *= s;
            next[2 * i + 1] *= s;
          }
        }
        u = next;
        if (it > 2 && std::abs(quotient - previousQuotient) <= 1e-6 * std::abs(quotient))
        {
          break;
        }
        previousQuotient = quotient;
      }
    }
    if (!u.allFinite())
    {
      return Status::Error("direction field solve produced non-finite values");
    }
  }
  angles.assign(nf, 0.0);
  for (int f = 0; f < nf; ++f)
  {
    const int i = freeIndex[f];
    const double x = i >= 0 ? u[2 * i] : cre[f];
    const double y = i >= 0 ? u[2 * i + 1] : cim[f];
    angles[f] = std::atan2(y, x) / n;
  }
  return Status();
}

namespace
{
int Find(std::vector<int>& parent, int a)
{
  while (parent[a] != a)
  {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}
} // namespace

Status DirectionFieldSolver::SolvePrescribed(int n,
  const std::vector<VertexSingularity>& singularities,
  const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles)
{
  const int nf = Surface.NumberOfFaces(), nv = Surface.NumberOfVertices();
  if (Status symmetry = CheckSymmetry(n); !symmetry.Ok())
  {
    return symmetry;
  }
  if (nf == 0)
  {
    return Status::Error("empty mesh");
  }
  std::vector<double> index(nv, 0.0);
  for (const VertexSingularity& s : singularities)
  {
    if (s.Vertex < 0 || s.Vertex >= nv || !std::isfinite(s.Index))
    {
      return Status::Error("invalid singularity (vertex " + std::to_string(s.Vertex) + ")");
    }
    if (std::abs(s.Index * n - std::round(s.Index * n)) > 1e-6)
    {
      return Status::Error("singularity index " + std::to_string(s.Index) + " at vertex " +
        std::to_string(s.Vertex) + " is not a multiple of 1/" + std::to_string(n));
    }
    index[s.Vertex] += std::round(s.Index * n) / n;
  }
  for (const FaceDirectionConstraint& c : constraints)
  {
    if (c.Face < 0 || c.Face >= nf || !IsFinite(c.Direction) ||
      std::hypot(Dot(c.Direction, BasisX[c.Face]), Dot(c.Direction, BasisY[c.Face])) <= 0.0)
    {
      return Status::Error("invalid direction constraint (face " + std::to_string(c.Face) + ")");
    }
  }
  // A face constrained twice keeps its first constraint.
  std::vector<FaceDirectionConstraint> unique;
  {
    std::vector<char> seen(nf, 0);
    for (const FaceDirectionConstraint& c : constraints)
    {
      if (!seen[c.Face])
      {
        seen[c.Face] = 1;
        unique.push_back(c);
      }
    }
  }
  return SolvePrescribedUnique(n, index, unique, angles);
}

Status DirectionFieldSolver::SolvePrescribedUnique(int n, const std::vector<double>& index,
  const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles)
{
  const int nf = Surface.NumberOfFaces(), nv = Surface.NumberOfVertices(),
            nh = Surface.NumberOfHalfedges();
  std::vector<int> constrainedFaces;
  for (const FaceDirectionConstraint& c : constraints)
  {
    constrainedFaces.push_back(c.Face);
  }

  if (!ConnectionCache || ConnectionCache->ConstrainedFaces != constrainedFaces)
  {
    auto cf = std::make_unique<ConnectionFactorization>();
    cf->ConstrainedFaces = constrainedFaces;
    // Interior edges.
    cf->EdgeOf.assign(nh, -1);
    int ne = 0;
    std::vector<double> weight;
    for (int h = 0; h < nh; ++h)
    {
      const int t = Surface.Twin(h);
      if (t > h)
      {
        cf->EdgeOf[h] = cf->EdgeOf[t] = ne++;
        weight.push_back(EdgeWeight[h]);
      }
    }
    double meanW = 0.0;
    for (double w : weight)
    {
      meanW += w;
    }
    meanW = ne > 0 ? meanW / ne : 1.0;
    cf->InverseWeight.resize(ne);
    for (int e = 0; e < ne; ++e)
    {
      cf->InverseWeight[e] = 1.0 / std::max(weight[e], 1e-9 * meanW);
    }
    // Primal spanning forest: boundary edges first (each loop minus one edge), then the rest.
    std::vector<int> uf(nv);
    for (int v = 0; v < nv; ++v)
    {
      uf[v] = v;
    }
    std::vector<char> inTree(nh, 0);
    auto tryAdd = [&](int h) {
      const int a = Find(uf, Surface.Origin(h)), b = Find(uf, Surface.Destination(h));
      if (a != b)
      {
        uf[a] = b;
        inTree[h] = 1;
        if (Surface.Twin(h) >= 0)
        {
          inTree[Surface.Twin(h)] = 1;
        }
      }
    };
    for (int h = 0; h < nh; ++h)
    {
      if (Surface.Twin(h) < 0)
      {
        tryAdd(h);
      }
    }
    for (int h = 0; h < nh; ++h)
    {
      if (Surface.Twin(h) > h)
      {
        tryAdd(h);
      }
    }
    // Dual spanning forest avoiding the primal tree (breadth first).
    cf->ParentHalfedge.assign(nf, -2);
    cf->Depth.assign(nf, 0);
    std::vector<char> inDual(nh, 0);
    for (int root = 0; root < nf; ++root)
    {
      if (cf->ParentHalfedge[root] != -2)
      {
        continue;
      }
      cf->ParentHalfedge[root] = -1;
      size_t head = cf->Order.size();
      cf->Order.push_back(root);
      while (head < cf->Order.size())
      {
        const int f = cf->Order[head++];
        for (int c = 0; c < 3; ++c)
        {
          const int h = 3 * f + c, t = Surface.Twin(h);
          if (t < 0 || inTree[h])
          {
            continue;
          }
          const int g = TriangleMesh::FaceOf(t);
          if (cf->ParentHalfedge[g] != -2)
          {
            continue;
          }
          cf->ParentHalfedge[g] = h;
          cf->Depth[g] = cf->Depth[f] + 1;
          inDual[h] = inDual[t] = 1;
          cf->Order.push_back(g);
        }
      }
    }
    auto pathBetween = [&](int a, int b) {
      // Crossed half-edges from face a to face b along the dual tree.
      std::vector<int> up, down;
      while (cf->Depth[a] > cf->Depth[b])
      {
        up.push_back(Surface.Twin(cf->ParentHalfedge[a]));
        a = TriangleMesh::FaceOf(cf->ParentHalfedge[a]);
      }
      while (cf->Depth[b] > cf->Depth[a])
      {
        down.push_back(cf->ParentHalfedge[b]);
        b = TriangleMesh::FaceOf(cf->ParentHalfedge[b]);
      }
      while (a != b)
      {
        up.push_back(Surface.Twin(cf->ParentHalfedge[a]));
        a = TriangleMesh::FaceOf(cf->ParentHalfedge[a]);
        down.push_back(cf->ParentHalfedge[b]);
        b = TriangleMesh::FaceOf(cf->ParentHalfedge[b]);
      }
      up.insert(up.end(), down.rbegin(), down.rend());
      return up;
    };
    for (int h = 0; h < nh; ++h)
    {
      const int t = Surface.Twin(h);
      if (t > h && !inTree[h] && !inDual[h])
      {
        std::vector<int> cycle{ h };
        const std::vector<int> back = pathBetween(TriangleMesh::FaceOf(t), TriangleMesh::FaceOf(h));
        cycle.insert(cycle.end(), back.begin(), back.end());
        cf->Cycles.push_back(cycle);
      }
    }
    for (size_t i = 1; i < constrainedFaces.size(); ++i)
    {
      const int a = constrainedFaces[i - 1], b = constrainedFaces[i];
      if (a == b || Surface.FaceComponent(a) != Surface.FaceComponent(b))
      {
        continue;
      }
      std::vector<int> path;
      for (int c = 0; c < 3; ++c)
      {
        const int t = Surface.Twin(3 * a + c);
        if (t >= 0 && TriangleMesh::FaceOf(t) == b)
        {
          path = { 3 * a + c };
        }
      }
      if (path.empty())
      {
        path = pathBetween(a, b);
      }
      cf->Paths.push_back(path);
      cf->PathEnds.emplace_back(static_cast<int>(i - 1), static_cast<int>(i));
    }
    // Rows: interior vertices and boundary loops (a loop's dual cycle is the union of its
    // vertices' fans), all but the last of each component (they sum to zero).
    const int ncomp = std::max(1, Surface.NumberOfComponents());
    std::vector<std::pair<int, int>> candidates; // (vertex, -1) or (-1, loop)
    std::vector<int> lastOfComponent(ncomp, -1);
    for (int v = 0; v < nv; ++v)
    {
      if (!Surface.IsBoundaryVertex(v))
      {
        lastOfComponent[Surface.VertexComponent(v)] = static_cast<int>(candidates.size());
        candidates.emplace_back(v, -1);
      }
    }
    const auto& loops = Surface.BoundaryLoops();
    for (int l = 0; l < static_cast<int>(loops.size()); ++l)
    {
      lastOfComponent[Surface.VertexComponent(loops[l][0])] = static_cast<int>(candidates.size());
      candidates.emplace_back(-1, l);
    }
    std::vector<char> drop(candidates.size(), 0);
    for (int c : lastOfComponent)
    {
      if (c >= 0)
      {
        drop[c] = 1;
      }
    }
    std::vector<Eigen::Triplet<double>> trip;
    int row = 0;
    auto addCrossing = [&](int r, int h) {
      const int e = cf->EdgeOf[h];
      if (e >= 0)
      {
        trip.emplace_back(r, e, h < Surface.Twin(h) ? 1.0 : -1.0);
      }
    };
    for (size_t i = 0; i < candidates.size(); ++i)
    {
      if (drop[i])
      {
        continue;
      }
      const std::vector<int> single{ candidates[i].first };
      const std::vector<int>& vertices =
        candidates[i].first >= 0 ? single : loops[candidates[i].second];
      for (int v : vertices)
      {
        for (int h : Surface.OutgoingHalfedges(v))
        {
          addCrossing(row, TriangleMesh::Prev(h));
        }
      }
      cf->RowVertices.push_back(vertices);
      ++row;
    }
    for (const auto& cycle : cf->Cycles)
    {
      for (int h : cycle)
      {
        addCrossing(row, h);
      }
      ++row;
    }
    for (const auto& path : cf->Paths)
    {
      for (int h : path)
      {
        addCrossing(row, h);
      }
      ++row;
    }
    cf->Holonomy.resize(row, ne);
    cf->Holonomy.setFromTriplets(trip.begin(), trip.end());
    const Eigen::SparseMatrix<double> k =
      cf->Holonomy * cf->InverseWeight.asDiagonal() * cf->Holonomy.transpose();
    cf->Solver.compute(k);
    if (cf->Solver.info() != Eigen::Success)
    {
      return Status::Error("factorization of the trivial-connection system failed");
    }
    cf->ComponentEuler.assign(ncomp, 0.0);
    for (int v = 0; v < nv; ++v)
    {
      cf->ComponentEuler[Surface.VertexComponent(v)] += 1.0;
    }
    for (int f = 0; f < nf; ++f)
    {
      cf->ComponentEuler[Surface.FaceComponent(f)] += 1.0;
      for (int c = 0; c < 3; ++c)
      {
        const int h = 3 * f + c;
        cf->ComponentEuler[Surface.FaceComponent(f)] -=
          Surface.Twin(h) < 0 ? 1.0 : (Surface.Twin(h) > h ? 1.0 : 0.0);
      }
    }
    ConnectionCache = std::move(cf);
  }
  ConnectionFactorization& cf = *ConnectionCache;

  // Poincare-Hopf check per component.
  std::vector<double> sum(cf.ComponentEuler.size(), 0.0);
  for (int v = 0; v < nv; ++v)
  {
    sum[Surface.VertexComponent(v)] += index[v];
  }
  for (size_t c = 0; c < sum.size(); ++c)
  {
    if (std::abs(sum[c] - cf.ComponentEuler[c]) > 1e-6)
    {
      char buffer[256];
      std::snprintf(buffer, sizeof(buffer),
        "singularity indices sum to %g but must sum to the Euler characteristic %g%s "
        "(boundary vertices count the field's turning against the boundary)",
        sum[c], cf.ComponentEuler[c],
        sum.size() > 1 ? (" of connected component " + std::to_string(c)).c_str() : "");
      return Status::Error(buffer);
    }
  }
  // Right-hand side.
  const int rows = static_cast<int>(cf.Holonomy.rows());
  Eigen::VectorXd b(rows);
  int row = 0;
  for (const std::vector<int>& vertices : cf.RowVertices)
  {
    double rhs = 0.0;
    for (int v : vertices)
    {
      const double defect = (Surface.IsBoundaryVertex(v) ? Pi : TwoPi) - Surface.TotalAngle(v);
      rhs += TwoPi * index[v] - defect;
    }
    b[row++] = rhs;
  }
  const double quantum = TwoPi / n;
  for (const auto& cycle : cf.Cycles)
  {
    double hol = 0.0;
    for (int h : cycle)
    {
      hol += Transport[h];
    }
    b[row++] = quantum * std::round(hol / quantum) - hol;
  }
  for (size_t i = 0; i < cf.Paths.size(); ++i)
  {
    const FaceDirectionConstraint& a = constraints[cf.PathEnds[i].first];
    const FaceDirectionConstraint& c = constraints[cf.PathEnds[i].second];
    double hol = 0.0;
    for (int h : cf.Paths[i])
    {
      hol += Transport[h];
    }
    b[row++] = WrapSymmetric(AngleInFace(c.Face, c.Direction) - AngleInFace(a.Face, a.Direction) - hol, n);
  }
  const Eigen::VectorXd lambda = cf.Solver.solve(b);
  const Eigen::VectorXd x = cf.InverseWeight.asDiagonal() * (cf.Holonomy.transpose() * lambda);
  const double residual = (cf.Holonomy * x - b).norm();
  if (!x.allFinite() || residual > 1e-7 * (1.0 + b.norm()))
  {
    return Status::Error("the singularities and direction constraints are incompatible (a "
                         "constraint crosses a singularity or two constraints disagree): "
                         "residual " +
      std::to_string(residual));
  }
  // Transport over the dual tree, then rotate each component onto its first constraint.
  angles.assign(nf, 0.0);
  for (int f : cf.Order)
  {
    const int h = cf.ParentHalfedge[f];
    if (h < 0)
    {
      continue;
    }
    const int e = cf.EdgeOf[h];
    angles[f] =
      angles[TriangleMesh::FaceOf(h)] + Transport[h] + (h < Surface.Twin(h) ? x[e] : -x[e]);
  }
  std::vector<char> rotated(cf.ComponentEuler.size(), 0);
  std::vector<double> shift(cf.ComponentEuler.size(), 0.0);
  for (const FaceDirectionConstraint& c : constraints)
  {
    const int comp = Surface.FaceComponent(c.Face);
    if (!rotated[comp])
    {
      rotated[comp] = 1;
      shift[comp] = AngleInFace(c.Face, c.Direction) - angles[c.Face];
    }
  }
  for (int f = 0; f < nf; ++f)
  {
    angles[f] = WrapPi(angles[f] + shift[Surface.FaceComponent(f)]);
  }
  return Status();
}


Streamline DirectionFieldSolver::TraceStreamline(int n, const std::vector<double>& angles,
  const SurfacePoint& start, double initialAngle, double length, const std::vector<double>* indices,
  double maxTurn) const
{
  StreamlineTracer tracer(*this, n, angles, start, initialAngle, length, indices, maxTurn);
  tracer.Continue();
  return std::move(tracer.Line());
}

DirectionFieldSolver::StreamlineTracer::StreamlineTracer(const DirectionFieldSolver& solver, int n,
  const std::vector<double>& angles, const SurfacePoint& start, double initialAngle, double length,
  const std::vector<double>* indices, double maxTurn)
  : Solver(solver)
  , Angles(angles)
  , Indices(indices)
  , Symmetry(n)
  , MaxTurn(maxTurn < 0 ? 0.9 * Pi / std::max(n, 1) : maxTurn)
{
  const TriangleMesh& surface = Solver.Surface;
  const int nf = surface.NumberOfFaces();
  if (n < 1 || static_cast<int>(angles.size()) != nf || nf == 0 || !(length >= 0.0) ||
    !std::isfinite(length))
  {
    Traced.Reason = Streamline::Stuck;
    Done = true;
    return;
  }
  Face = start.Face;
  if (start.IsVertex())
  {
    Face = TriangleMesh::FaceOf(surface.VertexHalfedge(start.Vertex));
    Point = surface.Position(start.Vertex);
  }
  else
  {
    Point = surface.Interpolate(Face, start.Bary);
  }
  Traced.End = SurfacePoint::InFace(Face, 0, 0, 0);
  Traced.End.Bary = surface.ClampedBarycentric(Face, Point);
  if (Singular(Face))
  {
    Traced.Reason = Streamline::ReachedSingularity;
    Done = true;
    return;
  }
  // Representative closest to the wanted angle.
  Angle = initialAngle + WrapSymmetric(Angles[Face] - initialAngle, Symmetry);
  Direction = Solver.DirectionInFace(Face, Angle);
  Remaining = length;
  // (At most 10 nf + 1000 faces crossed, whatever the stages.)
  StepsLeft = 10LL * nf + 1000;
}

bool DirectionFieldSolver::StreamlineTracer::Singular(int face) const
{
  if (!Indices)
  {
    return false;
  }
  const TriangleMesh& surface = Solver.Surface;
  for (int c = 0; c < 3; ++c)
  {
    if (std::abs((*Indices)[surface.Face(face)[c]]) > 1e-9 &&
      !surface.IsBoundaryVertex(surface.Face(face)[c]))
    {
      return true;
    }
  }
  return false;
}

void DirectionFieldSolver::StreamlineTracer::Finish()
{
  Done = true;
  Traced.End = SurfacePoint::InFace(Face, 0, 0, 0);
  Traced.End.Bary = Solver.Surface.ClampedBarycentric(Face, Point);
}

bool DirectionFieldSolver::StreamlineTracer::Continue(double until)
{
  const TriangleMesh& surface = Solver.Surface;
  while (!Done && !(Traced.Length >= until))
  {
    if (StepsLeft-- <= 0)
    {
      Finish(); // (Reason stays ReachedLength, as the loop of old ended)
      break;
    }
    const FaceExit out = FindFaceExit(surface, Face, Point, Direction, Entry);
    if (out.Edge < 0)
    {
      Traced.Reason = Streamline::Stuck;
      Finish();
      break;
    }
    if (out.T >= Remaining)
    {
      const Vec3 y = Point + Direction * Remaining;
      Traced.Pieces.push_back({ Face, Point, y });
      Traced.Length += Remaining;
      Point = y;
      Traced.Reason = Streamline::ReachedLength;
      Finish();
      break;
    }
    const double s = std::min(1.0 - 1e-9, std::max(1e-9, out.S));
    const Vec3 P = surface.Position(surface.Origin(out.Edge)),
               Q = surface.Position(surface.Destination(out.Edge));
    const Vec3 y = P + (Q - P) * s;
    Traced.Pieces.push_back({ Face, Point, y });
    Traced.Length += out.T;
    Remaining -= out.T;
    Point = y;
    const int t = surface.Twin(out.Edge);
    if (t < 0)
    {
      Traced.Reason = Streamline::ReachedBoundary;
      Finish();
      break;
    }
    const int g = TriangleMesh::FaceOf(t);
    // Incoming direction transported into g, then the field's closest representative.
    const double incoming = Angle + Solver.Transport[out.Edge];
    const double next = incoming + WrapSymmetric(Angles[g] - incoming, Symmetry);
    if (std::abs(next - incoming) > MaxTurn || Singular(g))
    {
      Traced.Reason = Streamline::ReachedSingularity;
      Finish();
      break;
    }
    Face = g;
    Angle = next;
    Direction = Solver.DirectionInFace(Face, Angle);
    Entry = t;
  }
  return !Done;
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
