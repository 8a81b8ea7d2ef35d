#pragma once
// Who keeps a connection to the HMI (docs/hmi.md, Security): the operator always gets in,
// however many viewers are connected or half-connected. Every connection must send its request
// within a deadline; one peer keeps a bounded share; the WebSocket seats keep a reserve that
// only the operator may hold; sockets that show no token, or fall silent, are closed. Pure: the
// relay in front of the web server tells it what happens and closes what it names.
#include "hmi_bridge/core/access_policy.hpp"

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mcnc::hmi {

struct RoomLimits {
  std::size_t connections = 256;  // open at once in all (each a file descriptor)
  std::size_t per_peer = 8;       // of one peer address, the operator's not counted
  std::size_t seats = 14;         // WebSockets at once (each holds a web server thread)
  std::size_t reserve = 2;        // of the seats, held only by the operator
  std::chrono::milliseconds head_within{2000};      // the whole request head
  std::chrono::milliseconds token_within{10000};    // a token, where viewing needs one
  std::chrono::milliseconds operator_within{2000};  // the operator token, on probation
  std::chrono::milliseconds silent_within{65000};   // nothing from a WebSocket's client
  std::chrono::milliseconds page_within{30000};     // a page's request, answered and read
};

using ConnectionId = std::uint64_t;  // increasing: a smaller one is older

struct Closing {
  ConnectionId id = 0;
  std::string reason;
};

struct Admission {
  bool admitted = true;
  std::string refusal;             // why not, when not admitted
  std::vector<Closing> evictions;  // older connections closed to make room
};

class ConnectionRoom {
 public:
  // `viewing_needs_token`: a socket that has shown no token sees nothing (a viewer token is
  // configured), and is closed after token_within.
  ConnectionRoom(RoomLimits limits, bool viewing_needs_token);

  // A TCP connection from `peer` (its address) was accepted. At `connections` in all the oldest
  // that is not a WebSocket makes room, else it is refused. A peer at its share evicts its
  // oldest connection that has shown no token, or is put on probation: it may fetch pages,
  // and keeps a WebSocket only by showing the operator token within operator_within.
  Admission arrive(ConnectionId id, const std::string& peer,
                   std::chrono::steady_clock::time_point now);
  // Its request head is complete; `websocket`: it asks for the WebSocket. Beyond the viewers'
  // share of the seats a socket is on probation; with every seat taken, the oldest socket on
  // probation makes room, or the request is refused.
  Admission request(ConnectionId id, bool websocket, std::chrono::steady_clock::time_point now);
  // The socket showed a token that gave `role`.
  void shown(ConnectionId id, Role role);
  // Bytes came from the client.
  void heard(ConnectionId id, std::chrono::steady_clock::time_point now);
  // The connection closed.
  void left(ConnectionId id);
  // Connections past a deadline, forgotten here; the caller closes them.
  std::vector<Closing> due(std::chrono::steady_clock::time_point now);

  [[nodiscard]] std::size_t open() const noexcept { return entries_.size(); }

 private:
  enum class Phase : std::uint8_t { head, page, socket };
  struct Entry {
    std::string peer;
    Phase phase = Phase::head;
    Role shown = Role::none;  // the role its token gave; none before a token
    bool probation = false;
    std::chrono::steady_clock::time_point since;  // arrival, or the socket's opening
    std::chrono::steady_clock::time_point heard;
  };
  [[nodiscard]] bool is_operator(const Entry& e) const noexcept {
    return e.shown == Role::operator_;
  }
  // The oldest connection matching `pick`, removed into `out` with `reason`; false if none.
  template <typename Pick>
  bool evict_oldest(Pick pick, const std::string& reason, std::vector<Closing>& out);

  RoomLimits limits_;
  bool viewing_needs_token_;
  std::map<ConnectionId, Entry> entries_;
};

}  // namespace mcnc::hmi
