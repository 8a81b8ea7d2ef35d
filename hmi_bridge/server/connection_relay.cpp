#include "hmi_bridge/server/connection_relay.hpp"

#include "hmi_bridge/core/client_stream.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <sys/socket.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <vector>

namespace mcnc::hmi {

namespace {

// What one connection may have waiting in each direction: a client that stops reading, or a
// web server that stops taking, is not read from until it drains.
constexpr std::size_t kToUpstreamBytes = 65536;
constexpr std::size_t kToClientBytes = 262144;
constexpr int kTickMs = 100;  // the deadlines' resolution
constexpr std::chrono::milliseconds kTick{kTickMs};

void set_nonblocking(int fd) {
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL, 0) | O_NONBLOCK);
}

std::string peer_of(const sockaddr_storage& a) {
  std::array<char, INET6_ADDRSTRLEN> text{};
  if (a.ss_family == AF_INET6) {
    ::inet_ntop(AF_INET6, &reinterpret_cast<const sockaddr_in6&>(a).sin6_addr, text.data(),
                text.size());
  } else {
    ::inet_ntop(AF_INET, &reinterpret_cast<const sockaddr_in&>(a).sin_addr, text.data(),
                text.size());
  }
  return text.data();
}

std::string oversized(std::uint64_t announced) {
  return "a WebSocket frame of " + std::to_string(announced) +
         " bytes announced (the most read: " + std::to_string(kMaxFrameBytes) + ")";
}

int listen_on(const std::string& listen, int& port) {
  const std::string cannot =
      "mcnc-hmi: cannot listen on " + listen + " (address in use, or not an address of this host)";
  const std::size_t colon = listen.rfind(':');
  if (colon == std::string::npos) {
    throw std::runtime_error(cannot);
  }
  std::string host = listen.substr(0, colon);
  if (host.size() >= 2 && host.front() == '[' && host.back() == ']') {
    host = host.substr(1, host.size() - 2);
  }
  sockaddr_storage address{};
  socklen_t size = 0;
  int wanted = 0;
  try {
    wanted = std::stoi(listen.substr(colon + 1));
  } catch (const std::exception&) {
    throw std::runtime_error(cannot);
  }
  auto& v4 = reinterpret_cast<sockaddr_in&>(address);
  auto& v6 = reinterpret_cast<sockaddr_in6&>(address);
  if (::inet_pton(AF_INET, host.c_str(), &v4.sin_addr) == 1) {
    v4.sin_family = AF_INET;
    v4.sin_port = htons(static_cast<std::uint16_t>(wanted));
    size = sizeof(v4);
  } else if (::inet_pton(AF_INET6, host.c_str(), &v6.sin6_addr) == 1) {
    v6.sin6_family = AF_INET6;
    v6.sin6_port = htons(static_cast<std::uint16_t>(wanted));
    size = sizeof(v6);
  } else {
    throw std::runtime_error(cannot);
  }
  const int fd = ::socket(address.ss_family, SOCK_STREAM | SOCK_CLOEXEC, 0);
  const int yes = 1;
  ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&address), size) != 0 ||
      ::listen(fd, 256) != 0) {
    if (fd >= 0) {
      ::close(fd);
    }
    throw std::runtime_error(cannot);
  }
  set_nonblocking(fd);
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &size);
  port = ntohs(address.ss_family == AF_INET6 ? v6.sin6_port : v4.sin_port);
  return fd;
}

}  // namespace

struct ConnectionRelay::Connection {
  ConnectionId id = 0;
  int client = -1;
  int upstream = -1;
  int upstream_port = 0;
  std::string peer;
  std::string head;  // the request head, until the relay starts
  std::string to_upstream;
  std::string to_client;
  bool relaying = false;
  bool websocket = false;
  bool client_done = false;    // the client sent its end
  bool upstream_done = false;  // the web server sent its end
  bool upstream_shut = false;  // the client's end passed on
  FrameScanner frames;
};

ConnectionRelay::ConnectionRelay(const std::string& listen, int upstream_port, ConnectionRoom room)
    : upstream_port_(upstream_port), room_(std::move(room)) {
  listener_ = listen_on(listen, port_);
  if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) {
    ::close(listener_);
    throw std::runtime_error("mcnc-hmi: no pipe for the relay: " + std::string(strerror(errno)));
  }
  thread_ = std::thread([this] { loop(); });
}

ConnectionRelay::~ConnectionRelay() {
  stop_ = true;
  const char byte = 0;
  [[maybe_unused]] const auto n = ::write(wake_[1], &byte, 1);
  thread_.join();
  for (const auto& [id, c] : connections_) {
    ::close(c->client);
    if (c->upstream >= 0) {
      ::close(c->upstream);
    }
  }
  ::close(listener_);
  ::close(wake_[0]);
  ::close(wake_[1]);
}

bool ConnectionRelay::admitted_socket(int upstream_local_port) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ports_.count(upstream_local_port) != 0;
}

void ConnectionRelay::shown(int upstream_local_port, Role role) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = ports_.find(upstream_local_port);
  if (it != ports_.end()) {
    room_.shown(it->second, role);
  }
}

void ConnectionRelay::loop() {
  std::vector<pollfd> fds;
  std::vector<ConnectionId> owners;  // per entry of fds past the first two
  std::vector<Closing> closing;
  std::chrono::steady_clock::time_point last_due{};
  while (!stop_) {
    fds.clear();
    owners.clear();
    fds.push_back({listener_, POLLIN, 0});
    fds.push_back({wake_[0], POLLIN, 0});
    for (const auto& [id, c] : connections_) {
      short client_events = 0;
      if (!c->client_done && (c->relaying ? c->to_upstream.size() < kToUpstreamBytes : true)) {
        client_events |= POLLIN;
      }
      if (!c->to_client.empty()) {
        client_events |= POLLOUT;
      }
      fds.push_back({c->client, client_events, 0});
      owners.push_back(id);
      if (c->upstream >= 0) {
        short upstream_events = 0;
        if (!c->upstream_done && c->to_client.size() < kToClientBytes) {
          upstream_events |= POLLIN;
        }
        if (!c->to_upstream.empty()) {
          upstream_events |= POLLOUT;
        }
        fds.push_back({c->upstream, upstream_events, 0});
        owners.push_back(id);
      }
    }
    if (::poll(fds.data(), fds.size(), kTickMs) < 0 && errno != EINTR) {
      spdlog::error("HMI relay: poll: {}", strerror(errno));
      return;
    }
    if ((fds[0].revents & POLLIN) != 0) {
      accept_all();
    }
    closing.clear();
    for (std::size_t i = 2; i < fds.size(); ++i) {
      const auto it = connections_.find(owners[i - 2]);
      if (it == connections_.end() || fds[i].revents == 0) {
        continue;
      }
      Connection& c = *it->second;
      const bool is_client = fds[i].fd == c.client;
      std::optional<std::string> reason;
      if ((fds[i].revents & POLLOUT) != 0 &&
          !flush(fds[i].fd, is_client ? c.to_client : c.to_upstream)) {
        reason = "";
      }
      if (!reason && (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) != 0) {
        if (is_client) {
          reason = from_client(c);
        } else if (!from_upstream(c)) {
          reason = "";
        }
      }
      bool end = reason.has_value();
      if (!end && c.client_done && c.relaying && c.to_upstream.empty() && !c.upstream_shut) {
        // A page's client may end its side and wait for the answer; a socket's end is its close.
        end = c.websocket;
        ::shutdown(c.upstream, SHUT_WR);
        c.upstream_shut = true;
      }
      end = end || (c.client_done && !c.relaying) || (c.upstream_done && c.to_client.empty());
      if (end) {
        closing.push_back({c.id, reason.value_or("")});
      }
    }
    // The deadlines once a tick, not at every wake of a busy relay.
    if (const auto now = std::chrono::steady_clock::now(); now - last_due >= kTick) {
      last_due = now;
      std::lock_guard<std::mutex> lock(mutex_);
      for (Closing& c : room_.due(now)) {
        closing.push_back(std::move(c));
      }
    }
    for (const Closing& c : closing) {
      close(c.id, c.reason);
    }
  }
}

void ConnectionRelay::accept_all() {
  while (true) {
    sockaddr_storage address{};
    socklen_t size = sizeof(address);
    const int fd = ::accept4(listener_, reinterpret_cast<sockaddr*>(&address), &size,
                             SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd < 0) {
      if (errno == EMFILE || errno == ENFILE) {
        spdlog::warn("HMI relay: no file descriptor for a new connection");
      }
      return;
    }
    auto c = std::make_unique<Connection>();
    c->id = next_id_++;
    c->client = fd;
    c->peer = peer_of(address);
    Admission a;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      a = room_.arrive(c->id, c->peer, std::chrono::steady_clock::now());
    }
    for (const Closing& e : a.evictions) {
      close(e.id, e.reason);
    }
    if (!a.admitted) {
      spdlog::info("HMI connection from {} refused: {}", c->peer, a.refusal);
      ::close(fd);
      continue;
    }
    connections_.emplace(c->id, std::move(c));
  }
}

std::optional<std::string> ConnectionRelay::from_client(Connection& c) {
  std::array<char, 16384> buffer;
  const std::size_t room = c.relaying
                               ? kToUpstreamBytes - std::min(kToUpstreamBytes, c.to_upstream.size())
                               : buffer.size();
  const ssize_t n = ::read(c.client, buffer.data(), std::min(room, buffer.size()));
  if (n == 0) {
    c.client_done = true;
    return std::nullopt;
  }
  if (n < 0) {
    return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR
               ? std::nullopt
               : std::optional<std::string>("");
  }
  const std::string_view bytes(buffer.data(), static_cast<std::size_t>(n));
  {
    std::lock_guard<std::mutex> lock(mutex_);
    room_.heard(c.id, std::chrono::steady_clock::now());
  }
  if (!c.relaying) {
    c.head.append(bytes);
    const std::size_t end = request_head_end(c.head);
    if (end != std::string::npos) {
      return start_relay(c, end);
    }
    if (c.head.size() > kMaxRequestHeadBytes) {
      return "a request head longer than " + std::to_string(kMaxRequestHeadBytes) + " bytes";
    }
    return std::nullopt;
  }
  if (c.websocket) {
    if (const std::uint64_t announced = c.frames.scan(bytes); announced != 0) {
      return oversized(announced);
    }
  }
  c.to_upstream.append(bytes);
  return std::nullopt;
}

bool ConnectionRelay::from_upstream(Connection& c) {
  std::array<char, 16384> buffer;
  const ssize_t n = ::read(c.upstream, buffer.data(), buffer.size());
  if (n == 0) {
    c.upstream_done = true;
    return true;
  }
  if (n < 0) {
    return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
  }
  c.to_client.append(buffer.data(), static_cast<std::size_t>(n));
  return true;
}

bool ConnectionRelay::flush(int fd, std::string& pending) {
  while (!pending.empty()) {
    const ssize_t n = ::send(fd, pending.data(), pending.size(), MSG_NOSIGNAL);
    if (n < 0) {
      return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR;
    }
    pending.erase(0, static_cast<std::size_t>(n));
  }
  return true;
}

std::optional<std::string> ConnectionRelay::start_relay(Connection& c, std::size_t head_end) {
  c.websocket = asks_websocket(std::string_view(c.head).substr(0, head_end));
  Admission a;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    a = room_.request(c.id, c.websocket, std::chrono::steady_clock::now());
  }
  for (const Closing& e : a.evictions) {
    close(e.id, e.reason);
  }
  if (!a.admitted) {
    const std::string busy =
        "HTTP/1.1 503 Service Unavailable\r\nConnection: close\r\nContent-Length: 0\r\n\r\n";
    [[maybe_unused]] const auto n = ::send(c.client, busy.data(), busy.size(), MSG_NOSIGNAL);
    return a.refusal;
  }
  sockaddr_in upstream{};
  upstream.sin_family = AF_INET;
  upstream.sin_port = htons(static_cast<std::uint16_t>(upstream_port_));
  upstream.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  c.upstream = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  // On loopback the connection is made at once (the web server's backlog is 200).
  if (c.upstream < 0 ||
      ::connect(c.upstream, reinterpret_cast<sockaddr*>(&upstream), sizeof(upstream)) != 0) {
    return "the web server cannot be reached: " + std::string(strerror(errno));
  }
  set_nonblocking(c.upstream);
  sockaddr_in local{};
  socklen_t size = sizeof(local);
  ::getsockname(c.upstream, reinterpret_cast<sockaddr*>(&local), &size);
  c.upstream_port = ntohs(local.sin_port);
  if (c.websocket) {
    // Known before the web server reads the head: it admits only sockets relayed here.
    std::lock_guard<std::mutex> lock(mutex_);
    ports_[c.upstream_port] = c.id;
  }
  c.relaying = true;
  c.to_upstream = std::move(c.head);
  c.head.clear();
  if (c.websocket) {
    if (const std::uint64_t announced =
            c.frames.scan(std::string_view(c.to_upstream).substr(head_end));
        announced != 0) {
      return oversized(announced);
    }
  }
  return std::nullopt;
}

void ConnectionRelay::close(ConnectionId id, const std::string& reason) {
  const auto it = connections_.find(id);
  if (it == connections_.end()) {
    return;
  }
  Connection& c = *it->second;
  if (!reason.empty()) {
    spdlog::info("HMI connection from {} closed: {}", c.peer, reason);
  }
  ::close(c.client);
  if (c.upstream >= 0) {
    ::close(c.upstream);
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ports_.erase(c.upstream_port);
    room_.left(id);
  }
  connections_.erase(it);
}

}  // namespace mcnc::hmi
