#pragma once
// A text file's lines as written, for showing them (trace block text, the HMI's program view).
#include <string>
#include <vector>

namespace mcnc::text {

// The lines of `text`, a trailing CR of each dropped.
std::vector<std::string> split_lines(const std::string& text);
// The lines of the file at `path`; empty when it cannot be read.
std::vector<std::string> read_lines(const std::string& path);

}  // namespace mcnc::text
