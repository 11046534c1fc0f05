#include "techniques/common/shadow_volume/volume_cover.h"

#include <array>
#include <cmath>
#include <limits>

#include <algorithm>

namespace penumbra {
namespace {

constexpr double kGuard = 2.0;
constexpr int kPlanes = 5;
constexpr int kMaxPolygon = 4 + kPlanes;

// A point of the face: clip coordinates and the world homogeneous coordinate h (1 for a finite
// point, 0 at infinity), both linear along the face's edges.
struct Point {
  glm::dvec4 clip;
  double h;
};

// Plane 0 keeps depth >= clipNear: w - clipNear h >= 0, linear in (clip, h), so it means depth
// clipNear for finite points, w >= 0 at infinity and the right depth in between.
double planeValue(int k, const Point& p, double clipNear) {
  const glm::dvec4& c = p.clip;
  switch (k) {
    case 0:
      return c.w - clipNear * p.h;
    case 1:
      return kGuard * c.w - c.x;
    case 2:
      return kGuard * c.w + c.x;
    case 3:
      return kGuard * c.w - c.y;
    default:
      return kGuard * c.w + c.y;
  }
}

// The corner of the square [-1, 1]^2 furthest along the normal n, quadrants counted counter-
// clockwise from +x.
int quadrant(const glm::dvec2& n) {
  if (n.x > 0.0 && n.y >= 0.0) return 0;
  if (n.x <= 0.0 && n.y > 0.0) return 1;
  if (n.x < 0.0 && n.y <= 0.0) return 2;
  return 3;
}
glm::dvec2 squareCorner(int k) { return {k == 0 || k == 3 ? 1.0 : -1.0, k < 2 ? 1.0 : -1.0}; }

}  // namespace

double coverMargin(int subpixelBits) { return 3.0 * std::ldexp(1.0, -std::max(subpixelBits, 4)); }

std::size_t appendCover(const CoverView& view, const glm::dvec4* corners, int n, std::vector<glm::vec2>& out) {
  std::array<Point, kMaxPolygon> poly{}, next{};
  // The magnitude the fragment shader's decisions about the face round at: its finite points,
  // and the light for a face with points at infinity (its decisions take the light's position).
  double reach = 0.0;
  for (int i = 0; i < n; ++i)
    reach = std::max(reach, corners[i].w != 0.0 ? glm::length(glm::dvec3(corners[i])) : glm::length(view.light));
  for (int i = 0; i < n; ++i) {
    const glm::dvec4& x = corners[i];
    const glm::dvec4 world = x.w != 0.0 ? x : glm::dvec4(glm::dvec3(x) - view.light, 0.0);
    poly[std::size_t(i)] = {view.clipFromWorld * world, x.w != 0.0 ? 1.0 : 0.0};
  }
  // Sutherland-Hodgman, one plane at a time.
  for (int k = 0; k < kPlanes && n > 0; ++k) {
    int m = 0;
    for (int i = 0; i < n; ++i) {
      const Point& p = poly[std::size_t(i)];
      const Point& q = poly[std::size_t((i + 1) % n)];
      const double fp = planeValue(k, p, view.clipNear), fq = planeValue(k, q, view.clipNear);
      if (fp >= 0.0) next[std::size_t(m++)] = p;
      if ((fp >= 0.0) != (fq >= 0.0)) {
        const double t = fp / (fp - fq);
        next[std::size_t(m++)] = {p.clip + (q.clip - p.clip) * t, p.h + (q.h - p.h) * t};
      }
    }
    n = m;
    poly = next;
  }
  if (n == 0) return 0;
  // On screen, counter-clockwise, without repeated points (a point at w = 0, where the
  // guard band leaves only x = y = 0, has no place on screen: a polygon through it is
  // degenerate, its corner dropped).
  std::array<glm::dvec2, kMaxPolygon> q{}, r{};
  double area = 0.0, nearest = std::numeric_limits<double>::infinity();
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    const glm::dvec4& p = poly[std::size_t(i)].clip;
    if (poly[std::size_t(i)].h > 0.0) nearest = std::min(nearest, p.w / poly[std::size_t(i)].h);
    if (p.w > 0.0) q[std::size_t(kept++)] = glm::dvec2(p.x / p.w * 0.5 + 0.5, -p.y / p.w * 0.5 + 0.5) * view.viewport;
  }
  n = kept;
  if (n == 0) return 0;
  for (int i = 0; i < n; ++i) {
    const glm::dvec2 &a = q[std::size_t(i)], &b = q[std::size_t((i + 1) % n)];
    area += a.x * b.y - b.x * a.y;
  }
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const glm::dvec2 x = q[std::size_t(area >= 0.0 ? i : n - 1 - i)];
    if (m == 0 || x != r[std::size_t(m - 1)]) r[std::size_t(m++)] = x;
  }
  while (m > 1 && r[std::size_t(m - 1)] == r[0]) --m;
  // Grown by the margin in the max norm: each edge's line pushed out by the margin's reach along
  // its normal (the square's support, margin (|n.x| + |n.y|)), consecutive lines met at their
  // intersection (the polygon keeps its vertex count, so its fan its triangle count), except at
  // a sharp or nearly straight corner, where the intersection runs off (or is ill-conditioned)
  // and the corner is cut by the two square corners furthest along the two normals (which lie on
  // the two pushed lines). A point alone becomes the square, a segment the segment's hexagon.
  const double rounding = 16.0 * std::ldexp(1.0, -24) * view.focalPixels * (2.0 + reach / nearest);
  const double margin = std::max(view.margin, rounding);
  const std::size_t first = out.size();
  if (m == 1)
    for (int k = 0; k < 4; ++k) out.emplace_back(r[0] + margin * squareCorner(k));
  for (int i = 0; i < m && m > 1; ++i) {
    const glm::dvec2& x = r[std::size_t(i)];
    const glm::dvec2 in = x - r[std::size_t((i + m - 1) % m)], outEdge = r[std::size_t((i + 1) % m)] - x;
    const glm::dvec2 nIn = glm::normalize(glm::dvec2(in.y, -in.x)),
                     nOut = glm::normalize(glm::dvec2(outEdge.y, -outEdge.x));
    const double det = nIn.x * nOut.y - nIn.y * nOut.x;
    if (m > 2 && det > 1e-6) {
      const double hIn = margin * (std::abs(nIn.x) + std::abs(nIn.y)),
                   hOut = margin * (std::abs(nOut.x) + std::abs(nOut.y));
      // Solve nIn . d = hIn, nOut . d = hOut for the offset d; a spike longer than a pixel is cut.
      const glm::dvec2 d = glm::dvec2(hIn * nOut.y - hOut * nIn.y, hOut * nIn.x - hIn * nOut.x) / det;
      if (glm::dot(d, d) <= 1.0) {
        out.emplace_back(x + d);
        continue;
      }
    }
    int k = quadrant(nIn);
    const int last = quadrant(nOut);
    out.emplace_back(x + margin * squareCorner(k));
    // Counter-clockwise through the square's corners; a turn the wrong way (rounding at a
    // straight corner) adds the outgoing corner only.
    const bool turn = det >= 0.0 || m == 2;
    for (int j = 0; j < 3 && k != last; ++j) {
      k = turn ? (k + 1) % 4 : last;
      out.emplace_back(x + margin * squareCorner(k));
    }
  }
  // A cover that holds no pixel centre (most caps of a fine mesh) is not drawn at all.
  glm::dvec2 lo(out[first]), hi(out[first]);
  for (std::size_t i = first + 1; i < out.size(); ++i) {
    lo = glm::min(lo, glm::dvec2(out[i]));
    hi = glm::max(hi, glm::dvec2(out[i]));
  }
  lo = glm::max(lo, glm::dvec2(0.0));
  hi = glm::min(hi, view.viewport);
  if (std::floor(hi.x - 0.5) < std::ceil(lo.x - 0.5) || std::floor(hi.y - 0.5) < std::ceil(lo.y - 0.5)) {
    out.resize(first);
    return 0;
  }
  return out.size() - first;
}

}  // namespace penumbra
