// Greedy mode: every newly accepted shape proposes candidates around itself at the tables' safe
// distance (touching it and a neighbour, or the lattice neighbours of the densest lattice the
// tables admit for copies turned alike), so that fronts fill the surface tightly.
#include "ShapeDistributorImpl.h"

#include "GeodesicShooting.h"
#include "Hash.h"

#include <cmath>
#include <limits>

namespace gs
{
using namespace distribution;

void ShapeDistributor::Impl::ComputeLattices()
{
  // For copies of one part turned alike, the tables give the smallest admissible offset in
  // each direction beta (of the line from one centre to the other, in the shape's frame):
  // D(beta) = max(T(-beta, -beta), T(-beta - pi, -beta - pi)) (the pair seen from either
  // shape). A lattice {i u + j v} is admissible when every lattice vector w is at least
  // D(angle(w)) long; the densest one has basis vectors on the boundary |w| = D: searched over
  // pairs of boundary samples, smallest cell area first. Greedy then proposes the lattice
  // neighbours of each placed shape, so that a cluster grows as one crystal instead of grains
  // of two-contact growth that leave gaps where they meet.
  Lattices.ByClass.assign(Tables.Classes.size(), {});
  if (Options.Mode != DistributionMode::Greedy || CircleMode)
  {
    return;
  }
  for (std::size_t c = 0; c < Tables.Classes.size(); ++c)
  {
    if (Tables.Classes[c].Parts.size() != 1)
    {
      continue;
    }
    const int p = Tables.Classes[c].Parts[0];
    Hasher h;
    h.AddValue(Tables.AngleBins);
    h.AddValue(Tables.Parts[p].Radius);
    const std::size_t ka = static_cast<std::size_t>(Tables.AngleBins);
    const std::size_t pair = static_cast<std::size_t>(p) * Tables.Parts.size() + p;
    h.Add(Tables.Values.data() + pair * ka * ka, ka * ka * sizeof(double));
    auto it = Lattices.Cache.find(h.H);
    if (it == Lattices.Cache.end())
    {
      if (Lattices.Cache.size() >= 64)
      {
        Lattices.Cache.clear();
      }
      it = Lattices.Cache.emplace(h.H, PartLattice(p)).first;
    }
    Lattices.ByClass[c] = it->second;
  }
}

std::vector<Vec2> ShapeDistributor::Impl::PartLattice(int p) const
{
  // (Within 2e-3 rad of beta too: a lattice vector on a bin boundary must not depend on the
  // last bits of the angle the conflict check will compute.)
  auto D = [&](double beta) {
    double d = 0.0;
    for (const double b : { beta - 2e-3, beta, beta + 2e-3 })
    {
      d = std::max({ d, Tables.Lookup(p, p, -b, -b), Tables.Lookup(p, p, -b - Pi, -b - Pi) });
    }
    return d;
  };
  const double cap = 2.0 * Tables.Parts[p].Radius; // no table value exceeds r_A + r_B
  auto admissible = [&](const Vec2& u, const Vec2& v, int range) {
    for (int i = -range; i <= range; ++i)
    {
      for (int j = 0; j <= range; ++j)
      {
        if (j == 0 && i <= 0)
        {
          continue; // w and -w: one of them, and not 0
        }
        const Vec2 w = u * i + v * j;
        const double len = Norm(w);
        if (len < cap && len < D(std::atan2(w.y, w.x)) * (1.0 - 1e-12))
        {
          return false;
        }
      }
    }
    return true;
  };
  // Boundary samples: four per angle bin, 256 to 512 (the search is quadratic in them).
  const int n = std::min(512, std::max(256, 4 * Tables.AngleBins));
  std::vector<Vec2> boundary(n);
  for (int k = 0; k < n; ++k)
  {
    const double beta = Pi * (k + 0.5) / n; // half a turn: -w is in the lattice too
    boundary[k] = Vec2{ std::cos(beta), std::sin(beta) } * (D(beta) * (1.0 + 1e-9));
  }
  double bestArea = std::numeric_limits<double>::infinity();
  Vec2 bu, bv;
  for (int a = 0; a < n; ++a)
  {
    for (int b = 0; b < n; ++b)
    {
      // v anywhere in the open half turn after u (as v or -v).
      for (const double sign : { 1.0, -1.0 })
      {
        const Vec2 u = boundary[a], v = boundary[b] * sign;
        const double area = Cross(u, v);
        if (!(area > 1e-12 * cap * cap) || area >= bestArea || !admissible(u, v, 4))
        {
          continue;
        }
        bestArea = area;
        bu = u;
        bv = v;
      }
    }
  }
  if (!(bestArea < std::numeric_limits<double>::infinity()) || !admissible(bu, bv, 8))
  {
    return {};
  }
  const Vec2 w = Norm(bu - bv) < Norm(bu + bv) ? bu - bv : bu + bv;
  return { bu, bv, w, bu * -1.0, bv * -1.0, w * -1.0 };
}

// The contact curve of a Greedy parent for a new shape turned like it: the safe distance in
// each direction beta of the parent's frame, and the clearance from the parent's placed
// neighbours (as its chart sees them).
struct ShapeDistributor::Impl::Contact
{
  const Impl& Distributor; // the distributor it serves
  bool Tabled; // both single-part classes: the tables (otherwise a fraction of the radii)
  int Pa, Pc;  // the parent's part, the new shape's
  double Unit;
  double RadiusSum; // the two class radii
  std::vector<Neighbour> Near;

  // Safe distance of the new shape (turned like A) in direction beta from A (A's frame).
  double Reach(double beta) const
  {
    return Tabled ? Distributor.Tables.Lookup(Pa, Pc, -beta, -beta) * Unit
                  : (Distributor.CircleMode ? 1.0 : 0.75) * RadiusSum * Unit;
  }
  Vec2 At(double beta) const { return Vec2{ std::cos(beta), std::sin(beta) } * Reach(beta); }
  // Clearance of a new shape at P (turned like A) from neighbour b: > 0 when free.
  double Clearance(const Vec2& P, const Neighbour& b) const
  {
    const Vec2 w = P - b.Centre;
    const double dist = Norm(w), line = std::atan2(w.y, w.x);
    const double safe = Distributor.CircleMode
      ? (Distributor.PartRadius(b.Part) + Distributor.PartRadius(Pc))
      : Distributor.Tables.Lookup(b.Part, Pc, b.Axis - line, -line);
    return dist - safe * b.Unit;
  }
  bool FreeOfAll(double beta) const
  {
    const Vec2 P = At(beta);
    for (const Neighbour& b : Near)
    {
      if (Clearance(P, b) < 0.0)
      {
        return false;
      }
    }
    return true;
  }
};

std::vector<ShapeDistributor::Impl::Proposal> ShapeDistributor::Impl::Propose(
  int parentId, int round, int slot) const
{
  std::vector<Proposal> out;
  const Record& A = Accepted.Records[parentId];
  Random rng(Options.Seed, 2, static_cast<std::uint64_t>(round), static_cast<std::uint64_t>(slot));
  const int cls = Sampling.RandomClass(rng);
  const SafeDistanceClass& ac = Tables.Classes[A.Shape.ClassId];
  const SafeDistanceClass& cc = Tables.Classes[cls];
  const double unit = Options.ShapeSize * A.Shape.Scale * (1.0 + Options.SafetyMargin);
  const double a0 = TangentAngle(Mesh, A.Shape.Centre, A.Shape.Direction);
  if (!std::isfinite(a0))
  {
    return out;
  }
  const bool tabled = !CircleMode && ac.Parts.size() == 1 && cc.Parts.size() == 1;
  const int pa = CircleMode ? A.Shape.ClassId : ac.Parts[0];
  const int pc = CircleMode ? cls : cc.Parts[0];
  Contact contact{ *this, tabled, pa, pc, unit, ac.Radius + cc.Radius, {} };
  if (tabled || CircleMode)
  {
    contact.Near = NeighboursInChart(parentId, pa, pc);
  }
  // lengths: the lattice vectors' lengths; empty: each proposal lies on A's contact curve
  // (reach(beta)).
  std::vector<double> betas, lengths;
  if (cls == A.Shape.ClassId && !Lattices.ByClass[cls].empty())
  {
    LatticeDirections(contact, cls, betas, lengths);
  }
  else if (contact.Near.empty())
  {
    const double offset = rng.Uniform();
    for (int j = 0; j < Options.GreedyDirections; ++j)
    {
      betas.push_back(TwoPi * (j + offset) / Options.GreedyDirections);
    }
  }
  else
  {
    ContactDirections(contact, betas);
  }
  ShootProposals(A, cls, contact, betas, lengths, a0, out);
  return out;
}

std::vector<ShapeDistributor::Impl::Neighbour> ShapeDistributor::Impl::NeighboursInChart(
  int parentId, int pa, int pc) const
{
  const Record& A = Accepted.Records[parentId];
  std::vector<Neighbour> near;
  std::vector<int> ids;
  if (!A.Charts.empty())
  {
    for (const ChartEntry& e : A.Charts[0].Entries)
    {
      ids.insert(ids.end(), Accepted.CentreIndex[e.Vertex].begin(), Accepted.CentreIndex[e.Vertex].end());
    }
  }
  SortUnique(ids);
  for (int id : ids)
  {
    if (id == parentId)
    {
      continue;
    }
    const Record& B = Accepted.Records[id];
    if (B.Shape.Parts.size() != 1)
    {
      continue;
    }
    const PlacedPart& pb = B.Shape.Parts[0];
    const auto& corners = Mesh.Face(pb.Centre.Face);
    const ChartEntry* e[3];
    bool all = true;
    for (int k = 0; k < 3 && all; ++k)
    {
      e[k] = A.Charts[0].Find(corners[k]);
      all = e[k] != nullptr;
    }
    if (!all)
    {
      continue;
    }
    Vec2 P[3];
    for (int k = 0; k < 3; ++k)
    {
      P[k] = Vec2{ e[k]->X, e[k]->Y };
    }
    Neighbour b;
    b.Centre = P[0] * pb.Centre.Bary[0] + P[1] * pb.Centre.Bary[1] + P[2] * pb.Centre.Bary[2];
    // B's axis carried into the chart by the face's affine map.
    const Vec3 x0 = Mesh.Position(corners[0]);
    const Vec3 e1 = Mesh.Position(corners[1]) - x0, e2 = Mesh.Position(corners[2]) - x0;
    const double g11 = Dot(e1, e1), g12 = Dot(e1, e2), g22 = Dot(e2, e2);
    const double det = g11 * g22 - g12 * g12;
    if (!(det > 0.0))
    {
      continue;
    }
    const double r1 = Dot(pb.Axis, e1), r2 = Dot(pb.Axis, e2);
    const double u = (g22 * r1 - g12 * r2) / det, v = (g11 * r2 - g12 * r1) / det;
    const Vec2 axis = (P[1] - P[0]) * u + (P[2] - P[0]) * v;
    b.Axis = std::atan2(axis.y, axis.x);
    b.Part = pb.Part;
    b.Unit =
      Options.ShapeSize * std::max(B.Shape.Scale, A.Shape.Scale) * (1.0 + Options.SafetyMargin);
    if (Norm(b.Centre) < (PartRadius(pa) + 2.0 * PartRadius(pc) + PartRadius(b.Part)) * b.Unit)
    {
      near.push_back(b);
    }
  }
  return near;
}

void ShapeDistributor::Impl::LatticeDirections(const Contact& contact, int cls, std::vector<double>& betas,
  std::vector<double>& lengths) const
{
  // The lattice neighbours of A that no placed neighbour already rules out.
  const double unit = contact.Unit;
  for (const Vec2& w : Lattices.ByClass[cls])
  {
    const Vec2 P = w * unit;
    bool free = true;
    for (const Neighbour& b : contact.Near)
    {
      free = free && contact.Clearance(P, b) >= -1e-9 * unit;
    }
    if (free)
    {
      betas.push_back(std::atan2(w.y, w.x));
      lengths.push_back(Norm(w) * unit);
    }
  }
}

void ShapeDistributor::Impl::ContactDirections(const Contact& contact, std::vector<double>& betas) const
{
  // Touching A and a neighbour: where the clearance from that neighbour changes sign along
  // A's contact curve (the side with clearance >= 0, refined by bisection).
  const int samples = 4 * Options.GreedyDirections;
  for (const Neighbour& b : contact.Near)
  {
    double previous = contact.Clearance(contact.At(0.0), b);
    for (int j = 1; j <= samples; ++j)
    {
      const double beta = TwoPi * j / samples;
      const double now = contact.Clearance(contact.At(beta), b);
      if ((previous < 0.0) != (now < 0.0))
      {
        double lo = TwoPi * (j - 1) / samples, hi = beta; // lo: the previous sample
        const bool loFree = previous >= 0.0;
        for (int it = 0; it < 20; ++it)
        {
          const double mid = 0.5 * (lo + hi);
          const bool midFree = contact.Clearance(contact.At(mid), b) >= 0.0;
          (midFree == loFree ? lo : hi) = mid;
        }
        const double free = loFree ? lo : hi;
        if (contact.FreeOfAll(free))
        {
          betas.push_back(free);
        }
      }
      previous = now;
    }
  }
}

void ShapeDistributor::Impl::ShootProposals(const Record& A, int cls, const Contact& contact,
  const std::vector<double>& betas, const std::vector<double>& lengths, double a0,
  std::vector<Proposal>& out) const
{
  const SafeDistanceClass& ac = Tables.Classes[A.Shape.ClassId];
  for (std::size_t k = 0; k < betas.size(); ++k)
  {
    const double beta = betas[k];
    const double d = (k < lengths.size() ? lengths[k] : contact.Reach(beta)) * (1.0 + 1e-6) + 1e-9 * Measures.MaxEdge;
    const GeodesicShot shot = ShootGeodesic(Mesh, A.Shape.Centre, a0 + beta, d);
    if (shot.ReachedBoundary || shot.End.Face < 0 || !(Sampling.FaceWeight[shot.End.Face] > 0.0) ||
      Sampling.DeadForClass(cls, shot.End.Face))
    {
      continue; // off the surface or in a region without density
    }
    Proposal p;
    p.Centre = shot.End;
    p.Class = cls;
    p.Prefer = FaceDirection[A.Shape.Centre.Face];
    if (Options.Symmetry > 1)
    {
      // The parent's own choice among the N directions (its class axis for short shapes).
      p.Prefer = ac.Parts.size() <= 1 ? A.Shape.Direction : p.Prefer;
    }
    p.Key = Norm(Mesh.Interpolate(p.Centre.Face, p.Centre.Bary) - Accepted.Records[0].Shape.Position);
    out.push_back(p);
  }
}

} // namespace gs
