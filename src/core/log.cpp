#include "core/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>

namespace penumbra {

void setLogLevel(const std::string& level) {
  static bool once = [] {
    auto logger = spdlog::stderr_color_mt("penumbra");
    logger->set_pattern("[%^%l%$] %v");
    spdlog::set_default_logger(logger);
    return true;
  }();
  (void)once;
  spdlog::set_level(spdlog::level::from_str(level));
}

}  // namespace penumbra
