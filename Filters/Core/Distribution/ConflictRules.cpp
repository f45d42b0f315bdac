// The conflict test (Section 4, Algorithm 2): two parts conflict when the geodesic distance of
// their centres, read in the polar chart of one of them, is below the safe distance the tables
// give for the angles between each part's axis and the geodesic joining the centres. Around it:
// the cheap checks (against accepted shapes' charts, the centre inside a silhouette), the
// boundary (KeepInside) and the drawn check (outlines as drawn, the tables' rigid copies aside).
#include "ShapeDistributorImpl.h"
#include "GeodesicShooting.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs
{
using namespace distribution;

void ShapeDistributor::Impl::ClassSilhouettes::Prepare(const std::vector<SafeDistanceClass>& classes)
{
  Regions.clear();
  double largest = 0.0;
  std::vector<double> clearance(classes.size(), -1.0);
  for (std::size_t k = 0; k < classes.size(); ++k)
  {
    const SafeDistanceClass& c = classes[k];
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
  for (const SafeDistanceClass& c : classes)
  {
    Regions.emplace_back(c.Outline.Rings, c.Radius, std::max(largest, 0.01 * c.Radius));
  }
  Clearance = clearance;
  MaxClearance = largest;
}

bool ShapeDistributor::Impl::ConflictInCharts(const Record& X, const Record& Y) const
{
  const double fmax = std::max(X.Shape.Scale, Y.Shape.Scale);
  const double unit = Options.ShapeSize * fmax * (1.0 + Options.SafetyMargin);
  for (std::size_t i = 0; i < X.Shape.Parts.size() && i < X.Charts.size(); ++i)
  {
    const Chart& chart = X.Charts[i];
    const int pa = X.Shape.Parts[i].Part;
    for (const PlacedPart& py : Y.Shape.Parts)
    {
      const int g = py.Centre.Face;
      const auto& corners = Mesh.Face(g);
      const ChartEntry* e[3];
      bool all = true;
      for (int k = 0; k < 3 && all; ++k)
      {
        e[k] = chart.Find(corners[k]);
        all = e[k] != nullptr;
      }
      if (!all)
      {
        // A corner beyond the chart radius R: Y's centre is at least R minus the face's
        // longest edge away (a point of a triangle is within its longest edge of every corner). Farther than any safe distance: no conflict; otherwise (a face
        // with edges longer than the chart margin) judged conservatively.
        double longest = 0.0;
        for (int k = 0; k < 3; ++k)
        {
          longest = std::max(
            longest, Norm(Mesh.Position(corners[(k + 1) % 3]) - Mesh.Position(corners[k])));
        }
        if (ChartRadius(X.Shape, X.Shape.Parts[i]) - longest >=
          (PartRadius(pa) + PartRadius(py.Part)) * unit)
        {
          continue;
        }
        return true;
      }
      Vec2 P[3];
      for (int k = 0; k < 3; ++k)
      {
        P[k] = Vec2{ e[k]->X, e[k]->Y };
      }
      const Vec2 q = P[0] * py.Centre.Bary[0] + P[1] * py.Centre.Bary[1] + P[2] * py.Centre.Bary[2];
      const double d = Norm(q);
      if (d >= (PartRadius(pa) + PartRadius(py.Part)) * unit)
      {
        continue;
      }
      if (CircleMode)
      {
        return true;
      }
      // Angles: A's axis is the chart's x axis; the arrival direction at Y's centre is the
      // chart's radial direction pulled back into face g.
      const double alphaA = d > 0.0 ? -std::atan2(q.y, q.x) : 0.0;
      const Vec3 x0 = Mesh.Position(corners[0]);
      const Vec3 e1 = Mesh.Position(corners[1]) - x0, e2 = Mesh.Position(corners[2]) - x0;
      const Vec2 E1 = P[1] - P[0], E2 = P[2] - P[0];
      const double det = Cross(E1, E2);
      Vec3 t;
      if (d > 0.0 && std::abs(det) > 1e-12 * (Dot(E1, E1) + Dot(E2, E2)))
      {
        const Vec2 u = q * (1.0 / d);
        const double a = Cross(u, E2) / det, b = Cross(E1, u) / det;
        t = e1 * a + e2 * b;
      }
      else
      {
        t = py.Position - X.Shape.Parts[i].Position;
      }
      // Intrinsic distortion of the chart at Y's centre: the tables need rigid planar copies.
      const double stretch = std::max({ std::abs(Norm(E1) / Norm(e1) - 1.0),
        std::abs(Norm(E2) / Norm(e2) - 1.0), std::abs(Norm(E2 - E1) / Norm(e2 - e1) - 1.0) });
      if (!(stretch <= Options.DistortionLimit))
      {
        return true; // d < r_A + r_B: the circumcircles overlap
      }
      const Vec3 n = Mesh.FaceNormal(g);
      t = t - n * Dot(n, t);
      double alphaB = 0.0;
      if (Norm(t) > 0.0)
      {
        alphaB = std::atan2(Dot(n, Cross(t, py.Axis)), Dot(t, py.Axis));
      }
      // Holonomy: Y's outline, drawn by Y's own exponential map, is turned in X's chart by at
      // most the absolute curvature enclosed by X, Y and the outline point (area at most
      // (d + r_Y) r_Y / 2): a displacement of up to that angle times r_Y.
      const double rY = PartRadius(py.Part) * unit;
      const double turn = Options.HolonomyMargin * chart.Roughness * 0.5 * (d + rY) * rY;
      if (d < SafeDistance(pa, py.Part, alphaA, alphaB) * unit + turn * rY)
      {
        return true;
      }
    }
  }
  return false;
}

bool ShapeDistributor::Impl::CheapConflict(const Record& c, std::vector<int>& scratch) const
{
  scratch.clear();
  for (int v : CentreCorners(c))
  {
    scratch.insert(scratch.end(), Accepted.CoverIndex[v].begin(), Accepted.CoverIndex[v].end());
  }
  SortUnique(scratch);
  for (int x : scratch)
  {
    const Record& X = Accepted.Records[x];
    if (X.Key <= c.Key && X.Shape.Scale >= c.Shape.Scale && ConflictInCharts(X, c))
    {
      return true;
    }
  }
  return false;
}

bool ShapeDistributor::Impl::TouchesBoundary(const Record& c) const
{
  for (std::size_t k = 0; k < c.Charts.size() && k < c.Shape.Parts.size(); ++k)
  {
    const double reach =
      PartRadius(c.Shape.Parts[k].Part) * Options.ShapeSize * c.Shape.Scale + 0.5 * Measures.MaxEdge;
    const float r2 = static_cast<float>(reach * reach);
    for (const ChartEntry& e : c.Charts[k].Entries)
    {
      if (e.X * e.X + e.Y * e.Y < r2 && Mesh.IsBoundaryVertex(e.Vertex))
      {
        return true;
      }
    }
  }
  return false;
}

bool ShapeDistributor::Impl::FullConflict(const Record& c, std::vector<int>& scratch) const
{
  if (Options.KeepInside && TouchesBoundary(c))
  {
    return true;
  }
  scratch.clear();
  for (int v : ChartVertices(c))
  {
    scratch.insert(scratch.end(), Accepted.CentreIndex[v].begin(), Accepted.CentreIndex[v].end());
  }
  SortUnique(scratch);
  for (int y : scratch)
  {
    const Record& Y = Accepted.Records[y];
    if (Y.Key <= c.Key && Y.Shape.Scale < c.Shape.Scale && ConflictInCharts(c, Y))
    {
      return true;
    }
  }
  return false;
}

bool ShapeDistributor::Impl::CentreCovered(const SurfacePoint& centre, int cls, double scale,
  std::uint64_t key, std::vector<int>& scratch) const
{
  if (CircleMode || Silhouettes.Clearance[cls] < 0.0)
  {
    return false;
  }
  const auto& corners = Mesh.Face(centre.Face);
  scratch.clear();
  for (int v : corners)
  {
    scratch.insert(scratch.end(), Accepted.CoverIndex[v].begin(), Accepted.CoverIndex[v].end());
  }
  SortUnique(scratch);
  const Vec3 position = Mesh.Interpolate(centre.Face, centre.Bary);
  for (int x : scratch)
  {
    const Record& X = Accepted.Records[x];
    if (X.Key > key)
    {
      continue; // (decided after the candidate: see Record::Key)
    }
    const double unit = Options.ShapeSize * X.Shape.Scale;
    const ClassRegion& region = Silhouettes.Regions[X.Shape.ClassId];
    for (std::size_t i = 0; i < X.Shape.Parts.size() && i < X.Charts.size(); ++i)
    {
      const int pa = X.Shape.Parts[i].Part;
      if (Norm(X.Shape.Parts[i].Position - position) > PartRadius(pa) * unit)
      {
        continue; // beyond the part's circle (the geodesic distance is never shorter)
      }
      const double margin = 0.02 * PartRadius(pa);
      const double dilation = 0.9 * Silhouettes.Clearance[cls] * scale / X.Shape.Scale - margin;
      Vec2 q;
      if (!ChartPoint(X.Charts[i], centre, unit, q))
      {
        continue;
      }
      if (Norm(q) > PartRadius(pa))
      {
        continue;
      }
      const Vec2 p = Tables.Parts[pa].Centre + q;
      if (dilation >= 0.0 ? region.Within(p, std::min(dilation, Silhouettes.MaxClearance)) : region.DeeplyInside(p, -dilation))
      {
        return true;
      }
    }
  }
  return false;
}

void ShapeDistributor::Impl::DrawOutline(Record& c) const
{
  if (!c.HasDrawn)
  {
    c.Drawn = OutlineOf(c.Shape, OutlineSpacing());
    c.HasDrawn = true;
  }
  if (!c.Shape.Curve.empty() && !c.Frame)
  {
    std::shared_ptr<CurveGrid> frame =
      std::make_shared<CurveGrid>(BuildCurveGrid(c.Shape, Tables.Classes[c.Shape.ClassId]));
    frame->Index();
    c.Frame = frame;
  }
}

bool ShapeDistributor::Impl::PrepareExactMap(Record& c) const
{
  if (c.Exact)
  {
    return !c.Exact->Entries.empty();
  }
  // Over every face that meets the disc of the circumradius plus an outline spacing, as
  // VerifyOverlaps takes it (ComputeCoveringDisc): a neighbour's outline segment that reaches
  // into the circle has both ends there, and is read whole (read through a map truncated at the
  // faces the outline crosses, such a segment was tested at one end only, and VerifyOverlaps
  // found a pair the drawn check had let through: elephant-with-holes subdivided once, ShapeSize
  // 1.5%, seed 10). A margin of the mesh's longest edge, everywhere, did the same at up to 30
  // times the cost on meshes with a few long edges (a noisy scan; turbine, whose longest edge
  // is 14x the mean).
  ExactEngineLease lease(*this);
  GeodesicPolarCoordinates& engine = lease.Take();
  const double unit = Options.ShapeSize * c.Shape.Scale;
  const double reference = TangentAngle(Mesh, c.Shape.Centre, c.Shape.Direction);
  const bool ok = std::isfinite(reference) &&
    engine
      .ComputeCoveringDisc(c.Shape.Centre,
        Tables.Classes[c.Shape.ClassId].Radius * unit * (1.0 + 1e-9) + OutlineSpacing(), reference)
      .Ok();
  c.Exact = std::make_shared<const LogMapSnapshot>(ok ? engine.Snapshot() : LogMapSnapshot());
  return ok && !c.Exact->Entries.empty();
}

bool ShapeDistributor::Impl::Unfaithful(Record& c) const
{
  if (CircleMode || !Options.DrawnCheck || !Options.FaithfulCheck)
  {
    return false;
  }
  const bool isShort = c.Shape.Curve.empty();
  if (c.FaithfulChecked)
  {
    return c.FaithfulVerdict;
  }
  DrawOutline(c);
  c.FaithfulChecked = true;
  c.FaithfulVerdict = FaithfulnessFails(c, isShort);
  return c.FaithfulVerdict;
}

bool ShapeDistributor::Impl::FaithfulnessFails(Record& c, bool isShort) const
{
  const SafeDistanceClass& cls = Tables.Classes[c.Shape.ClassId];
  const double tolerance = Options.FaithfulTolerance * cls.Radius;
  // A short shape is read through the exact log map of its centre, the map its decal draws (the
  // placement's chart, on the geodesic graph, can be off by degrees behind saddles).
  if (isShort && !PrepareExactMap(c))
  {
    return true;
  }
  // Where the outline runs along the mesh boundary (a shape hanging over it), its points are
  // where the map stopped, inside the silhouette: the cut, not the silhouette's contour.
  auto onBoundary = [this](const SurfacePoint& q) {
    if (q.IsVertex())
    {
      return Mesh.IsBoundaryVertex(q.Vertex);
    }
    for (int k = 0; k < 3; ++k)
    {
      if (q.Bary[k] <= 1e-12 && Mesh.IsBoundaryHalfedge(3 * q.Face + (k + 1) % 3))
      {
        return true;
      }
    }
    return false;
  };
  // A long shape's outline is read as its decal reads the surface: from the grid node nearest
  // each point, not by descent from the previous point's. Where the grid folds (the curve turns
  // more tightly than the shape is wide), the descent stays on the sheet the outline was drawn
  // from and reads it back, while the decal, taking the nearest node, reads the other sheet and
  // drops the pieces where the two disagree: a strip of the outline left undrawn (refined_elephant
  // at ShapeSize 1%: 30 / 48 outline points outside their decal, 4 / 10 shapes, against 2 / 5
  // and 1 / 4 read this way, at no measurable cost).
  for (const OutlinePiece& piece : c.Drawn)
  {
    for (std::size_t i = 0; i < piece.Points.size() && i < piece.ClassPoints.size(); ++i)
    {
      if (onBoundary(piece.Points[i]))
      {
        continue;
      }
      Vec2 p;
      const bool read = isShort ? ClassPointOf(c, piece.Points[i], p)
                                : (c.Frame && c.Frame->ClassPoint(piece.Points[i], p));
      if (!read || Norm(p - piece.ClassPoints[i]) > tolerance)
      {
        return true;
      }
    }
  }
  return false;
}

bool ShapeDistributor::Impl::DrawnConflict(Record& c, std::vector<int>& scratch) const
{
  if (CircleMode || !Options.DrawnCheck)
  {
    return false;
  }
  const bool isLong = !c.Shape.Curve.empty();
  if (isLong && Unfaithful(c)) // (a short shape: after its neighbours', through its exact map)
  {
    c.Reason = Record::Rejection::Faithful;
    return true;
  }
  // (What rejects it from here on, but for the last test: the drawn check.)
  c.Reason = Record::Rejection::Drawn;
  DrawOutline(c);
  const bool shortC = c.Shape.Curve.empty() && !c.Charts.empty() && !c.Charts[0].Entries.empty();
  if (shortC && !PrepareExactMap(c))
  {
    return true; // (no exact log map to read it through)
  }
  scratch.clear();
  for (int v : CentreCorners(c))
  {
    scratch.insert(scratch.end(), Accepted.CoverIndex[v].begin(), Accepted.CoverIndex[v].end());
  }
  for (const Chart& chart : c.Charts)
  {
    for (const ChartEntry& e : chart.Entries)
    {
      scratch.insert(scratch.end(), Accepted.CentreIndex[e.Vertex].begin(), Accepted.CentreIndex[e.Vertex].end());
    }
  }
  SortUnique(scratch);
  const double unitC = Options.ShapeSize * c.Shape.Scale;
  const double radiusC = Tables.Classes[c.Shape.ClassId].Radius * unitC;
  for (int x : scratch)
  {
    if (Poll())
    {
      return true; // (aborted: the round is dropped, whatever this says)
    }
    const Record& X = Accepted.Records[x];
    if (X.Key > c.Key)
    {
      continue;
    }
    const double unitX = Options.ShapeSize * X.Shape.Scale;
    const double radiusX = Tables.Classes[X.Shape.ClassId].Radius * unitX;
    if (Norm(X.Shape.Position - c.Shape.Position) >= radiusX + radiusC)
    {
      continue; // the geodesic distance is never shorter
    }
    const bool shortX = X.Shape.Curve.empty() && !X.Charts.empty() && !X.Charts[0].Entries.empty();
    const double depth = 0.00125 * std::min(radiusX, radiusC);
    // (Outline points farther in space than sqrt(2) circumradii from a shape's centre are
    // outside it: its outline is drawn along paths of length |along| + |across| at most.)
    auto near = [this](const Record& R, double radius) {
      const Vec3 centre = R.Shape.Position;
      const double reach = 1.4143 * radius + Mesh.MeanEdgeLength();
      return [this, centre, reach](const SurfacePoint& q) {
        return Norm(Mesh.Position(q) -
                 centre) <= reach;
      };
    };
    const auto nearX = near(X, radiusX), nearC = near(c, radiusC);
    // (Through an exact log map, as VerifyOverlaps reads it: a jump across its cut locus is
    // tested at its ends only.)
    if (shortX &&
      OutlineEnters(
        Silhouettes.Regions[X.Shape.ClassId], c.Drawn,
        [this, &X](const SurfacePoint& q, Vec2& p) { return ClassPointOf(X, q, p); },
        depth / unitX, X.Exact ? &Mesh : nullptr, 1.0 / unitX))
    {
      return true;
    }
    int hint = -1;
    if (!shortX && X.Frame &&
      OutlineEnters(
        Silhouettes.Regions[X.Shape.ClassId], c.Drawn,
        [&X, &nearX, &hint](
          const SurfacePoint& q, Vec2& p) { return nearX(q) && X.Frame->ClassPoint(q, p, &hint); },
        depth / unitX))
    {
      return true;
    }
    if (shortC && X.HasDrawn &&
      OutlineEnters(
        Silhouettes.Regions[c.Shape.ClassId], X.Drawn,
        [this, &c](const SurfacePoint& q, Vec2& p) { return ClassPointOf(c, q, p); },
        depth / unitC, c.Exact ? &Mesh : nullptr, 1.0 / unitC))
    {
      return true;
    }
    hint = -1;
    if (!shortC && c.Frame && X.HasDrawn &&
      OutlineEnters(
        Silhouettes.Regions[c.Shape.ClassId], X.Drawn,
        [&c, &nearC, &hint](
          const SurfacePoint& q, Vec2& p) { return nearC(q) && c.Frame->ClassPoint(q, p, &hint); },
        depth / unitC))
    {
      return true;
    }
  }
  c.Reason = Unfaithful(c) ? Record::Rejection::Faithful : Record::Rejection::None;
  return c.Reason != Record::Rejection::None;
}

} // namespace gs
