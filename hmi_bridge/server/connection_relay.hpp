#pragma once
// The HMI's public listener. It takes every TCP connection itself, on one thread that waits on
// all of them, so that half-open and idle clients hold no web server thread; asks the
// ConnectionRoom whom to keep; and relays a connection to the web server (civetweb, on a
// loopback port of its own) only once its request head is complete. On a WebSocket it reads
// each frame's header on the way through and closes the connection when a frame announces more
// than kMaxFrameBytes: what a client announces is never allocated.
#include "hmi_bridge/core/access_policy.hpp"
#include "hmi_bridge/core/connection_room.hpp"

#include <atomic>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace mcnc::hmi {

class ConnectionRelay {
 public:
  // Listens on `listen` (IPADDRESS:PORT; port 0: any free one) and relays to 127.0.0.1:
  // `upstream_port`. Throws std::runtime_error when it cannot listen.
  ConnectionRelay(const std::string& listen, int upstream_port, ConnectionRoom room);
  ~ConnectionRelay();
  ConnectionRelay(const ConnectionRelay&) = delete;
  ConnectionRelay& operator=(const ConnectionRelay&) = delete;

  [[nodiscard]] int port() const noexcept { return port_; }
  // The web server's side of a connection, by the port its peer (this relay) has: whether it
  // is a WebSocket this relay admitted.
  [[nodiscard]] bool admitted_socket(int upstream_local_port) const;
  // That connection's client showed a token giving `role`.
  void shown(int upstream_local_port, Role role);

 private:
  struct Connection;
  void loop();
  void accept_all();
  // Each gives the reason to close the connection (empty: a quiet end), or nothing to keep it.
  std::optional<std::string> from_client(Connection& c);
  std::optional<std::string> start_relay(Connection& c, std::size_t head_end);
  // False when the connection is to close.
  bool from_upstream(Connection& c);
  static bool flush(int fd, std::string& pending);
  void close(ConnectionId id, const std::string& reason);

  int listener_ = -1;
  int port_ = 0;
  int upstream_port_ = 0;
  int wake_[2] = {-1, -1};  // the destructor's wake-up of the loop
  std::atomic<bool> stop_{false};
  mutable std::mutex mutex_;  // room_ and ports_: the web server's threads ask too
  ConnectionRoom room_;
  std::map<int, ConnectionId> ports_;  // upstream local port -> connection, for sockets
  std::map<ConnectionId, std::unique_ptr<Connection>> connections_;  // the loop's only
  ConnectionId next_id_ = 1;
  std::thread thread_;
};

}  // namespace mcnc::hmi
