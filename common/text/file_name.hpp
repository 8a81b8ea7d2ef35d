#pragma once
// File names that come from outside (the wire, a browser): read only as a file of one directory.
#include <string_view>

namespace mcnc::text {

// A plain file name: not empty, no directory part (no '/' or '\'), not "." or "..". Such a name
// joined to a directory names a file in it, never one elsewhere.
bool is_plain_file_name(std::string_view name) noexcept;

}  // namespace mcnc::text
