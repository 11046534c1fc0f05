#include "core/log.h"

#include <unistd.h>

#include <ctime>

#include <spdlog/sinks/stdout_color_sinks.h>

namespace penumbra {

void setLogLevel(const std::string& level) {
  static bool once = [] {
    auto logger = spdlog::stderr_color_mt("penumbra");
    // On a terminal a line starts by clearing the line, so a message printed while a progress
    // bar (core/progress.h) is drawn replaces the bar instead of running on after it.
    logger->set_pattern(::isatty(STDERR_FILENO) ? "\r\x1b[K[%^%l%$] %v" : "[%^%l%$] %v");
    spdlog::set_default_logger(logger);
    return true;
  }();
  (void)once;
  spdlog::set_level(spdlog::level::from_str(level));
}

std::string utcNow() {
  std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return date;
}

}  // namespace penumbra
