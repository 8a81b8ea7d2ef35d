#include "ws_client.hpp"

#include <civetweb.h>

#include <thread>

namespace mcnc::test {

namespace {

int on_data(mg_connection* /*conn*/, int bits, char* data, size_t size, void* user) {
  if ((bits & 0x0f) == MG_WEBSOCKET_OPCODE_TEXT) {
    static_cast<WsClient*>(user)->on_text(data, size);
  }
  return 1;
}

}  // namespace

WsClient::WsClient(const std::string& host, int port, const std::string& origin) {
  mg_init_library(0);
  char error[256] = {};
  conn_ = mg_connect_websocket_client(host.c_str(), port, 0, error, sizeof error, "/ws",
                                      origin.empty() ? nullptr : origin.c_str(), on_data, nullptr,
                                      this);
  error_ = error;
}

WsClient::~WsClient() {
  if (conn_ != nullptr) {
    mg_close_connection(conn_);
  }
}

bool WsClient::send(const std::string& text) {
  return conn_ != nullptr &&
         mg_websocket_client_write(conn_, MG_WEBSOCKET_OPCODE_TEXT, text.data(), text.size()) > 0;
}

void WsClient::on_text(const char* data, std::size_t size) {
  nlohmann::json j = nlohmann::json::parse(data, data + size, nullptr, false);
  std::lock_guard<std::mutex> lock(mutex_);
  received_.push_back(j.is_discarded() ? nlohmann::json(std::string(data, size)) : j);
}

std::vector<nlohmann::json> WsClient::received() {
  std::lock_guard<std::mutex> lock(mutex_);
  return received_;
}

std::vector<nlohmann::json> WsClient::of_type(const std::string& type) {
  std::vector<nlohmann::json> out;
  for (const nlohmann::json& j : received()) {
    if (j.is_object() && j.value("type", "") == type) {
      out.push_back(j);
    }
  }
  return out;
}

nlohmann::json WsClient::wait_for(const std::function<bool(const nlohmann::json&)>& pred,
                                  std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  std::size_t seen = 0;
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (; seen < received_.size(); ++seen) {
        if (pred(received_[seen])) {
          return received_[seen];
        }
      }
    }
    if (std::chrono::steady_clock::now() > deadline) {
      return nullptr;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

}  // namespace mcnc::test
