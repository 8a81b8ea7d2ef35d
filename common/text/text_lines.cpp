#include "common/text/text_lines.hpp"

#include <fstream>
#include <sstream>

namespace mcnc::text {

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
    }
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> read_lines(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    return {};
  }
  std::stringstream content;
  content << in.rdbuf();
  return split_lines(content.str());
}

}  // namespace mcnc::text
