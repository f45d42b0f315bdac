#!/usr/bin/env python3
"""What geometry allows Random and Greedy for 5-point stars turned alike.

Random sequential addition jams at a number density of about c / (excluded area), with
c = 2.19 for disks and 2.25 for aligned squares (jamming coverages 0.547 and 0.562). Two copies
of a shape A turned alike overlap when their centres are closer than the boundary of the
Minkowski sum A + (-A); for circumcircles of radius r it is the disk of radius 2r (area 4 pi
r^2). So Random / Circumcircle is about 4 pi r^2 / area(A + (-A)).

This computes area(A + (-A)) exactly up to the raster (1024^2, FFT convolution of A's indicator
with its point reflection) for regular 5-point stars of circumradius 1 and inner radius rho
(rho = 0.382: the regular pentagram {5/2}), without the safe distance tables' binning (the
tables are conservative: DistributionBenchmark prints their larger excluded area).

Greedy packs copies in the densest lattice the safe distances admit; for the exact region the
densest lattice of translates (basis vectors on its boundary, no lattice vector inside it) has
the cell printed here, against the pi r^2 / 0.547 a jammed circumcircle takes.

    python3 Benchmarks/star_exclusion_area.py [rho ...]      (numpy)
"""
import sys

import numpy as np

N, L = 2048, 4.4  # raster over [-2.2, 2.2]^2: the sum of two unit shapes fits in radius 2
xs = (np.arange(N) - N / 2 + 0.5) * (L / N)
X, Y = np.meshgrid(xs, xs)


def star(rho, points=5):
    """Indicator of the star polygon (even-odd rule over its 2 * points edges)."""
    angles = np.pi / 2 + np.arange(2 * points) * np.pi / points
    radii = np.where(np.arange(2 * points) % 2 == 0, 1.0, rho)
    px, py = radii * np.cos(angles), radii * np.sin(angles)
    inside = np.zeros_like(X, dtype=bool)
    for k in range(2 * points):
        x1, y1, x2, y2 = px[k], py[k], px[k - 1], py[k - 1]
        crosses = (y1 > Y) != (y2 > Y)
        xcross = x1 + (Y - y1) * (x2 - x1) / np.where(y2 != y1, y2 - y1, 1.0)
        inside ^= crosses & (X < xcross)
    return inside


def excluded_region(a):
    """Raster of A + (-A) (2N x 2N, same pixel size, centre at pixel N - 0.5)."""
    f = np.fft.rfft2(a.astype(float), s=(2 * N, 2 * N))
    g = np.fft.rfft2(a[::-1, ::-1].astype(float), s=(2 * N, 2 * N))
    return np.fft.irfft2(f * g, s=(2 * N, 2 * N)) > 0.5


def boundary_radius(region, betas):
    """D(beta): the region's extent along each direction (it is star-shaped about 0)."""
    h = L / N
    radii = np.linspace(0.0, 2.2, 8800)
    d = np.zeros(len(betas))
    for k, beta in enumerate(betas):
        px = np.clip(np.round(N - 1 + radii * np.cos(beta) / h).astype(int), 0, 2 * N - 1)
        py = np.clip(np.round(N - 1 + radii * np.sin(beta) / h).astype(int), 0, 2 * N - 1)
        inside = region[py, px]
        d[k] = radii[np.nonzero(inside)[0].max()] if inside.any() else 0.0
    return d


def densest_lattice(betas, d, reach=4):
    """Smallest cell of a lattice of translates with no vector inside D: basis vectors on the
    boundary (as ShapeDistributor's Greedy lattice, here from the exact region)."""
    bx, by = d * np.cos(betas), d * np.sin(betas)
    fine = np.linspace(0.0, 2.0 * np.pi, 8192, endpoint=False)
    dfine = np.interp(fine, np.concatenate([betas, betas + 2 * np.pi]),
                      np.concatenate([d, d]), period=2 * np.pi)
    ij = [(i, j) for i in range(-reach, reach + 1) for j in range(0, reach + 1)
          if not (j == 0 and i <= 0)]
    best = np.inf
    for a in range(len(betas)):
        ux, uy = bx[a], by[a]
        vx, vy = np.concatenate([bx, -bx]), np.concatenate([by, -by])
        area = ux * vy - uy * vx
        ok = area > 1e-9
        for i, j in ij:
            wx, wy = i * ux + j * vx, i * uy + j * vy
            ang = np.mod(np.arctan2(wy, wx), 2 * np.pi)
            lim = dfine[np.minimum((ang / (2 * np.pi) * 8192).astype(int), 8191)]
            ok &= np.hypot(wx, wy) >= lim * (1 - 2e-3)
        if ok.any():
            best = min(best, area[ok].min())
    return best


rhos = [float(v) for v in sys.argv[1:]] or [0.382, 0.3, 0.25, 0.2, 0.1]
# Jammed circumcircles (coverage 0.547 of disks of radius r) take pi r^2 / 0.547 each.
circle_cell = np.pi / 0.547
betas = np.linspace(0.0, np.pi, 1440, endpoint=False)  # lattices are symmetric under -w
print("rho    star area  excluded area  Random / Circumcircle (jamming estimate)  "
      "densest lattice cell  Greedy bound (lattice / circumcircle)")
for rho in rhos:
    shape = star(rho)
    region = excluded_region(shape)
    excl, area = region.sum() * (L / N) ** 2, shape.sum() * (L / N) ** 2
    cell = densest_lattice(betas, boundary_radius(region, betas))
    print(f"{rho:5.3f}  {area:9.3f}  {excl:13.3f}  {4 * np.pi / excl:6.2f}x"
          f"{'':35s}{cell:6.3f}{'':16s}{circle_cell / cell:6.2f}x")
print(f"(circumcircles: excluded area {4 * np.pi:.3f}, {circle_cell:.2f} r^2 each when jammed; "
      f"2.2x would need an excluded area of {4 * np.pi / 2.2:.2f}, 3.3x a cell of "
      f"{circle_cell / 3.3:.2f})")
