#pragma once
// The interpreter dialects by the names a user writes: `dialect` of a channel in the machine
// file, of the interpreter's parameter file and `mcnc interp --dialect`. One list for the
// machine file's check and the interpreter (channel/interp/dialect.hpp), in the order of
// interp::Dialect.
#include <array>
#include <string>
#include <string_view>

namespace mcnc::config {

inline constexpr std::array<std::string_view, 3> kDialectNames{"dafeng", "gsk", "fanuc-mill"};

// "dafeng, gsk or fanuc-mill", for messages.
inline std::string dialect_choices() {
  std::string s;
  for (std::size_t i = 0; i < kDialectNames.size(); ++i) {
    s += i == 0 ? "" : i + 1 == kDialectNames.size() ? " or " : ", ";
    s += kDialectNames[i];
  }
  return s;
}

}  // namespace mcnc::config
