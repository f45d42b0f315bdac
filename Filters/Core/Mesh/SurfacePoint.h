// A point on the surface: a vertex, or a face with barycentric coordinates (edge points are face
// points with one zero coordinate). Every geodesic query accepts it.
#pragma once

#include <array>

namespace gs
{

class TriangleMesh;

struct SurfacePoint
{
  int Vertex = -1; // >= 0 for a vertex point
  int Face = -1;   // >= 0 for a face point
  std::array<double, 3> Bary{ { 0.0, 0.0, 0.0 } }; // weights of Face's corners 0, 1, 2

  static SurfacePoint AtVertex(int v)
  {
    SurfacePoint p;
    p.Vertex = v;
    return p;
  }
  static SurfacePoint InFace(int f, double b0, double b1, double b2)
  {
    SurfacePoint p;
    p.Face = f;
    p.Bary = { { b0, b1, b2 } };
    return p;
  }
  bool IsVertex() const { return Vertex >= 0; }
};

} // namespace gs
