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

// Other names of a dialect: ARCHITECTURE.md's `fanuc-lathe` is the Dafeng lathe, whose manual
// follows the FANUC 0i-TF (the reference where the specs are silent).
struct DialectAlias {
  std::string_view alias;
  std::string_view name;
};
inline constexpr std::array<DialectAlias, 1> kDialectAliases{{{"fanuc-lathe", "dafeng"}}};

// The dialect's name (one of kDialectNames) for a name or an alias; empty for neither.
inline std::string_view canonical_dialect_name(std::string_view name) {
  for (const std::string_view n : kDialectNames) {
    if (n == name) {
      return n;
    }
  }
  for (const DialectAlias& a : kDialectAliases) {
    if (a.alias == name) {
      return a.name;
    }
  }
  return {};
}

// "dafeng, gsk or fanuc-mill (fanuc-lathe: dafeng)", for messages.
inline std::string dialect_choices() {
  std::string s;
  for (std::size_t i = 0; i < kDialectNames.size(); ++i) {
    s += i == 0 ? "" : i + 1 == kDialectNames.size() ? " or " : ", ";
    s += kDialectNames[i];
  }
  for (std::size_t i = 0; i < kDialectAliases.size(); ++i) {
    s += std::string(i == 0 ? " (" : ", ") + std::string(kDialectAliases[i].alias) + ": " +
         std::string(kDialectAliases[i].name);
  }
  return s + (kDialectAliases.empty() ? "" : ")");
}

}  // namespace mcnc::config
