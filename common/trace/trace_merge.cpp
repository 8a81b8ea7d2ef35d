#include "common/trace/trace_merge.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace mcnc::trace {

namespace {
constexpr char kPrefix[] = "{\"cycle\":";
}

std::uint64_t merge_parts(const std::vector<std::string>& part_paths, const std::string& out_path,
                          std::size_t* lines_written) {
  struct Line {
    std::uint64_t cycle;
    std::size_t part;
    std::size_t index;
    std::string text;
  };
  std::vector<Line> lines;
  for (std::size_t p = 0; p < part_paths.size(); ++p) {
    std::ifstream in(part_paths[p]);
    std::size_t index = 0;
    for (std::string text; std::getline(in, text);) {
      if (text.rfind(kPrefix, 0) != 0) {
        continue;
      }
      const std::uint64_t cycle = std::strtoull(text.c_str() + sizeof(kPrefix) - 1, nullptr, 10);
      lines.push_back(Line{cycle, p, index++, std::move(text)});
    }
  }
  std::stable_sort(lines.begin(), lines.end(), [](const Line& a, const Line& b) {
    if (a.cycle != b.cycle) {
      return a.cycle < b.cycle;
    }
    return a.part != b.part ? a.part < b.part : a.index < b.index;
  });
  std::ofstream out(out_path, std::ios::trunc);
  if (!out) {
    throw std::runtime_error("cannot write trace " + out_path);
  }
  std::uint64_t last = 0;
  for (const auto& line : lines) {
    out << line.text << '\n';
    last = std::max(last, line.cycle);
  }
  if (lines_written != nullptr) {
    *lines_written = lines.size();
  }
  return last;
}

}  // namespace mcnc::trace
