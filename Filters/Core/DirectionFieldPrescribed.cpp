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

} // namespace gs
