// Shape charts: the geodesic polar coordinates (log map) about every part centre of a shape;
// what indexes an accepted shape (its chart's vertices, the corners of its centres' faces);
// commit and take back, which keep the accepted shapes (AcceptedShapes) and the sampling state
// (SamplingState) in step; the pool of exact chart engines (ExactEngineLease).
#include "ShapeDistributorImpl.h"

#include "GeodesicShooting.h"

#include <cmath>

namespace gs
{
using namespace distribution;


void ShapeDistributor::Impl::PrepareChartMeasures()
{
  const int nv = Mesh.NumberOfVertices();
  Measures.MaxEdge = Mesh.LongestEdgeLength();
  Measures.ChartMargin = 2.0 * Mesh.MeanEdgeLength();
  if (static_cast<int>(Measures.Defect.size()) != nv)
  {
    Measures.Defect.assign(nv, 0.0);
    for (int v = 0; v < nv; ++v)
    {
      Measures.Defect[v] = Mesh.IsBoundaryVertex(v) ? 0.0 : std::abs(TwoPi - Mesh.TotalAngle(v));
    }
  }
  Measures.RMax = 0.0;
  if (CircleMode)
  {
    for (const SafeDistanceClass& c : Tables.Classes)
    {
      Measures.RMax = std::max(Measures.RMax, c.Radius);
    }
  }
  else
  {
    for (const SafeDistancePart& p : Tables.Parts)
    {
      Measures.RMax = std::max(Measures.RMax, p.Radius);
    }
  }
}

void ShapeDistributor::Impl::EnsureEngines(int threads)
{
  const int nv = Mesh.NumberOfVertices();
  if (static_cast<int>(PerThread.Marks.size()) < threads)
  {
    PerThread.Marks.resize(threads);
  }
  for (auto& m : PerThread.Marks)
  {
    if (static_cast<int>(m.size()) != nv)
    {
      m.assign(nv, 0);
    }
  }
  const int have = static_cast<int>(PerThread.Engines.size());
  if (have >= threads)
  {
    return;
  }
  PerThread.Engines.resize(threads);
  ParallelFor(threads - have, threads - have, 1,
    [&](int k, int) { PerThread.Engines[have + k].reset(new GeodesicPolarCoordinates(Mesh, Graph)); });
}

void ShapeDistributor::Impl::ComputeCharts(Record& r, GeodesicPolarCoordinates& engine) const
{
  r.Charts.assign(r.Shape.Parts.size(), Chart());
  for (std::size_t k = 0; k < r.Shape.Parts.size(); ++k)
  {
    const PlacedPart& p = r.Shape.Parts[k];
    const double reference = TangentAngle(Mesh, p.Centre, p.Axis);
    if (!std::isfinite(reference) ||
      !engine.Compute(p.Centre, ChartRadius(r.Shape, p), reference).Ok())
    {
      continue; // an empty chart: this part is evaluated from the other side only
    }
    Chart& c = r.Charts[k];
    c.Entries.reserve(engine.Inside().size());
    for (int v : engine.Inside())
    {
      const double rho = engine.Rho(v), theta = engine.Theta(v);
      c.Entries.push_back(ChartEntry{ v, static_cast<float>(rho * std::cos(theta)),
        static_cast<float>(rho * std::sin(theta)) });
    }
    std::sort(c.Entries.begin(), c.Entries.end(),
      [](const ChartEntry& a, const ChartEntry& b) { return a.Vertex < b.Vertex; });
    double defects = 0.0;
    for (const ChartEntry& e : c.Entries)
    {
      defects += Measures.Defect[e.Vertex];
    }
    const double radius = ChartRadius(r.Shape, p);
    c.Roughness = static_cast<float>(defects / (Pi * radius * radius));
  }
}

std::vector<int> ShapeDistributor::Impl::ChartVertices(const Record& r)
{
  std::vector<int> vs;
  for (const Chart& c : r.Charts)
  {
    for (const ChartEntry& e : c.Entries)
    {
      vs.push_back(e.Vertex);
    }
  }
  SortUnique(vs);
  return vs;
}

std::vector<int> ShapeDistributor::Impl::CentreCorners(const Record& r) const
{
  std::vector<int> vs;
  for (const PlacedPart& p : r.Shape.Parts)
  {
    for (int v : Mesh.Face(p.Centre.Face))
    {
      vs.push_back(v);
    }
  }
  SortUnique(vs);
  return vs;
}

bool ShapeDistributor::Impl::ChartPoint(const Chart& chart, const SurfacePoint& x, double unit, Vec2& p) const
{
  const double inverse = 1.0 / unit;
  if (x.IsVertex())
  {
    const ChartEntry* e = chart.Find(x.Vertex);
    if (!e)
    {
      return false;
    }
    p = Vec2{ e->X * inverse, e->Y * inverse };
    return true;
  }
  if (x.Face < 0 || x.Face >= Mesh.NumberOfFaces())
  {
    return false;
  }
  const auto& corners = Mesh.Face(x.Face);
  Vec2 c[3];
  for (int k = 0; k < 3; ++k)
  {
    const ChartEntry* e = chart.Find(corners[k]);
    if (!e)
    {
      return false;
    }
    c[k] = Vec2{ e->X, e->Y };
  }
  if (!ChartFaceHolds(Mesh, x.Face, c, 1.0))
  {
    return false;
  }
  p = (c[0] * x.Bary[0] + c[1] * x.Bary[1] + c[2] * x.Bary[2]) * inverse;
  return true;
}

bool distribution::ChartFaceHolds(const TriangleMesh& mesh, int f, const Vec2 (&c)[3], double unit)
{
  double chart2 = 0.0, space = 0.0;
  for (int k = 0; k < 3; ++k)
  {
    const Vec2 e = c[(k + 1) % 3] - c[k];
    chart2 = std::max(chart2, Dot(e, e));
    space = std::max(space, mesh.EdgeLength(3 * f + k));
  }
  const double most = MaxChartStretch * space / unit;
  return chart2 <= most * most;
}

namespace
{
// The exact log map over the face this thread read last: an outline's points come a few to a
// face, and each face's set-up (its corners found, the face unfolded) is then made once. Keyed
// by the map itself, held so that its address is not taken by another map meanwhile.
struct LastFaceRead
{
  std::shared_ptr<const LogMapSnapshot> Map;
  int Face = -1;
  FacePolarCoordinates Coordinates;
};

bool ReadExactMap(const TriangleMesh& mesh, const std::shared_ptr<const LogMapSnapshot>& map,
  const SurfacePoint& x, Vec2& p)
{
  if (x.IsVertex())
  {
    return map->LogMapAt(mesh, x, p);
  }
  thread_local LastFaceRead last;
  if (last.Map != map || last.Face != x.Face)
  {
    last.Map = map;
    last.Face = x.Face;
    last.Coordinates = map->OnFace(mesh, x.Face);
  }
  return last.Coordinates.LogMapAt(x.Bary, p);
}
} // namespace

bool ShapeDistributor::Impl::ClassPointOf(const Record& r, const SurfacePoint& x, Vec2& p) const
{
  // Charts computed but empty (the engine failed): nothing reads, as ever. Not computed yet
  // (FaithfulCheck run before the charts): the exact log map alone reads.
  if (!r.Shape.Curve.empty() || (!r.Charts.empty() && r.Charts[0].Entries.empty()))
  {
    return false;
  }
  const double unit = Options.ShapeSize * r.Shape.Scale;
  if (r.Exact) // (the drawn check's: the exact log map of the centre)
  {
    if (!ReadExactMap(Mesh, r.Exact, x, p))
    {
      return false;
    }
    p = p * (1.0 / unit);
    return true;
  }
  if (r.Charts.empty())
  {
    return false;
  }
  return ChartPoint(r.Charts[0], x, unit, p);
}

void ShapeDistributor::Impl::PrepareCommit(Record& r, std::vector<char>& mark, std::vector<int>& marked) const
{
  r.Cover = ChartVertices(r);
  r.Centres = CentreCorners(r);
  CollectKills(r, mark, marked, r.Kills);
  r.Prepared = true;
}

void ShapeDistributor::Impl::Commit(Record&& r)
{
  Sampling.BeginShape();
  if (Pool.KillOnCommit)
  {
    KillFaces(r);
  }
  std::vector<int> cover, centres;
  if (r.Prepared)
  {
    cover.swap(r.Cover);
    centres.swap(r.Centres);
  }
  else
  {
    cover = ChartVertices(r);
    centres = CentreCorners(r);
  }
  if (Pool.Active && r.Prepared)
  {
    std::sort(r.Kills.begin(), r.Kills.end()); // (KilledBefore)
  }
  else
  {
    r.Kills.clear();
    r.Kills.shrink_to_fit();
  }
  r.Prepared = false;
  Accepted.Add(std::move(r), cover, centres);
}

ShapeDistributor::Impl::Record ShapeDistributor::Impl::Uncommit()
{
  const Record& last = Accepted.Records.back();
  Record r = Accepted.TakeLast(ChartVertices(last), CentreCorners(last));
  Sampling.ReviveLast();
  return r;
}

GeodesicPolarCoordinates& ShapeDistributor::Impl::ExactEngineLease::Take()
{
  if (!Engine)
  {
    {
      std::lock_guard<std::mutex> lock(Owner.ExactEngines.Mutex);
      if (!Owner.ExactEngines.Free.empty())
      {
        Engine = std::move(Owner.ExactEngines.Free.back());
        Owner.ExactEngines.Free.pop_back();
      }
    }
    if (!Engine)
    {
      Engine.reset(new GeodesicPolarCoordinates(Owner.Mesh));
    }
  }
  return *Engine;
}

ShapeDistributor::Impl::ExactEngineLease::~ExactEngineLease()
{
  if (Engine)
  {
    std::lock_guard<std::mutex> lock(Owner.ExactEngines.Mutex);
    Owner.ExactEngines.Free.push_back(std::move(Engine));
  }
}

} // namespace gs
