#include "hmi_bridge/core/connection_room.hpp"

#include <algorithm>
#include <utility>

namespace mcnc::hmi {

namespace {

std::string in_words(std::chrono::milliseconds d) {
  const auto ms = d.count();
  return ms % 1000 == 0 ? std::to_string(ms / 1000) + " s" : std::to_string(ms) + " ms";
}

}  // namespace

ConnectionRoom::ConnectionRoom(RoomLimits limits, bool viewing_needs_token)
    : limits_(limits), viewing_needs_token_(viewing_needs_token) {
  // The reserve is part of the seats: at least one seat stays for viewers.
  limits_.seats = std::max<std::size_t>(limits_.seats, 2);
  limits_.reserve = std::min(limits_.reserve, limits_.seats - 1);
}

template <typename Pick>
bool ConnectionRoom::evict_oldest(Pick pick, const std::string& reason, std::vector<Closing>& out) {
  // The map is ordered by id: the first match is the oldest.
  const auto it = std::find_if(entries_.begin(), entries_.end(),
                               [&](const auto& kv) { return pick(kv.second); });
  if (it == entries_.end()) {
    return false;
  }
  out.push_back({it->first, reason});
  entries_.erase(it);
  return true;
}

Admission ConnectionRoom::arrive(ConnectionId id, const std::string& peer,
                                 std::chrono::steady_clock::time_point now) {
  Admission a;
  if (entries_.size() >= limits_.connections &&
      !evict_oldest([](const Entry& e) { return e.phase != Phase::socket; },
                    "made room for a newer connection", a.evictions)) {
    a.admitted = false;
    a.refusal = "the HMI holds " + std::to_string(entries_.size()) + " connections, its most";
    return a;
  }
  const auto of_peer = std::count_if(entries_.begin(), entries_.end(), [&](const auto& kv) {
    return kv.second.peer == peer && !is_operator(kv.second);
  });
  bool probation = false;
  if (static_cast<std::size_t>(of_peer) >= limits_.per_peer) {
    // Its share is full: a connection of its that has shown nothing makes room; when every
    // one has shown a token, the newcomer may still be the operator.
    probation =
        !evict_oldest([&](const Entry& e) { return e.peer == peer && e.shown == Role::none; },
                      "made room for a newer connection from " + peer, a.evictions);
  }
  Entry entry;
  entry.peer = peer;
  entry.probation = probation;
  entry.since = now;
  entry.heard = now;
  entries_.emplace(id, std::move(entry));
  return a;
}

Admission ConnectionRoom::request(ConnectionId id, bool websocket,
                                  std::chrono::steady_clock::time_point now) {
  Admission a;
  const auto it = entries_.find(id);
  if (it == entries_.end()) {
    a.admitted = false;
    a.refusal = "closed already";
    return a;
  }
  Entry& e = it->second;
  if (!websocket) {
    e.phase = Phase::page;
    e.since = now;
    return a;
  }
  std::size_t sockets = 0;
  std::size_t viewers = 0;  // sockets not the operator's
  for (const auto& [other, entry] : entries_) {
    if (entry.phase == Phase::socket) {
      ++sockets;
      viewers += is_operator(entry) ? 0 : 1;
    }
  }
  e.phase = Phase::socket;
  e.since = now;
  e.heard = now;
  e.probation = e.probation || viewers >= limits_.seats - limits_.reserve;
  if (sockets >= limits_.seats && !evict_oldest(
                                      [&](const Entry& o) {
                                        return o.phase == Phase::socket && o.probation &&
                                               !is_operator(o) && &o != &e;
                                      },
                                      "made room on a seat kept for the operator", a.evictions)) {
    entries_.erase(id);
    a.admitted = false;
    a.refusal = "every seat is taken by the operator";
  }
  return a;
}

void ConnectionRoom::shown(ConnectionId id, Role role) {
  const auto it = entries_.find(id);
  if (it == entries_.end() || role == Role::none) {
    return;
  }
  it->second.shown = role;
  if (role == Role::operator_) {
    it->second.probation = false;
  }
}

void ConnectionRoom::heard(ConnectionId id, std::chrono::steady_clock::time_point now) {
  const auto it = entries_.find(id);
  if (it != entries_.end()) {
    it->second.heard = now;
  }
}

void ConnectionRoom::left(ConnectionId id) {
  entries_.erase(id);
}

std::vector<Closing> ConnectionRoom::due(std::chrono::steady_clock::time_point now) {
  std::vector<Closing> out;
  for (auto it = entries_.begin(); it != entries_.end();) {
    const Entry& e = it->second;
    std::string reason;
    if (e.phase == Phase::head && now - e.since > limits_.head_within) {
      reason = "no request within " + in_words(limits_.head_within);
    } else if (e.phase == Phase::page && now - e.since > limits_.page_within) {
      reason = "a page not taken within " + in_words(limits_.page_within);
    } else if (e.phase == Phase::socket && e.probation && !is_operator(e) &&
               now - e.since > limits_.operator_within) {
      reason = "no operator token within " + in_words(limits_.operator_within) +
               " on a seat kept for the operator";
    } else if (e.phase == Phase::socket && viewing_needs_token_ && e.shown == Role::none &&
               now - e.since > limits_.token_within) {
      reason = "no token within " + in_words(limits_.token_within);
    } else if (e.phase == Phase::socket && now - e.heard > limits_.silent_within) {
      reason = "nothing heard for " + in_words(limits_.silent_within);
    }
    if (reason.empty()) {
      ++it;
    } else {
      out.push_back({it->first, std::move(reason)});
      it = entries_.erase(it);
    }
  }
  return out;
}

}  // namespace mcnc::hmi
