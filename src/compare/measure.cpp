#include "compare/measure.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace penumbra {
namespace {

// Every light's visibility buffer stacked vertically (all the same size).
Image stackedVisibility(const FrameResult& f) {
  if (f.lights.empty()) return {};
  Image out(f.lights.front().visibility.width, 0, f.lights.front().visibility.channels);
  for (auto& l : f.lights) {
    out.height += l.visibility.height;
    out.data.insert(out.data.end(), l.visibility.data.begin(), l.visibility.data.end());
  }
  return out;
}

template <class T>
std::vector<T> repeat(const std::vector<T>& v, std::size_t times) {
  std::vector<T> out;
  for (std::size_t i = 0; i < times; ++i) out.insert(out.end(), v.begin(), v.end());
  return out;
}

// See TemporalErrors::flicker; `b` null: a's own change.
double temporalRms(const std::vector<FrameVisibility>& a, const std::vector<FrameVisibility>* b) {
  double sum = 0.0;
  std::int64_t count = 0;
  for (std::size_t f = 1; f < a.size(); ++f) {
    const int channels = a[f].visibility.channels;
    for (std::size_t i = 0; i < a[f].visibility.data.size(); ++i) {
      const std::size_t px = i / std::size_t(channels);
      if (!a[f].valid[px] || !a[f - 1].valid[px]) continue;
      double d = double(a[f].visibility.data[i]) - a[f - 1].visibility.data[i];
      if (b) d -= double((*b)[f].visibility.data[i]) - (*b)[f - 1].visibility.data[i];
      sum += d * d;
      ++count;
    }
  }
  return count ? std::sqrt(sum / double(count)) : 0.0;
}

}  // namespace

std::optional<ReferenceNoise> referenceNoise(const FrameResult& ref) {
  const auto& valid = ref.gbuffer.valid;
  // sqrt of the mean of `variance` over surface pixels and channels; false if it has none.
  auto rms = [&](const Image& variance, double& sum, std::int64_t& count) {
    if (variance.pixelCount() != valid.size() || variance.channels != 3) return false;
    for (std::size_t i = 0; i < valid.size(); ++i)
      if (valid[i])
        for (int c = 0; c < 3; ++c) sum += double(variance.data[i * 3 + std::size_t(c)]), ++count;
    return true;
  };
  ReferenceNoise n;
  double sum = 0.0;
  std::int64_t count = 0;
  if (!rms(ref.colorVariance, sum, count)) return std::nullopt;
  n.shaded = count ? std::sqrt(sum / double(count)) : 0.0;
  sum = 0.0, count = 0;
  for (const LightResult& l : ref.lights)
    if (!rms(l.visibilityVariance, sum, count)) return std::nullopt;
  n.visibility = count ? std::sqrt(sum / double(count)) : 0.0;
  return n;
}

TechniqueErrors measureErrors(const FrameResult& frame, const FrameResult& ref) {
  PENUMBRA_CHECK(frame.lights.size() == ref.lights.size() && !ref.lights.empty(), "frames of different scenes");
  TechniqueErrors e;
  const auto& valid = ref.gbuffer.valid;
  std::size_t n = valid.size(), L = ref.lights.size();

  std::vector<std::uint8_t> band;
  std::vector<std::uint8_t> anyBand(n, 0);
  for (std::size_t l = 0; l < L; ++l) {
    auto m = edgeBandMask(ref.lights[l].visibility, 1);
    band.insert(band.end(), m.begin(), m.end());
    for (std::size_t i = 0; i < n; ++i) anyBand[i] |= m[i];
  }
  Image va = stackedVisibility(frame), vb = stackedVisibility(ref);
  auto validL = repeat(valid, L);
  e.visibility = compareImages(va, vb, {}, validL);
  std::vector<std::uint8_t> unshadowed(n * L, 0);
  for (std::size_t l = 0; l < L; ++l) {
    const auto& m = frame.lights[l].unshadowed;
    if (m.size() != n) continue;
    for (std::size_t i = 0; i < n; ++i)
      if (m[i] && valid[i]) unshadowed[l * n + i] = 1, ++e.unshadowedPixels;
  }
  e.visibilityExceptUnshadowed = e.unshadowedPixels ? compareImages(va, vb, unshadowed, validL) : e.visibility;
  e.visibilityOutsideBand = compareImages(va, vb, band, validL);
  e.shaded = compareImages(frame.color, ref.color, {}, valid);
  e.shadedOutsideBand = compareImages(frame.color, ref.color, anyBand, valid);

  std::int64_t agree = 0, pairs = 0;
  std::array<std::int64_t, TechniqueErrors::kRings> ringAgree{}, ringPairs{};
  for (std::size_t l = 0; l < L; ++l) {
    const auto& fa = frame.lights[l];
    const auto& fb = ref.lights[l];
    const bool rings = fa.sampleRadius.size() == std::size_t(std::max(0, fb.samples));
    float decision = 0.5f / float(std::max(1, fb.samples));
    for (std::size_t i = 0; i < n; ++i) {
      if (!valid[i] || band[l * n + i]) continue;
      float d = 0.0f;
      for (int c = 0; c < 3; ++c)
        d = std::max(d, std::abs(fa.visibility.data[i * 3 + c] - fb.visibility.data[i * 3 + c]));
      if (d > decision) ++e.misclassifiedPixels;
      if (fa.perSample.empty() || fb.perSample.empty() || fa.samples != fb.samples) continue;
      for (int k = 0; k < fb.samples; ++k) {
        std::size_t idx = i * std::size_t(fb.samples) + std::size_t(k);
        const bool same = std::abs(fa.perSample[idx] - fb.perSample[idx]) < 1e-3f;
        agree += same;
        ++pairs;
        if (rings) {
          const int ring = std::clamp(int(fa.sampleRadius[std::size_t(k)] * float(TechniqueErrors::kRings)), 0,
                                      TechniqueErrors::kRings - 1);
          ringAgree[std::size_t(ring)] += same, ++ringPairs[std::size_t(ring)];
        }
      }
    }
  }
  if (pairs > 0) e.sampleAgreement = double(agree) / double(pairs);
  for (std::size_t r = 0; r < ringPairs.size(); ++r)
    if (ringPairs[r] > 0) e.sampleAgreementByRing[r] = double(ringAgree[r]) / double(ringPairs[r]);
  e.samplePairs = pairs;
  e.sampleMismatches = pairs - agree;
  return e;
}

FrameVisibility keepVisibility(const FrameResult& f) {
  return {stackedVisibility(f), repeat(f.gbuffer.valid, f.lights.size())};
}

TemporalErrors measureTemporal(const std::vector<FrameVisibility>& frames, const std::vector<FrameVisibility>& ref) {
  PENUMBRA_CHECK(frames.size() == ref.size() && !frames.empty(), "measureTemporal: frames of different runs");
  TemporalErrors t;
  t.flicker = temporalRms(frames, &ref);
  t.referenceMotion = temporalRms(ref, nullptr);
  double sum = 0.0;
  for (std::size_t k = 0; k < frames.size(); ++k)
    sum += compareImages(frames[k].visibility, ref[k].visibility, {}, ref[k].valid).rmse;
  t.meanFrameRmse = sum / double(frames.size());
  return t;
}

}  // namespace penumbra
