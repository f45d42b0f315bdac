// Candidate sampling (dart throwing, Section 4): classes by ClassWeights, faces with probability
// area / f^2 among the faces still alive, a uniform point in the face; the masks of dead faces
// (where no candidate of a class can fit any more); a candidate's geometry (direction,
// streamline of a long class, parts).
#include "ShapeDistributorImpl.h"

#include "GeodesicShooting.h"
#include "SaddleVertexGraph.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace gs
{
using namespace distribution;

Status ShapeDistributor::Impl::PrepareClassWeights()
{
  std::vector<double> w = Options.ClassWeights;
  if (w.empty())
  {
    w.assign(Tables.Classes.size(), 1.0);
  }
  if (w.size() != Tables.Classes.size())
  {
    return Status::Error("ClassWeights has " + std::to_string(w.size()) + " values for " +
      std::to_string(Tables.Classes.size()) + " classes");
  }
  Sampling.ClassCdf.clear();
  double sum = 0.0;
  for (double x : w)
  {
    if (!(x >= 0.0) || !std::isfinite(x))
    {
      return Status::Error("ClassWeights must be non-negative finite numbers");
    }
    sum += x;
    Sampling.ClassCdf.push_back(sum);
  }
  if (!(sum > 0.0))
  {
    return Status::Error("ClassWeights are all zero");
  }
  return Status();
}

Status ShapeDistributor::Impl::PrepareDirections(const std::vector<Vec3>& faceDirections)
{
  const int nf = Mesh.NumberOfFaces();
  if (static_cast<int>(faceDirections.size()) != nf)
  {
    return Status::Error("one direction per face is needed (" +
      std::to_string(faceDirections.size()) + " given for " + std::to_string(nf) + " faces)");
  }
  FaceDirection.assign(nf, Vec3{ 0, 0, 0 });
  ParallelFor(nf, ThreadCount(Options.NumberOfThreads), 4096, [&](int f, int) {
    const Vec3& d = faceDirections[f];
    if (!IsFinite(d))
    {
      return;
    }
    const Vec3 n = Mesh.FaceNormal(f);
    const Vec3 t = d - n * Dot(n, d);
    if (Norm(t) > 1e-12 * Norm(d) && Norm(t) > 0.0)
    {
      FaceDirection[f] = Unit(t);
    }
  });
  return Status();
}

Status ShapeDistributor::Impl::PrepareFaceWeights(const std::vector<double>& vertexDensity)
{
  const int nf = Mesh.NumberOfFaces(), nv = Mesh.NumberOfVertices();
  if (!vertexDensity.empty() && static_cast<int>(vertexDensity.size()) != nv)
  {
    return Status::Error("one density factor per vertex is needed (" +
      std::to_string(vertexDensity.size()) + " given for " + std::to_string(nv) + " vertices)");
  }
  Density = vertexDensity;
  Sampling.FaceWeight.assign(nf, 0.0);
  Sampling.AllCdf.assign(nf, 0.0);
  Sampling.MaxFaceDensity = 0.0;
  double total = 0.0;
  double minimumScale = std::numeric_limits<double>::infinity();
  for (int f = 0; f < nf; ++f)
  {
    double fm = 1.0;
    bool ok = true;
    if (!Density.empty())
    {
      fm = 0.0;
      for (int v : Mesh.Face(f))
      {
        ok = ok && Density[v] > 0.0 && std::isfinite(Density[v]);
        fm += Density[v] / 3.0;
      }
    }
    if (ok)
    {
      Sampling.FaceWeight[f] = Mesh.FaceArea(f) / (fm * fm);
      total += Sampling.FaceWeight[f];
      minimumScale = std::min(minimumScale, fm);
      for (int v : Mesh.Face(f))
      {
        Sampling.MaxFaceDensity = std::max(Sampling.MaxFaceDensity, Density.empty() ? 1.0 : Density[v]);
      }
    }
    Sampling.AllCdf[f] = total;
  }
  NumberOfClasses = static_cast<int>(Tables.Classes.size());
  Sampling.Reset(nf, NumberOfClasses);
  Sampling.BuildCdf();
  if (!(total > 0.0))
  {
    return Status::Error("no face has a positive density factor at all its corners");
  }
  double area = 0.0;
  for (int f = 0; f < nf; ++f)
  {
    area += Mesh.FaceArea(f);
  }
  {
    double smallest = std::numeric_limits<double>::infinity();
    for (const SafeDistanceClass& c : Tables.Classes)
    {
      smallest = std::min(smallest, c.Radius);
    }
    const double r = Options.ShapeSize * minimumScale * smallest;
    // (Divided twice: r * r underflows for absurdly small sizes.)
    if (!(area / r / r <= 1e9))
    {
      return Status::Error("ShapeSize (times the smallest density factor) is too small for this "
                           "mesh: more than 1e9 shapes would fit");
    }
  }
  if (Status size = CheckShapeSizeAgainstSurface(); !size.Ok())
  {
    return size;
  }
  return CheckMemory();
}

Status ShapeDistributor::Impl::CheckShapeSizeAgainstSurface() const
{
  // A shape's circumscribed disc (at the largest density factor) against the disc of the area
  // of the largest connected part of the surface: a shape whose circumdisc holds more area
  // than the whole part cannot lie on it without wrapping round it (a closed surface) or
  // leaving it (an open one), and its geodesics would wrap round again and again.
  std::vector<double> componentArea(static_cast<std::size_t>(Mesh.NumberOfComponents()), 0.0);
  for (int f = 0; f < Mesh.NumberOfFaces(); ++f)
  {
    componentArea[Mesh.FaceComponent(f)] += Mesh.FaceArea(f);
  }
  const double largestArea = *std::max_element(componentArea.begin(), componentArea.end());
  double largestRadius = 0.0;
  for (const SafeDistanceClass& c : Tables.Classes)
  {
    largestRadius = std::max(largestRadius, c.Radius);
  }
  const double extent = largestRadius * Options.ShapeSize * Sampling.MaxFaceDensity;
  const double allowed = std::sqrt(largestArea / Pi);
  if (!(extent <= allowed))
  {
    std::ostringstream message;
    message << "ShapeSize " << Options.ShapeSize;
    if (Sampling.MaxFaceDensity != 1.0)
    {
      message << " times the largest density factor " << Sampling.MaxFaceDensity;
    }
    message << " makes shapes larger than the surface: the largest class's circumradius would be "
            << extent << ", and a disc of that radius holds more than the area of the "
            << (Mesh.NumberOfComponents() > 1 ? "largest connected part of the " : "")
            << "surface (" << largestArea << ", the disc of radius " << allowed
            << "). Use a ShapeSize below "
            << allowed / (largestRadius * Sampling.MaxFaceDensity);
    if (Sampling.MaxFaceDensity != 1.0)
    {
      message << " or smaller density factors";
    }
    return Status::Error(message.str());
  }
  return Status();
}

double ShapeDistributor::Impl::EstimatedShapes() const
{
  // ExpectedCount's disc packing at the mean class radius, times 3: the tables pack shapes
  // closer than their circumcircles (measured: 1.45x for a star, 3.0x for a 4:1 bar).
  double radius = 0.0;
  for (const SafeDistanceClass& c : Tables.Classes)
  {
    radius += c.Radius / static_cast<double>(Tables.Classes.size());
  }
  const double r = Options.ShapeSize * radius;
  const double weight = Sampling.AllCdf.empty() ? 0.0 : Sampling.AllCdf.back(); // sum of area / f^2
  return 3.0 * 0.5 * (weight / (Pi * r)) / r;
}

Status ShapeDistributor::Impl::CheckMemory() const
{
  // Bytes a placed shape holds through the run and its drawing, measured on the torus (slope of
  // the peak between two sizes): about 33 KB for a short shape, 154 KB for a long one (its
  // curve grid). Refused, before any work, above 80% of the memory available, as the graph
  // build does.
  double longShare = 0.0;
  for (const SafeDistanceClass& c : Tables.Classes)
  {
    longShare += (c.Parts.size() > 1 ? 1.0 : 0.0) / static_cast<double>(Tables.Classes.size());
  }
  const double perShape = (1.0 - longShare) * ShortShapeBytes + longShare * LongShapeBytes;
  const double shapes = EstimatedShapes();
  const double bytes = shapes * perShape;
  const double available = SaddleVertexGraph::AvailableMemoryBytes();
  if (available > 0.0 && !(bytes <= 0.8 * available))
  {
    std::ostringstream message;
    message.precision(3);
    message << "about " << shapes << " shapes would need about " << bytes / 1e9
            << " GB, more than 80% of the " << available / 1e9
            << " GB available: use a larger ShapeSize (now " << Options.ShapeSize
            << "), density factors further from 0 or MaximumShapes";
    if (Options.MaximumShapes > 0 && Options.MaximumShapes * perShape <= 0.8 * available)
    {
      return Status(); // MaximumShapes bounds the run
    }
    return Status::Error(message.str());
  }
  return Status();
}

void ShapeDistributor::Impl::PrepareDeadFaces()
{
  // Dead faces: per (part, class), the smallest safe distance of the part against any part of
  // the class (2% less, for the charts' approximations); per class, its reach.
  {
    const int np = CircleMode ? static_cast<int>(Tables.Classes.size()) : Tables.NumberOfParts();
    const int nc = static_cast<int>(Tables.Classes.size());
    Sampling.KillRadius.assign(static_cast<std::size_t>(np) * nc, std::numeric_limits<double>::infinity());
    Sampling.KillReach.assign(nc, 0.0);
    const std::size_t ka = static_cast<std::size_t>(Tables.AngleBins);
    for (int x = 0; x < np; ++x)
    {
      for (int c = 0; c < nc; ++c)
      {
        double& kill = Sampling.KillRadius[static_cast<std::size_t>(x) * nc + c];
        if (CircleMode)
        {
          kill = Tables.Classes[x].Radius + Tables.Classes[c].Radius;
        }
        else
        {
          for (int pc : Tables.Classes[c].Parts)
          {
            const double* table =
              &Tables.Values[(static_cast<std::size_t>(x) * Tables.Parts.size() + pc) * ka * ka];
            kill = std::min(kill, *std::min_element(table, table + ka * ka));
          }
        }
        kill *= 0.98;
      }
    }
    for (int c = 0; c < nc && !CircleMode; ++c)
    {
      if (Tables.Classes[c].Parts.size() <= 1)
      {
        continue;
      }
      for (int pc : Tables.Classes[c].Parts)
      {
        const Vec2& q = Tables.Parts[pc].Centre;
        Sampling.KillReach[c] = std::max(Sampling.KillReach[c],
          std::abs(Dot(q, Tables.Classes[c].MajorAxis)) +
            std::abs(Cross(Tables.Classes[c].MajorAxis, q)));
      }
    }
  }
}

void ShapeDistributor::Impl::PrepareLongClasses()
{
  const int nf = Mesh.NumberOfFaces();
  Long.ClassExtentMin.assign(Tables.Classes.size(), 0.0);
  Long.ClassExtentMax.assign(Tables.Classes.size(), 0.0);
  Long.BehindParts.assign(Tables.Classes.size(), {});
  bool anyLong = false;
  for (std::size_t k = 0; k < Tables.Classes.size(); ++k)
  {
    const SafeDistanceClass& c = Tables.Classes[k];
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
      const double a = Dot(Tables.Parts[part].Centre, c.MajorAxis);
      lo = std::min(lo, a);
      hi = std::max(hi, a);
    }
    Long.ClassExtentMin[k] = lo;
    Long.ClassExtentMax[k] = hi;
    for (int part : c.Parts)
    {
      if (Dot(Tables.Parts[part].Centre, c.MajorAxis) < 0.0)
      {
        Long.BehindParts[k].push_back(part);
      }
    }
    std::stable_sort(Long.BehindParts[k].begin(), Long.BehindParts[k].end(), [&](int a, int b) {
      return Dot(Tables.Parts[a].Centre, c.MajorAxis) > Dot(Tables.Parts[b].Centre, c.MajorAxis);
    });
  }
  if (anyLong)
  {
    if (!Long.Field)
    {
      Long.Field.reset(new DirectionFieldSolver(Mesh));
    }
    Long.FieldAngles.assign(nf, 0.0);
    for (int f = 0; f < nf; ++f)
    {
      Long.FieldAngles[f] = Norm(FaceDirection[f]) > 0.0 ? Long.Field->AngleInFace(f, FaceDirection[f]) : 0.0;
    }
  }
}

void ShapeDistributor::Impl::Generate(std::vector<Record>& batch, int round) const
{
  const int n = static_cast<int>(batch.size());
  ParallelForEachThread<std::vector<int>>(n, ThreadCount(Options.NumberOfThreads), 64,
    [&](int i, std::vector<int>& scratch) {
      if (Poll())
      {
        batch[i].Valid = false; // (aborted: the round is dropped)
        return;
      }
      Random rng(Options.Seed, 1, static_cast<std::uint64_t>(round), static_cast<std::uint64_t>(i));
      const int cls = Sampling.RandomClass(rng);
      const SurfacePoint centre = Sampling.RandomPoint(rng);
      // A class that certainly cannot fit in this face, or (long classes, whose shapes cost a
      // streamline) at this centre: no need to build the shape.
      const bool covered = Sampling.DeadForClass(cls, centre.Face) ||
        (Tables.Classes[cls].Parts.size() > 1 &&
          CentreCovered(centre, cls, DensityAt(centre), 0, scratch));
      batch[i].Valid = !covered && MakeShape(centre, cls, rng, batch[i].Shape, nullptr, &scratch);
      batch[i].Reason = batch[i].Valid ? Record::Rejection::None
        : covered                      ? Record::Rejection::Tables
                                       : Record::Rejection::WithoutShape;
    });
}

bool ShapeDistributor::Impl::PlacePart(int face, const Vec3& x, const Vec3& tangent, int part,
  double across, double phiM, PlacedPart& p) const
{
  p.Part = part;
  Vec3 endTangent;
  bool boundary = false;
  if (!Across(face, x, tangent, across, p.Centre, endTangent, &boundary) || boundary)
  {
    return false;
  }
  p.Position = Mesh.Interpolate(p.Centre.Face, p.Centre.Bary);
  p.Axis = Unit(RotateTangent(endTangent, Mesh.FaceNormal(p.Centre.Face), -phiM));
  return true;
}

Vec3 ShapeDistributor::Impl::ShapeFieldDirection(int f, const Vec3& normal, double spin,
  const Vec3* prefer) const
{
  Vec3 dir = FaceDirection[f];
  if (!(Norm(dir) > 0.0))
  {
    const auto& v = Mesh.Face(f);
    return RotateTangent(Unit(Mesh.Position(v[1]) - Mesh.Position(v[0])), normal, TwoPi * spin);
  }
  if (prefer && Options.Symmetry > 1)
  {
    Vec3 best = dir;
    double bestDot = -2.0;
    for (int k = 0; k < Options.Symmetry; ++k)
    {
      const Vec3 candidate = RotateTangent(dir, normal, TwoPi * k / Options.Symmetry);
      const double d = Dot(candidate, *prefer);
      if (d > bestDot)
      {
        bestDot = d;
        best = candidate;
      }
    }
    dir = Unit(best);
  }
  return dir;
}

double ShapeDistributor::Impl::PartDistanceAlongCurve(int cls, int part, double scale) const
{
  return std::abs(Dot(Tables.Parts[part].Centre, Tables.Classes[cls].MajorAxis)) * scale;
}

bool ShapeDistributor::Impl::PlacePartOnCurve(const Streamline& line, bool behind, int cls,
  int part, double scale, double phiM, PlacedPart& p) const
{
  int face = -1;
  Vec3 x, tangent;
  if (!PointOnCurve(Mesh, line.Pieces, PartDistanceAlongCurve(cls, part, scale), face, x, tangent))
  {
    return false;
  }
  // (0 - t, not -t: a zero component stays +0, as the opposite piece's difference gives it.)
  return PlacePart(face, x, behind ? Vec3{ 0.0, 0.0, 0.0 } - tangent : tangent, part,
    Cross(Tables.Classes[cls].MajorAxis, Tables.Parts[part].Centre) * scale, phiM, p);
}

bool ShapeDistributor::Impl::BehindPartsFit(DirectionFieldSolver::StreamlineTracer& tracer,
  const PlacedShape& s, double scale, double phiM, std::vector<int>& precheck,
  std::uint64_t key) const
{
  const int cls = s.ClassId;
  Record partial;
  partial.Shape.ClassId = cls;
  partial.Shape.Scale = s.Scale;
  partial.Key = key;
  for (std::size_t k = 0; k < Long.BehindParts[cls].size(); ++k)
  {
    const int part = Long.BehindParts[cls][k];
    const double at = PartDistanceAlongCurve(cls, part, scale);
    tracer.Continue(at);
    if (tracer.Line().Length < at)
    {
      break; // (the streamline ended: the whole shape fails in MakeLongShape)
    }
    PlacedPart p;
    if (!PlacePartOnCurve(tracer.Line(), true, cls, part, scale, phiM, p))
    {
      return false; // (the whole shape stops at this part too)
    }
    partial.Shape.Parts.push_back(p);
    // Checked when the next part needs more streamline (or at the last).
    const bool more = k + 1 < Long.BehindParts[cls].size() &&
      PartDistanceAlongCurve(cls, Long.BehindParts[cls][k + 1], scale) <= tracer.Line().Length;
    if (!more && CheapConflict(partial, precheck))
    {
      return false;
    }
  }
  return true;
}

bool ShapeDistributor::Impl::MakeLongShape(const Vec3& dir, PlacedShape& s,
  std::vector<int>* precheck, std::uint64_t key) const
{
  // The major axis follows the field: trace the streamline both ways. A part is placed by
  // walking its curve from the centre, so that the part nearest behind the centre is placed
  // (and checked, in BehindPartsFit) as soon as the streamline reaches it.
  const int cls = s.ClassId, f = s.Centre.Face;
  const SafeDistanceClass& c = Tables.Classes[cls];
  const double scale = Options.ShapeSize * s.Scale;
  const double phiM = std::atan2(c.MajorAxis.y, c.MajorAxis.x);
  s.Direction = Unit(RotateTangent(dir, s.Normal, -phiM));
  const int n = Options.Symmetry == 1 ? 2 : Options.Symmetry;
  const double a0 = Long.Field->AngleInFace(f, dir);
  const double forward = Long.ClassExtentMax[cls] * scale, backward = -Long.ClassExtentMin[cls] * scale;
  // Behind first: a candidate whose parts there conflict needs no streamline ahead, and most
  // conflict at the part nearest the centre, which needs only the streamline up to it.
  DirectionFieldSolver::StreamlineTracer tracer(
    *Long.Field, n, Long.FieldAngles, s.Centre, a0 + Pi, backward);
  if (precheck && Options.EarlyRejection && !CircleMode &&
    !BehindPartsFit(tracer, s, scale, phiM, *precheck, key))
  {
    return false;
  }
  tracer.Continue();
  const Streamline& behind = tracer.Line();
  if (behind.Length < backward * (1.0 - 1e-9))
  {
    return false;
  }
  const Streamline ahead = Long.Field->TraceStreamline(n, Long.FieldAngles, s.Centre, a0, forward);
  if (ahead.Length < forward * (1.0 - 1e-9))
  {
    return false;
  }
  for (auto it = behind.Pieces.rbegin(); it != behind.Pieces.rend(); ++it)
  {
    s.Curve.push_back(CurvePiece{ it->Face, it->B, it->A });
  }
  s.CurveCentre = behind.Length;
  s.Curve.insert(s.Curve.end(), ahead.Pieces.begin(), ahead.Pieces.end());
  if (CircleMode)
  {
    return true; // (one circle at the centre: MakeShape adds it)
  }
  for (int part : c.Parts)
  {
    PlacedPart p;
    // (A part at the centre itself reads the curve's direction there on whichever side the
    // curve has length: a class may end at its centre.)
    const double along = Dot(Tables.Parts[part].Centre, c.MajorAxis);
    const bool behindPart = along < 0.0 || (along == 0.0 && !(ahead.Length > 0.0));
    if (!PlacePartOnCurve(behindPart ? behind : ahead, behindPart, cls, part, scale, phiM, p))
    {
      return false;
    }
    s.Parts.push_back(p);
  }
  return true;
}

bool ShapeDistributor::Impl::MakeShape(const SurfacePoint& centre, int cls, Random& rng, PlacedShape& s,
  const Vec3* prefer, std::vector<int>* precheck, std::uint64_t key) const
{
  s = PlacedShape();
  s.ClassId = cls;
  s.Centre = centre;
  s.Scale = DensityAt(centre);
  if (!(s.Scale > 0.0) || !std::isfinite(s.Scale))
  {
    return false;
  }
  const int f = centre.Face;
  s.Position = Mesh.Interpolate(f, centre.Bary);
  s.Normal = Mesh.FaceNormal(f);
  const double spin = rng.Uniform();
  const Vec3 dir = ShapeFieldDirection(f, s.Normal, spin, prefer);
  const SafeDistanceClass& c = Tables.Classes[cls];
  if (c.Parts.size() <= 1)
  {
    s.Direction = dir;
  }
  else if (!MakeLongShape(dir, s, precheck, key))
  {
    return false;
  }
  else if (!CircleMode)
  {
    return true;
  }
  // A short class, or any class as circles: one part, at the centre.
  PlacedPart p;
  p.Part = CircleMode ? cls : c.Parts[0];
  p.Centre = centre;
  p.Position = s.Position;
  p.Axis = s.Direction;
  s.Parts.push_back(p);
  return true;
}

void ShapeDistributor::Impl::CollectKills(const Record& r, std::vector<char>& mark, std::vector<int>& marked,
  std::vector<std::pair<int, int>>& kills) const
{
  kills.clear();
  const int nc = NumberOfClasses;
  for (std::size_t k = 0; k < r.Charts.size() && k < r.Shape.Parts.size(); ++k)
  {
    const Chart& chart = r.Charts[k];
    for (int c = 0; c < nc; ++c)
    {
      const double radius = Sampling.KillRadius[static_cast<std::size_t>(r.Shape.Parts[k].Part) * nc + c] *
          Options.ShapeSize * r.Shape.Scale -
        Sampling.KillReach[c] * Options.ShapeSize * Sampling.MaxFaceDensity;
      if (!(radius > 0.0))
      {
        continue;
      }
      const float r2 = static_cast<float>(radius * radius);
      marked.clear();
      for (const ChartEntry& e : chart.Entries)
      {
        if (e.X * e.X + e.Y * e.Y < r2)
        {
          mark[e.Vertex] = 1;
          marked.push_back(e.Vertex);
        }
      }
      for (int v : marked)
      {
        const int start = Mesh.VertexHalfedge(v);
        int h = start;
        do
        {
          const int f = h / 3;
          const auto& t = Mesh.Face(f);
          // Each face once: from its smallest marked corner.
          if (mark[t[0]] && mark[t[1]] && mark[t[2]] && v == std::min({ t[0], t[1], t[2] }))
          {
            kills.emplace_back(c, f);
          }
          h = Mesh.RotateCCW(h);
        } while (h >= 0 && h != start);
      }
      for (int v : marked)
      {
        mark[v] = 0;
      }
    }
  }
}

void ShapeDistributor::Impl::KillFaces(const Record& r)
{
  if (r.Prepared)
  {
    Sampling.Kill(r.Kills);
    return;
  }
  std::vector<std::pair<int, int>> own;
  CollectKills(r, PerThread.Marks[0], PerThread.Marked, own); // (serial: the first thread's scratch)
  Sampling.Kill(own);
}

} // namespace gs
