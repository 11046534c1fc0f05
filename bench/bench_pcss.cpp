// Benchmark (not a test) of the single-map studies (pcss, vssm) in one run on one machine:
//  1. Sterna's Table 1 (2018): the shadow-mask passes of regular soft shadows (fixed kernel),
//     regular contact-hardening (per-pixel blocker search), the penumbra mask + shadow mask, the
//     min filter, and checkerboarding of both, with their RMSE against the same-sample reference.
//     Sterna: the penumbra mask + shadow mask about 2.3x faster than regular contact-hardening
//     (0.74 against 1.72 ms on a GTX 660, 1080p, 2048^2 map, 16 shadow samples, 32 mask samples).
//  2. VSSM against PCSS as the light grows (VSSM paper: at least an order of magnitude faster
//     than PCSS for large penumbrae, where PCSS samples the whole kernel).
//  3. VSSM's stage breakdown (its Tables 1-2: shadow map, HSM, SAT, shadow pass) at 512^2,
//     1024^2, 2048^2 maps.
//  4. Errors against the same-sample and the converged reference on the shipped scenes and the
//     hard cases of the single-view methods (15-18, 23), mvr next to them.
//
//   penumbra_bench_pcss [SCENE] [-W 512] [-H 512] [--map 2048] [--samples 16] [--frames 5]
//                       [--warmup 1] [--backend egl]
#include <cstdio>

#include <fmt/format.h>

#include "bench_common.h"
#include "studies.h"
#include "core/error.h"
#include "core/log.h"
#include "gl/context.h"
#include "compare/compare.h"
#include "pipeline/renderer.h"
#include "scene/scene.h"
#include "techniques/registry.h"

using namespace penumbra;

namespace penumbra::bench {

int singleMapStudies(const SingleMapOptions& o, std::FILE* out) {
  setLogLevel("error");
  const std::string& scenePath = o.scene;
  const int width = o.width, height = o.height, map = o.map, samples = o.samples, frames = o.frames, warmup = o.warmup,
            errorSize = o.errorSize;
  try {
    auto ctx = gl::Context::create(o.backend);
    Scene scene = loadScene(scenePath);
    RenderSettings s;
    s.width = width, s.height = height;
    s.sampling.count = samples;
    s.perSampleResults = false;
    Renderer renderer(*ctx, scene, s);
    auto rayTech = makeTechnique("raytrace");
    FrameResult ref = renderer.render(*rayTech);
    std::fprintf(out,
                 "pcss studies: %s (%zu triangles), %dx%d image, %d^2 map, median of %d frames after %d "
                 "warm-up, ms (glFinish + steady clock), renderer %s\n\n",
                 scenePath.c_str(), scene.triangleCount(), width, height, map, frames, warmup, ctx->renderer().c_str());
    std::fprintf(out, "1. Sterna Table 1 shape: shadow-mask passes, 16 PCF samples, 32 blocker-search samples\n");
    std::fprintf(out, "%-40s %9s %9s %9s %9s %9s %8s %8s\n", "configuration", "min filt", "pen mask", "shadow",
                 "upsample", "passes", "x CHSS", "RMSE");
    // Rows of the table of techniques (src/techniques/pcss/rows.cpp) and their parameters, with
    // the passes each runs besides the shadow mask (a column it does not run reads 0).
    struct Row {
      const char* name;
      const char* technique;
      bool checker;
      std::vector<std::string> passes;
    };
    const std::string minFilter = "pcss min filter", mask = "pcss penumbra mask",
                      upsample = "pcss checkerboard upsample";
    const Row rows[] = {{"regular shadow mask (fixed kernel)", "pcss-fixed", false, {}},
                        {"regular CHSS", "pcss", false, {}},
                        {"penumbra mask + shadow mask", "pcss-mask", false, {mask}},
                        {"min filter + shadow mask", "pcss-minfilter", false, {minFilter}},
                        {"regular CHSS + checkerboard", "pcss", true, {upsample}},
                        {"penumbra mask + shadow mask + checker", "pcss-mask", true, {mask, upsample}}};
    double chss = 0.0;
    for (const Row& row : rows) {
      TechniqueParams given({"map=" + std::to_string(map), std::string("checkerboard=") + (row.checker ? "1" : "0")});
      auto tech = makeTechnique(row.technique, given);
      given.checkConsumed();
      bench::Timing t = bench::timeFrames(renderer, *tech, frames, warmup);
      const auto pass = [&](const std::string& stage) {
        return std::find(row.passes.begin(), row.passes.end(), stage) != row.passes.end() ? t.stage(stage) : 0.0;
      };
      double passes = t.sumOf(row.passes) + t.stage("pcss shadow mask");
      if (std::string(row.technique) == "pcss" && !row.checker) chss = passes;
      double rmse = measureErrors(t.last, ref).visibility.rmse;
      std::fprintf(out, "%-40s %9.2f %9.2f %9.2f %9.2f %9.2f %8s %8.4f\n", row.name, pass(minFilter), pass(mask),
                   t.stage("pcss shadow mask"), pass(upsample), passes,
                   chss > 0.0 ? fmt::format("{:.2f}", chss / passes).c_str() : "-", rmse);
      std::fflush(out);
    }
    std::fprintf(
        out,
        "(x CHSS: regular CHSS's passes over the row's; the shadow map itself, %d^2, is left out as in Sterna's "
        "table)\n\n",
        map);

    std::fprintf(out,
                 "2. VSSM (and msm-soft, evsm) against PCSS as the light grows (light side x1..x8, 1024^2 map): "
                 "shadow-stage ms (map excluded) and RMSE; 'pcss 256' samples 256 + 256 taps; pcss-dense every texel "
                 "of both kernels (up to 32 x 32)\n");
    std::fprintf(out, "%7s | %17s | %17s | %17s | %17s | %17s | %17s | %17s | %17s\n", "light x", "pcss 32/16",
                 "pcss-ultra 64/96", "pcss 256/256", "pcss-dense", "vssm", "vssm-uniform", "msm-soft", "evsm");
    for (float k : {1.0f, 2.0f, 4.0f, 8.0f}) {
      Scene grown = scene;
      for (auto& l : grown.lights) l.size *= k;
      Renderer r(*ctx, grown, s);
      auto rt = makeTechnique("raytrace");
      FrameResult gref = r.render(*rt);
      std::fprintf(out, "%7.0f |", k);
      // The shadow stages each records (its map excluded).
      struct Col {
        const char* name;
        std::vector<std::string> params;
        std::vector<std::string> stages;
      };
      const Col cols[] = {{"pcss", {}, {"pcss shadow mask"}},
                          {"pcss-ultra", {}, {"pcss shadow mask"}},
                          {"pcss", {"blocker-samples=256", "pcf-samples=256"}, {"pcss shadow mask"}},
                          {"pcss-dense", {}, {"pcss shadow mask"}},
                          {"vssm", {}, {"vssm hsm", "vssm sat", "vssm shadow pass"}},
                          {"vssm-uniform", {}, {"vssm-uniform hsm", "vssm-uniform sat", "vssm-uniform shadow pass"}},
                          {"msm-soft", {}, {"msm-soft sat", "msm-soft shadow pass"}},
                          {"evsm", {}, {"evsm sat", "evsm shadow pass"}}};
      for (const Col& c : cols) {
        std::vector<std::string> p = c.params;
        p.push_back("map=1024");
        auto t = makeTechnique(c.name, TechniqueParams(p));
        bench::Timing tm = bench::timeFrames(r, *t, frames, warmup);
        double ms = tm.sumOf(c.stages);
        std::fprintf(out, " %8.2f %8.4f |", ms, measureErrors(tm.last, gref).visibility.rmse);
        std::fflush(out);
      }
      std::fprintf(out, "\n");
    }
    std::fprintf(out, "\n3. VSSM stage breakdown (VSSM Tables 1-2 shape), light x1, ms\n");
    std::fprintf(out, "%6s %10s %8s %8s %12s %8s %10s\n", "map", "shadow map", "HSM", "SAT", "shadow pass", "total",
                 "MiB");
    for (int m : {512, 1024, 2048}) {
      auto t = makeTechnique("vssm", TechniqueParams({"map=" + std::to_string(m)}));
      bench::Timing tm = bench::timeFrames(renderer, *t, frames, warmup);
      double total =
          tm.stage("vssm shadow map") + tm.stage("vssm hsm") + tm.stage("vssm sat") + tm.stage("vssm shadow pass");
      std::fprintf(out, "%6d %10.2f %8.2f %8.2f %12.2f %8.2f %10.1f\n", m, tm.stage("vssm shadow map"),
                   tm.stage("vssm hsm"), tm.stage("vssm sat"), tm.stage("vssm shadow pass"), total,
                   double(tm.last.memoryBytes) / (1024.0 * 1024.0));
      std::fflush(out);
    }

    std::fprintf(out,
                 "\n4. Visibility RMSE against raytrace with the same %d samples / against raytrace-converged (1024 a "
                 "pixel), %dx%d, 1024^2 maps\n",
                 samples, errorSize, errorSize);
    std::fprintf(out, "%-24s | %15s | %15s | %15s | %15s | %15s | %15s | %15s\n", "scene", "mvr", "pcss", "pcss-ultra",
                 "vssm", "msm", "msm-soft", "evsm");
    for (const char* path :
         {"scenes/hard/23-analytic-square.json", "scenes/hard/15-two-plates.json", "scenes/hard/15-thin-blade.json",
          "scenes/hard/15-sphere-grid.json", "scenes/hard/16-contact.json", "scenes/hard/17-far-corner.json",
          "scenes/hard/18-grazing-receiver.json", "default", "scenes/stained-glass.json", "scenes/example.json",
          "scenes/semi-opaque.json", "scenes/glass-layers.json", "scenes/dcs-silhouettes.json", "scenes/engine.json"}) {
      Scene sc = std::string(path) == "default" ? defaultScene() : loadScene(path);
      RenderSettings es = s;
      es.width = es.height = errorSize;
      Renderer r(*ctx, sc, es);
      auto same = makeTechnique("raytrace");
      auto conv = makeTechnique("raytrace-converged");
      FrameResult sameRef = r.render(*same), convRef = r.render(*conv);
      std::string name = path;
      name = name.substr(name.rfind('/') + 1);
      if (name.size() > 5 && name.compare(name.size() - 5, 5, ".json") == 0) name = name.substr(0, name.size() - 5);
      std::fprintf(out, "%-24s |", name.c_str());
      for (const char* t : {"mvr", "pcss", "pcss-ultra", "vssm", "msm", "msm-soft", "evsm"}) {
        auto tech = makeTechnique(t);
        FrameResult f = r.render(*tech);
        std::fprintf(out, "  %6.4f / %6.4f |", measureErrors(f, sameRef).visibility.rmse,
                     measureErrors(f, convRef).visibility.rmse);
        std::fflush(out);
      }
      std::fprintf(out, "\n");
    }
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "penumbra_bench_pcss: %s\n", e.what());
    return int(e.exitCode());
  }
}

}  // namespace penumbra::bench
