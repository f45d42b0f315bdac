// The smoothest N-direction field (the smallest eigenvector of the connection Laplacian, with
// alignment and stroke constraints).
#include "DirectionFieldImpl.h"

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
// The constraints as unit complex numbers exp(i N angle) per face (the mean of a face's
// constraints, normalised) and the constrained faces in increasing order.
struct ConstraintValues
{
  std::vector<double> Re, Im;
  std::vector<char> IsConstrained;
  std::vector<int> Faces;
};

// Fills `values` from `constraints`; fails on an invalid constraint, one normal to its face, or
// constraints of one face that cancel.
Status GatherConstraintValues(const DirectionFieldSolver& solver, int n,
  const std::vector<FaceDirectionConstraint>& constraints, ConstraintValues& values)
{
  const int nf = solver.Mesh().NumberOfFaces();
  values.Re.assign(nf, 0.0);
  values.Im.assign(nf, 0.0);
  values.IsConstrained.assign(nf, 0);
  for (const FaceDirectionConstraint& c : constraints)
  {
    if (c.Face < 0 || c.Face >= nf || !IsFinite(c.Direction))
    {
      return Status::Error("invalid direction constraint (face " + std::to_string(c.Face) + ")");
    }
    const double a = solver.AngleInFace(c.Face, c.Direction);
    const double x = Dot(c.Direction, solver.FaceBasisX(c.Face)),
                 y = Dot(c.Direction, solver.FaceBasisY(c.Face));
    if (std::hypot(x, y) <= 0.0)
    {
      return Status::Error("direction constraint normal to its face " + std::to_string(c.Face));
    }
    values.Re[c.Face] += std::cos(n * a);
    values.Im[c.Face] += std::sin(n * a);
    values.IsConstrained[c.Face] = 1;
  }
  for (int f = 0; f < nf; ++f)
  {
    if (values.IsConstrained[f])
    {
      const double l = std::hypot(values.Re[f], values.Im[f]);
      if (l < 1e-12)
      {
        return Status::Error("contradictory direction constraints in face " + std::to_string(f));
      }
      values.Re[f] /= l;
      values.Im[f] /= l;
      values.Faces.push_back(f);
    }
  }
  return Status();
}

// Total edge weight over total area: the scale that makes the alignment and regularisation
// terms comparable with the smoothness energy.
double EnergyPerArea(const TriangleMesh& surface, const std::vector<double>& edgeWeight)
{
  double sumW = 0.0, sumA = 0.0;
  for (int h = 0; h < surface.NumberOfHalfedges(); ++h)
  {
    sumW += edgeWeight[h];
  }
  for (int f = 0; f < surface.NumberOfFaces(); ++f)
  {
    sumA += surface.FaceArea(f);
  }
  return sumA > 0 ? sumW / sumA : 1.0;
}

// Per face the angle of the field whose N-th power is u (free faces) or the constraint's value
// (constrained faces): the argument divided by N.
void AnglesFromPowers(int n, const std::vector<int>& freeIndex, const Eigen::VectorXd& u,
  const ConstraintValues& values, std::vector<double>& angles)
{
  const int nf = static_cast<int>(freeIndex.size());
  angles.assign(nf, 0.0);
  for (int f = 0; f < nf; ++f)
  {
    const int i = freeIndex[f];
    const double x = i >= 0 ? u[2 * i] : values.Re[f];
    const double y = i >= 0 ? u[2 * i + 1] : values.Im[f];
    angles[f] = std::atan2(y, x) / n;
  }
}
} // namespace

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
  ConstraintValues values;
  if (Status gathered = GatherConstraintValues(*this, n, constraints, values); !gathered.Ok())
  {
    return gathered;
  }
  const std::vector<int>& constrained = values.Faces;

  const double sigma = EnergyPerArea(Surface, EdgeWeight); // energy / area scale
  const double eps = 1e-10 * sigma;

  if (!Cache || Cache->Symmetry != n || Cache->Alignment != alignment ||
    Cache->Constrained != constrained)
  {
    Cache = std::make_unique<Factorization>();
    Cache->Symmetry = n;
    Cache->Alignment = alignment;
    Cache->Constrained = constrained;
    Cache->AssembleSystem(*this, sigma, eps);
    if (Status factorized = Cache->FactorizeFreeBlock(values.IsConstrained); !factorized.Ok())
    {
      Cache.reset();
      return factorized;
    }
  }

  const std::vector<int>& freeIndex = Cache->FreeIndex;
  const int nfree = static_cast<int>(freeIndex.size() - constrained.size());
  const Eigen::VectorXd rhsFixed = Cache->FixedRightHandSide(*this, values.Re, values.Im, sigma);
  // Components with neither constraints nor alignment: inverse iteration for the smallest
  // eigenvector (Knoppel et al.), normalised per component.
  const int ncomp = std::max(1, Surface.NumberOfComponents());
  std::vector<char> componentFree(ncomp, alignment > 0 ? 0 : 1);
  for (int f : constrained)
  {
    componentFree[Surface.FaceComponent(f)] = 0;
  }
  const bool iterate =
    std::find(componentFree.begin(), componentFree.end(), 1) != componentFree.end();
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
      u = Cache->InverseIterationPerComponent(Surface, componentFree, rhsFixed);
    }
    if (!u.allFinite())
    {
      return Status::Error("direction field solve produced non-finite values");
    }
  }
  AnglesFromPowers(n, freeIndex, u, values, angles);
  return Status();
}

void DirectionFieldSolver::Factorization::AssembleSystem(
  const DirectionFieldSolver& solver, double sigma, double eps)
{
  const TriangleMesh& surface = solver.Surface;
  const int nf = surface.NumberOfFaces(), n = Symmetry;
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(8 * surface.NumberOfHalfedges() + 2 * nf);
  for (int h = 0; h < surface.NumberOfHalfedges(); ++h)
  {
    const int t = surface.Twin(h);
    if (t < h)
    {
      continue; // boundary or already seen from its twin
    }
    const int f = TriangleMesh::FaceOf(h), g = TriangleMesh::FaceOf(t);
    const double w = solver.EdgeWeight[h];
    const double c = std::cos(n * solver.Transport[h]), s = std::sin(n * solver.Transport[h]);
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
    const double d = (Alignment * sigma + eps) * surface.FaceArea(f);
    trip.emplace_back(2 * f, 2 * f, d);
    trip.emplace_back(2 * f + 1, 2 * f + 1, d);
  }
  System.resize(2 * nf, 2 * nf);
  System.setFromTriplets(trip.begin(), trip.end());
}

Status DirectionFieldSolver::Factorization::FactorizeFreeBlock(
  const std::vector<char>& isConstrained)
{
  const int nf = static_cast<int>(isConstrained.size());
  FreeIndex.assign(nf, -1);
  int nfree = 0;
  for (int f = 0; f < nf; ++f)
  {
    if (!isConstrained[f])
    {
      FreeIndex[f] = nfree++;
    }
  }
  // Restrict to free rows / columns.
  std::vector<Eigen::Triplet<double>> ff, fc;
  std::vector<int> conIndex(nf, -1);
  for (size_t i = 0; i < Constrained.size(); ++i)
  {
    conIndex[Constrained[i]] = static_cast<int>(i);
  }
  for (int k = 0; k < System.outerSize(); ++k)
  {
    for (Eigen::SparseMatrix<double>::InnerIterator it(System, k); it; ++it)
    {
      const int rf = static_cast<int>(it.row()) / 2, cf = static_cast<int>(it.col()) / 2;
      const int rr = static_cast<int>(it.row()) % 2, cc = static_cast<int>(it.col()) % 2;
      if (FreeIndex[rf] < 0)
      {
        continue;
      }
      const int row = 2 * FreeIndex[rf] + rr;
      if (FreeIndex[cf] >= 0)
      {
        ff.emplace_back(row, 2 * FreeIndex[cf] + cc, it.value());
      }
      else
      {
        fc.emplace_back(row, 2 * conIndex[cf] + cc, it.value());
      }
    }
  }
  Eigen::SparseMatrix<double> bff(2 * nfree, 2 * nfree);
  bff.setFromTriplets(ff.begin(), ff.end());
  Bfc.resize(2 * nfree, 2 * static_cast<int>(Constrained.size()));
  Bfc.setFromTriplets(fc.begin(), fc.end());
  if (nfree > 0)
  {
    Solver.compute(bff);
    Bff = bff;
  }
  if (nfree > 0 && Solver.info() != Eigen::Success)
  {
    return Status::Error("factorization of the connection Laplacian failed");
  }
  return Status();
}

Eigen::VectorXd DirectionFieldSolver::Factorization::FixedRightHandSide(
  const DirectionFieldSolver& solver, const std::vector<double>& constrainedRe,
  const std::vector<double>& constrainedIm, double sigma) const
{
  const TriangleMesh& surface = solver.Surface;
  const int nf = surface.NumberOfFaces();
  const int nfree = static_cast<int>(FreeIndex.size() - Constrained.size());
  Eigen::VectorXd rhsFixed = Eigen::VectorXd::Zero(2 * nfree);
  if (!Constrained.empty())
  {
    Eigen::VectorXd uc(2 * Constrained.size());
    for (size_t i = 0; i < Constrained.size(); ++i)
    {
      uc[2 * i] = constrainedRe[Constrained[i]];
      uc[2 * i + 1] = constrainedIm[Constrained[i]];
    }
    rhsFixed -= Bfc * uc;
  }
  if (Alignment > 0)
  {
    std::vector<double> qre, qim;
    solver.ComputeCurvatureTarget(Symmetry, qre, qim);
    for (int f = 0; f < nf; ++f)
    {
      if (FreeIndex[f] >= 0)
      {
        rhsFixed[2 * FreeIndex[f]] += Alignment * sigma * surface.FaceArea(f) * qre[f];
        rhsFixed[2 * FreeIndex[f] + 1] += Alignment * sigma * surface.FaceArea(f) * qim[f];
      }
    }
  }
  return rhsFixed;
}

Eigen::VectorXd DirectionFieldSolver::Factorization::InverseIterationPerComponent(
  const TriangleMesh& surface, const std::vector<char>& componentFree,
  const Eigen::VectorXd& rhsFixed) const
{
  const int nf = surface.NumberOfFaces(), ncomp = static_cast<int>(componentFree.size());
  const int nfree = static_cast<int>(FreeIndex.size() - Constrained.size());
  Eigen::VectorXd u = Eigen::VectorXd::Zero(2 * nfree);
  std::mt19937 rng(12345u);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (int i = 0; i < 2 * nfree; ++i)
  {
    u[i] = uni(rng);
  }
  std::vector<double> norm(ncomp), compArea(ncomp, 0.0);
  for (int f = 0; f < nf; ++f)
  {
    compArea[surface.FaceComponent(f)] += surface.FaceArea(f);
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
      const int i = FreeIndex[f];
      if (i >= 0 && componentFree[surface.FaceComponent(f)])
      {
        rhs[2 * i] += surface.FaceArea(f) * u[2 * i];
        rhs[2 * i + 1] += surface.FaceArea(f) * u[2 * i + 1];
      }
    }
    Eigen::VectorXd next = Solver.solve(rhs);
    double uu = 0.0, un = 0.0;
    for (int f = 0; f < nf; ++f)
    {
      const int i = FreeIndex[f];
      if (i >= 0 && componentFree[surface.FaceComponent(f)])
      {
        uu += surface.FaceArea(f) * (u[2 * i] * u[2 * i] + u[2 * i + 1] * u[2 * i + 1]);
        un += surface.FaceArea(f) * (u[2 * i] * next[2 * i] + u[2 * i + 1] * next[2 * i + 1]);
      }
    }
    const double quotient = un != 0.0 ? uu / un : 0.0; // ~ smallest eigenvalue of B
    std::fill(norm.begin(), norm.end(), 0.0);
    for (int f = 0; f < nf; ++f)
    {
      const int i = FreeIndex[f];
      if (i >= 0)
      {
        norm[surface.FaceComponent(f)] +=
          surface.FaceArea(f) * (next[2 * i] * next[2 * i] + next[2 * i + 1] * next[2 * i + 1]);
      }
    }
    for (int f = 0; f < nf; ++f)
    {
      const int i = FreeIndex[f];
      const int c = surface.FaceComponent(f);
      if (i >= 0 && componentFree[c] && norm[c] > 0)
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
  return u;
}

} // namespace gs
