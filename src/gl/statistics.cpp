#include "gl/statistics.h"

#include <cstring>
#include <string>

#include "gl/context.h"

namespace penumbra::gl {
namespace {

// In the order of PipelineStatistics::ids_ and of PipelineCounts' fields.
constexpr GLenum kTargets[] = {GL_PRIMITIVES_SUBMITTED_ARB,        GL_VERTEX_SHADER_INVOCATIONS_ARB,
                               GL_GEOMETRY_SHADER_INVOCATIONS,     GL_CLIPPING_OUTPUT_PRIMITIVES_ARB,
                               GL_FRAGMENT_SHADER_INVOCATIONS_ARB, GL_COMPUTE_SHADER_INVOCATIONS_ARB};

}  // namespace

bool PipelineStatistics::supported() {
  GLint major = 0, minor = 0, n = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major > 4 || (major == 4 && minor >= 6)) return true;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  for (GLint i = 0; i < n; ++i) {
    const char* e = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, GLuint(i)));
    if (e && std::strcmp(e, "GL_ARB_pipeline_statistics_query") == 0) return true;
  }
  return false;
}

std::unique_ptr<PipelineStatistics> PipelineStatistics::create() {
  if (!supported()) return nullptr;
  return std::unique_ptr<PipelineStatistics>(new PipelineStatistics());
}

PipelineStatistics::PipelineStatistics() {
  // glGenQueries, not glCreateQueries: Mesa 22.3's glCreateQueries refuses the statistics targets
  // (GL_INVALID_ENUM); a generated name becomes a query of its target at its first glBeginQuery.
  glGenQueries(kCounters, ids_);
  Context::checkErrors("pipeline statistics queries");
}

PipelineStatistics::~PipelineStatistics() {
  if (active_)
    for (int i = 0; i < kCounters; ++i) glEndQuery(kTargets[i]);
  glDeleteQueries(kCounters, ids_);
}

void PipelineStatistics::begin() {
  if (active_) end();  // a stage that threw never ended its queries
  for (int i = 0; i < kCounters; ++i) glBeginQuery(kTargets[i], ids_[i]);
  active_ = true;
}

PipelineCounts PipelineStatistics::end() {
  PipelineCounts c;
  if (!active_) return c;
  for (int i = 0; i < kCounters; ++i) glEndQuery(kTargets[i]);
  active_ = false;
  GLuint64 v[kCounters] = {};
  for (int i = 0; i < kCounters; ++i) glGetQueryObjectui64v(ids_[i], GL_QUERY_RESULT, &v[i]);
  c.primitivesSubmitted = v[0], c.vertexInvocations = v[1], c.geometryInvocations = v[2];
  c.clippingOutputPrimitives = v[3], c.fragmentInvocations = v[4], c.computeInvocations = v[5];
  return c;
}

}  // namespace penumbra::gl
