// Where the Shape Distributor may still draw candidates: the class distribution, the face
// distribution (area / f^2 over the faces still alive) and the dead faces, where no candidate,
// or none of a class, can fit any more. Accepted shapes kill faces; the kills are logged per
// shape, so that taking the last shape back revives exactly the faces it killed.
#pragma once

#include "DistributionRandom.h"
#include "SurfacePoint.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace gs
{
namespace distribution
{

class SamplingState
{
public:
  std::vector<double> ClassCdf;   // cumulative class weights
  std::vector<double> FaceCdf;    // cumulative face weights (live faces only)
  std::vector<double> FaceWeight; // area / f^2 (0: no density)
  std::vector<double> AllCdf;     // cumulative face weights of all faces (probes)
  double MaxFaceDensity = 1.0;
  // The kill rule (ShapeDistributor::Impl::CollectKills): per (part, class), normalized, the
  // smallest safe distance of the part against any part of the class; per class, its reach.
  std::vector<double> KillRadius, KillReach;

  /// Every face alive for every one of `classes` classes, the kill log empty (the weights and
  /// ClassCdf are set by the caller; BuildCdf follows).
  void Reset(int faces, int classes);
  int NumberOfFaces() const { return static_cast<int>(Dead.size()); }
  /// Rebuilds the face distribution over the faces still alive.
  void BuildCdf();
  /// Faces killed since the face distribution was built (BuildCdf when positive).
  int KilledSinceCdf() const { return DeadSinceCdf; }
  bool AnyLiveFace() const { return FaceCdf.back() > 0.0; }
  bool DeadFace(int f) const { return Dead[f] != 0; }
  bool DeadForClass(int c, int f) const
  {
    return DeadFor[static_cast<std::size_t>(c) * Dead.size() + f] != 0;
  }
  /// A face drawn with probability area / f^2 (live faces only, or all), a uniform point in it.
  SurfacePoint RandomPoint(Random& rng, bool live = true) const;
  /// A class drawn by the class weights.
  int RandomClass(Random& rng) const;

  /// Starts the kill log of a newly accepted shape.
  void BeginShape() { KilledBy.push_back(Killed.size()); }
  /// Kills (class, face) pairs for the last shape begun; a face dead for every class that can
  /// be drawn dies for all.
  void Kill(const std::vector<std::pair<int, int>>& kills);
  /// Revives what the last shape begun killed, and forgets its log.
  void ReviveLast();
  /// Forgets the kill log (the faces stay as they are): after the accepted shapes are
  /// reordered, the last one is no longer the last killer.
  void ForgetKillLog()
  {
    Killed.clear();
    KilledBy.clear();
  }
  /// The number of shapes whose kills are logged.
  std::size_t LoggedShapes() const { return KilledBy.size(); }

private:
  std::vector<char> Dead;    // faces where no candidate can fit any more
  int DeadSinceCdf = 0;      // faces killed or revived since FaceCdf was built
  std::vector<char> DeadFor; // per (class, face): no candidate of that class fits there
  std::vector<std::pair<int, int>> Killed; // (class or -1 for all, face) killed, in order
  std::vector<std::size_t> KilledBy;       // per shape begun: its first entry in Killed
};

} // namespace distribution
} // namespace gs
