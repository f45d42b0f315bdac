// The public Shape Distributor: checks the inputs and sets up a run (Prepare), runs it
// (PriorityRounds.cpp), and answers the queries after it (shapes, maps, outlines, decals).
#include "ShapeDistributor.h"
#include "ShapeDistributorImpl.h"

#include "SaddleVertexGraph.h"

#include <cmath>
#include <limits>

namespace gs
{
using namespace distribution;

std::string ShapeDistributor::Impl::Prepare(const SafeDistanceTables& tables,
  const std::vector<Vec3>& faceDirections, const std::vector<double>& vertexDensity,
  const ShapeDistributionOptions& options)
{
  T = tables;
  O = options;
  CircleMode = O.Mode == DistributionMode::CircumcirclePoissonDisk;
  const int nf = M.NumberOfFaces(), nv = M.NumberOfVertices();
  if (nf == 0)
  {
    return "the mesh has no faces";
  }
  if (T.Classes.empty() || T.Parts.empty())
  {
    return "the tables hold no shape class";
  }
  const std::size_t ka = static_cast<std::size_t>(std::max(T.AngleBins, 0));
  if (T.AngleBins < 1 || T.Values.size() != T.Parts.size() * T.Parts.size() * ka * ka)
  {
    return "the tables are inconsistent (" + std::to_string(T.Values.size()) +
      " values for " + std::to_string(T.Parts.size()) + " parts and " +
      std::to_string(T.AngleBins) + " angle bins)";
  }
  for (const SafeDistanceClass& c : T.Classes)
  {
    if (c.Parts.empty() || !(c.Radius > 0.0) || !std::isfinite(c.Radius))
    {
      return "class '" + c.Name + "' has no part or no valid radius";
    }
  }
  for (double v : T.Values)
  {
    if (!std::isfinite(v) || v < 0.0)
    {
      return "the tables hold a negative or non-finite safe distance";
    }
  }
  if (!(O.ShapeSize > 0.0) || !std::isfinite(O.ShapeSize))
  {
    return "ShapeSize must be a positive finite number (it is " + std::to_string(O.ShapeSize) + ")";
  }
  if (O.ShapeSize * 1e7 < M.MeanEdgeLength())
  {
    return "ShapeSize " + std::to_string(O.ShapeSize) +
      " is absurdly small for this mesh (mean edge length " + std::to_string(M.MeanEdgeLength()) +
      "): it would take more than 1e14 shapes";
  }
  if (O.Symmetry != 1 && O.Symmetry != 2 && O.Symmetry != 4)
  {
    return "the direction field's symmetry must be 1, 2 or 4 (it is " + std::to_string(O.Symmetry) + ")";
  }
  if (O.MaximumShapes < 0 || O.MaximalFailures < 0 || O.GreedyDirections < 1 ||
    O.GreedyDirections > 1024 || !(O.SafetyMargin >= 0.0) || O.SafetyMargin > 10.0 ||
    !(O.DistortionLimit >= 0.0) || !(O.HolonomyMargin >= 0.0) || O.HolonomyMargin > 100.0)
  {
    return "invalid MaximumShapes, MaximalFailures, GreedyDirections (1..1024), SafetyMargin "
           "(0..10), DistortionLimit (>= 0) or HolonomyMargin (0..100)";
  }
  ComputeLattices();
  // Class weights.
  std::vector<double> w = O.ClassWeights;
  if (w.empty())
  {
    w.assign(T.Classes.size(), 1.0);
  }
  if (w.size() != T.Classes.size())
  {
    return "ClassWeights has " + std::to_string(w.size()) + " values for " +
      std::to_string(T.Classes.size()) + " classes";
  }
  ClassCdf.clear();
  double sum = 0.0;
  for (double x : w)
  {
    if (!(x >= 0.0) || !std::isfinite(x))
    {
      return "ClassWeights must be non-negative finite numbers";
    }
    sum += x;
    ClassCdf.push_back(sum);
  }
  if (!(sum > 0.0))
  {
    return "ClassWeights are all zero";
  }
  // Directions.
  if (static_cast<int>(faceDirections.size()) != nf)
  {
    return "one direction per face is needed (" + std::to_string(faceDirections.size()) +
      " given for " + std::to_string(nf) + " faces)";
  }
  FaceDirection.assign(nf, Vec3{ 0, 0, 0 });
#pragma omp parallel for schedule(static) num_threads(ThreadCount(O.NumberOfThreads))
  for (int f = 0; f < nf; ++f)
  {
    const Vec3& d = faceDirections[f];
    if (!IsFinite(d))
    {
      continue;
    }
    const Vec3 n = M.FaceNormal(f);
    const Vec3 t = d - n * Dot(n, d);
    if (Norm(t) > 1e-12 * Norm(d) && Norm(t) > 0.0)
    {
      FaceDirection[f] = Unit(t);
    }
  }
  // Density and the face weights.
  if (!vertexDensity.empty() && static_cast<int>(vertexDensity.size()) != nv)
  {
    return "one density factor per vertex is needed (" + std::to_string(vertexDensity.size()) +
      " given for " + std::to_string(nv) + " vertices)";
  }
  Density = vertexDensity;
  FaceWeight.assign(nf, 0.0);
  AllCdf.assign(nf, 0.0);
  MaxFaceDensity = 0.0;
  double total = 0.0;
  double minimumScale = std::numeric_limits<double>::infinity();
  for (int f = 0; f < nf; ++f)
  {
    double fm = 1.0;
    bool ok = true;
    if (!Density.empty())
    {
      fm = 0.0;
      for (int v : M.Face(f))
      {
        ok = ok && Density[v] > 0.0 && std::isfinite(Density[v]);
        fm += Density[v] / 3.0;
      }
    }
    if (ok)
    {
      FaceWeight[f] = M.FaceArea(f) / (fm * fm);
      total += FaceWeight[f];
      minimumScale = std::min(minimumScale, fm);
      for (int v : M.Face(f))
      {
        MaxFaceDensity = std::max(MaxFaceDensity, Density.empty() ? 1.0 : Density[v]);
      }
    }
    AllCdf[f] = total;
  }
  Dead.assign(nf, 0);
  NumberOfClasses = static_cast<int>(T.Classes.size());
  DeadFor.assign(static_cast<std::size_t>(NumberOfClasses) * nf, 0);
  Killed.clear();
  KilledBy.clear();
  BuildCdf();
  if (!(total > 0.0))
  {
    return "no face has a positive density factor at all its corners";
  }
  double area = 0.0;
  for (int f = 0; f < nf; ++f)
  {
    area += M.FaceArea(f);
  }
  {
    double smallest = std::numeric_limits<double>::infinity();
    for (const SafeDistanceClass& c : T.Classes)
    {
      smallest = std::min(smallest, c.Radius);
    }
    const double r = O.ShapeSize * minimumScale * smallest;
    if (area / (r * r) > 1e9)
    {
      return "ShapeSize (times the smallest density factor) is too small for this mesh: more than "
             "1e9 shapes would fit";
    }
  }
  MaxEdge = 0.0;
  {
    double longest = 0.0;
#pragma omp parallel for schedule(static) reduction(max : longest) num_threads(ThreadCount(O.NumberOfThreads))
    for (int h = 0; h < M.NumberOfHalfedges(); ++h)
    {
      longest = std::max(longest, M.EdgeLength(h));
    }
    MaxEdge = longest;
  }
  ChartMargin = 2.0 * M.MeanEdgeLength();
  if (static_cast<int>(Defect.size()) != nv)
  {
    Defect.assign(nv, 0.0);
    for (int v = 0; v < nv; ++v)
    {
      Defect[v] = M.IsBoundaryVertex(v) ? 0.0 : std::abs(TwoPi - M.TotalAngle(v));
    }
  }
  RMax = 0.0;
  if (CircleMode)
  {
    for (const SafeDistanceClass& c : T.Classes)
    {
      RMax = std::max(RMax, c.Radius);
    }
  }
  else
  {
    for (const SafeDistancePart& p : T.Parts)
    {
      RMax = std::max(RMax, p.Radius);
    }
  }
  // Dead faces: per (part, class), the smallest safe distance of the part against any part of
  // the class (2% less, for the charts' approximations); per class, its reach.
  {
    const int np = CircleMode ? static_cast<int>(T.Classes.size()) : T.NumberOfParts();
    const int nc = static_cast<int>(T.Classes.size());
    KillRadius.assign(static_cast<std::size_t>(np) * nc, std::numeric_limits<double>::infinity());
    KillReach.assign(nc, 0.0);
    const std::size_t ka = static_cast<std::size_t>(T.AngleBins);
    for (int x = 0; x < np; ++x)
    {
      for (int c = 0; c < nc; ++c)
      {
        double& kill = KillRadius[static_cast<std::size_t>(x) * nc + c];
        if (CircleMode)
        {
          kill = T.Classes[x].Radius + T.Classes[c].Radius;
        }
        else
        {
          for (int pc : T.Classes[c].Parts)
          {
            const double* table = &T.Values[(static_cast<std::size_t>(x) * T.Parts.size() + pc) * ka * ka];
            kill = std::min(kill, *std::min_element(table, table + ka * ka));
          }
        }
        kill *= 0.98;
      }
    }
    for (int c = 0; c < nc && !CircleMode; ++c)
    {
      if (T.Classes[c].Parts.size() <= 1)
      {
        continue;
      }
      for (int pc : T.Classes[c].Parts)
      {
        const Vec2& q = T.Parts[pc].Centre;
        KillReach[c] = std::max(KillReach[c],
          std::abs(Dot(q, T.Classes[c].MajorAxis)) + std::abs(Cross(T.Classes[c].MajorAxis, q)));
      }
    }
  }
  // Long classes: their extent along the major axis, and the field's angles for streamlines.
  ClassExtentMin.assign(T.Classes.size(), 0.0);
  ClassExtentMax.assign(T.Classes.size(), 0.0);
  bool anyLong = false;
  for (std::size_t k = 0; k < T.Classes.size(); ++k)
  {
    const SafeDistanceClass& c = T.Classes[k];
    if (c.Parts.size() <= 1)
    {
      continue;
    }
    anyLong = true;
    double lo = 0.0, hi = 0.0;
    for (const auto& ring : c.Outline.Rings)
    {
      for (const Vec2& p : ring)
      {
        lo = std::min(lo, Dot(p, c.MajorAxis));
        hi = std::max(hi, Dot(p, c.MajorAxis));
      }
    }
    for (int part : c.Parts)
    {
      const double a = Dot(T.Parts[part].Centre, c.MajorAxis);
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
    ClassExtentMin[k] = lo;
    ClassExtentMax[k] = hi;
  }
  Regions.clear();
  Clearance.assign(T.Classes.size(), -1.0);
  {
    double largest = 0.0;
    std::vector<double> clearance(T.Classes.size(), -1.0);
    for (std::size_t k = 0; k < T.Classes.size(); ++k)
    {
      const SafeDistanceClass& c = T.Classes[k];
      ClassRegion probe(c.Outline.Rings, c.Radius, 0.0);
      if (probe.Inside(Vec2{ 0.0, 0.0 }))
      {
        double d = std::numeric_limits<double>::infinity();
        for (const auto& ring : c.Outline.Rings)
        {
          for (std::size_t i = 0, n = ring.size(); i < n; ++i)
          {
            const Vec2 a = ring[i], ab = ring[(i + 1) % n] - ring[i];
            const double l2 = Dot(ab, ab);
            const double t = l2 > 0.0 ? std::min(1.0, std::max(0.0, -Dot(a, ab) / l2)) : 0.0;
            d = std::min(d, Norm(a + ab * t));
          }
        }
        clearance[k] = d;
        largest = std::max(largest, d);
      }
    }
    for (const SafeDistanceClass& c : T.Classes)
    {
      Regions.emplace_back(c.Outline.Rings, c.Radius, std::max(largest, 0.01 * c.Radius));
    }
    Clearance = clearance;
    MaxClearance = largest;
  }
  if (anyLong)
  {
    if (!Field)
    {
      Field.reset(new DirectionFieldSolver(M));
    }
    FieldAngles.assign(nf, 0.0);
    for (int f = 0; f < nf; ++f)
    {
      FieldAngles[f] = Norm(FaceDirection[f]) > 0.0 ? Field->AngleInFace(f, FaceDirection[f]) : 0.0;
    }
  }
  Accepted.clear();
  Placed.clear();
  CoverIndex.assign(nv, {});
  CentreIndex.assign(nv, {});
  return std::string();
}

double ShapeDistributor::OutlineSpacing() const
{
  return P->OutlineSpacing();
}

std::shared_ptr<const CurveGrid> ShapeDistributor::Frame(int shape) const
{
  const Impl& I = *P;
  const PlacedShape& s = I.Placed.at(shape);
  if (s.Curve.empty())
  {
    return nullptr;
  }
  if (I.Accepted.at(shape).Frame)
  {
    return I.Accepted.at(shape).Frame;
  }
  auto grid = std::make_shared<CurveGrid>(I.BuildCurveGrid(s, I.T.Classes[s.ClassId]));
  grid->Index();
  return grid;
}

double ShapeDistributor::ExpectedCount(const TriangleMesh& mesh, const SafeDistanceTables& tables,
  const std::vector<double>& vertexDensity, double shapeSize)
{
  if (tables.Classes.empty() || !(shapeSize > 0.0))
  {
    return 0.0;
  }
  double radius = 0.0;
  for (const SafeDistanceClass& c : tables.Classes)
  {
    radius += c.Radius / static_cast<double>(tables.Classes.size());
  }
  double weight = 0.0;
  for (int f = 0; f < mesh.NumberOfFaces(); ++f)
  {
    double factor = 1.0;
    if (vertexDensity.size() == static_cast<std::size_t>(mesh.NumberOfVertices()))
    {
      const auto& c = mesh.Face(f);
      factor = std::min({ vertexDensity[c[0]], vertexDensity[c[1]], vertexDensity[c[2]] });
    }
    if (factor > 0.0 && std::isfinite(factor))
    {
      weight += mesh.FaceArea(f) / (factor * factor);
    }
  }
  const double r = shapeSize * radius;
  return 0.5 * weight / (Pi * r * r);
}

ShapeDistributor::ShapeDistributor(const TriangleMesh& mesh, const SaddleVertexGraph* graph)
  : P(new Impl(mesh, graph && graph->NumberOfVertices() == mesh.NumberOfVertices() ? graph : nullptr))
{
}

ShapeDistributor::~ShapeDistributor() = default;

const std::vector<PlacedShape>& ShapeDistributor::Shapes() const
{
  return P->Placed;
}

const TriangleMesh& ShapeDistributor::Mesh() const
{
  return P->M;
}

const SafeDistanceTables& ShapeDistributor::Tables() const
{
  return P->T;
}

const ShapeDistributionOptions& ShapeDistributor::Options() const
{
  return P->O;
}

bool ShapeDistributor::ClassPoint(int shape, const SurfacePoint& x, Vec2& p) const
{
  return P->ClassPointOf(P->Accepted.at(shape), x, p);
}

double ShapeDistributor::ProbeFitFraction(int probes, std::uint64_t seed)
{
  Impl& I = *P;
  if (probes <= 0 || I.AllCdf.empty())
  {
    return 0.0;
  }
  const int threads = ThreadCount(I.O.NumberOfThreads);
  I.EnsureEngines(threads);
  long long fits = 0;
#pragma omp parallel num_threads(threads) reduction(+ : fits)
  {
    std::vector<int> scratch;
#pragma omp for schedule(dynamic, 64)
    for (int i = 0; i < probes; ++i)
    {
      Random rng(seed, 3, 0, static_cast<std::uint64_t>(i));
      Impl::Record r;
      const int cls = I.RandomClass(rng);
      const SurfacePoint centre = I.RandomPoint(rng, false);
      if (!I.MakeShape(centre, cls, rng, r.S) || I.CheapConflict(r, scratch))
      {
        continue;
      }
      I.ComputeCharts(r, I.Engine());
      if (!I.FullConflict(r, scratch) && !I.DrawnConflict(r, scratch))
      {
        ++fits;
      }
    }
  }
  return static_cast<double>(fits) / probes;
}

SurfacePoint ShapeDistributor::MapToSurface(int shape, const Vec2& p) const
{
  return Map(shape, p).End;
}

MappedPoint ShapeDistributor::Map(int shape, const Vec2& p) const
{
  return P->MapShape(P->Placed.at(shape), p);
}

std::vector<OutlinePiece> ShapeDistributor::Outline(int shape, double spacing) const
{
  const Impl::Record& r = P->Accepted.at(shape);
  if (r.HasDrawn && spacing == P->OutlineSpacing())
  {
    return r.Drawn; // drawn when the shape was checked
  }
  return P->OutlineOf(P->Placed.at(shape), spacing);
}

} // namespace gs
