#include "channel/interp/path/path_text.hpp"

#include <cstdio>

namespace mcnc::interp::path {

std::string mm_text(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace mcnc::interp::path
