#include "hmi_bridge/server/hmi_server.hpp"

#include "common/config/cyclic_routes.hpp"

#include "hmi_bridge/core/client_message.hpp"
#include "hmi_bridge/core/hmi_messages.hpp"

#include <civetweb.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <variant>

namespace mcnc::hmi {

namespace {

HmiServer& server_of(void* cbdata) {
  return *static_cast<HmiServer*>(cbdata);
}

int connect_trampoline(const mg_connection* conn, void* cbdata) {
  return server_of(cbdata).on_connect(conn);
}
void ready_trampoline(mg_connection* conn, void* cbdata) {
  server_of(cbdata).on_ready(conn);
}
int data_trampoline(mg_connection* conn, int bits, char* data, size_t size, void* cbdata) {
  return server_of(cbdata).on_data(conn, bits, data, size);
}
void close_trampoline(const mg_connection* conn, void* cbdata) {
  server_of(cbdata).on_close(conn);
}

int log_trampoline(const mg_connection* /*conn*/, const char* message) {
  spdlog::debug("civetweb: {}", message);
  return 1;  // logged here; civetweb prints nothing itself
}

}  // namespace

HmiServer::HmiServer(HmiServerConfig config, const config::MachineConfig& machine,
                     AccessPolicy access, MachineFeed& feed)
    : config_(std::move(config)),
      machine_(machine),
      access_(std::move(access)),
      feed_(feed),
      origins_(allowed_origins(config_.listen, config_.extra_origins)) {
  mg_init_library(0);
  // Each open WebSocket holds a thread; two stay for the pages' files.
  const std::string threads = std::to_string(config_.room.seats + 2);
  // The page only talks to its own server, and is never framed by another site's.
  const std::string headers =
      "Content-Security-Policy: default-src 'self'; connect-src 'self'; img-src 'self' data:\r\n"
      "X-Frame-Options: DENY\r\n"
      "X-Content-Type-Options: nosniff";
  // A write to a client that stopped reading gives up after request_timeout_ms, and the
  // client goes; a browser that only listens answers civetweb's pings, and stays.
  // Only the relay connects to it (on_connect refuses a socket the relay did not admit).
  const char* options[] = {"listening_ports",
                           "127.0.0.1:0",
                           "document_root",
                           config_.web_dir.c_str(),
                           "num_threads",
                           threads.c_str(),
                           "enable_directory_listing",
                           "no",
                           "additional_header",
                           headers.c_str(),
                           "request_timeout_ms",
                           "5000",
                           "websocket_timeout_ms",
                           "30000",
                           "enable_websocket_ping_pong",
                           "yes",
                           nullptr};
  mg_callbacks callbacks{};
  callbacks.log_message = log_trampoline;
  ctx_ = mg_start(&callbacks, this, options);
  mg_server_port ports[4] = {};
  if (ctx_ == nullptr || mg_get_server_ports(ctx_, 4, ports) < 1) {
    if (ctx_ != nullptr) {
      mg_stop(ctx_);
    }
    mg_exit_library();
    throw std::runtime_error("mcnc-hmi: cannot start its web server on a loopback port");
  }
  try {
    relay_ = std::make_unique<ConnectionRelay>(
        config_.listen, ports[0].port,
        ConnectionRoom(config_.room, access_.initial_role() == Role::none));
  } catch (const std::exception&) {
    mg_stop(ctx_);
    mg_exit_library();
    throw;
  }
  // Set once the relay is there: a socket's handler asks it.
  mg_set_websocket_handler(ctx_, "/ws", connect_trampoline, ready_trampoline, data_trampoline,
                           close_trampoline, this);
  if (config_.listen.ends_with(":0")) {
    // A port chosen by the system: the page's own origin has that port.
    const std::string host = config_.listen.substr(0, config_.listen.size() - 2);
    origins_ = allowed_origins(host + ":" + std::to_string(relay_->port()), config_.extra_origins);
  }
  publisher_ = std::thread([this] { publish_loop(); });
}

HmiServer::~HmiServer() {
  stop_ = true;
  if (publisher_.joinable()) {
    publisher_.join();
  }
  mg_stop(ctx_);
  relay_.reset();  // after civetweb: its handlers ask the relay
  mg_exit_library();
}

std::string HmiServer::address() const {
  const std::size_t colon = config_.listen.rfind(':');
  return "http://" + config_.listen.substr(0, colon) + ":" + std::to_string(relay_->port()) + "/";
}

HmiCounters HmiServer::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

int HmiServer::on_connect(const mg_connection* conn) {
  const mg_request_info* request = mg_get_request_info(conn);
  if (request == nullptr || !relay_->admitted_socket(request->remote_port)) {
    spdlog::warn("WebSocket refused: it did not come through the HMI's listen address");
    return 1;  // the relay keeps the room; nothing else may take a seat
  }
  const char* origin = mg_get_header(conn, "Origin");
  std::lock_guard<std::mutex> lock(mutex_);
  if (!origin_allowed(origin != nullptr ? origin : "", origins_)) {
    ++counters_.origin_refused;
    spdlog::warn("WebSocket from origin {} refused (allowed: this server's own pages)", origin);
    return 1;  // closed before the handshake
  }
  return 0;
}

std::shared_ptr<HmiServer::Client> HmiServer::client_of(const mg_connection* conn) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = clients_.find(conn);
  return it == clients_.end() ? nullptr : it->second;
}

void HmiServer::on_ready(mg_connection* conn) {
  auto client = std::make_shared<Client>();
  client->conn = conn;
  const mg_request_info* request = mg_get_request_info(conn);
  client->relay_port = request != nullptr ? request->remote_port : 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    clients_[conn] = client;
  }
  set_role(*client, access_.initial_role());
}

void HmiServer::set_role(Client& client, Role role) {
  // Under the client's write lock: the publisher sends it nothing until its welcome is out.
  std::lock_guard<std::mutex> lock(client.write);
  const Role before = client.role;
  client.role = role;
  write_locked(client, role_message(role));
  if (before == Role::none && role != Role::none) {
    // It starts to see: the layout, the alarm history and the programs, then the states.
    write_locked(client, machine_message(machine_));
    for (const std::string& m : feed_.welcome()) {
      write_locked(client, m);
    }
  }
}

void HmiServer::on_close(const mg_connection* conn) {
  const std::shared_ptr<Client> client = client_of(conn);
  if (client) {
    std::lock_guard<std::mutex> lock(client->write);  // waits for a write under way
    client->open = false;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  clients_.erase(conn);
}

void HmiServer::write_locked(Client& client, const std::string& text) {
  if (client.open) {
    mg_websocket_write(client.conn, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size());
  }
}

void HmiServer::send(Client& client, const std::string& text) {
  std::lock_guard<std::mutex> lock(client.write);
  write_locked(client, text);
}

void HmiServer::count(std::uint64_t HmiCounters::*counter) {
  std::lock_guard<std::mutex> lock(mutex_);
  ++(counters_.*counter);
}

int HmiServer::on_data(mg_connection* conn, int bits, const char* data, std::size_t size) {
  const std::shared_ptr<Client> client = client_of(conn);
  if (!client) {
    return 0;
  }
  const int opcode = bits & 0x0f;
  const bool final_frame = (bits & 0x80) != 0;
  switch (opcode) {
    case MG_WEBSOCKET_OPCODE_CONNECTION_CLOSE:
      return 0;
    case MG_WEBSOCKET_OPCODE_PING: {
      std::lock_guard<std::mutex> lock(client->write);
      mg_websocket_write(conn, MG_WEBSOCKET_OPCODE_PONG, data, size);
      return 1;
    }
    case MG_WEBSOCKET_OPCODE_PONG:
      return 1;
    case MG_WEBSOCKET_OPCODE_TEXT:
      if (final_frame) {
        return handle_text(*client, std::string_view(data, size)) ? 1 : 0;
      }
      break;
    default:
      break;
  }
  count(&HmiCounters::malformed);
  send(*client, error_message("only whole text messages are read"));
  return 1;
}

bool HmiServer::handle_text(Client& client, std::string_view text) {
  const ClientMessage message = read_client_message(text, machine_);
  if (const auto* e = std::get_if<MessageError>(&message)) {
    count(&HmiCounters::malformed);
    send(client, e->id >= 0 ? reply_message(e->id, false, e->reason) : error_message(e->reason));
    return true;
  }
  if (const auto* auth = std::get_if<AuthMessage>(&message)) {
    const Role role = access_.role_of(auth->token);
    if (role == Role::none) {
      send(client, error_message("unknown token"));
      return false;  // closed: every guess costs a new connection
    }
    relay_->shown(client.relay_port, role);  // a token shown: the relay keeps its seat
    set_role(client, role);
    return true;
  }
  const auto& command = std::get<CommandMessage>(message);
  Role role = Role::none;
  {
    std::lock_guard<std::mutex> lock(client.write);
    role = client.role;
  }
  CommandRefusal refusal;
  if (role != Role::operator_) {
    refusal.reason = role == Role::viewer ? "a viewer cannot command: show the operator token"
                                          : "commands need the operator token";
  }
  if (refusal.reason.empty() && feed_.send(command, refusal)) {
    count(&HmiCounters::commands);
    spdlog::info("operator command {} {}", process::to_string(command.action),
                 command.channel == 0 ? std::string("(machine)")
                                      : config::channel_name(machine_, command.channel));
    send(client, reply_message(command.id, true, ""));
    return true;
  }
  count(&HmiCounters::refused);
  if (!refusal.code.empty()) {
    spdlog::warn("operator command {} {}", process::to_string(command.action), refusal.reason);
  }
  send(client, reply_message(command.id, false, refusal.reason, refusal.code, refusal.process));
  return true;
}

void HmiServer::publish_loop() {
  const auto period = std::chrono::duration_cast<std::chrono::steady_clock::duration>(
      std::chrono::duration<double>(1.0 / config_.rate_hz));
  auto next = std::chrono::steady_clock::now();
  std::vector<std::shared_ptr<Client>> clients;
  while (!stop_) {
    // After a stall, the next state on time rather than the missed ones in a burst.
    next = std::max(next + period, std::chrono::steady_clock::now());
    std::this_thread::sleep_until(next);
    const std::string state = feed_.state();
    const std::vector<std::string> news = feed_.take_news();
    {
      std::lock_guard<std::mutex> lock(mutex_);
      clients.clear();
      for (const auto& [conn, client] : clients_) {
        clients.push_back(client);
      }
    }
    for (const std::shared_ptr<Client>& client : clients) {
      std::lock_guard<std::mutex> lock(client->write);
      if (client->role == Role::none) {
        continue;  // the relay closes it when no token comes in time
      }
      for (const std::string& m : news) {
        write_locked(*client, m);
      }
      write_locked(*client, state);
    }
  }
}

}  // namespace mcnc::hmi
