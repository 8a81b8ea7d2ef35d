#include "common/config/yaml_reader.hpp"

#include <charconv>
#include <cmath>
#include <system_error>

#include "common/config/machine_config.hpp"

namespace mcnc::config::detail {

namespace {

// yaml-cpp tags a plain scalar "?"; quoted scalars get "!" and explicit tags their own name.
bool is_plain(const YAML::Node& node) {
  return node.Tag() == "?";
}

// Optional leading '+' is accepted because YAML allows it; from_chars does not.
std::string_view strip_plus(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+') {
    text.remove_prefix(1);
  }
  return text;
}

}  // namespace

std::string join_key(const std::string& path, std::string_view key) {
  if (path.empty()) {
    return std::string(key);
  }
  std::string out = path;
  out += '.';
  out += key;
  return out;
}

std::string join_index(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

void YamlValue::fail(const std::string& reason) const {
  fail_at(path_, reason);
}

void YamlValue::fail_at(std::string path, const std::string& reason) const {
  const YAML::Mark mark = node_.Mark();
  if (mark.is_null()) {
    throw ConfigError(std::move(path), reason);
  }
  // yaml-cpp counts from 0; editors count from 1.
  throw ConfigError(std::move(path), reason + " (line " + std::to_string(mark.line + 1) +
                                         ", column " + std::to_string(mark.column + 1) + ")");
}

std::string YamlValue::describe() const {
  switch (node_.Type()) {
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Scalar:
      return is_plain(node_) ? "'" + node_.Scalar() + "'" : "the string \"" + node_.Scalar() + "\"";
    case YAML::NodeType::Null:
    case YAML::NodeType::Undefined:
      break;
  }
  return "nothing";
}

YamlMap YamlValue::map(std::initializer_list<std::string_view> allowed) const {
  if (!node_.IsMap()) {
    fail("expected a map, got " + describe());
  }
  std::vector<std::pair<std::string, YAML::Node>> entries;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    // Copies: yaml-cpp's iterator yields a temporary pair, so a reference into it dangles.
    const YAML::Node key_node = it->first;
    const YAML::Node value_node = it->second;
    if (!key_node.IsScalar()) {
      fail("map keys must be plain names");
    }
    const std::string key = key_node.Scalar();
    const YamlValue key_value(key_node, join_key(path_, key));
    bool known = false;
    for (std::string_view name : allowed) {
      known = known || name == key;
    }
    if (!known) {
      key_value.fail("unknown key");
    }
    // yaml-cpp keeps both entries of a repeated key; reject instead of picking one silently.
    for (const auto& [seen, unused] : entries) {
      if (seen == key) {
        key_value.fail("duplicate key");
      }
    }
    entries.emplace_back(key, value_node);
  }
  return YamlMap(*this, std::move(entries));
}

YamlValue YamlValue::child(std::string_view key) const {
  const YAML::Node& node = node_;  // const lookup: never inserts
  return YamlValue(node[std::string(key)], join_key(path_, key));
}

std::vector<YamlValue> YamlValue::list() const {
  if (!node_.IsSequence()) {
    fail("expected a list, got " + describe());
  }
  std::vector<YamlValue> out;
  out.reserve(node_.size());
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.emplace_back(node_[i], join_index(path_, i));
  }
  return out;
}

std::string YamlValue::string() const {
  if (!node_.IsScalar()) {
    fail("expected a string, got " + describe());
  }
  return node_.Scalar();
}

const std::string& YamlValue::plain_scalar(std::string_view expected) const {
  if (!node_.IsScalar() || !is_plain(node_)) {
    fail("expected " + std::string(expected) + ", got " + describe());
  }
  return node_.Scalar();
}

std::int64_t YamlValue::integer(std::int64_t min, std::int64_t max) const {
  const std::string& raw = plain_scalar("an integer");
  const std::string_view text = strip_plus(raw);
  std::int64_t value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc::result_out_of_range) {
    fail("integer " + raw + " is out of range " + std::to_string(min) + ".." + std::to_string(max));
  }
  if (ec != std::errc() || end != text.data() + text.size()) {
    fail("expected an integer, got '" + raw + "'");
  }
  if (value < min || value > max) {
    fail("value " + raw + " is out of range " + std::to_string(min) + ".." + std::to_string(max));
  }
  return value;
}

double YamlValue::number() const {
  const std::string& raw = plain_scalar("a number");
  const std::string_view text = strip_plus(raw);
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  // from_chars also accepts "inf" and "nan"; neither is a usable machine parameter.
  if (ec != std::errc() || end != text.data() + text.size() || !std::isfinite(value)) {
    fail("expected a number, got '" + raw + "'");
  }
  return value;
}

double YamlValue::positive_number() const {
  const double value = number();
  if (!(value > 0.0)) {
    fail("value " + plain_scalar("a number") + " must be greater than 0");
  }
  return value;
}

bool YamlValue::boolean() const {
  const std::string& raw = plain_scalar("true or false");
  // Only the YAML 1.2 spellings: yes/no/on/off are too easy to write by accident.
  if (raw == "true" || raw == "True" || raw == "TRUE") {
    return true;
  }
  if (raw == "false" || raw == "False" || raw == "FALSE") {
    return false;
  }
  fail("expected true or false, got '" + raw + "'");
}

std::optional<YamlValue> YamlMap::optional(std::string_view key) const {
  for (const auto& [name, node] : entries_) {
    if (name == key) {
      return YamlValue(node, join_key(path(), key));
    }
  }
  return std::nullopt;
}

YamlValue YamlMap::required(std::string_view key) const {
  if (auto value = optional(key)) {
    return *value;
  }
  // The missing key has no node of its own: the location is that of the map that should hold it.
  self_.fail_at(join_key(path(), key), "missing required key");
}

}  // namespace mcnc::config::detail
