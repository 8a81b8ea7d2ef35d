#pragma once
// Who may do what on the HMI (docs/hmi.md, Security): a token gives a role, and a browser's
// WebSocket must come from a page of this server. Pure: the server asks, this answers.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace mcnc::hmi {

enum class Role : std::uint8_t {
  none,      // sees nothing until it shows a token
  viewer,    // sees everything, commands nothing
  operator_  // sees and commands
};

const char* to_string(Role role) noexcept;

class AccessPolicy {
 public:
  // `operator_token` must not be empty. An empty `viewer_token`: anybody who reaches the
  // server may view without a token.
  AccessPolicy(std::string operator_token, std::string viewer_token);

  // The role of a connection that has shown no token yet.
  [[nodiscard]] Role initial_role() const noexcept;
  // The role `token` gives (none for a wrong one). Compared in time independent of where the
  // texts differ.
  [[nodiscard]] Role role_of(std::string_view token) const noexcept;

 private:
  std::string operator_token_;
  std::string viewer_token_;
};

// The origins a browser page of a server listening on `listen` ("HOST:PORT") has: http://HOST:PORT,
// and for a loopback address also http://localhost:PORT and http://127.0.0.1:PORT; plus `extra`.
std::vector<std::string> allowed_origins(std::string_view listen,
                                         const std::vector<std::string>& extra);

// A WebSocket upgrade may proceed: no Origin (not a browser: it still needs a token to command),
// or one of `allowed` exactly. The Host header is not trusted (DNS rebinding).
bool origin_allowed(std::string_view origin, const std::vector<std::string>& allowed) noexcept;

// A fresh operator token: 32 hex digits from the system's random source.
std::string generate_token();

}  // namespace mcnc::hmi
