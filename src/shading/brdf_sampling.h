// Sampling the BRDF's lobes (shading/shaders/shading.h penumbraBrdf) in a local frame whose z axis is the
// shading normal: what the LTC fit (ltc.h) and the converged reference's BRDF strategy
// (light_integral.h) draw directions from. Directions are unit; densities are per solid angle.
#pragma once

#include <glm/glm.hpp>

namespace penumbra::shading {

// An orthonormal frame (x, y, z) around the unit vector z (Duff et al. 2017, "Building an
// orthonormal basis, revisited", listing 3: no branch on a threshold, continuous but at -z).
struct Frame {
  glm::dvec3 x, y, z;
  static Frame around(const glm::dvec3& z);
  glm::dvec3 toLocal(const glm::dvec3& w) const { return {glm::dot(w, x), glm::dot(w, y), glm::dot(w, z)}; }
  glm::dvec3 toWorld(const glm::dvec3& w) const { return w.x * x + w.y * y + w.z * z; }
};

// GGX normal sampling (Walter, Marschner, Li and Torrance 2007, eq. 35-36: h with density
// D(h) (n.h)), the view v reflected about h; l may fall below the horizon (the lobe is 0 there).
glm::dvec3 sampleGgxReflection(const glm::dvec3& v, double alpha, double u1, double u2);
// Its density at l: D(h) (n.h) / (4 |v.h|) with h = normalize(v + l) (eq. 14's Jacobian); 0 where
// h is below the horizon.
double ggxReflectionPdf(const glm::dvec3& v, const glm::dvec3& l, double alpha);

// The clamped cosine (n.l) / pi, sampled by its inverse CDF in polar coordinates.
glm::dvec3 sampleCosine(double u1, double u2);
double cosinePdf(const glm::dvec3& l);

}  // namespace penumbra::shading
