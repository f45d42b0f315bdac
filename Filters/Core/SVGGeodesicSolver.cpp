#include "SVGGeodesicSolver.h"

#include "GeodesicUnfolding.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{

namespace
{
constexpr double Inf = std::numeric_limits<double>::infinity();

double PointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double l2 = Dot(ab, ab);
  double t = l2 > 0.0 ? Dot(p - a, ab) / l2 : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return Norm(p - (a + ab * t));
}
} // namespace

SVGGeodesicSolver::SVGGeodesicSolver(const TriangleMesh& mesh, const SaddleVertexGraph& graph)
  : M(mesh)
  , G(graph)
  , Local(mesh)
  , Graph(graph)
{
  AnchorVertex.assign(M.NumberOfVertices(), 0);
  for (int v = 0; v < M.NumberOfVertices(); ++v)
  {
    AnchorVertex[v] = M.IsPseudoSourceVertex(v) ? 1 : 0;
  }
  Graph.SetAnchorVertices(&AnchorVertex);
  Done.assign(M.NumberOfVertices(), 0);
}

void SVGGeodesicSolver::Refine(double maxDistance)
{
  const double limit = maxDistance > 0.0 ? maxDistance : Inf;
  struct Item
  {
    double D;
    int V;
    bool operator<(const Item& o) const { return D > o.D; }
  };
  std::vector<Item> heap;
  const std::vector<int>& reached = Graph.Reached();
  heap.reserve(reached.size());
  for (int v : reached)
  {
    heap.push_back({ Graph.Distance(v), v });
  }
  std::make_heap(heap.begin(), heap.end());
  Reached.assign(reached.begin(), reached.end());
  // The anchor shared by an edge's end points, and its own distance: for a vertex anchor its
  // distance, for a source point zero.
  auto sigma = [&](int a) { return a >= 0 ? Graph.Distance(a) : 0.0; };
  while (!heap.empty())
  {
    std::pop_heap(heap.begin(), heap.end());
    const Item it = heap.back();
    heap.pop_back();
    const int v = it.V;
    if (Done[v] || it.D > Graph.Distance(v))
    {
      continue;
    }
    Done[v] = 1;
    const int av = Graph.StoredAnchor(v);
    int h = M.VertexHalfedge(v);
    const int start = h;
    do
    {
      // Face (v, a, b): update b from edge (v, a) and a from edge (v, b).
      for (int side = 0; side < 2; ++side)
      {
        const int e = side == 0 ? h : TriangleMesh::Prev(h); // edge v-w in this face
        const int w = side == 0 ? M.Destination(h) : M.Origin(e);
        const int c = side == 0 ? M.Opposite(h) : M.Destination(h);
        if (!Done[w] || Done[c])
        {
          continue;
        }
        const int aw = Graph.StoredAnchor(w);
        int anchor;
        if (av == aw && av != -1)
          anchor = av;
        else if (aw == v && AnchorVertex[v])
          anchor = v;
        else if (av == w && AnchorVertex[w])
          anchor = w;
        else
          continue;
        const double s0 = sigma(anchor);
        const double rv = anchor == v ? 0.0 : Graph.Distance(v) - s0;
        const double rw = anchor == w ? 0.0 : Graph.Distance(w) - s0;
        if (!(rv >= 0.0) || !(rw >= 0.0))
          continue;
        // Layout: v at the origin, w on the x axis, c above.
        const double L = M.EdgeLength(e);
        const double lvc = side == 0 ? M.EdgeLength(TriangleMesh::Prev(h)) : M.EdgeLength(h);
        const double angle = M.CornerAngle(h); // angle at v in this face
        const double cx = lvc * std::cos(angle), cy = lvc * std::sin(angle);
        const double x = (rv * rv - rw * rw + L * L) / (2.0 * L);
        const double y2 = rv * rv - x * x;
        if (y2 < 0.0)
          continue;
        const double sy = -std::sqrt(y2);
        const double denom = cy - sy;
        if (!(denom > 0.0))
          continue;
        const double xc = x + (cx - x) * (-sy) / denom;
        if (xc < -1e-9 * L || xc > L * (1.0 + 1e-9))
          continue;
        const double cand = s0 + std::hypot(cx - x, cy - sy);
        if (cand < Graph.Distance(c) * (1.0 - 1e-12) && cand <= limit)
        {
          if (!std::isfinite(Graph.Distance(c)))
          {
            Reached.push_back(c);
          }
          Graph.Lower(c, cand, anchor);
          heap.push_back({ cand, c });
          std::push_heap(heap.begin(), heap.end());
        }
      }
      h = M.RotateCCW(h);
    } while (h >= 0 && h != start);
  }
  for (int v : Reached)
  {
    Done[v] = 0;
  }
}

bool SVGGeodesicSolver::ValidPoint(const SurfacePoint& p) const
{
  if (p.IsVertex())
  {
    return p.Vertex < M.NumberOfVertices();
  }
  if (p.Face < 0 || p.Face >= M.NumberOfFaces())
  {
    return false;
  }
  const double sum = p.Bary[0] + p.Bary[1] + p.Bary[2];
  return std::isfinite(sum) && std::abs(sum - 1.0) <= 1e-6 && p.Bary[0] >= -1e-6 &&
    p.Bary[1] >= -1e-6 && p.Bary[2] >= -1e-6;
}

Vec3 SVGGeodesicSolver::PositionOf(const SurfacePoint& p) const
{
  return p.IsVertex() ? M.Position(p.Vertex) : M.Interpolate(p.Face, p.Bary);
}

bool SVGGeodesicSolver::SolveFromPieces(const std::vector<SurfacePoint>& exactSources,
  int finalVertices, const SVGSolveOptions& options)
{
  std::sort(Pieces.begin(), Pieces.end(), [](const Piece& a, const Piece& b) { return a.Face < b.Face; });
  // Anchors of seeds: -2 - i for source point i of the exact solve (distance 0), a vertex id for
  // a saddle the exact path passed through, -2 - n - j for curve piece j.
  std::vector<std::pair<int, double>> seeds;
  std::vector<int> anchors;
  const int n = static_cast<int>(exactSources.size());
  if (!exactSources.empty())
  {
    ExactGeodesicOptions local;
    local.MaximumFinalVertices = std::min(finalVertices, M.NumberOfVertices());
    local.MaximumDistance = options.MaximumDistance;
    if (!Local.Solve(exactSources, local))
    {
      return false;
    }
    for (int v : Local.FinalVertices())
    {
      seeds.emplace_back(v, Local.Distance(v));
      const int origin = Local.PathOrigin(v);
      anchors.push_back(origin >= 0 ? -2 - origin : -1 - origin);
    }
  }
  // Corners of faces holding a piece: the exact in-face distance to the piece.
  for (std::size_t j = 0; j < Pieces.size(); ++j)
  {
    const Piece& p = Pieces[j];
    const auto& t = M.Face(p.Face);
    for (int k = 0; k < 3; ++k)
    {
      seeds.emplace_back(t[k], PointSegmentDistance(M.Position(t[k]), p.A, p.B));
      anchors.push_back(-2 - n - static_cast<int>(j));
    }
  }
  Graph.Solve(seeds, options.Algorithm, options.MaximumDistance, anchors);
  if (options.Refine)
  {
    Refine(options.MaximumDistance);
  }
  return true;
}

bool SVGGeodesicSolver::Solve(const std::vector<SurfacePoint>& sources, const SVGSolveOptions& options)
{
  Pieces.clear();
  if (sources.empty() || G.NumberOfVertices() != M.NumberOfVertices())
  {
    Graph.Solve({}, options.Algorithm);
    return false;
  }
  std::vector<SurfacePoint> facePoints;
  std::vector<std::pair<int, double>> vertexSeeds;
  for (const SurfacePoint& s : sources)
  {
    if (!ValidPoint(s))
    {
      Graph.Solve({}, options.Algorithm);
      return false;
    }
    if (s.IsVertex())
    {
      vertexSeeds.emplace_back(s.Vertex, 0.0);
    }
    else
    {
      facePoints.push_back(s);
      const Vec3 p = PositionOf(s);
      Pieces.push_back({ s.Face, p, p });
    }
  }
  if (facePoints.empty())
  {
    Graph.Solve(vertexSeeds, options.Algorithm, options.MaximumDistance);
    if (options.Refine)
    {
      Refine(options.MaximumDistance);
    }
    return true;
  }
  // Vertex sources join the exact local solve so that its truncation sees all sources.
  for (const auto& v : vertexSeeds)
  {
    facePoints.push_back(SurfacePoint::AtVertex(v.first));
  }
  const int k = std::max(G.GetK(), 1);
  return SolveFromPieces(facePoints, k * static_cast<int>(facePoints.size()), options);
}

bool SVGGeodesicSolver::SolveCurves(
  const std::vector<std::vector<SurfacePoint>>& curves, const SVGSolveOptions& options)
{
  Pieces.clear();
  std::vector<CurvePiece> pieces;
  bool valid = !curves.empty() && G.NumberOfVertices() == M.NumberOfVertices();
  for (const auto& curve : curves)
  {
    valid = valid && !curve.empty();
    for (const SurfacePoint& s : curve)
    {
      valid = valid && ValidPoint(s);
    }
  }
  if (!valid)
  {
    Graph.Solve({}, options.Algorithm);
    return false;
  }
  for (const auto& curve : curves)
  {
    const std::vector<CurvePiece> traced = TraceSurfaceCurve(M, curve);
    pieces.insert(pieces.end(), traced.begin(), traced.end());
  }
  // The exact local solve starts from samples along the pieces, dense enough that the sampled
  // curve is within a small fraction of an edge of the true one; the pieces themselves give the
  // exact in-face distances.
  const std::vector<SurfacePoint> samples =
    SampleCurvePieces(M, pieces, CurveSampleSpacing * M.MeanEdgeLength());
  std::vector<int> faces;
  for (const CurvePiece& p : pieces)
  {
    Pieces.push_back({ p.Face, p.A, p.B });
    faces.push_back(p.Face);
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  const long long wanted = static_cast<long long>(std::max(G.GetK(), 1)) * static_cast<long long>(faces.size());
  return SolveFromPieces(
    samples, static_cast<int>(std::min<long long>(wanted, M.NumberOfVertices())), options);
}

double SVGGeodesicSolver::DistanceAt(const SurfacePoint& q) const
{
  if (!ValidPoint(q))
  {
    return Inf;
  }
  if (q.IsVertex())
  {
    return Graph.Distance(q.Vertex);
  }
  const auto& t = M.Face(q.Face);
  double best = UnfoldedDistance(M, q.Face, q.Bary,
    { { Graph.Distance(t[0]), Graph.Distance(t[1]), Graph.Distance(t[2]) } });
  // Sources in the same face: the straight segment inside the face.
  auto it = std::lower_bound(Pieces.begin(), Pieces.end(), q.Face,
    [](const Piece& p, int f) { return p.Face < f; });
  if (it != Pieces.end() && it->Face == q.Face)
  {
    const Vec3 x = PositionOf(q);
    for (; it != Pieces.end() && it->Face == q.Face; ++it)
    {
      best = std::min(best, PointSegmentDistance(x, it->A, it->B));
    }
  }
  return best;
}

double SVGGeodesicSolver::Distance(const SurfacePoint& a, const SurfacePoint& b)
{
  if (!Solve({ a }))
  {
    return Inf;
  }
  return DistanceAt(b);
}

std::vector<double> SVGGeodesicSolver::DistancesTo(
  const SurfacePoint& a, const std::vector<SurfacePoint>& targets)
{
  std::vector<double> out(targets.size(), Inf);
  if (!Solve({ a }))
  {
    return out;
  }
  for (std::size_t i = 0; i < targets.size(); ++i)
  {
    out[i] = DistanceAt(targets[i]);
  }
  return out;
}

} // namespace gs
