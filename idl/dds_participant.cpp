#include "idl/dds_participant.hpp"

#include <cstdlib>
#include <stdexcept>

namespace mcnc::dds {

std::string qos_profiles_path() {
  const char* env = std::getenv("MCNC_QOS_PROFILES");
  return env != nullptr && *env != '\0' ? env : MCNC_QOS_PROFILES_FILE;
}

std::optional<Middleware> parse_middleware(std::string_view name) noexcept {
  if (name == "fastdds") {
    return Middleware::fastdds;
  }
  if (name == "cyclonedds") {
    return Middleware::cyclonedds;
  }
  return std::nullopt;
}

const char* middleware_name(Middleware middleware) noexcept {
  return middleware == Middleware::cyclonedds ? "cyclonedds" : "fastdds";
}

Middleware middleware_from_env() {
  const char* env = std::getenv("MCNC_MIDDLEWARE");
  if (env == nullptr || *env == '\0') {
    return kDefaultMiddleware;
  }
  const std::optional<Middleware> middleware = parse_middleware(env);
  if (!middleware) {
    throw std::runtime_error(std::string("MCNC_MIDDLEWARE must be fastdds or cyclonedds, not '") +
                             env + "'");
  }
  return *middleware;
}

namespace detail {
std::string partition_key(const Partitions& partitions) {
  std::string key;
  for (const std::string& name : partitions.names) {
    key += name;
    key += '\n';
  }
  return key;
}
}  // namespace detail

Participant::Participant(int domain, const std::string& name, CyclicClock clock,
                         std::optional<Middleware> middleware, LocalTransport local,
                         std::optional<security::IdentityFiles> security)
    : middleware_(middleware ? *middleware : middleware_from_env()),
      impl_(middleware_ == Middleware::cyclonedds
                ? detail::make_cyclonedds_participant(domain, name, clock,
                                                      local == LocalTransport::shared_memory,
                                                      security ? &*security : nullptr)
                : detail::make_fastdds_participant(domain, name, clock,
                                                   security ? &*security : nullptr)) {}

Participant::~Participant() = default;

std::chrono::nanoseconds participant_lease(const Participant& participant) {
  return participant.impl().lease();
}

}  // namespace mcnc::dds
