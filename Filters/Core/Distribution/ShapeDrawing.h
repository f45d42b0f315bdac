// ShapeDrawing: the shapes of a ShapeDistributor run drawn as geometry, every shape's decal and
// outline computed in parallel, and their points lifted off the surface along the face normals
// (so that a renderer draws them over the surface rather than fighting it for depth).
#pragma once

#include "ShapeDistributor.h"
#include "ShapeOutline.h"
#include "SurfacePoint.h"
#include "TriangleMesh.h"
#include "Vector.h"

#include <array>
#include <functional>
#include <vector>

namespace gs
{

/// ShapeDistributor::Decal(s, tolerance) of every placed shape s, over `numberOfThreads` OpenMP
/// threads (0: OpenMP's default; at most the run's NumberOfThreads). With `seconds` (may be
/// null): each shape's wall time, for benchmarks. `progress` (optional; PhasePoll.h) sees the
/// fraction of shapes done from the calling thread, at most every 0.1 s; returning false skips
/// the rest (an abort: the result is incomplete).
std::vector<ShapeDecal> DrawDecals(const ShapeDistributor& distributor, double tolerance,
  int numberOfThreads, std::vector<double>* seconds = nullptr,
  const std::function<bool(double)>& progress = {});

/// ShapeDistributor::Outline(s, distributor.OutlineSpacing()) of every placed shape s (the
/// outlines the drawn check drew), over `numberOfThreads` OpenMP threads (0: OpenMP's default);
/// `progress` as for DrawDecals.
std::vector<std::vector<OutlinePiece>> DrawOutlines(const ShapeDistributor& distributor,
  int numberOfThreads, const std::function<bool(double)>& progress = {});

/// A decal triangle's corner (barycentric coordinates `bary` in mesh face `face`) in space,
/// `lift` (world units) along the face's normal.
inline Vec3 LiftedFacePoint(
  const TriangleMesh& mesh, int face, const std::array<double, 3>& bary, double lift)
{
  const Vec3 n = mesh.FaceNormal(face) * lift;
  const auto& corners = mesh.Face(face);
  return mesh.Position(corners[0]) * bary[0] + mesh.Position(corners[1]) * bary[1] +
    mesh.Position(corners[2]) * bary[2] + n;
}

/// An outline point (a face point) in space, `lift` (world units) along its face's normal.
inline Vec3 LiftedSurfacePoint(const TriangleMesh& mesh, const SurfacePoint& q, double lift)
{
  return mesh.Interpolate(q.Face, q.Bary) + mesh.FaceNormal(q.Face) * lift;
}

} // namespace gs
