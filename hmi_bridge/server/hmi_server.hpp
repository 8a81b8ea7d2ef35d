#pragma once
// mcnc-hmi's web server (civetweb): the static HMI from a folder, and one WebSocket at /ws that
// carries the protocol of docs/hmi.md. Clients reach it only through the ConnectionRelay on the
// listen address (civetweb itself listens on a loopback port of its own), which keeps room for
// the operator. A connection starts with AccessPolicy's initial role and changes it with an
// auth message; commands need the operator role; an upgrade from a foreign Origin is refused
// before the socket opens. Every browser that views gets the state at `rate` per second and the
// news (alarms, programs) as they come.
#include "common/config/machine_config.hpp"
#include "hmi_bridge/core/access_policy.hpp"
#include "hmi_bridge/core/connection_room.hpp"
#include "hmi_bridge/server/connection_relay.hpp"
#include "hmi_bridge/server/machine_feed.hpp"

#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

struct mg_context;
struct mg_connection;

namespace mcnc::hmi {

struct HmiServerConfig {
  std::string listen = "127.0.0.1:8080";   // HOST:PORT
  std::string web_dir;                     // the static files
  std::vector<std::string> extra_origins;  // besides the listen address's own
  double rate_hz = 25.0;                   // state messages per second
  RoomLimits room;                         // who keeps a connection
};

struct HmiCounters {
  std::uint64_t malformed = 0;  // messages answered with an error
  std::uint64_t refused = 0;    // commands refused (role, not supported)
  std::uint64_t commands = 0;   // commands sent
  std::uint64_t origin_refused = 0;
};

class HmiServer {
 public:
  // Throws std::runtime_error when it cannot listen (start-up error).
  HmiServer(HmiServerConfig config, const config::MachineConfig& machine, AccessPolicy access,
            MachineFeed& feed);
  ~HmiServer();
  HmiServer(const HmiServer&) = delete;
  HmiServer& operator=(const HmiServer&) = delete;

  // The address browsers open, http://HOST:PORT/ (the port the server got).
  [[nodiscard]] std::string address() const;
  [[nodiscard]] HmiCounters counters() const;

  // civetweb's callbacks (public for the C trampolines only).
  int on_connect(const mg_connection* conn);
  void on_ready(mg_connection* conn);
  int on_data(mg_connection* conn, int bits, const char* data, std::size_t size);
  void on_close(const mg_connection* conn);

 private:
  // One WebSocket. Its writes go one at a time under `write`, never under mutex_, so that a
  // client that stops reading holds up only itself. The close handler clears `open` under
  // `write`: nothing is written to the connection once civetweb frees it.
  struct Client {
    mg_connection* conn = nullptr;
    std::mutex write;
    bool open = true;        // under write
    Role role = Role::none;  // under write
    int relay_port = 0;      // the relay's end of it: how the relay knows it
  };
  [[nodiscard]] std::shared_ptr<Client> client_of(const mg_connection* conn) const;
  // Writes `text` unless the client closed; the caller holds client.write.
  static void write_locked(Client& client, const std::string& text);
  void send(Client& client, const std::string& text);
  // False when the connection is to be closed (a wrong token).
  bool handle_text(Client& client, std::string_view text);
  void set_role(Client& client, Role role);
  void count(std::uint64_t HmiCounters::*counter);
  void publish_loop();

  HmiServerConfig config_;
  const config::MachineConfig& machine_;
  AccessPolicy access_;
  MachineFeed& feed_;
  std::vector<std::string> origins_;
  mg_context* ctx_ = nullptr;
  std::unique_ptr<ConnectionRelay> relay_;
  mutable std::mutex mutex_;  // clients_ and counters_
  std::map<const mg_connection*, std::shared_ptr<Client>> clients_;
  HmiCounters counters_;
  std::atomic<bool> stop_{false};
  std::thread publisher_;
};

}  // namespace mcnc::hmi
