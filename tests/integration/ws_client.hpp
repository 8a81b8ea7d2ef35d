#pragma once
// A WebSocket client for the HMI tests (civetweb's client): connects to mcnc-hmi's /ws as a
// browser page of `origin` would (empty: no Origin header), keeps every text message it
// receives, sends text.
#include <nlohmann/json.hpp>

#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

struct mg_connection;

namespace mcnc::test {

class WsClient {
 public:
  // Connects; connected() says whether the server let it in.
  WsClient(const std::string& host, int port, const std::string& origin);
  ~WsClient();
  WsClient(const WsClient&) = delete;
  WsClient& operator=(const WsClient&) = delete;

  [[nodiscard]] bool connected() const { return conn_ != nullptr; }
  [[nodiscard]] const std::string& error() const { return error_; }
  bool send(const std::string& text);
  // The messages received so far, parsed (a message that is not JSON is kept as a string).
  std::vector<nlohmann::json> received();
  // Waits until a received message satisfies `pred`; that message, or null after `timeout`.
  nlohmann::json wait_for(const std::function<bool(const nlohmann::json&)>& pred,
                          std::chrono::milliseconds timeout);
  // The messages of that type received so far.
  std::vector<nlohmann::json> of_type(const std::string& type);

  // For the civetweb callback.
  void on_text(const char* data, std::size_t size);

 private:
  mg_connection* conn_ = nullptr;
  std::string error_;
  std::mutex mutex_;
  std::vector<nlohmann::json> received_;
};

}  // namespace mcnc::test
