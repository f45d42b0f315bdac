// The local step of the discrete geodesic graph (DGG: Wang, Fang, Wu, Xin, He, CAGD 2017; fast
// construction: Adikusuma, Fang, He, ACM TOG 2020): from one vertex s, the direct geodesics
// (through no saddle or boundary vertex) that no shorter route through another vertex
// approximates within the accuracy epsilon. They become the graph's links from s.
//
// How (our formulation of the papers' idea). Window propagation as in the exact solver, from s
// only and along direct geodesics only (windows behind saddle and boundary vertices are those
// vertices' own business: their links continue the path). Each window also carries up to six
// "anchors": vertices its rays passed exactly (the ends of an edge its interval reached, split
// points), kept by a child while the segments from the anchor to both ends of the child's
// interval cross the parent's edge inside the parent's interval. By induction the straight
// segment from an anchor a to any point x the window reaches stays in the unfolded strip of
// faces and is a path on the surface: d(a, x) <= |a x|. A point x is covered when
//     d(s, a) + |a x| <= (1 + epsilon) d(s, x),
// the route through a being then at most epsilon longer. Along any ray from I (the window's
// unfolded source) the slack (1 + epsilon)|I x| - |a x| - |I a| grows (its derivative is at
// least epsilon), so a window whose whole interval is covered stays covered beyond: it is
// dropped, and the propagation dies out by itself once every direction has passed close enough
// to a vertex (on a flat region after about 1 / sqrt(epsilon) edges in the worst directions).
// Coverage of an interval is proven, not sampled (Covered: |I x| is convex along the edge, so
// above its tangent; |a x| is convex, so below its chord). A reached vertex whose best arrival
// is not covered becomes a link, with the length of its direct geodesic.
//
// Every link is the length of a real surface path, so graph distances never fall below the
// geodesic distance; the route that replaces a dropped link is at most epsilon longer per step
// of replacement, and steps compound over shorter and shorter pieces: the graph's error is a
// small multiple of epsilon (the DGG papers' O(epsilon)). SaddleVertexGraph::Build turns the
// user's accuracy into epsilon with the factor DGGEpsilonPerAccuracy, measured so that the
// largest relative error found against the exact solver stays below the accuracy asked for.
#pragma once

#include "TriangleMesh.h"
#include "WindowGeometry.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace gs
{

struct DGGStatistics
{
  std::int64_t WindowsPropagated = 0;
  std::int64_t WindowsCovered = 0; // dropped because their whole interval was covered
};

class DGGPropagation
{
public:
  // The mesh must outlive the object; reused for many sources (each Run resets what it touched).
  // `lengthScale` sets the distance tolerance as in ExactGeodesicSolver (0: the mesh's bounding
  // box diagonal).
  explicit DGGPropagation(const TriangleMesh& mesh, double lengthScale = 0.0);

  struct Link
  {
    int Target;
    double Distance; // length of the direct geodesic from the source
    double Angle;    // direction it leaves the source (as ExactGeodesicSolver::DepartureAngle)
  };
  // The links of vertex s for epsilon (> 0): its mesh neighbours (always) and every vertex whose
  // shortest direct geodesic from s is not covered. The propagation ends by itself once every
  // window is covered, trimmed away or has left the mesh. `reached` (optional): the other
  // vertices reached, whose best arrival was covered (the source excluded), with the length and
  // direction of that arrival's direct geodesic.
  void Run(int s, double epsilon, std::vector<Link>& links, std::vector<Link>* reached = nullptr);
  // Faces the propagation must not enter (one flag per face; null: none), as
  // ExactGeodesicOptions::Fence; FenceFacesEntered: those the last Run entered (each once or
  // more; empty when none).
  void SetFence(const std::vector<unsigned char>* fence) { Fence = fence; }
  const std::vector<int>& FenceFacesEntered() const { return Fenced.Entered; }

  const DGGStatistics& Statistics() const { return Stats; }

private:
  // Vertices behind a window from which the straight segment to any point of its interval stays
  // in the unfolded strip (see Propagate), with their distance from the source.
  static constexpr int MaxAnchors = 6;
  struct Anchor
  {
    double X, Y, D;
  };
  struct Window
  {
    double Key;    // smallest distance over the interval
    double B0, B1; // interval along half-edge H from Origin(H)
    double Ix, Iy; // unfolded source in H's frame (Iy < 0)
    // Departure angle of the ray towards x: Phi + the angle of R (x - I), R (a unit complex
    // number, Rc + i Rs) turning this frame into that of the first window, where the angle is
    // in (0, pi): the turns are multiplied rather than their angles added (no atan2 per window).
    double Phi;
    double Rc, Rs;
    Anchor Anchors[MaxAnchors]; // sorted by distance
    int NumAnchors;
    int H;
  };
  static void AddAnchor(Window& w, double x, double y);

  void Reset();
  // v reached at distance d, leaving the source at phi + the angle of (dx, dy).
  void Reach(int v, double d, bool covered, double phi, double dx, double dy, int via,
    double crossing);
  bool Trim(Window& w) const;
  bool Covered(const Window& w, double epsilon) const;
  void Push(Window& w, double epsilon);
  void Propagate(const Window& w, double epsilon);

  const TriangleMesh& Mesh;
  std::vector<double> Cx, Cy;    // opposite vertex of each half-edge in its frame
  std::vector<double> FanAngle;  // half-edge direction about its origin (as in the exact solver)
  std::vector<double> Dist;      // best direct distance found
  std::vector<unsigned char> IsCovered; // whether that best arrival is covered
  std::vector<double> AnglePhi, AngleX, AngleY; // its departure angle (as Reach's arguments)
  std::vector<int> CrossHalfedge;
  std::vector<double> CrossX;
  std::vector<int> Touched;
  window_geometry::WindowQueue<Window> Queue;
  double Tolerance = 0.0;
  const std::vector<unsigned char>* Fence = nullptr;
  window_geometry::FenceWatch Fenced;
  DGGStatistics Stats;
};

} // namespace gs
