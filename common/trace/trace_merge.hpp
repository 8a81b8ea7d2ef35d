#pragma once
// Merges the per-process trace parts into one trace ordered by cycle. Within one cycle, events
// keep the order of the parts as given and, within a part, the order they were written.
#include <cstdint>
#include <string>
#include <vector>

namespace mcnc::trace {

// Reads the parts, writes the merged lines to `out_path` (without a trailing summary) and
// returns the highest cycle seen. Lines that do not start with {"cycle":N are skipped.
std::uint64_t merge_parts(const std::vector<std::string>& part_paths, const std::string& out_path,
                          std::size_t* lines_written = nullptr);

}  // namespace mcnc::trace
