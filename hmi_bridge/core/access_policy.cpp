#include "hmi_bridge/core/access_policy.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <random>

namespace mcnc::hmi {

const char* to_string(Role role) noexcept {
  switch (role) {
    case Role::none:
      return "none";
    case Role::viewer:
      return "viewer";
    case Role::operator_:
      return "operator";
  }
  return "none";
}

namespace {

bool same(std::string_view a, std::string_view b) noexcept {
  // Every character of the longer is looked at, whatever matched: no early exit to time.
  const std::size_t n = std::max(a.size(), b.size());
  unsigned diff = a.size() == b.size() ? 0U : 1U;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char x = i < a.size() ? static_cast<unsigned char>(a[i]) : 0;
    const unsigned char y = i < b.size() ? static_cast<unsigned char>(b[i]) : 0;
    diff |= static_cast<unsigned>(x ^ y);
  }
  return diff == 0;
}

}  // namespace

AccessPolicy::AccessPolicy(std::string operator_token, std::string viewer_token)
    : operator_token_(std::move(operator_token)), viewer_token_(std::move(viewer_token)) {}

Role AccessPolicy::initial_role() const noexcept {
  return viewer_token_.empty() ? Role::viewer : Role::none;
}

Role AccessPolicy::role_of(std::string_view token) const noexcept {
  if (!operator_token_.empty() && same(token, operator_token_)) {
    return Role::operator_;
  }
  if (!viewer_token_.empty() && same(token, viewer_token_)) {
    return Role::viewer;
  }
  return Role::none;
}

std::vector<std::string> allowed_origins(std::string_view listen,
                                         const std::vector<std::string>& extra) {
  std::vector<std::string> origins;
  const std::size_t colon = listen.rfind(':');
  const std::string_view host = colon == std::string_view::npos ? listen : listen.substr(0, colon);
  const std::string_view port =
      colon == std::string_view::npos ? std::string_view("80") : listen.substr(colon + 1);
  origins.push_back("http://" + std::string(host) + ":" + std::string(port));
  if (host == "127.0.0.1" || host == "localhost") {
    origins.push_back("http://127.0.0.1:" + std::string(port));
    origins.push_back("http://localhost:" + std::string(port));
  }
  origins.insert(origins.end(), extra.begin(), extra.end());
  std::sort(origins.begin(), origins.end());
  origins.erase(std::unique(origins.begin(), origins.end()), origins.end());
  return origins;
}

bool origin_allowed(std::string_view origin, const std::vector<std::string>& allowed) noexcept {
  return origin.empty() || std::find(allowed.begin(), allowed.end(), origin) != allowed.end();
}

std::string generate_token() {
  std::random_device source;
  std::array<char, 33> text{};
  for (std::size_t i = 0; i < 32; i += 8) {
    std::snprintf(text.data() + i, 9, "%08x", static_cast<unsigned>(source()));
  }
  return std::string(text.data(), 32);
}

}  // namespace mcnc::hmi
