// The public Shape Distributor: checks the inputs and sets up a run (Prepare), runs it
// (PriorityRounds.cpp), and answers the queries after it (shapes, maps, outlines, decals).
#include "ShapeDistributor.h"
#include "ShapeDistributorImpl.h"

#include "SaddleVertexGraph.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace gs
{
using namespace distribution;

int MaximumThreadCount()
{
#ifdef _OPENMP
  return std::max(1, omp_get_num_procs());
#else
  return 1;
#endif
}

int ThreadCount(int requested)
{
#ifdef _OPENMP
  return requested > 0 ? requested : omp_get_max_threads();
#else
  (void)requested;
  return 1;
#endif
}

Status ShapeDistributor::Impl::Prepare(const SafeDistanceTables& tables,
  const std::vector<Vec3>& faceDirections, const std::vector<double>& vertexDensity,
  const ShapeDistributionOptions& options)
{
  Tables = tables;
  Options = options;
  CircleMode = Options.Mode == DistributionMode::CircumcirclePoissonDisk;
  if (Status checked = CheckTablesAndOptions(); !checked.Ok())
  {
    return checked;
  }
  ComputeLattices();
  if (Status weights = PrepareClassWeights(); !weights.Ok())
  {
    return weights;
  }
  if (Status directions = PrepareDirections(faceDirections); !directions.Ok())
  {
    return directions;
  }
  if (Status density = PrepareFaceWeights(vertexDensity); !density.Ok())
  {
    return density;
  }
  PrepareChartMeasures();
  PreparePool(); // (after RMax)
  PrepareDeadFaces();
  PrepareLongClasses();
  PrepareClassRegions();
  Accepted.Reset(Mesh.NumberOfVertices());
  return Status();
}

Status ShapeDistributor::CheckOptionRanges(const ShapeDistributionOptions& options)
{
  // Each option on its own, with its value (the Shape Distributor filter's properties carry
  // the same names, and it calls this before any work).
  auto outside = [](const char* name, double value, const char* range) {
    std::ostringstream message;
    message << name << " must be " << range << "; it is " << value;
    return Status::Error(message.str());
  };
  if (options.MaximumShapes < 0)
    return outside("MaximumShapes", options.MaximumShapes, "at least 0 (0: no limit)");
  if (options.MaximalFailures < 0)
    return outside("MaximalFailures", options.MaximalFailures, "at least 0 (0: automatic)");
  if (options.NumberOfThreads < 0)
    return outside("NumberOfThreads", options.NumberOfThreads, "at least 0 (0: all cores)");
  if (options.GreedyDirections < 1 || options.GreedyDirections > 1024)
    return outside("GreedyDirections", options.GreedyDirections, "from 1 to 1024");
  if (!(options.SafetyMargin >= 0.0) || options.SafetyMargin > 10.0)
    return outside("SafetyMargin", options.SafetyMargin, "from 0 to 10");
  if (!(options.DistortionLimit >= 0.0))
    return outside("DistortionLimit", options.DistortionLimit, "at least 0 (0: no limit)");
  if (!(options.HolonomyMargin >= 0.0) || options.HolonomyMargin > 100.0)
    return outside("HolonomyMargin", options.HolonomyMargin, "from 0 to 100");
  if (!(options.FaithfulTolerance > 0.0) || options.FaithfulTolerance > 1.0)
    return outside("FaithfulTolerance", options.FaithfulTolerance, "above 0 and at most 1");
  if (options.Order != CandidateOrder::Rounds && options.Order != CandidateOrder::PlaceKeyed)
    return outside("CandidateOrder", static_cast<int>(options.Order), "0 (Rounds) or 1 (PlaceKeyed)");
  if (!(options.MaximumEditShare >= 0.0) || options.MaximumEditShare > 1.0)
    return outside("MaximumEditShare", options.MaximumEditShare, "from 0 to 1");
  if (options.PoolLevels < 1 || options.PoolLevels > 16)
    return outside("PoolLevels", options.PoolLevels, "from 1 to 16");
  return Status();
}

Status ShapeDistributor::Impl::CheckTablesAndOptions() const
{
  if (Mesh.NumberOfFaces() == 0)
  {
    return Status::Error("the mesh has no faces");
  }
  if (const Status graphFits = Graph ? Graph->CheckMesh(Mesh) : Status(); !graphFits.Ok())
  {
    return graphFits;
  }
  if (Tables.Classes.empty() || Tables.Parts.empty())
  {
    return Status::Error("the tables hold no shape class");
  }
  const std::size_t ka = static_cast<std::size_t>(std::max(Tables.AngleBins, 0));
  if (Tables.AngleBins < 1 ||
    Tables.Values.size() != Tables.Parts.size() * Tables.Parts.size() * ka * ka)
  {
    return Status::Error("the tables are inconsistent (" + std::to_string(Tables.Values.size()) +
      " values for " + std::to_string(Tables.Parts.size()) + " parts and " +
      std::to_string(Tables.AngleBins) + " angle bins)");
  }
  for (const SafeDistanceClass& c : Tables.Classes)
  {
    if (c.Parts.empty() || !(c.Radius > 0.0) || !std::isfinite(c.Radius))
    {
      return Status::Error("class '" + c.Name + "' has no part or no valid radius");
    }
  }
  for (double v : Tables.Values)
  {
    if (!std::isfinite(v) || v < 0.0)
    {
      return Status::Error("the tables hold a negative or non-finite safe distance");
    }
  }
  if (!(Options.ShapeSize > 0.0) || !std::isfinite(Options.ShapeSize))
  {
    return Status::Error("ShapeSize must be a positive finite number (it is " +
      std::to_string(Options.ShapeSize) + ")");
  }
  if (Options.ShapeSize * 1e7 < Mesh.MeanEdgeLength())
  {
    std::ostringstream message;
    message << "ShapeSize " << Options.ShapeSize << " is absurdly small for this mesh (mean edge "
            << "length " << Mesh.MeanEdgeLength() << "): it would take more than 1e14 shapes";
    return Status::Error(message.str());
  }
  if (Options.Symmetry != 1 && Options.Symmetry != 2 && Options.Symmetry != 4)
  {
    return Status::Error("the direction field's symmetry must be 1, 2 or 4 (it is " +
      std::to_string(Options.Symmetry) + ")");
  }
  if (Options.Mode != DistributionMode::Random && Options.Mode != DistributionMode::Greedy &&
    Options.Mode != DistributionMode::CircumcirclePoissonDisk)
  {
    return Status::Error("unknown Mode " + std::to_string(static_cast<int>(Options.Mode)) +
      ": 0 (Random), 1 (Greedy) or 2 (Circumcircle Poisson disk)");
  }
  if (Status ranges = CheckOptionRanges(Options); !ranges.Ok())
  {
    return ranges;
  }
  return Status();
}

double ShapeDistributor::OutlineSpacing() const
{
  return Internal->OutlineSpacing();
}

std::shared_ptr<const CurveGrid> ShapeDistributor::Frame(int shape) const
{
  return Internal->FrameOf(shape);
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
  : Internal(new Impl(mesh, graph))
{
}

ShapeDistributor::~ShapeDistributor() = default;

const std::vector<PlacedShape>& ShapeDistributor::Shapes() const
{
  return Internal->Accepted.Placed;
}

const TriangleMesh& ShapeDistributor::Mesh() const
{
  return Internal->Mesh;
}

const SafeDistanceTables& ShapeDistributor::Tables() const
{
  return Internal->Tables;
}

const ShapeDistributionOptions& ShapeDistributor::Options() const
{
  return Internal->Options;
}

bool ShapeDistributor::ClassPoint(int shape, const SurfacePoint& x, Vec2& p) const
{
  return Internal->ClassPointOf(Internal->Accepted.Records.at(shape), x, p);
}

Result<ShapeDistribution> ShapeDistributor::Run(const SafeDistanceTables& tables,
  const std::vector<Vec3>& faceDirections, const std::vector<double>& vertexDensity,
  const ShapeDistributionOptions& options, const std::function<bool(double)>& progress)
{
  const auto start = std::chrono::steady_clock::now();
  ShapeDistribution result;
  Impl& I = *Internal;
  // A PlaceKeyed run after one with the same inputs but the density re-decides the edit only.
  const bool pool = options.Order == CandidateOrder::PlaceKeyed && options.Mode != DistributionMode::Greedy;
  const std::uint64_t fingerprint = pool ? Impl::PoolFingerprint(tables, faceDirections, options) : 0;
  bool incremental = pool && options.MaximumShapes == 0 && options.ReuseLastRun &&
    I.CanRunIncrementally(fingerprint, vertexDensity);
  // (A fresh place-keyed run after one with the same inputs but the density: the shapes both
  // place are the same, bit for bit, and keep their decals.)
  if (pool && !incremental && I.Pool.Last.Valid && I.Pool.Last.Fingerprint == fingerprint)
  {
    I.StashDecals();
  }
  else
  {
    I.Pool.DecalStash.clear(); // (drawn for other tables, sizes or fields)
  }
  Impl::LastPoolRun last = std::move(I.Pool.Last);
  I.Pool.Last = Impl::LastPoolRun();
  std::vector<Impl::Record> accepted;
  std::vector<std::vector<int>> cover, centres;
  if (incremental)
  {
    accepted.swap(I.Accepted.Records);
    cover.swap(I.Accepted.CoverIndex);
    centres.swap(I.Accepted.CentreIndex);
  }
  if (Status prepared = I.Prepare(tables, faceDirections, vertexDensity, options); !prepared.Ok())
  {
    I.Accepted.Records.clear();
    I.Accepted.Placed.clear();
    return prepared;
  }
  I.Pool.Active = pool;
  if (incremental)
  {
    // (The kept kills assume the largest density factor they were collected at. An edit whose
    // faces hold a large share of the pool runs fresh, in parallel: sooner, the same shapes.)
    result.Statistics.EditShare = I.EditShare(last.Density);
    const bool reuse = I.Sampling.MaxFaceDensity == I.Pool.KillsMaxFaceDensity &&
      result.Statistics.EditShare <= I.Options.MaximumEditShare;
    I.Accepted.Records.swap(accepted);
    if (reuse)
    {
      I.Accepted.CoverIndex.swap(cover);
      I.Accepted.CentreIndex.swap(centres);
    }
    else
    {
      I.StashDecals();
      I.Accepted.Records.clear();
      incremental = false;
    }
  }
  const int threads = ThreadCount(I.Options.NumberOfThreads);
  I.EnsureEngines(threads);
  result.Statistics.PrepareSeconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const bool finished = incremental ? I.RunPoolIncremental(last.Density, progress, result.Statistics)
    : pool                            ? I.RunPool(threads, progress, result.Statistics)
                                      : I.RunRounds(threads, progress, result.Statistics);
  // (The polling belongs to this run: later queries, e.g. ProbeFitFraction, never see it.)
  I.Progress.Polling.reset();
  if (!finished)
  {
    I.Accepted.Records.clear();
    I.Accepted.Placed.clear();
    return Status::Aborted();
  }
  if (pool)
  {
    I.TakeStashedDecals();
    I.Pool.KillsMaxFaceDensity = I.Sampling.MaxFaceDensity;
    I.Pool.Last.Valid = true;
    I.Pool.Last.Fingerprint = fingerprint;
    I.Pool.Last.Density = vertexDensity;
  }
  result.Statistics.Seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.Shapes = I.Accepted.Placed;
  if (progress)
  {
    progress(1.0);
  }
  return result;
}

SurfacePoint ShapeDistributor::MapToSurface(int shape, const Vec2& p) const
{
  return Map(shape, p).End;
}

MappedPoint ShapeDistributor::Map(int shape, const Vec2& p) const
{
  return Internal->MapShape(Internal->Accepted.Placed.at(shape), p);
}

std::vector<OutlinePiece> ShapeDistributor::Outline(int shape, double spacing) const
{
  const Impl::Record& r = Internal->Accepted.Records.at(shape);
  if (r.HasDrawn && spacing == Internal->OutlineSpacing())
  {
    return r.Drawn; // drawn when the shape was checked
  }
  return Internal->OutlineOf(Internal->Accepted.Placed.at(shape), spacing);
}

} // namespace gs
