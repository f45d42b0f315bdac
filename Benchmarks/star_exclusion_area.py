#!/usr/bin/env python3
"""What geometry allows Random (dart throwing) for 5-point stars turned alike.

Random sequential addition jams at a number density of about c / (excluded area), with
c = 2.19 for disks and 2.25 for aligned squares (jamming coverages 0.547 and 0.562). Two copies
of a shape A turned alike overlap when their centres are closer than the boundary of the
Minkowski sum A + (-A); for circumcircles of radius r it is the disk of radius 2r (area 4 pi
r^2). So Random / Circumcircle is about 4 pi r^2 / area(A + (-A)).

This computes area(A + (-A)) exactly up to the raster (1024^2, FFT convolution of A's indicator
with its point reflection) for regular 5-point stars of circumradius 1 and inner radius rho
(rho = 0.382: the regular pentagram {5/2}), without the safe distance tables' binning (the
tables are conservative: DistributionBenchmark prints their larger excluded area).

    python3 Benchmarks/star_exclusion_area.py [rho ...]      (numpy)
"""
import sys

import numpy as np

N, L = 1024, 4.4  # raster over [-2.2, 2.2]^2: the sum of two unit shapes fits in radius 2
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


def excluded_area(a):
    f = np.fft.rfft2(a.astype(float), s=(2 * N, 2 * N))
    g = np.fft.rfft2(a[::-1, ::-1].astype(float), s=(2 * N, 2 * N))
    overlap = np.fft.irfft2(f * g, s=(2 * N, 2 * N))
    return (overlap > 0.5).sum() * (L / N) ** 2, a.sum() * (L / N) ** 2


rhos = [float(v) for v in sys.argv[1:]] or [0.382, 0.3, 0.25, 0.2, 0.1]
print("rho    star area  excluded area  Random / Circumcircle (jamming estimate)")
for rho in rhos:
    excl, area = excluded_area(star(rho))
    print(f"{rho:5.3f}  {area:9.3f}  {excl:13.3f}  {4 * np.pi / excl:6.2f}x")
print(f"(circumcircles: excluded area {4 * np.pi:.3f}; 2.2x would need {4 * np.pi / 2.2:.2f})")
