#include "ShapeOutline.h"

#include <algorithm>
#include <cmath>

namespace gs
{
namespace
{
constexpr double Pi = 3.14159265358979323846;
constexpr double TwoPi = 2.0 * Pi;

double SignedArea(const std::vector<Vec2>& ring)
{
  double a = 0.0;
  for (std::size_t k = 0, n = ring.size(); k < n; ++k)
  {
    a += Cross(ring[k], ring[(k + 1) % n]);
  }
  return 0.5 * a;
}

bool InsideRing(const std::vector<Vec2>& ring, const Vec2& q)
{
  bool in = false;
  for (std::size_t k = 0, n = ring.size(); k < n; ++k)
  {
    const Vec2& a = ring[k];
    const Vec2& b = ring[(k + 1) % n];
    if ((a.y > q.y) != (b.y > q.y) && q.x < a.x + (b.x - a.x) * (q.y - a.y) / (b.y - a.y))
    {
      in = !in;
    }
  }
  return in;
}

// A ring sampled at `spacing`: the ring's corners and points between them.
std::vector<Vec2> Sample(const std::vector<Vec2>& ring, double spacing)
{
  std::vector<Vec2> out;
  for (std::size_t k = 0, n = ring.size(); k < n; ++k)
  {
    const Vec2 a = ring[k], b = ring[(k + 1) % n];
    const int pieces = std::max(1, std::min(100000, static_cast<int>(std::ceil(Norm(b - a) / spacing))));
    for (int j = 0; j < pieces; ++j)
    {
      out.push_back(a + (b - a) * (static_cast<double>(j) / pieces));
    }
  }
  return out;
}

// Points strictly between a and b (both stopped by the boundary), in order, where the segment
// may dip into the reach: the midpoint is tried when the boundary is within half the segment of
// it along its ray (or it is reached), recursively down to `finest`.
void Refine(const Vec2& a, const Vec2& b, double finest,
  const std::function<MappedPoint(const Vec2&)>& map, std::vector<Vec2>& samples,
  std::vector<MappedPoint>& mapped)
{
  const double length = Norm(b - a);
  if (length <= finest)
  {
    return;
  }
  const Vec2 mid = (a + b) * 0.5;
  const MappedPoint m = map(mid);
  const double beyond = Norm(mid) * (1.0 - m.Reach);
  if (!m.Reached && beyond > 0.5 * length)
  {
    return;
  }
  if (!m.Reached)
  {
    Refine(a, mid, finest, map, samples, mapped);
  }
  samples.push_back(mid);
  mapped.push_back(m);
  if (!m.Reached)
  {
    Refine(mid, b, finest, map, samples, mapped);
  }
}

double Wrap(double a)
{
  a = std::fmod(a, TwoPi);
  return a < 0.0 ? a + TwoPi : a;
}

using PointMap = std::function<MappedPoint(const Vec2&)>;

// A ring of the class outline sampled for drawing, each sample with where the map takes it.
struct SampledRing
{
  std::vector<Vec2> Samples;
  std::vector<MappedPoint> Mapped;
  std::vector<int> CrossingAt; // per edge (sample k to k + 1): its crossing, or -1
};

// Where a ring crosses the boundary of the reach D: the last reached point of the edge.
struct Crossing
{
  int Ring, Edge;
  bool Exit; // the ring leaves D there (true) or enters it
  Vec2 P;
  MappedPoint Mapped;
  double Theta; // polar angle of P in [0, 2 pi)
  bool Used;
};

// The oriented rings sampled at `spacing` and mapped. Between two stopped samples the ring may
// still dip into D (cutting a corner of the surface): such edges are split where the boundary
// is within half an edge of the midpoint, down to 1/256 of the spacing. `allReached` and
// `anyReached` say whether all or any of the samples were reached.
std::vector<SampledRing> SampleRings(const std::vector<std::vector<Vec2>>& oriented, double spacing,
  const PointMap& map, bool& allReached, bool& anyReached)
{
  std::vector<SampledRing> sampled(oriented.size());
  allReached = true;
  anyReached = false;
  for (std::size_t r = 0; r < oriented.size(); ++r)
  {
    SampledRing& ring = sampled[r];
    const std::vector<Vec2> samples = Sample(oriented[r], spacing);
    std::vector<MappedPoint> mapped(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k)
    {
      mapped[k] = map(samples[k]);
    }
    for (std::size_t k = 0; k < samples.size(); ++k)
    {
      const std::size_t next = (k + 1) % samples.size();
      ring.Samples.push_back(samples[k]);
      ring.Mapped.push_back(mapped[k]);
      if (!mapped[k].Reached && !mapped[next].Reached)
      {
        Refine(samples[k], samples[next], spacing / 256.0, map, ring.Samples, ring.Mapped);
      }
    }
    for (const MappedPoint& m : ring.Mapped)
    {
      allReached = allReached && m.Reached;
      anyReached = anyReached || m.Reached;
    }
  }
  return sampled;
}

// A sampled ring drawn whole, as a closed piece.
OutlinePiece WholePiece(const SampledRing& ring)
{
  OutlinePiece piece;
  for (std::size_t k = 0; k < ring.Samples.size(); ++k)
  {
    piece.Points.push_back(ring.Mapped[k].End);
    piece.ClassPoints.push_back(ring.Samples[k]);
  }
  return piece;
}

// The boundary of D, traced by rays longer than the circle (`Far`), stopped by the mesh
// boundary.
struct ReachBoundary
{
  const PointMap& Map;
  double Spacing;
  double Far;  // length of the rays: a hair beyond the circle
  double Step; // angle between rays: the spacing at the circle

  // Between two rays (angles t0, t1, stops s0, s1) the boundary may turn a corner that the
  // chord of their stops would cut: rays in between are added where the boundary departs from
  // that chord by more than 1/1000 of the spacing (to 1/4096 of the angle step).
  void Refine(double t0, const Vec2& s0, double t1, const Vec2& s1, OutlinePiece& piece) const
  {
    if (t1 - t0 < Step / 4096.0)
    {
      return;
    }
    const double t = 0.5 * (t0 + t1);
    const Vec2 p{ Far * std::cos(t), Far * std::sin(t) };
    const MappedPoint m = Map(p);
    const Vec2 stop = p * m.Reach;
    const Vec2 chord = s1 - s0;
    const double length = Norm(chord);
    const double off = length > 0.0 ? std::abs(Cross(chord, stop - s0)) / length : Norm(stop - s0);
    if (off <= 1e-3 * Spacing)
    {
      return;
    }
    Refine(t0, s0, t, stop, piece);
    piece.Points.push_back(m.End);
    piece.ClassPoints.push_back(stop);
    Refine(t, stop, t1, s1, piece);
  }

  // Appends the stops of rays from polar angle `from` counter-clockwise by `sweep`, after the
  // stop `first` (at `from`) and before `last` (at from + sweep), which are not added.
  void AddArc(double from, const Vec2& first, double sweep, const Vec2& last, OutlinePiece& piece) const
  {
    const int steps = std::max(1, static_cast<int>(std::ceil(sweep / Step)));
    double t0 = from;
    Vec2 s0 = first;
    for (int j = 1; j <= steps; ++j)
    {
      const double t = from + sweep * j / steps;
      Vec2 stop = last;
      MappedPoint m;
      if (j < steps)
      {
        const Vec2 p{ Far * std::cos(t), Far * std::sin(t) };
        m = Map(p);
        stop = p * m.Reach;
      }
      Refine(t0, s0, t, stop, piece);
      if (j < steps)
      {
        piece.Points.push_back(m.End);
        piece.ClassPoints.push_back(stop);
      }
      t0 = t;
      s0 = stop;
    }
  }
};

// The crossings of the rings with D's boundary: on every edge between a reached and a stopped
// sample, the last reached point, by bisection to 1e-9 of the radius. Sets each ring's
// CrossingAt.
std::vector<Crossing> FindCrossings(std::vector<SampledRing>& sampled, double radius, const PointMap& map)
{
  std::vector<Crossing> crossings;
  for (std::size_t r = 0; r < sampled.size(); ++r)
  {
    SampledRing& ring = sampled[r];
    const std::size_t n = ring.Samples.size();
    ring.CrossingAt.assign(n, -1);
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::size_t next = (k + 1) % n;
      if (ring.Mapped[k].Reached == ring.Mapped[next].Reached)
      {
        continue;
      }
      const bool exit = ring.Mapped[k].Reached;
      Vec2 in = exit ? ring.Samples[k] : ring.Samples[next];
      Vec2 outside = exit ? ring.Samples[next] : ring.Samples[k];
      MappedPoint last = exit ? ring.Mapped[k] : ring.Mapped[next];
      for (int it = 0; it < 60 && Norm(outside - in) > 1e-9 * radius; ++it)
      {
        const Vec2 mid = (in + outside) * 0.5;
        const MappedPoint m = map(mid);
        if (m.Reached)
        {
          in = mid;
          last = m;
        }
        else
        {
          outside = mid;
        }
      }
      ring.CrossingAt[k] = static_cast<int>(crossings.size());
      crossings.push_back(Crossing{ static_cast<int>(r), static_cast<int>(k), exit, in, last,
        Wrap(std::atan2(in.y, in.x)), false });
    }
  }
  return crossings;
}

// The outline when no ring crosses D's boundary: each ring wholly inside D or wholly beyond
// it. The rings inside D are drawn whole; when D lies within the region (a surface smaller
// than the shape, around the centre), all of D's boundary is drawn.
void DrawWithoutCrossings(const std::vector<SampledRing>& sampled,
  const std::vector<std::vector<Vec2>>& oriented, bool anyReached, const ReachBoundary& boundary,
  std::vector<OutlinePiece>& out)
{
  for (const SampledRing& ring : sampled)
  {
    if (!ring.Mapped.empty() && ring.Mapped[0].Reached)
    {
      out.push_back(WholePiece(ring));
    }
  }
  bool centreInside = false;
  for (const auto& ring : oriented)
  {
    centreInside = InsideRing(ring, Vec2{ 0.0, 0.0 }) != centreInside;
  }
  if (!anyReached && centreInside)
  {
    OutlinePiece piece;
    const double far = boundary.Far;
    const MappedPoint m = boundary.Map(Vec2{ far, 0.0 });
    const Vec2 stop = Vec2{ far, 0.0 } * m.Reach;
    piece.Points.push_back(m.End);
    piece.ClassPoints.push_back(stop);
    boundary.AddArc(0.0, stop, TwoPi, stop, piece);
    out.push_back(std::move(piece));
  }
}

// The entry that the boundary of D reaches first counter-clockwise from `exit` (-1: none), and
// in `sweep` the angle to it. Crossings on the exit's own ray: the boundary runs along that
// ray only when it passes through the centre (a centre on the mesh boundary); it comes in
// along the ray if the rays just after it are stopped closer than the exit, and goes out
// along it otherwise.
int NextEntry(const std::vector<Crossing>& crossings, const Crossing& exit,
  const ReachBoundary& boundary, double& sweepToEntry)
{
  const double far = boundary.Far;
  bool inward = false, inwardKnown = false;
  int entry = -1;
  double best = 2.0 * TwoPi, bestAlong = 0.0;
  for (int c = 0; c < static_cast<int>(crossings.size()); ++c)
  {
    if (crossings[c].Exit)
    {
      continue;
    }
    double sweep = Wrap(crossings[c].Theta - exit.Theta);
    double along = 0.0;
    if (sweep < 1e-7 || sweep > TwoPi - 1e-7) // (bisection places crossings to 1e-9 R)
    {
      if (!inwardKnown)
      {
        const double t = exit.Theta + 1e-5;
        const MappedPoint after = boundary.Map(Vec2{ far * std::cos(t), far * std::sin(t) });
        inward = far * after.Reach < Norm(exit.P);
        inwardKnown = true;
      }
      along = Norm(crossings[c].P) - Norm(exit.P);
      sweep = (along < 0.0) == inward ? 0.0 : TwoPi;
      along = std::abs(along);
    }
    else if (sweep <= 0.0)
    {
      sweep += TwoPi;
    }
    if (sweep < best || (sweep == best && along < bestAlong))
    {
      best = sweep;
      bestAlong = along;
      entry = c;
    }
  }
  sweepToEntry = best;
  return entry;
}

// Appends the samples of `ring` after edge `edge` (an entry's) up to the end of the edge that
// holds the ring's next crossing; returns that crossing (-1: none).
int FollowRing(const SampledRing& ring, int edge, OutlinePiece& piece)
{
  const int n = static_cast<int>(ring.Samples.size());
  for (int j = 1; j <= n; ++j)
  {
    const int k = (edge + j) % n;
    piece.Points.push_back(ring.Mapped[k].End);
    piece.ClassPoints.push_back(ring.Samples[k]);
    if (ring.CrossingAt[k] >= 0)
    {
      return ring.CrossingAt[k];
    }
  }
  return -1;
}

// The outline piece walked from exit `start`: counter-clockwise along D's boundary to the next
// entry, along that ring to its next exit, and so on until back at the first exit. Marks the
// crossings it passes as used.
OutlinePiece WalkFromExit(int start, std::vector<Crossing>& crossings,
  const std::vector<SampledRing>& sampled, const ReachBoundary& boundary)
{
  const int count = static_cast<int>(crossings.size());
  OutlinePiece piece;
  int current = start;
  for (int guard = 0; guard <= count; ++guard)
  {
    Crossing& exit = crossings[current];
    exit.Used = true;
    piece.Points.push_back(exit.Mapped.End);
    piece.ClassPoints.push_back(exit.P);
    double sweep = 0.0;
    const int entry = NextEntry(crossings, exit, boundary, sweep);
    if (entry < 0)
    {
      break;
    }
    Crossing& in = crossings[entry];
    boundary.AddArc(exit.Theta, exit.P, sweep, in.P, piece);
    in.Used = true;
    piece.Points.push_back(in.Mapped.End);
    piece.ClassPoints.push_back(in.P);
    // Along the ring from the entry to its next exit.
    const int next = FollowRing(sampled[in.Ring], in.Edge, piece);
    if (next < 0 || !crossings[next].Exit || next == start || crossings[next].Used)
    {
      break;
    }
    current = next;
  }
  return piece;
}
} // namespace

std::vector<std::vector<Vec2>> OrientRings(const std::vector<std::vector<Vec2>>& rings)
{
  std::vector<std::vector<Vec2>> out;
  for (std::size_t i = 0; i < rings.size(); ++i)
  {
    if (rings[i].size() < 3)
    {
      continue;
    }
    int depth = 0;
    for (std::size_t j = 0; j < rings.size(); ++j)
    {
      depth += j != i && rings[j].size() >= 3 && InsideRing(rings[j], rings[i][0]) ? 1 : 0;
    }
    std::vector<Vec2> ring = rings[i];
    if ((SignedArea(ring) > 0.0) != (depth % 2 == 0))
    {
      std::reverse(ring.begin(), ring.end());
    }
    out.push_back(std::move(ring));
  }
  return out;
}

std::vector<OutlinePiece> DrawOutlinePieces(const std::vector<std::vector<Vec2>>& rings,
  double spacing, const std::function<MappedPoint(const Vec2&)>& map)
{
  std::vector<OutlinePiece> out;
  for (const auto& ring : rings)
  {
    const std::vector<Vec2> samples = Sample(ring, spacing);
    const std::size_t n = samples.size();
    std::vector<MappedPoint> mapped(n);
    std::size_t firstMissed = n;
    for (std::size_t k = 0; k < n; ++k)
    {
      mapped[k] = map(samples[k]);
      if (!mapped[k].Reached && firstMissed == n)
      {
        firstMissed = k;
      }
    }
    if (firstMissed == n)
    {
      OutlinePiece piece;
      piece.Closed = true;
      for (std::size_t k = 0; k < n; ++k)
      {
        piece.Points.push_back(mapped[k].End);
        piece.ClassPoints.push_back(samples[k]);
      }
      out.push_back(std::move(piece));
      continue;
    }
    // Open runs of reached samples, starting after a missed one (so that no run wraps).
    OutlinePiece piece;
    piece.Closed = false;
    for (std::size_t j = 1; j <= n; ++j)
    {
      const std::size_t k = (firstMissed + j) % n;
      if (mapped[k].Reached)
      {
        piece.Points.push_back(mapped[k].End);
        piece.ClassPoints.push_back(samples[k]);
        continue;
      }
      if (piece.Points.size() >= 2)
      {
        out.push_back(piece);
      }
      piece.Points.clear();
      piece.ClassPoints.clear();
    }
  }
  return out;
}

std::vector<OutlinePiece> DrawRadialOutline(const std::vector<std::vector<Vec2>>& rings,
  double spacing, double radius, const std::function<MappedPoint(const Vec2&)>& map)
{
  std::vector<OutlinePiece> out;
  if (!(spacing > 0.0) || !(radius > 0.0))
  {
    return out;
  }
  // Interior on the left of every ring: the boundary of the drawn region then continues, where a
  // ring leaves the reach D, counter-clockwise along D's boundary (D on the left too).
  const std::vector<std::vector<Vec2>> oriented = OrientRings(rings);
  bool allReached = true, anyReached = false;
  std::vector<SampledRing> sampled = SampleRings(oriented, spacing, map, allReached, anyReached);
  if (allReached)
  {
    for (const SampledRing& ring : sampled)
    {
      out.push_back(WholePiece(ring));
    }
    return out;
  }
  const ReachBoundary boundary{ map, spacing, radius * (1.0 + 1e-6), spacing / radius };
  std::vector<Crossing> crossings = FindCrossings(sampled, radius, map);
  if (crossings.empty())
  {
    DrawWithoutCrossings(sampled, oriented, anyReached, boundary, out);
    return out;
  }
  for (const SampledRing& ring : sampled)
  {
    bool in = true;
    for (const MappedPoint& m : ring.Mapped)
    {
      in = in && m.Reached;
    }
    if (in)
    {
      out.push_back(WholePiece(ring));
    }
  }
  const int count = static_cast<int>(crossings.size());
  for (int start = 0; start < count; ++start)
  {
    if (!crossings[start].Exit || crossings[start].Used)
    {
      continue;
    }
    OutlinePiece piece = WalkFromExit(start, crossings, sampled, boundary);
    if (piece.Points.size() >= 3)
    {
      out.push_back(std::move(piece));
    }
  }
  return out;
}

} // namespace gs
