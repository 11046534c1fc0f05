// Closed forms of hard case 23 (shared/docs/hard-cases.md): the fraction of a light hidden from a
// floor point (x, 0, z) by a parallel occluder centred above the origin under a parallel light
// centred above it. Used by the reference's analytic test and the scale tests of hard case 25.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

namespace penumbra::test {

// Fraction of the square light [-0.5,0.5]^2 (at lightHeight) hidden from floor point (x, 0, z)
// by the square occluder [-0.5,0.5]^2 at occluderHeight: the occluder projects from p onto the
// light plane as a square of side 0.5 * 2 * s, s = lightHeight / occluderHeight, centred at
// p + (0 - p) * s; the hidden fraction is the overlap area.
inline double squareHiddenFraction(double x, double z, double occluderHeight, double lightHeight) {
  const double s = lightHeight / occluderHeight;
  const double cx = x * (1.0 - s), cz = z * (1.0 - s), half = 0.5 * s;
  auto overlap = [](double c, double h) { return std::max(0.0, std::min(0.5, c + h) - std::max(-0.5, c - h)); };
  return overlap(cx, half) * overlap(cz, half);
}

// Same for the disc of radius 0.5 under the disc light of radius 0.5: the lens area of two
// circles (radii 0.5 and 0.5 s, centre distance d) over the light's area.
inline double discHiddenFraction(double x, double z, double occluderHeight, double lightHeight) {
  const double s = lightHeight / occluderHeight;
  const double r1 = 0.5, r2 = 0.5 * s, d = std::hypot(x, z) * (s - 1.0);
  const double pi = std::numbers::pi;
  double area;
  if (d >= r1 + r2)
    area = 0.0;
  else if (d <= std::abs(r2 - r1))
    area = pi * std::min(r1, r2) * std::min(r1, r2);
  else {
    const double a1 = std::acos((d * d + r1 * r1 - r2 * r2) / (2 * d * r1));
    const double a2 = std::acos((d * d + r2 * r2 - r1 * r1) / (2 * d * r2));
    area = r1 * r1 * (a1 - std::sin(2 * a1) / 2) + r2 * r2 * (a2 - std::sin(2 * a2) / 2);
  }
  return area / (pi * r1 * r1);
}

// Form factor from a receiver at the origin facing +y to the rectangle [x0, x1] x [z0, z1] at
// height h above it, parallel to it (Howell's catalogue of configuration factors, B-1: a
// differential area and a parallel rectangle with one corner above it, here summed with signs
// over the four corners). The receiver's irradiance from a Lambertian emitter of radiance L is
// pi L F, its outgoing radiance albedo L F. An oracle independent of shading/shaders/shading.h's polygon formula.
inline double parallelRectFormFactor(double x0, double x1, double z0, double z1, double h) {
  const auto corner = [h](double a, double b) {
    const double A = std::abs(a) / h, B = std::abs(b) / h;
    const double sa = std::sqrt(1.0 + A * A), sb = std::sqrt(1.0 + B * B);
    const double f = (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb)) / (2.0 * std::numbers::pi);
    return (a < 0 ? -1.0 : 1.0) * (b < 0 ? -1.0 : 1.0) * f;
  };
  return corner(x1, z1) - corner(x0, z1) - corner(x1, z0) + corner(x0, z0);
}

// Configuration factor from a differential area to a parallel disk of radius R at height h whose
// centre is offset by rho from the area's normal (Howell's catalogue of configuration factors):
// F = 1/2 (1 - (h^2 + rho^2 - R^2) / sqrt((h^2 + rho^2 + R^2)^2 - 4 R^2 rho^2)).
inline double parallelDiskFormFactor(double rho, double h, double R) {
  const double a = h * h + rho * rho;
  return 0.5 * (1.0 - (a - R * R) / std::sqrt((a + R * R) * (a + R * R) - 4.0 * R * R * rho * rho));
}

}  // namespace penumbra::test
