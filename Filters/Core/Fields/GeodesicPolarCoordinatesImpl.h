// What the geodesic polar coordinates' files share (GeodesicPolarCoordinates.cpp,
// GeodesicCurveCoordinates.cpp, IsoCurveAngles.cpp). Not part of the core's interface.
#pragma once

#include "GeodesicPolarCoordinates.h"

#include <cmath>
#include <limits>
#include <string>

namespace gs
{

namespace
{
constexpr double TwoPi = 6.28318530717958647692;
const double NaN = std::numeric_limits<double>::quiet_NaN();

inline double Wrap(double a)
{
  a = std::fmod(a, TwoPi);
  return a < 0.0 ? a + TwoPi : a;
}

inline Status RadiusError(double radius)
{
  return Status::Error("Radius must be > 0 (it is " + std::to_string(radius) + ")");
}
} // namespace

} // namespace gs
