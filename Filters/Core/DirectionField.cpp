#include "DirectionField.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <random>

namespace gs
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double TwoPi = 2.0 * Pi;

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
  int N = 0;
  double Alignment = -1.0;
  std::vector<int> Constrained; // sorted constrained faces
  std::vector<int> FreeIndex;   // face -> row block among free faces, -1 if constrained
  Eigen::SparseMatrix<double> B;   // full 2F x 2F system matrix
  Eigen::SparseMatrix<double> Bfc; // free rows x constrained columns
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> Solver;
  bool Ok = false;
};

DirectionFieldSolver::DirectionFieldSolver(const TriangleMesh& mesh)
  : M(mesh)
{
  const int nf = M.NumberOfFaces();
  BasisX.resize(nf);
  BasisY.resize(nf);
  for (int f = 0; f < nf; ++f)
  {
    const Vec3 n = M.FaceNormal(f);
    Vec3 x = M.Position(M.Destination(3 * f)) - M.Position(M.Origin(3 * f));
    const double l = Norm(x);
    x = l > 0 ? x / l : Vec3(1, 0, 0);
    BasisX[f] = x;
    BasisY[f] = Cross(n, x);
  }
  Transport.assign(M.NumberOfHalfedges(), 0.0);
  EdgeWeight.assign(M.NumberOfHalfedges(), 0.0);
  for (int h = 0; h < M.NumberOfHalfedges(); ++h)
  {
    const int t = M.Twin(h);
    if (t < 0)
    {
      continue;
    }
    const Vec3 e = M.Position(M.Destination(h)) - M.Position(M.Origin(h));
    const int f = TriangleMesh::FaceOf(h), g = TriangleMesh::FaceOf(t);
    // e has angle a_f in f and a_g in g: phi in f is (phi - a_f) from e, hence a_g + phi - a_f.
    Transport[h] = WrapPi(AngleInFace(g, e) - AngleInFace(f, e));
    const double areas = M.FaceArea(f) + M.FaceArea(g);
    const double l = M.EdgeLength(h);
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

void DirectionFieldSolver::ComputeCurvatureTarget(
  int n, std::vector<double>& re, std::vector<double>& im) const
{
  const int nf = M.NumberOfFaces();
  const int nv = M.NumberOfVertices();
  std::vector<Vec3> vn(nv, Vec3(0, 0, 0));
  for (int f = 0; f < nf; ++f)
  {
    const Vec3 fn = M.FaceNormal(f) * M.FaceArea(f);
    for (int c = 0; c < 3; ++c)
    {
      vn[M.Face(f)[c]] += fn;
    }
  }
  for (Vec3& v : vn)
  {
    const double l = Norm(v);
    v = l > 0 ? v / l : v;
  }
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
      const Vec3 e = M.Position(M.Destination(h)) - M.Position(M.Origin(h));
      const Vec3 dn = vn[M.Destination(h)] - vn[M.Origin(h)];
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
    total += std::hypot(x, y) * M.FaceArea(f);
    area += M.FaceArea(f);
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

bool DirectionFieldSolver::SolveSmoothest(int n, double alignment,
  const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles,
  std::string& error)
{
  const int nf = M.NumberOfFaces();
  if (n != 1 && n != 2 && n != 4)
  {
    error = "symmetry must be 1, 2 or 4 (got " + std::to_string(n) + ")";
    return false;
  }
  if (!(alignment >= 0.0) || !std::isfinite(alignment))
  {
    error = "curvature alignment weight must be finite and >= 0";
    return false;
  }
  if (n == 1)
  {
    alignment = 0.0; // principal directions are lines: no vector (N = 1) target
  }
  if (nf == 0)
  {
    error = "empty mesh";
    return false;
  }
  // Constrained faces and their values exp(i N angle); repeated faces average their constraints.
  std::vector<double> cre(nf, 0.0), cim(nf, 0.0);
  std::vector<char> isConstrained(nf, 0);
  for (const FaceDirectionConstraint& c : constraints)
  {
    if (c.Face < 0 || c.Face >= nf || !IsFinite(c.Direction))
    {
      error = "invalid direction constraint (face " + std::to_string(c.Face) + ")";
      return false;
    }
    const double a = AngleInFace(c.Face, c.Direction);
    const double x = Dot(c.Direction, BasisX[c.Face]), y = Dot(c.Direction, BasisY[c.Face]);
    if (std::hypot(x, y) <= 0.0)
    {
      error = "direction constraint normal to its face " + std::to_string(c.Face);
      return false;
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
        error = "contradictory direction constraints in face " + std::to_string(f);
        return false;
      }
      cre[f] /= l;
      cim[f] /= l;
      constrained.push_back(f);
    }
  }

  double sumW = 0.0, sumA = 0.0;
  for (int h = 0; h < M.NumberOfHalfedges(); ++h)
  {
    sumW += EdgeWeight[h];
  }
  for (int f = 0; f < nf; ++f)
  {
    sumA += M.FaceArea(f);
  }
  const double sigma = sumA > 0 ? sumW / sumA : 1.0; // energy / area scale
  const double eps = 1e-10 * sigma;

  if (!Cache || Cache->N != n || Cache->Alignment != alignment || Cache->Constrained != constrained)
  {
    Cache = std::make_unique<Factorization>();
    Cache->N = n;
    Cache->Alignment = alignment;
    Cache->Constrained = constrained;
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(8 * M.NumberOfHalfedges() + 2 * nf);
    for (int h = 0; h < M.NumberOfHalfedges(); ++h)
    {
      const int t = M.Twin(h);
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
      const double d = (alignment * sigma + eps) * M.FaceArea(f);
      trip.emplace_back(2 * f, 2 * f, d);
      trip.emplace_back(2 * f + 1, 2 * f + 1, d);
    }
    Cache->B.resize(2 * nf, 2 * nf);
    Cache->B.setFromTriplets(trip.begin(), trip.end());
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
    for (int k = 0; k < Cache->B.outerSize(); ++k)
    {
      for (Eigen::SparseMatrix<double>::InnerIterator it(Cache->B, k); it; ++it)
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
      Cache->Ok = Cache->Solver.info() == Eigen::Success;
    }
    else
    {
      Cache->Ok = true;
    }
    if (!Cache->Ok)
    {
      Cache.reset();
      error = "factorization of the connection Laplacian failed";
      return false;
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
        rhsFixed[2 * freeIndex[f]] += alignment * sigma * M.FaceArea(f) * qre[f];
        rhsFixed[2 * freeIndex[f] + 1] += alignment * sigma * M.FaceArea(f) * qim[f];
      }
    }
  }
  // Components with neither constraints nor alignment: inverse iteration for the smallest
  // eigenvector (Knoppel et al.), normalised per component.
  const int ncomp = std::max(1, M.NumberOfComponents());
  std::vector<char> compFree(ncomp, alignment > 0 ? 0 : 1);
  for (int f : constrained)
  {
    compFree[M.FaceComponent(f)] = 0;
  }
  const bool iterate = std::find(compFree.begin(), compFree.end(), 1) != compFree.end();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(2 * nfree);
  if (nfree > 0)
  {
    if (!iterate)
    {
      u = Cache->Solver.solve(rhsFixed);
    }
    else
    {
      std::mt19937 rng(12345u);
      std::uniform_real_distribution<double> uni(-1.0, 1.0);
      for (int i = 0; i < 2 * nfree; ++i)
      {
        u[i] = uni(rng);
      }
      std::vector<double> norm(ncomp);
      for (int it = 0; it < 60; ++it)
      {
        Eigen::VectorXd rhs = rhsFixed;
        for (int f = 0; f < nf; ++f)
        {
          const int i = freeIndex[f];
          if (i >= 0 && compFree[M.FaceComponent(f)])
          {
            rhs[2 * i] += M.FaceArea(f) * u[2 * i];
            rhs[2 * i + 1] += M.FaceArea(f) * u[2 * i + 1];
          }
        }
        Eigen::VectorXd next = Cache->Solver.solve(rhs);
        std::fill(norm.begin(), norm.end(), 0.0);
        for (int f = 0; f < nf; ++f)
        {
          const int i = freeIndex[f];
          if (i >= 0)
          {
            norm[M.FaceComponent(f)] +=
              M.FaceArea(f) * (next[2 * i] * next[2 * i] + next[2 * i + 1] * next[2 * i + 1]);
          }
        }
        double change = 0.0;
        for (int f = 0; f < nf; ++f)
        {
          const int i = freeIndex[f];
          const int c = M.FaceComponent(f);
          if (i >= 0 && compFree[c] && norm[c] > 0)
          {
            const double s = 1.0 / std::sqrt(norm[c]);
            next[2 * i] *= s;
            next[2 * i + 1] *= s;
            change = std::max(
              change, std::hypot(next[2 * i] - u[2 * i], next[2 * i + 1] - u[2 * i + 1]));
          }
        }
        u = next;
        if (it > 3 && change < 1e-10)
        {
          break;
        }
      }
    }
    if (!u.allFinite())
    {
      error = "direction field solve produced non-finite values";
      return false;
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
  return true;
}

std::vector<double> DirectionFieldSolver::VertexIndices(int n, const std::vector<double>& angles) const
{
  const int nv = M.NumberOfVertices();
  std::vector<double> index(nv, 0.0);
  for (int v = 0; v < nv; ++v)
  {
    const std::vector<int> out = M.OutgoingHalfedges(v);
    double jumps = 0.0;
    for (int h : out)
    {
      const int p = TriangleMesh::Prev(h); // crossing p goes to the next face counter-clockwise
      const int t = M.Twin(p);
      if (t < 0)
      {
        continue;
      }
      const int f = TriangleMesh::FaceOf(h), g = TriangleMesh::FaceOf(t);
      jumps += WrapSymmetric(angles[g] - (angles[f] + Transport[p]), n);
    }
    const double defect = (M.IsBoundaryVertex(v) ? Pi : TwoPi) - M.TotalAngle(v);
    index[v] = (jumps + defect) / TwoPi;
  }
  return index;
}

std::vector<double> DirectionFieldSolver::RoundedVertexIndices(
  int n, const std::vector<double>& angles) const
{
  std::vector<double> index = VertexIndices(n, angles);
  for (int v = 0; v < M.NumberOfVertices(); ++v)
  {
    if (!M.IsBoundaryVertex(v))
    {
      index[v] = std::round(index[v] * n) / n;
    }
  }
  return index;
}

double DirectionFieldSolver::Energy(int n, const std::vector<double>& angles) const
{
  double e = 0.0, a = 0.0;
  for (int h = 0; h < M.NumberOfHalfedges(); ++h)
  {
    const int t = M.Twin(h);
    if (t < h)
    {
      continue;
    }
    const int f = TriangleMesh::FaceOf(h), g = TriangleMesh::FaceOf(t);
    const double d = n * (angles[g] - angles[f] - Transport[h]);
    e += EdgeWeight[h] * 2.0 * (1.0 - std::cos(d));
  }
  for (int f = 0; f < M.NumberOfFaces(); ++f)
  {
    a += M.FaceArea(f);
  }
  return a > 0 ? e / a : 0.0;
}

} // namespace gs
