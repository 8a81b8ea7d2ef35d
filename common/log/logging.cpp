#include "common/log/logging.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>
#include <cstdlib>

namespace mcnc::log {

void setup(const std::string& process_name, const std::string& level) {
  std::string chosen = level;
  if (chosen.empty()) {
    const char* env = std::getenv("MCNC_LOG_LEVEL");
    chosen = env != nullptr ? env : "info";
  }
  auto logger = spdlog::stderr_color_mt(process_name);
  logger->set_pattern("[%H:%M:%S.%e] [%n] [%^%l%$] %v");
  logger->set_level(spdlog::level::from_str(chosen));
  spdlog::set_default_logger(logger);
}

}  // namespace mcnc::log
