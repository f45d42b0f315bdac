// Fields with prescribed singularities: trivial connections (Crane et al. 2010) with stroke
// constraints.
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
int Find(std::vector<int>& parent, int a)
{
  while (parent[a] != a)
  {
    parent[a] = parent[parent[a]];
    a = parent[a];
  }
  return a;
}

// A spanning forest of the primal edges (both twins marked): the boundary edges first, so that
// every boundary loop keeps all but one of its edges in the tree, then the interior edges.
std::vector<char> PrimalSpanningForest(const TriangleMesh& surface)
{
  const int nv = surface.NumberOfVertices(), nh = surface.NumberOfHalfedges();
  std::vector<int> uf(nv);
  for (int v = 0; v < nv; ++v)
  {
    uf[v] = v;
  }
  std::vector<char> inTree(nh, 0);
  auto tryAdd = [&](int h) {
    const int a = Find(uf, surface.Origin(h)), b = Find(uf, surface.Destination(h));
    if (a != b)
    {
      uf[a] = b;
      inTree[h] = 1;
      if (surface.Twin(h) >= 0)
      {
        inTree[surface.Twin(h)] = 1;
      }
    }
  };
  for (int h = 0; h < nh; ++h)
  {
    if (surface.Twin(h) < 0)
    {
      tryAdd(h);
    }
  }
  for (int h = 0; h < nh; ++h)
  {
    if (surface.Twin(h) > h)
    {
      tryAdd(h);
    }
  }
  return inTree;
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
  std::vector<int> constrainedFaces;
  for (const FaceDirectionConstraint& c : constraints)
  {
    constrainedFaces.push_back(c.Face);
  }

  if (!ConnectionCache || ConnectionCache->ConstrainedFaces != constrainedFaces)
  {
    auto cf = std::make_unique<ConnectionFactorization>();
    if (Status built = cf->Build(*this, constrainedFaces); !built.Ok())
    {
      return built;
    }
    ConnectionCache = std::move(cf);
  }
  const ConnectionFactorization& cf = *ConnectionCache;

  if (Status sums = cf.CheckIndexSums(Surface, index); !sums.Ok())
  {
    return sums;
  }
  // The smallest (weighted) change x of the connection with Holonomy x = b.
  const Eigen::VectorXd b = cf.HolonomyTargets(*this, n, index, constraints);
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
  cf.IntegrateAngles(*this, x, constraints, angles);
  return Status();
}

Status DirectionFieldSolver::ConnectionFactorization::Build(
  const DirectionFieldSolver& solver, const std::vector<int>& constrainedFaces)
{
  const TriangleMesh& surface = solver.Surface;
  ConstrainedFaces = constrainedFaces;
  const int ne = IndexInteriorEdges(surface, solver.EdgeWeight);
  const std::vector<char> inPrimalTree = PrimalSpanningForest(surface);
  const std::vector<char> inDualTree = BuildDualForest(surface, inPrimalTree);
  CollectCycles(surface, inPrimalTree, inDualTree);
  CollectConstraintPaths(surface);
  const int ncomp = std::max(1, surface.NumberOfComponents());
  SelectVertexRows(surface, ncomp);
  AssembleHolonomy(surface, ne);
  const Eigen::SparseMatrix<double> k =
    Holonomy * InverseWeight.asDiagonal() * Holonomy.transpose();
  Solver.compute(k);
  if (Solver.info() != Eigen::Success)
  {
    return Status::Error("factorization of the trivial-connection system failed");
  }
  CountComponentEuler(surface, ncomp);
  return Status();
}

int DirectionFieldSolver::ConnectionFactorization::IndexInteriorEdges(
  const TriangleMesh& surface, const std::vector<double>& edgeWeight)
{
  const int nh = surface.NumberOfHalfedges();
  EdgeOf.assign(nh, -1);
  int ne = 0;
  std::vector<double> weight;
  for (int h = 0; h < nh; ++h)
  {
    const int t = surface.Twin(h);
    if (t > h)
    {
      EdgeOf[h] = EdgeOf[t] = ne++;
      weight.push_back(edgeWeight[h]);
    }
  }
  double meanW = 0.0;
  for (double w : weight)
  {
    meanW += w;
  }
  meanW = ne > 0 ? meanW / ne : 1.0;
  InverseWeight.resize(ne);
  for (int e = 0; e < ne; ++e)
  {
    InverseWeight[e] = 1.0 / std::max(weight[e], 1e-9 * meanW);
  }
  return ne;
}

std::vector<char> DirectionFieldSolver::ConnectionFactorization::BuildDualForest(
  const TriangleMesh& surface, const std::vector<char>& inPrimalTree)
{
  const int nf = surface.NumberOfFaces(), nh = surface.NumberOfHalfedges();
  ParentHalfedge.assign(nf, -2);
  Depth.assign(nf, 0);
  std::vector<char> inDual(nh, 0);
  for (int root = 0; root < nf; ++root)
  {
    if (ParentHalfedge[root] != -2)
    {
      continue;
    }
    ParentHalfedge[root] = -1;
    size_t head = Order.size();
    Order.push_back(root);
    while (head < Order.size())
    {
      const int f = Order[head++];
      for (int c = 0; c < 3; ++c)
      {
        const int h = 3 * f + c, t = surface.Twin(h);
        if (t < 0 || inPrimalTree[h])
        {
          continue;
        }
        const int g = TriangleMesh::FaceOf(t);
        if (ParentHalfedge[g] != -2)
        {
          continue;
        }
        ParentHalfedge[g] = h;
        Depth[g] = Depth[f] + 1;
        inDual[h] = inDual[t] = 1;
        Order.push_back(g);
      }
    }
  }
  return inDual;
}

std::vector<int> DirectionFieldSolver::ConnectionFactorization::DualTreePath(
  const TriangleMesh& surface, int from, int to) const
{
  int a = from, b = to;
  std::vector<int> up, down;
  while (Depth[a] > Depth[b])
  {
    up.push_back(surface.Twin(ParentHalfedge[a]));
    a = TriangleMesh::FaceOf(ParentHalfedge[a]);
  }
  while (Depth[b] > Depth[a])
  {
    down.push_back(ParentHalfedge[b]);
    b = TriangleMesh::FaceOf(ParentHalfedge[b]);
  }
  while (a != b)
  {
    up.push_back(surface.Twin(ParentHalfedge[a]));
    a = TriangleMesh::FaceOf(ParentHalfedge[a]);
    down.push_back(ParentHalfedge[b]);
    b = TriangleMesh::FaceOf(ParentHalfedge[b]);
  }
  up.insert(up.end(), down.rbegin(), down.rend());
  return up;
}

void DirectionFieldSolver::ConnectionFactorization::CollectCycles(const TriangleMesh& surface,
  const std::vector<char>& inPrimalTree, const std::vector<char>& inDualTree)
{
  for (int h = 0; h < surface.NumberOfHalfedges(); ++h)
  {
    const int t = surface.Twin(h);
    if (t > h && !inPrimalTree[h] && !inDualTree[h])
    {
      std::vector<int> cycle{ h };
      const std::vector<int> back =
        DualTreePath(surface, TriangleMesh::FaceOf(t), TriangleMesh::FaceOf(h));
      cycle.insert(cycle.end(), back.begin(), back.end());
      Cycles.push_back(cycle);
    }
  }
}

void DirectionFieldSolver::ConnectionFactorization::CollectConstraintPaths(
  const TriangleMesh& surface)
{
  for (size_t i = 1; i < ConstrainedFaces.size(); ++i)
  {
    const int a = ConstrainedFaces[i - 1], b = ConstrainedFaces[i];
    if (a == b || surface.FaceComponent(a) != surface.FaceComponent(b))
    {
      continue;
    }
    std::vector<int> path;
    for (int c = 0; c < 3; ++c)
    {
      const int t = surface.Twin(3 * a + c);
      if (t >= 0 && TriangleMesh::FaceOf(t) == b)
      {
        path = { 3 * a + c };
      }
    }
    if (path.empty())
    {
      path = DualTreePath(surface, a, b);
    }
    Paths.push_back(path);
    PathEnds.emplace_back(static_cast<int>(i - 1), static_cast<int>(i));
  }
}

void DirectionFieldSolver::ConnectionFactorization::SelectVertexRows(
  const TriangleMesh& surface, int ncomp)
{
  // A boundary loop's dual cycle is the union of its vertices' fans; the rows of a component sum
  // to zero, so its last one is left out.
  const int nv = surface.NumberOfVertices();
  std::vector<std::pair<int, int>> candidates; // (vertex, -1) or (-1, loop)
  std::vector<int> lastOfComponent(ncomp, -1);
  for (int v = 0; v < nv; ++v)
  {
    if (!surface.IsBoundaryVertex(v))
    {
      lastOfComponent[surface.VertexComponent(v)] = static_cast<int>(candidates.size());
      candidates.emplace_back(v, -1);
    }
  }
  const auto& loops = surface.BoundaryLoops();
  for (int l = 0; l < static_cast<int>(loops.size()); ++l)
  {
    lastOfComponent[surface.VertexComponent(loops[l][0])] = static_cast<int>(candidates.size());
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
  for (size_t i = 0; i < candidates.size(); ++i)
  {
    if (drop[i])
    {
      continue;
    }
    const std::vector<int> single{ candidates[i].first };
    const std::vector<int>& vertices =
      candidates[i].first >= 0 ? single : loops[candidates[i].second];
    RowVertices.push_back(vertices);
  }
}

void DirectionFieldSolver::ConnectionFactorization::AssembleHolonomy(
  const TriangleMesh& surface, int ne)
{
  std::vector<Eigen::Triplet<double>> trip;
  int row = 0;
  auto addCrossing = [&](int r, int h) {
    const int e = EdgeOf[h];
    if (e >= 0)
    {
      trip.emplace_back(r, e, h < surface.Twin(h) ? 1.0 : -1.0);
    }
  };
  for (const std::vector<int>& vertices : RowVertices)
  {
    for (int v : vertices)
    {
      for (int h : surface.OutgoingHalfedges(v))
      {
        addCrossing(row, TriangleMesh::Prev(h));
      }
    }
    ++row;
  }
  for (const auto& cycle : Cycles)
  {
    for (int h : cycle)
    {
      addCrossing(row, h);
    }
    ++row;
  }
  for (const auto& path : Paths)
  {
    for (int h : path)
    {
      addCrossing(row, h);
    }
    ++row;
  }
  Holonomy.resize(row, ne);
  Holonomy.setFromTriplets(trip.begin(), trip.end());
}

void DirectionFieldSolver::ConnectionFactorization::CountComponentEuler(
  const TriangleMesh& surface, int ncomp)
{
  ComponentEuler.assign(ncomp, 0.0);
  for (int v = 0; v < surface.NumberOfVertices(); ++v)
  {
    ComponentEuler[surface.VertexComponent(v)] += 1.0;
  }
  for (int f = 0; f < surface.NumberOfFaces(); ++f)
  {
    ComponentEuler[surface.FaceComponent(f)] += 1.0;
    for (int c = 0; c < 3; ++c)
    {
      const int h = 3 * f + c;
      ComponentEuler[surface.FaceComponent(f)] -=
        surface.Twin(h) < 0 ? 1.0 : (surface.Twin(h) > h ? 1.0 : 0.0);
    }
  }
}

Status DirectionFieldSolver::ConnectionFactorization::CheckIndexSums(
  const TriangleMesh& surface, const std::vector<double>& index) const
{
  std::vector<double> sum(ComponentEuler.size(), 0.0);
  for (int v = 0; v < surface.NumberOfVertices(); ++v)
  {
    sum[surface.VertexComponent(v)] += index[v];
  }
  for (size_t c = 0; c < sum.size(); ++c)
  {
    if (std::abs(sum[c] - ComponentEuler[c]) > 1e-6)
    {
      char buffer[256];
      std::snprintf(buffer, sizeof(buffer),
        "singularity indices sum to %g but must sum to the Euler characteristic %g%s "
        "(boundary vertices count the field's turning against the boundary)",
        sum[c], ComponentEuler[c],
        sum.size() > 1 ? (" of connected component " + std::to_string(c)).c_str() : "");
      return Status::Error(buffer);
    }
  }
  return Status();
}

Eigen::VectorXd DirectionFieldSolver::ConnectionFactorization::HolonomyTargets(
  const DirectionFieldSolver& solver, int n, const std::vector<double>& index,
  const std::vector<FaceDirectionConstraint>& constraints) const
{
  const TriangleMesh& surface = solver.Surface;
  const std::vector<double>& transport = solver.Transport;
  const int rows = static_cast<int>(Holonomy.rows());
  Eigen::VectorXd b(rows);
  int row = 0;
  for (const std::vector<int>& vertices : RowVertices)
  {
    double rhs = 0.0;
    for (int v : vertices)
    {
      const double defect = (surface.IsBoundaryVertex(v) ? Pi : TwoPi) - surface.TotalAngle(v);
      rhs += TwoPi * index[v] - defect;
    }
    b[row++] = rhs;
  }
  const double quantum = TwoPi / n;
  for (const auto& cycle : Cycles)
  {
    double hol = 0.0;
    for (int h : cycle)
    {
      hol += transport[h];
    }
    b[row++] = quantum * std::round(hol / quantum) - hol;
  }
  for (size_t i = 0; i < Paths.size(); ++i)
  {
    const FaceDirectionConstraint& a = constraints[PathEnds[i].first];
    const FaceDirectionConstraint& c = constraints[PathEnds[i].second];
    double hol = 0.0;
    for (int h : Paths[i])
    {
      hol += transport[h];
    }
    b[row++] = WrapSymmetric(
      solver.AngleInFace(c.Face, c.Direction) - solver.AngleInFace(a.Face, a.Direction) - hol, n);
  }
  return b;
}

void DirectionFieldSolver::ConnectionFactorization::IntegrateAngles(
  const DirectionFieldSolver& solver, const Eigen::VectorXd& edgeRotation,
  const std::vector<FaceDirectionConstraint>& constraints, std::vector<double>& angles) const
{
  const TriangleMesh& surface = solver.Surface;
  const std::vector<double>& transport = solver.Transport;
  const int nf = surface.NumberOfFaces();
  angles.assign(nf, 0.0);
  for (int f : Order)
  {
    const int h = ParentHalfedge[f];
    if (h < 0)
    {
      continue;
    }
    const int e = EdgeOf[h];
    angles[f] = angles[TriangleMesh::FaceOf(h)] + transport[h] +
      (h < surface.Twin(h) ? edgeRotation[e] : -edgeRotation[e]);
  }
  std::vector<char> rotated(ComponentEuler.size(), 0);
  std::vector<double> shift(ComponentEuler.size(), 0.0);
  for (const FaceDirectionConstraint& c : constraints)
  {
    const int comp = surface.FaceComponent(c.Face);
    if (!rotated[comp])
    {
      rotated[comp] = 1;
      shift[comp] = solver.AngleInFace(c.Face, c.Direction) - angles[c.Face];
    }
  }
  for (int f = 0; f < nf; ++f)
  {
    angles[f] = WrapPi(angles[f] + shift[surface.FaceComponent(f)]);
  }
}

} // namespace gs
