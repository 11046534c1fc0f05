#include "shading/brdf_sampling.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace penumbra::shading {

constexpr double kPi = std::numbers::pi;

Frame Frame::around(const glm::dvec3& z) {
  const double sign = std::copysign(1.0, z.z);
  const double a = -1.0 / (sign + z.z), b = z.x * z.y * a;
  return {{1.0 + sign * z.x * z.x * a, sign * b, -sign * z.x}, {b, sign + z.y * z.y * a, -z.y}, z};
}

glm::dvec3 sampleGgxReflection(const glm::dvec3& v, double alpha, double u1, double u2) {
  const double phi = 2.0 * kPi * u2;
  const double tan2 = alpha * alpha * u1 / (1.0 - u1);
  const double cosT = 1.0 / std::sqrt(1.0 + tan2), sinT = std::sqrt(std::max(1.0 - cosT * cosT, 0.0));
  const glm::dvec3 h(sinT * std::cos(phi), sinT * std::sin(phi), cosT);
  return 2.0 * glm::dot(v, h) * h - v;
}

double ggxReflectionPdf(const glm::dvec3& v, const glm::dvec3& l, double alpha) {
  glm::dvec3 h = v + l;
  const double len = glm::length(h);
  if (!(len > 0.0)) return 0.0;
  h /= len;
  if (!(h.z > 0.0)) return 0.0;
  const double a2 = alpha * alpha;
  const double d = h.z * h.z * (a2 - 1.0) + 1.0;
  const double D = a2 / (kPi * d * d);
  const double vh = std::abs(glm::dot(v, h));
  return vh > 0.0 ? D * h.z / (4.0 * vh) : 0.0;
}

glm::dvec3 sampleCosine(double u1, double u2) {
  const double cosT = std::sqrt(u1), sinT = std::sqrt(1.0 - u1), phi = 2.0 * kPi * u2;
  return {sinT * std::cos(phi), sinT * std::sin(phi), cosT};
}

double cosinePdf(const glm::dvec3& l) { return std::max(l.z, 0.0) / kPi; }

}  // namespace penumbra::shading
