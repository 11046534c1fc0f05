// Logging goes to stderr through spdlog; stdout is kept for --json output.
#pragma once

#include <spdlog/spdlog.h>

namespace penumbra {
// Sets the level from "trace|debug|info|warn|error|off"; default "info".
void setLogLevel(const std::string& level);
// The date and time now, "YYYY-MM-DD HH:MM UTC": the stamp of reports and benchmark results.
std::string utcNow();
}  // namespace penumbra

#define PLOG_TRACE(...) ::spdlog::trace(__VA_ARGS__)
#define PLOG_DEBUG(...) ::spdlog::debug(__VA_ARGS__)
#define PLOG_INFO(...) ::spdlog::info(__VA_ARGS__)
#define PLOG_WARN(...) ::spdlog::warn(__VA_ARGS__)
#define PLOG_ERROR(...) ::spdlog::error(__VA_ARGS__)
