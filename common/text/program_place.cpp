#include "common/text/program_place.hpp"

namespace mcnc::text {

std::string program_place(std::string_view file, int line, int column) {
  if (line <= 0) {
    return {};
  }
  if (file.empty()) {
    return "line " + std::to_string(line);
  }
  std::string place(file);
  place += ":" + std::to_string(line);
  if (column > 0) {
    place += ":" + std::to_string(column);
  }
  return place;
}

}  // namespace mcnc::text
