// Analytic test surfaces with known geodesic distances: the bundled Data/ meshes and the unit
// tests are made from these.
#pragma once

#include "Vector.h"

#include <array>
#include <string>
#include <vector>

namespace gs
{

struct TriangleSoup
{
  std::vector<Vec3> Points;
  std::vector<std::array<long long, 3>> Triangles;
};

// Planar grid on [0, sizeX] x [0, sizeY] (z = 0), nx x ny quads split into two triangles each,
// the diagonals alternating so that the mesh has no preferred direction.
TriangleSoup MakePlanarGrid(int nx, int ny, double sizeX, double sizeY);
// The n x n planar grid of a side x side square made irregular: interior vertices moved by up to
// `jitter` of a cell in x and in y (uniformly, seeded), and with `randomDiagonals` each cell split
// along a random diagonal (vertex degrees 4 to 8). Moves of 0.3 of a cell or more may turn
// triangles over (a folded surface, no plane).
TriangleSoup MakeIrregularPlanarGrid(int n, double side, double jitter, bool randomDiagonals, unsigned seed);
// L-shaped planar domain: [0, 2]^2 minus (1, 2] x (1, 2], n cells per unit length. Its re-entrant
// corner at (1, 1) is a boundary vertex with a 270 degree angle.
TriangleSoup MakeLShape(int n);
// Open cone (developable) of apex angle 2*halfAngle, slant height `slant`, `rings` rings and
// `sectors` sectors; the apex is vertex 0. The lateral surface unrolls to a circular sector.
TriangleSoup MakeCone(double halfAngle, double slant, int rings, int sectors);
// Open cylinder of radius r along z from 0 to height, `sectors` x `rings` (developable).
TriangleSoup MakeCylinder(double radius, double height, int sectors, int rings);
// Unit-radius-scaled sphere by subdividing an icosahedron `level` times (20 * 4^level faces).
TriangleSoup MakeIcosphere(double radius, int level);
// Each triangle split into four at its edge midpoints: the same surface, four times the faces.
TriangleSoup SubdivideAtMidpoints(const TriangleSoup& soup);
// Torus with major radius R and minor radius r, n x m quads split into triangles.
TriangleSoup MakeTorus(double majorRadius, double minorRadius, int n, int m);

// A star outline centred at the origin: 2 * points vertices, counter-clockwise, alternately at
// `outer` (the first on +y) and `inner` distance. points = 5, inner / outer = 0.382: the
// regular pentagram's outline.
std::vector<Vec2> MakeStarPolygon(int points, double outer, double inner);

} // namespace gs
