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

  // System: the connection Laplacian for N = Symmetry (sum over interior edges of
  // w |u_g - R u_f|^2) plus (Alignment sigma + eps) times the face areas on the diagonal.
  void AssembleSystem(const DirectionFieldSolver& solver, double sigma, double eps);
  // FreeIndex, Bfc and the factorized Bff: System split into its free and constrained blocks.
  Status FactorizeFreeBlock(const std::vector<char>& isConstrained);
  // The free faces' right-hand side of everything but the eigenproblem: minus Bfc times the
  // constrained values, plus the curvature alignment target.
  Eigen::VectorXd FixedRightHandSide(const DirectionFieldSolver& solver,
    const std::vector<double>& constrainedRe, const std::vector<double>& constrainedIm,
    double sigma) const;
  // The smallest eigenvector of (Bff, M), M the face areas of `surface` (Rayleigh-Ritz).
  Eigen::VectorXd SmallestEigenvector(const TriangleMesh& surface, int nf) const;
  // Inverse iteration (Knoppel et al.) on the components marked in `componentFree`, the other
  // free faces solved with `rhsFixed`; each iterated component normalised to its area.
  Eigen::VectorXd InverseIterationPerComponent(const TriangleMesh& surface,
    const std::vector<char>& componentFree, const Eigen::VectorXd& rhsFixed) const;
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

  // Everything that depends only on the mesh and the constrained faces: the tree-cotree
  // decomposition, the holonomy rows and the factorization of their weighted normal equations.
  Status Build(const DirectionFieldSolver& solver, const std::vector<int>& constrainedFaces);
  // EdgeOf and InverseWeight (the inverse edge weights, floored relative to their mean);
  // returns the number of interior edges.
  int IndexInteriorEdges(const TriangleMesh& surface, const std::vector<double>& edgeWeight);
  // ParentHalfedge, Depth and Order: a breadth-first spanning forest of the dual graph that never
  // crosses a primal tree edge. Returns the half-edges it crosses (both twins marked).
  std::vector<char> BuildDualForest(
    const TriangleMesh& surface, const std::vector<char>& inPrimalTree);
  // The half-edges crossed going from face `from` to face `to` along the dual tree.
  std::vector<int> DualTreePath(const TriangleMesh& surface, int from, int to) const;
  // Cycles: one homology generator per edge in neither the primal nor the dual tree.
  void CollectCycles(const TriangleMesh& surface, const std::vector<char>& inPrimalTree,
    const std::vector<char>& inDualTree);
  // Paths and PathEnds: a dual path between each two consecutive constrained faces of a component.
  void CollectConstraintPaths(const TriangleMesh& surface);
  // RowVertices: every interior vertex and boundary loop but the last of each component (the
  // last one's holonomy follows from the others').
  void SelectVertexRows(const TriangleMesh& surface, int ncomp);
  // Holonomy: the signed interior edges crossed by each row (vertices, cycles, paths).
  void AssembleHolonomy(const TriangleMesh& surface, int ne);
  // ComponentEuler: V - E + F of each connected component.
  void CountComponentEuler(const TriangleMesh& surface, int ncomp);
  // Fails unless the indices of each component sum to its Euler characteristic (Poincare-Hopf).
  Status CheckIndexSums(const TriangleMesh& surface, const std::vector<double>& index) const;
  // The holonomy change each row asks of the connection: the prescribed index less the angle
  // defect (vertices), the rounding to a multiple of 2 pi / N (cycles), the constraints' relative
  // angle (paths).
  Eigen::VectorXd HolonomyTargets(const DirectionFieldSolver& solver, int n,
    const std::vector<double>& index,
    const std::vector<FaceDirectionConstraint>& constraints) const;
  // Angles transported over the dual tree with the connection changed by `edgeRotation`, each
  // component then rotated onto its first constraint and wrapped to [-pi, pi).
  void IntegrateAngles(const DirectionFieldSolver& solver, const Eigen::VectorXd& edgeRotation,
    const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles) const;
};

} // namespace gs
