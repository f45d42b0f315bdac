// What the direction field solver's files share (DirectionField.cpp, DirectionFieldSmoothest.cpp,
// DirectionFieldPrescribed.cpp, StreamlineTracer.cpp): the factorizations the solver keeps
// between solves and a few helpers. Not part of the core's interface.
#pragma once

#include "DirectionField.h"

#include <Eigen/Dense>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace gs
{

namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double TwoPi = 2.0 * Pi;

inline Status CheckSymmetry(int n)
{
  if (n != 1 && n != 2 && n != 4)
  {
    return Status::Error(
      "Symmetry must be 1 (vector field), 2 (line field) or 4 (cross field); it is " +
      std::to_string(n));
  }
  return Status();
}

inline double WrapPi(double a)
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

} // namespace gs
