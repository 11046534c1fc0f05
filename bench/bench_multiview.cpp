// Benchmark (not a test) of the multi-view shadow-map studies, in one run on one
// machine (VWSS paper, section 4):
//  1. Tables 1-2: scenes of about 110k, 220k, 550k and 660k triangles (the engine instanced
//     1, 2, 5 and 6 times), 24 and 128 maps: points, G-buffer, point generation, depth maps,
//     lighting, total, range, speed-up of depth maps and total over mvr, RMSE against the
//     same-sample reference; memory; the slope of depth-map time against triangles (Fig. 12).
//  2. Figure 13 top: buffered against unbuffered as the number of maps grows.
//  3. Figure 13 bottom: the same points rendered by compute (serial, partially parallel,
//     fully parallel) and by the graphics pipeline.
//  4. Figure 8: the light grows to 16x its area at a constant sample density (8 to 128 samples;
//     our limit is PENUMBRA_MAX_SAMPLES = 128, the paper goes to 64x and 512); vwss against mvr
//     per-sample as the samples move away from the light centre.
//  5. Convergence: mvr, vwss and reproject RMSE at 512^2, 1024^2, 2048^2 maps on the same frames.
//
//   penumbra_bench_multiview [SCENE] [-W 256] [-H 256] [--map 1024] [--frames 3] [--warmup 1]
//                            [--copies 1,2,5,6] [--maps 24,128] [--study 1,2,3,4,5] [--backend egl]
#include <cmath>
#include <cstdio>
#include <set>

#include "bench_common.h"
#include "studies.h"
#include "core/error.h"
#include "core/log.h"
#include "gl/context.h"
#include "compare/compare.h"
#include "pipeline/renderer.h"
#include "sampling/light_samples.h"
#include "scene/scene.h"
#include "scene/variants.h"

using namespace penumbra;
using bench::frameStatistic;

namespace {

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

struct Run {
  bench::Timing timing;
  double rmse = 0.0;
};

struct Bench {
  gl::Context& ctx;
  int width, height, frames, warmup;

  RenderSettings settings(int samples) const {
    RenderSettings s;
    s.width = width, s.height = height;
    s.sampling.count = samples;
    s.perSampleResults = false;  // timing: no readback of per-sample layers
    return s;
  }
  FrameResult reference(const Scene& scene, const RenderSettings& s) const {
    Renderer r(ctx, scene, s);
    auto t = makeTechnique("raytrace");
    return r.render(*t);
  }
  Run run(const Scene& scene, const RenderSettings& s, const std::string& name, const std::vector<std::string>& params,
          const FrameResult* ref) const {
    Renderer r(ctx, scene, s);
    auto t = makeTechnique(name, TechniqueParams(params));
    Run out;
    out.timing = bench::timeFrames(r, *t, frames, warmup);
    if (ref) out.rmse = measureErrors(out.timing.last, *ref).visibility.rmse;
    return out;
  }
};

// Least-squares slope of y against x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= double(x.size()), my /= double(y.size());
  double num = 0, den = 0;
  for (std::size_t i = 0; i < x.size(); ++i) num += (x[i] - mx) * (y[i] - my), den += (x[i] - mx) * (x[i] - mx);
  return den > 0 ? num / den : 0.0;
}

}  // namespace

namespace penumbra::bench {

int multiviewStudies(const MultiviewOptions& o, std::FILE* out) {
  setLogLevel("error");
  const std::string& scenePath = o.scene;
  const int width = o.width, height = o.height, map = o.map, frames = o.frames, warmup = o.warmup;
  const float spacing = o.spacing;
  try {
    auto ctx = gl::Context::create(o.backend);
    Scene base = loadScene(scenePath);
    Bench b{*ctx, width, height, frames, warmup};
    const std::string mapParam = "map=" + std::to_string(map);
    std::set<int> studies;
    for (int s : o.studies) studies.insert(s);
    std::fprintf(out,
                 "Multi-view shadow-map studies: %s, %dx%d image, %d^2 maps, median of %d frames after %d "
                 "warm-up, times in ms (glFinish + steady clock), renderer %s\n\n",
                 scenePath.c_str(), width, height, map, frames, warmup, ctx->renderer().c_str());

    if (studies.count(1)) {
      std::fprintf(out,
                   "1. VWSS Tables 1-2 shape: mvr (a draw per map), mvr-layered, vwss (buffered, compute, k=8), "
                   "reproject, and the single-map pcss-ultra (64-sample blocker search, 96-sample PCF, as the paper's "
                   "PCSS rows; its 'maps' column is its one map, 'points' its shadow pass); RMSE of the visibility "
                   "buffer against raytrace with the same samples\n");
      for (int n : o.maps) {
        std::fprintf(out, "\n%d maps of %d^2 (%d PCF taps per map: %d depth samples per pixel)\n", n, map, 5, 5 * n);
        std::fprintf(out, "%-9s %8s %-12s %8s %8s %8s %8s %8s %8s %8s %7s %7s %8s %9s\n", "triangles", "points",
                     "technique", "G-buffer", "points", "maps", "lighting", "total", "range", "x maps", "x total",
                     "RMSE", "map MiB", "point MiB");
        std::vector<double> tris;
        std::map<std::string, std::vector<double>> depthTimes;
        for (int copies : o.copies) {
          Scene scene = withOccludersInstanced(base, copies, spacing);
          RenderSettings s = b.settings(n);
          FrameResult ref = b.reference(scene, s);
          tris.push_back(double(scene.triangleCount()));
          double mvrMaps = 0, mvrTotal = 0;
          // The stages each technique records, by the table's columns: points (or the central
          // map they are made from), depth maps, lighting (the pipeline's shading included).
          struct Columns {
            std::string name;
            std::vector<std::string> points, maps, lighting;
          };
          const Columns columns[] = {
              {"mvr", {}, {"mvr depth maps"}, {"mvr lighting", "mvr views", "shading"}},
              {"mvr-layered", {}, {"mvr-layered depth maps"}, {"mvr-layered lighting", "mvr-layered views", "shading"}},
              {"vwss", {"vwss points"}, {"vwss depth maps"}, {"vwss lighting", "vwss views", "shading"}},
              {"reproject",
               {"reproject central map"},
               {"reproject depth maps"},
               {"reproject lighting", "reproject views", "shading"}},
              {"pcss-ultra", {}, {"pcss shadow map"}, {"pcss shadow mask", "pcss views", "shading"}}};
          for (const Columns& c : columns) {
            const std::string& name = c.name;
            Run r = b.run(scene, s, name, {mapParam}, &ref);
            const auto& t = r.timing;
            double points = t.sumOf(c.points);
            double maps = points + t.sumOf(c.maps);
            double lighting = t.sumOf(c.lighting);
            if (name == "mvr") mvrMaps = maps, mvrTotal = t.total.median;
            depthTimes[name].push_back(maps);
            std::fprintf(out, "%-9zu %8.0f %-12s %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %8.2f %7.2f %7.4f %8.0f %9.1f\n",
                         scene.triangleCount(), frameStatistic(t.last, "points"), name.c_str(), t.stage("gbuffer"),
                         points, t.sumOf(c.maps), lighting, t.total.median, t.total.max - t.total.min,
                         mvrMaps / std::max(maps, 1e-9), mvrTotal / std::max(t.total.median, 1e-9), r.rmse,
                         mib(frameStatistic(t.last, "map bytes")), mib(frameStatistic(t.last, "point buffer bytes")));
            std::fflush(out);
          }
        }
        std::fprintf(out, "slope of depth-map time (points + maps) against triangles, ms per 100k triangles:");
        for (auto& [name, v] : depthTimes) std::fprintf(out, "  %s %.3f", name.c_str(), 1e5 * slope(tris, v));
        std::fprintf(out, "\n");
      }
      std::fprintf(
          out, "(x maps, x total: mvr's time over the row's; range: max - min of the total over the timed frames)\n\n");
    }

    Scene two = withOccludersInstanced(base, 2, spacing);
    if (studies.count(2)) {
      std::fprintf(out,
                   "2. VWSS Figure 13 top: buffered (points, then compute splat k=8) against unbuffered (splat in the "
                   "point-generation fragment shader); %zu triangles; depth-map generation ms\n",
                   two.triangleCount());
      std::fprintf(out, "%6s %10s %10s %8s\n", "maps", "buffered", "unbuffered", "ratio");
      for (int n : {8, 16, 32, 64, 128}) {
        RenderSettings s = b.settings(n);
        Run bu = b.run(two, s, "vwss", {mapParam}, nullptr), un = b.run(two, s, "vwss-unbuffered", {mapParam}, nullptr);
        double tb = bu.timing.stage("vwss points") + bu.timing.stage("vwss depth maps");
        double tu = un.timing.stage("vwss-unbuffered points+maps");
        std::fprintf(out, "%6d %10.2f %10.2f %8.2f\n", n, tb, tu, tu / std::max(tb, 1e-9));
        std::fflush(out);
      }
      std::fprintf(out, "\n");
    }

    if (studies.count(3)) {
      std::fprintf(out,
                   "3. VWSS Figure 13 bottom: the same points into the maps by compute (serial k=1, partially parallel "
                   "k=8, fully parallel k=all) and by the graphics pipeline (GL_POINTS, a draw per map); ms of the "
                   "depth-map stage only\n");
      std::fprintf(out, "%6s %10s %10s %10s %10s %10s\n", "maps", "points", "serial", "partial", "full", "graphics");
      for (int n : {24, 128}) {
        RenderSettings s = b.settings(n);
        Run serial = b.run(two, s, "vwss", {mapParam, "k=1"}, nullptr);
        Run partial = b.run(two, s, "vwss", {mapParam, "k=8"}, nullptr);
        Run full = b.run(two, s, "vwss", {mapParam, "k=0"}, nullptr);
        Run graphics = b.run(two, s, "vwss-graphics", {mapParam}, nullptr);
        std::fprintf(out, "%6d %10.0f %10.2f %10.2f %10.2f %10.2f\n", n, frameStatistic(serial.timing.last, "points"),
                     serial.timing.stage("vwss depth maps"), partial.timing.stage("vwss depth maps"),
                     full.timing.stage("vwss depth maps"), graphics.timing.stage("vwss-graphics depth maps"));
        std::fflush(out);
      }
      std::fprintf(out, "\n");
    }

    if (studies.count(4)) {
      std::fprintf(out,
                   "4. VWSS Figure 8: the light grows at one sample per 1/8 of its first area; RMSE against raytrace "
                   "(same samples) and the fraction of per-sample decisions where vwss and mvr differ, by the "
                   "sample's distance from the centre in units of the first light's half-size\n");
      std::fprintf(out, "%6s %7s %9s %9s %9s | %8s %8s %8s %8s %8s\n", "area x", "samples", "mvr RMSE", "vwss RMSE",
                   "vwss-mvr", "[0,1)", "[1,2)", "[2,3)", "[3,4]", "scale");
      const Light light0 = base.lights.at(0);
      const float half0 = 0.5f * std::max(light0.size.x, light0.size.y);
      for (int f : {1, 2, 4, 8, 16}) {
        Scene scene = base;
        scene.lights.resize(1);
        scene.lights[0].size = light0.size * std::sqrt(float(f));
        RenderSettings s = b.settings(8 * f);
        s.perSampleResults = true;
        FrameResult ref = b.reference(scene, s);
        Run mvr = b.run(scene, s, "mvr", {mapParam}, &ref), vwss = b.run(scene, s, "vwss", {mapParam}, &ref);
        LightSampleSet samples = makeLightSamples(scene, scene.lights[0], s.sampling);
        double differ[4] = {0, 0, 0, 0}, count[4] = {0, 0, 0, 0};
        const auto& a = mvr.timing.last.lights[0].perSample;
        const auto& v = vwss.timing.last.lights[0].perSample;
        const int nS = samples.count;
        for (std::size_t px = 0; px < ref.gbuffer.valid.size(); ++px) {
          if (!ref.gbuffer.valid[px]) continue;
          for (int k = 0; k < nS; ++k) {
            glm::vec3 r = samples.position(0, k) - scene.lights[0].position;
            float dist = std::max(std::abs(glm::dot(r, scene.lights[0].tangent)),
                                  std::abs(glm::dot(r, scene.lights[0].bitangent()))) /
                         half0;
            int bin = std::min(3, int(dist));
            count[bin] += 1;
            differ[bin] +=
                std::abs(a[px * std::size_t(nS) + std::size_t(k)] - v[px * std::size_t(nS) + std::size_t(k)]) > 0.5f;
          }
        }
        double vsMvr = 0, n = 0;
        for (std::size_t i = 0; i < mvr.timing.last.lights[0].visibility.data.size(); ++i) {
          double d = mvr.timing.last.lights[0].visibility.data[i] - vwss.timing.last.lights[0].visibility.data[i];
          vsMvr += d * d, n += 1;
        }
        std::fprintf(out, "%6d %7d %9.4f %9.4f %9.4f |", f, nS, mvr.rmse, vwss.rmse,
                     std::sqrt(vsMvr / std::max(n, 1.0)));
        for (int i = 0; i < 4; ++i) {
          if (count[i] > 0)
            std::fprintf(out, " %8.4f", differ[i] / count[i]);
          else
            std::fprintf(out, " %8s", "-");
        }
        std::fprintf(out, " %8.2f\n", frameStatistic(vwss.timing.last, "source resolution") / double(map));
        std::fflush(out);
      }
      std::fprintf(
          out, "(vwss-mvr: RMSE between the two visibility buffers over all pixels; scale: vwss's eq. 3 factor)\n\n");
    }

    if (studies.count(5)) {
      std::fprintf(
          out,
          "5. Convergence with map resolution, 24 samples, %zu triangles: RMSE against raytrace (same samples), "
          "depth-map ms (points + maps), memory MiB (maps + point buffer / central map)\n",
          base.triangleCount());
      std::fprintf(out, "%6s | %9s %8s %8s | %9s %8s %8s | %9s %8s %8s\n", "map", "mvr RMSE", "ms", "MiB", "vwss RMSE",
                   "ms", "MiB", "repr RMSE", "ms", "MiB");
      RenderSettings s = b.settings(24);
      FrameResult ref = b.reference(base, s);
      for (int m : {512, 1024, 2048}) {
        std::fprintf(out, "%6d |", m);
        // Each technique's depth-map stages: its points or central map, and the maps.
        const std::pair<std::string, std::vector<std::string>> depthStages[] = {
            {"mvr", {"mvr depth maps"}},
            {"vwss", {"vwss points", "vwss depth maps"}},
            {"reproject", {"reproject central map", "reproject depth maps"}}};
        for (const auto& [name, stages] : depthStages) {
          Run r = b.run(base, s, name, {"map=" + std::to_string(m)}, &ref);
          const auto& t = r.timing;
          double ms = t.sumOf(stages);
          std::fprintf(out, " %9.4f %8.2f %8.0f |", r.rmse, ms, mib(double(t.last.memoryBytes)));
          std::fflush(out);
        }
        std::fprintf(out, "\n");
      }
    }
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench_multiview: %s\n", e.what());
    return int(e.exitCode());
  }
}

}  // namespace penumbra::bench
