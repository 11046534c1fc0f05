#include "study/run.h"

#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "compare/compare.h"
#include "compare/frame_file.h"
#include "core/error.h"
#include "core/files.h"
#include "core/key_values.h"
#include "core/log.h"
#include "core/machine.h"
#include "core/names.h"
#include "sampling/light_samples.h"
#include "pipeline/renderer.h"
#include "scene/scene.h"
#include "scene/variants.h"
#include "study/plan.h"
#include "techniques/registry.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace penumbra::study {
namespace {

constexpr const char* kRow = "row.json";
constexpr const char* kFrame = "frame.bin";  // a reference's frame (compare/frame_file.h)

json readJson(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  json j = json::parse(in, nullptr, false);
  return j.is_discarded() ? json(nullptr) : j;
}

// Every regular file under `dir`, relative to it, sorted.
std::vector<std::string> filesUnder(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir).string());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

json finishedRow(const std::string& dir, const Job& j) {
  const fs::path jobDir = fs::path(dir) / "jobs" / j.id;
  json row = readJson(jobDir / kRow);
  if (!row.is_object() || row.value("id", "") != j.id || !row.contains("files")) return nullptr;
  for (const auto& f : row["files"])
    if (!f.is_string() || !fs::is_regular_file(jobDir / f.get<std::string>())) return nullptr;
  return row;
}

namespace {

class Runner {
 public:
  Runner(const RunOptions& o, std::vector<Job> jobs) : o_(o), jobs_(std::move(jobs)) {
    for (const Job& j : jobs_) byId_[j.id] = &j;
    fs::create_directories(jobsDir());
  }

  const std::vector<Job>& jobs() const { return jobs_; }

  json doneRow(const Job& j) const { return finishedRow(o_.dir, j); }

  // The job's row: the one there, or (none there, or forced) rendered now under the job's lock,
  // its references first.
  json ensure(const Job& j, bool force) {
    if (!force)
      if (json row = doneRow(j); !row.is_null()) return row;
    const FileLock lock((jobsDir() / (j.id + ".lock")).string());
    if (!force)  // another process may have done it while this one waited
      if (json row = doneRow(j); !row.is_null()) return row;
    std::vector<std::pair<std::string, json>> needs;
    for (const std::string& id : {j.converged, j.reference})
      if (!id.empty()) needs.emplace_back(id, ensure(job(id), false));
    return render(j, needs);
  }

 private:
  fs::path jobsDir() const { return fs::path(o_.dir) / "jobs"; }

  const Job& job(const std::string& id) const {
    auto it = byId_.find(id);
    if (it == byId_.end()) throw Error((fs::path(o_.dir) / "jobs.jsonl").string(), "no job " + id + " in the plan");
    return *it->second;
  }

  gl::Context& context() {
    if (!context_) context_ = gl::Context::create(o_.backend);
    return *context_;
  }

  // The last scene a job used (its file, its variant and its lights' scale), kept for the next
  // job (a study's jobs come scene by scene).
  const Scene& scene(const Job& j) {
    const json key = {j.scene, j.variant, j.lightScale};
    if (sceneKey_ != key || !scene_) {
      scene_.reset();
      Scene s = j.scene == "default" ? defaultScene() : loadScene(j.scene);
      if (!j.variant.empty()) s = applySceneVariant(std::move(s), j.variant);
      if (j.lightScale != 1.0) s = withLightsScaled(std::move(s), j.lightScale);
      scene_ = std::make_unique<Scene>(std::move(s));
      sceneKey_ = key;
    }
    return *scene_;
  }

  RenderSettings settingsOf(const Job& j, const Scene& s) const {
    RenderSettings r;
    r.width = j.size.width;
    r.height =
        j.size.height > 0 ? j.size.height : std::max(1, int(std::lround(double(j.size.width) * s.height / s.width)));
    // The converged reference takes its own sample counts (reference-samples); the pipeline's
    // light samples stay at their default for it.
    if (j.kind != "converged") r.sampling.count = j.samples;
    r.sampling.seed = j.seed;
    const auto strategy = valueNamed(kSampleStrategyNames, j.strategy);
    if (!strategy) throw Error(j.id, "unknown sample strategy '" + j.strategy + "'", ExitCode::Usage);
    r.sampling.strategy = *strategy;
    const auto shading = valueNamed(kShadingModeNames, j.shading);
    const auto pattern = valueNamed(kPixelPatternNames, j.pattern);
    if (!shading) throw Error(j.id, "unknown shading mode '" + j.shading + "'", ExitCode::Usage);
    if (!pattern) throw Error(j.id, "unknown pixel pattern '" + j.pattern + "'", ExitCode::Usage);
    r.shading = *shading;
    r.sampling.pattern = *pattern;
    return r;
  }

  // Renders a job into a temporary folder and renames it into place, its row last written; a
  // failure is a failed row. `needs`: the rows of the references it reads, by id.
  json render(const Job& j, const std::vector<std::pair<std::string, json>>& needs) {
    const fs::path final = jobsDir() / j.id;
    // One name each for the job's temporary folder and its previous folder on the way out: only
    // the holder of the job's lock writes them, and whatever a killed run left is removed here.
    const fs::path tmp = jobsDir() / (j.id + ".tmp"), old = jobsDir() / (j.id + ".old");
    fs::remove_all(tmp);
    fs::remove_all(old);
    fs::create_directories(tmp);
    json row = j.json();
    const auto t0 = std::chrono::steady_clock::now();
    try {
      for (const auto& [id, need] : needs)
        if (need.value("status", "") != "ok")
          throw Error(j.id, fmt::format("its {} job {} failed: {}", job(id).kind, id, need.value("error", "?")));
      row.update(execute(j, tmp));
      row["status"] = "ok";
    } catch (const std::exception& e) {
      const auto* error = dynamic_cast<const Error*>(&e);
      PLOG_ERROR("study: job {} ({} {} on {}) failed: {}", j.id, j.kind, j.technique, j.scene, e.what());
      fs::remove_all(tmp);  // a failed job's images are not kept: its row says why
      fs::create_directories(tmp);
      row["status"] = "failed";
      row["error"] = e.what();
      row["exitCode"] = int(error ? error->exitCode() : ExitCode::Error);
    }
    const MachineFacts m = machineFacts();
    row["machine"] = {{"host", m.host}, {"cpu", m.cpu}, {"cores", m.cores}, {"memory", m.memory}, {"os", m.os}};
    if (context_) row["renderer"] = context_->renderer(), row["glVersion"] = context_->version();
    row["backend"] = gl::toString(o_.backend);
    row["build"] = buildIdentity();
    row["date"] = utcNow();
    row["seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    row["files"] = filesUnder(tmp);
    writeTextFile((tmp / kRow).string(), row.dump() + "\n");
    publish(tmp, final, old);
    return row;
  }

  // `tmp` becomes `final`; a folder already there (a forced job, or one whose row or images were
  // deleted) is moved to `old` first and removed after.
  static void publish(const fs::path& tmp, const fs::path& final, const fs::path& old) {
    if (fs::exists(final)) fs::rename(final, old);
    fs::rename(tmp, final);
    std::error_code ec;
    fs::remove_all(old, ec);
  }

  // What a job measures, as fields of its row.
  json execute(const Job& j, const fs::path& tmp) {
    const Scene& s = scene(j);
    const RenderSettings settings = settingsOf(j, s);
    if (j.kind == "converged") return renderConverged(j, s, settings, tmp);
    std::optional<FrameResult> reference, converged;
    if (!j.converged.empty()) converged = readFrameFile((jobsDir() / j.converged / kFrame).string());
    CompareOptions c;
    c.reference = findTechnique("raytrace");
    c.convergedReference = findTechnique("raytrace-converged");
    c.converged = converged.has_value();
    c.givenConverged = converged ? &*converged : nullptr;
    c.timingFrames = j.frames, c.warmup = j.warmup;
    c.outDir = tmp.string();
    c.writeImages = j.images != "none", c.writeExr = j.images == "all";
    c.progress = 0;
    if (j.kind == "technique") {
      reference = readFrameFile((jobsDir() / j.reference / kFrame).string());
      c.givenReference = &*reference;
      c.techniques = {findTechnique(j.technique)};
      c.params = j.params;
    } else {
      c.onReference = [&](const FrameResult& f) { writeFrameFile((tmp / kFrame).string(), f); };
    }
    const CompareResult r = compareTechniques(context(), s, settings, c);
    json out = r.json();
    if (out["runs"].size() != 1) throw Error(j.id, fmt::format("{} rows where one was due", out["runs"].size()));
    json run = out["runs"][0];
    out.erase("runs");
    if (run.value("status", "") == "failed") throw Error(j.technique, run.value("error", "?"));
    if (!j.profile.empty()) run["statistics"] = profiledStatistics(j, s, settings);
    run["statisticsFrom"] =
        j.profile.empty() ? "the last timed frame" : "a profiled frame (" + joinKeys(j.profile) + ")";
    return {{"result", run}, {"info", out}};
  }

  // The statistics of one more, untimed frame with the job's profile parameters added (counters
  // that would slow the timed frames); a later frame, as the timed ones (dcs plans a light's
  // later frames from its first).
  json profiledStatistics(const Job& j, const Scene& s, const RenderSettings& settings) {
    std::vector<std::string> params = j.params;
    params.insert(params.end(), j.profile.begin(), j.profile.end());
    TechniqueParams read(params);
    auto tech = findTechnique(j.technique).make(read);
    read.checkConsumed();
    Renderer renderer(context(), s, settings);
    for (int i = 0; i < std::max(j.warmup, 1); ++i) renderer.render(*tech, j.technique);
    json stats = json::object();
    for (const auto& [k, v] : renderer.render(*tech, j.technique).statistics) stats[k] = v;
    return stats;
  }

  // raytrace-converged of a scene and size: its frame for the jobs that read it, its image, its
  // own noise and statistics.
  json renderConverged(const Job& j, const Scene& s, RenderSettings settings, const fs::path& tmp) {
    const std::vector<std::string> params = {fmt::format("reference-samples={}", j.samples),
                                             fmt::format("reference-max-samples={}", j.samples)};
    TechniqueParams read(params);
    auto tech = findTechnique("raytrace-converged").make(read);
    read.checkConsumed();
    Renderer renderer(context(), s, settings);
    const auto t0 = std::chrono::steady_clock::now();
    const FrameResult f = renderer.render(*tech, "raytrace-converged");
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    writeFrameFile((tmp / kFrame).string(), f);
    if (j.images == "all") writeFrame((tmp / "raytrace-converged.exr").string(), f);
    json stats = json::object();
    for (const auto& [k, v] : f.statistics) stats[k] = v;
    json result = {{"name", "raytrace-converged"}, {"ms", ms}, {"statistics", stats}, {"memoryBytes", f.memoryBytes}};
    if (const auto noise = referenceNoise(f))
      result["noise"] = {{"visibilityRmse", noise->visibility}, {"shadedRmse", noise->shaded}};
    return {{"result", result}, {"info", {{"width", settings.width}, {"height", settings.height}}}};
  }

  const RunOptions& o_;
  std::vector<Job> jobs_;
  std::map<std::string, const Job*> byId_;
  std::unique_ptr<gl::Context> context_;
  std::unique_ptr<Scene> scene_;
  json sceneKey_;
};

// The jobs a run selects, by index.
std::vector<std::size_t> selected(const RunOptions& o, std::size_t count) {
  if (o.index) {
    if (*o.index >= count)
      throw Error("index", fmt::format("{} is past the plan's last job ({} jobs: 0-{})", *o.index, count, count - 1),
                  ExitCode::Usage);
    return {*o.index};
  }
  if (o.shards < 1 || o.shard < 0 || o.shard >= o.shards)
    throw Error("shard", fmt::format("{}/{}: the shard must be in 0..N-1", o.shard, o.shards), ExitCode::Usage);
  std::vector<std::size_t> out;
  for (std::size_t i = std::size_t(o.shard); i < count; i += std::size_t(o.shards)) out.push_back(i);
  return out;
}

}  // namespace

RunSummary runStudy(const RunOptions& o) {
  Runner runner(o, readPlan(o.dir));
  const auto& jobs = runner.jobs();
  RunSummary sum;
  std::vector<std::size_t> todo;
  for (std::size_t i : selected(o, jobs.size())) {
    ++sum.selected;
    const json row = o.force ? json(nullptr) : runner.doneRow(jobs[i]);
    if (row.is_null() || (o.retryFailed && row.value("status", "") != "ok")) {
      todo.push_back(i);
    } else {
      ++sum.done;
      sum.failed += row.value("status", "") != "ok";
    }
  }
  if (o.parallel <= 1) {
    for (std::size_t i : todo) {
      const json row = runner.ensure(jobs[i], o.force || o.retryFailed);
      PLOG_INFO("study: job {} ({}/{}) {} {}: {}", jobs[i].id, i, jobs.size(), jobs[i].kind, jobs[i].technique,
                row.value("status", "?"));
    }
  } else {
    // One process a job, `parallel` at once, forked before this process made any GL context or
    // thread; jobs in plan order (references first): a job whose reference another process is
    // rendering waits for that job's lock.
    std::map<pid_t, std::size_t> running;
    auto reap = [&]() {
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, 0);
      if (pid < 0) throw Error("study run", "waitpid failed");
      const std::size_t i = running.at(pid);
      running.erase(pid);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        PLOG_ERROR("study: job {} ended with {}", jobs[i].id,
                   WIFSIGNALED(status) ? fmt::format("signal {}", WTERMSIG(status))
                                       : fmt::format("exit {}", WEXITSTATUS(status)));
    };
    for (std::size_t i : todo) {
      while (int(running.size()) >= o.parallel) reap();
      std::fflush(nullptr);
      const pid_t pid = ::fork();
      if (pid < 0) throw Error("study run", "fork failed");
      if (pid == 0) {
        int code = 0;
        try {
          code = runner.ensure(jobs[i], o.force || o.retryFailed).value("status", "") == "ok" ? 0 : 1;
        } catch (const std::exception& e) {
          std::fprintf(stderr, "penumbra: %s\n", e.what());
          code = 1;
        }
        std::fflush(nullptr);
        ::_exit(code);
      }
      running[pid] = i;
    }
    while (!running.empty()) reap();
  }
  // Rendered: the jobs that were not done when this run began and are now (by this process, a
  // child, or as the reference of another job); a job left without a row failed.
  for (std::size_t i : todo) {
    const json row = runner.doneRow(jobs[i]);
    if (row.is_null()) {
      ++sum.failed;
      PLOG_ERROR("study: job {} ({} {} on {}) has no row", jobs[i].id, jobs[i].kind, jobs[i].technique, jobs[i].scene);
      continue;
    }
    ++sum.rendered;
    sum.failed += row.value("status", "") != "ok";
  }
  return sum;
}

}  // namespace penumbra::study
