#include "launch/ephemeral_ports.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

namespace mcnc::launch {

namespace {

// A port number 0-65535 at the start of `text` (digits only).
std::optional<int> port_at(std::string_view& text) {
  int value = -1;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || value < 0 || value > 65535) {
    return std::nullopt;
  }
  text.remove_prefix(static_cast<std::size_t>(end - text.data()));
  return value;
}

std::string_view trimmed(const std::string& text) {
  std::string_view view(text);
  while (!view.empty() && std::isspace(static_cast<unsigned char>(view.back())) != 0) {
    view.remove_suffix(1);
  }
  while (!view.empty() && std::isspace(static_cast<unsigned char>(view.front())) != 0) {
    view.remove_prefix(1);
  }
  return view;
}

}  // namespace

std::optional<PortRange> parse_port_range(const std::string& text) {
  std::string_view view = trimmed(text);
  const auto first = port_at(view);
  const auto blank = view.find_first_not_of(" \t");
  if (!first || blank == 0 || blank == std::string_view::npos) {
    return std::nullopt;
  }
  view.remove_prefix(blank);
  const auto last = port_at(view);
  if (!last || !view.empty() || *last < *first) {
    return std::nullopt;
  }
  return PortRange{*first, *last};
}

std::optional<std::vector<PortRange>> parse_port_list(const std::string& text) {
  std::string_view view = trimmed(text);
  std::vector<PortRange> ranges;
  while (!view.empty()) {
    const auto first = port_at(view);
    if (!first) {
      return std::nullopt;
    }
    PortRange range{*first, *first};
    if (!view.empty() && view.front() == '-') {
      view.remove_prefix(1);
      const auto last = port_at(view);
      if (!last || *last < *first) {
        return std::nullopt;
      }
      range.last = *last;
    }
    ranges.push_back(range);
    if (!view.empty()) {
      if (view.front() != ',' || view.size() == 1) {
        return std::nullopt;
      }
      view.remove_prefix(1);
    }
  }
  return ranges;
}

std::vector<PortRange> exposed_ports(PortRange wanted, PortRange ephemeral,
                                     const std::vector<PortRange>& reserved) {
  std::vector<PortRange> exposed;
  const int first = std::max(wanted.first, ephemeral.first);
  const int last = std::min(wanted.last, ephemeral.last);
  for (int port = first; port <= last; ++port) {
    const bool is_reserved = std::any_of(reserved.begin(), reserved.end(), [&](const PortRange& r) {
      return r.first <= port && port <= r.last;
    });
    if (is_reserved) {
      continue;
    }
    if (!exposed.empty() && exposed.back().last == port - 1) {
      exposed.back().last = port;
    } else {
      exposed.push_back({port, port});
    }
  }
  return exposed;
}

std::string port_list(const std::vector<PortRange>& ranges) {
  std::string text;
  for (const PortRange& r : ranges) {
    text += (text.empty() ? "" : ",") + std::to_string(r.first);
    if (r.last != r.first) {
      text += "-" + std::to_string(r.last);
    }
  }
  return text;
}

}  // namespace mcnc::launch
