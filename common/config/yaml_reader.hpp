#pragma once
// Strict, path-tracking access to a parsed YAML tree. Every accessor knows the key path that led
// to its node, so each rejection names exactly where the problem is (e.g. "axes[1].node_id").
// Internal to the loader: the rest of the code base sees only MachineConfig and ConfigError.
#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace mcnc::config::detail {

class YamlMap;

// One YAML node plus its key path.
class YamlValue {
 public:
  YamlValue(YAML::Node node, std::string path) : node_(std::move(node)), path_(std::move(path)) {}

  [[nodiscard]] const std::string& path() const noexcept { return path_; }

  // Throws ConfigError(path, reason) with the node's line and column appended.
  [[noreturn]] void fail(const std::string& reason) const;
  // The same, for a key path other than this node's (a missing key is reported at its own path
  // but located at the map that lacks it).
  [[noreturn]] void fail_at(std::string path, const std::string& reason) const;

  // A map whose keys are all in `allowed` (unknown and duplicate keys are rejected).
  [[nodiscard]] YamlMap map(std::initializer_list<std::string_view> allowed) const;
  // The value under `key` of a map already checked with map(), for errors found after parsing
  // (duplicates, cross references) that should still point at the offending line.
  [[nodiscard]] YamlValue child(std::string_view key) const;
  // A list; its elements carry the paths "path[0]", "path[1]", ...
  [[nodiscard]] std::vector<YamlValue> list() const;
  // Any scalar, quoted or not, taken as text.
  [[nodiscard]] std::string string() const;
  // A plain (unquoted) decimal integer within [min, max].
  [[nodiscard]] std::int64_t integer(std::int64_t min, std::int64_t max) const;
  // A plain finite decimal number.
  [[nodiscard]] double number() const;
  // A plain finite decimal number strictly greater than zero.
  [[nodiscard]] double positive_number() const;
  // A plain true or false.
  [[nodiscard]] bool boolean() const;

 private:
  // A plain scalar's text, or a type error naming `expected`. Quoted scalars are strings, so a
  // quoted "1000" where a number is wanted is rejected rather than silently converted.
  [[nodiscard]] const std::string& plain_scalar(std::string_view expected) const;
  // "a list", "a map", "nothing", or the scalar text, for type errors.
  [[nodiscard]] std::string describe() const;

  YAML::Node node_;
  std::string path_;
};

// The entries of a validated map, looked up by key.
class YamlMap {
 public:
  YamlMap(YamlValue self, std::vector<std::pair<std::string, YAML::Node>> entries)
      : self_(std::move(self)), entries_(std::move(entries)) {}

  [[nodiscard]] const std::string& path() const noexcept { return self_.path(); }
  [[noreturn]] void fail(const std::string& reason) const { self_.fail(reason); }

  [[nodiscard]] std::optional<YamlValue> optional(std::string_view key) const;
  // Throws "missing required key" at "path.key" when absent.
  [[nodiscard]] YamlValue required(std::string_view key) const;

 private:
  YamlValue self_;
  std::vector<std::pair<std::string, YAML::Node>> entries_;
};

// "a.b" from ("a", "b"); a top-level key has no leading dot.
[[nodiscard]] std::string join_key(const std::string& path, std::string_view key);
// "a[3]" from ("a", 3).
[[nodiscard]] std::string join_index(const std::string& path, std::size_t index);

}  // namespace mcnc::config::detail
