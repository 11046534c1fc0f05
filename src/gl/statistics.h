// Pipeline statistics (ARB_pipeline_statistics_query, core in GL 4.6): per timed stage, the
// primitives, shader invocations and compute invocations the GL counted. Unlike milliseconds
// they do not depend on the machine: they explain a llvmpipe time and predict a GPU's.
#pragma once

#include <memory>

#include "core/timer.h"
#include "gl/gl.h"

namespace penumbra::gl {

class PipelineStatistics final : public StageCounter {
 public:
  // Whether the current context counts them (GL 4.6 or GL_ARB_pipeline_statistics_query).
  static bool supported();
  // The counters for the current context; null where supported() is false.
  static std::unique_ptr<PipelineStatistics> create();
  PipelineStatistics(const PipelineStatistics&) = delete;
  PipelineStatistics& operator=(const PipelineStatistics&) = delete;
  ~PipelineStatistics() override;
  void begin() override;
  PipelineCounts end() override;

 private:
  PipelineStatistics();
  static constexpr int kCounters = 6;
  GLuint ids_[kCounters] = {};
  bool active_ = false;
};

}  // namespace penumbra::gl
