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

namespace mcnc::trace {

namespace {

// The string value of "key":"value" in a trace line, or empty.
std::string string_field(const std::string& line, const std::string& key) {
  const std::string pattern = "\"" + key + "\":\"";
  const auto at = line.find(pattern);
  if (at == std::string::npos) {
    return {};
  }
  const auto begin = at + pattern.size();
  const auto end = line.find('"', begin);
  return end == std::string::npos ? std::string() : line.substr(begin, end - begin);
}

long long number_field(const std::string& line, const std::string& key) {
  const std::string pattern = "\"" + key + "\":";
  const auto at = line.find(pattern);
  return at == std::string::npos ? -1
                                 : std::strtoll(line.c_str() + at + pattern.size(), nullptr, 10);
}

}  // namespace

std::map<std::string, ChannelRun> channel_runs(const std::string& trace_path) {
  std::map<std::string, ChannelRun> runs;
  std::ifstream in(trace_path);
  for (std::string line; std::getline(in, line);) {
    const std::string ev = string_field(line, "ev");
    if (ev == "state" && string_field(line, "state") == "running") {
      ChannelRun& run = runs[string_field(line, "ch")];
      if (!run.started) {
        run.started = true;
        run.start_cycle = static_cast<std::uint64_t>(number_field(line, "cycle"));
      }
    } else if (ev == "end") {
      ChannelRun& run = runs[string_field(line, "ch")];
      if (!run.ended) {
        run.ended = true;
        run.end_cycle = static_cast<std::uint64_t>(number_field(line, "cycle"));
        run.end_code = static_cast<int>(number_field(line, "code"));
      }
    }
  }
  return runs;
}

}  // namespace mcnc::trace
