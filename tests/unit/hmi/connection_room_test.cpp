#include "hmi_bridge/core/connection_room.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace mcnc::hmi {
namespace {

using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

const Clock::time_point t0{};

std::vector<ConnectionId> ids(const std::vector<Closing>& closings) {
  std::vector<ConnectionId> out;
  for (const Closing& c : closings) {
    out.push_back(c.id);
  }
  return out;
}

// A socket from `peer` admitted at `now` (arrived and asked for the WebSocket).
Admission socket(ConnectionRoom& room, ConnectionId id, const std::string& peer,
                 Clock::time_point now = t0) {
  Admission a = room.arrive(id, peer, now);
  if (!a.admitted) {
    return a;
  }
  Admission b = room.request(id, true, now);
  b.evictions.insert(b.evictions.begin(), a.evictions.begin(), a.evictions.end());
  return b;
}

std::string peer(int i) {
  return "10.0.0." + std::to_string(i);
}

TEST(ConnectionRoom, ConnectionsThatSendNoRequestAreClosedAfterTheHeadDeadline) {
  ConnectionRoom room(RoomLimits{}, false);
  for (ConnectionId id = 1; id <= 50; ++id) {
    ASSERT_TRUE(room.arrive(id, peer(static_cast<int>(id)), t0).admitted);
  }
  ASSERT_TRUE(room.request(7, false, t0).admitted);  // a page: no deadline of the room's
  EXPECT_TRUE(room.due(t0 + 2s).empty());
  const std::vector<Closing> closed = room.due(t0 + 2s + 1ms);
  ASSERT_EQ(closed.size(), 49U);
  EXPECT_EQ(closed[0].reason, "no request within 2 s");
  const std::vector<ConnectionId> closed_ids = ids(closed);
  EXPECT_EQ(std::count(closed_ids.begin(), closed_ids.end(), 7U), 0);
  EXPECT_EQ(room.open(), 1U);
  EXPECT_TRUE(room.due(t0 + 10s).empty());  // each named once
  // The page's answer must be taken within 30 s.
  const std::vector<Closing> page = room.due(t0 + 30001ms);
  ASSERT_EQ(ids(page), (std::vector<ConnectionId>{7}));
  EXPECT_EQ(page[0].reason, "a page not taken within 30 s");
}

TEST(ConnectionRoom, APeerAtItsShareMakesRoomFromItsOldestConnectionThatShowedNothing) {
  ConnectionRoom room(RoomLimits{}, false);  // 8 a peer
  for (ConnectionId id = 1; id <= 8; ++id) {
    ASSERT_TRUE(socket(room, id, "10.0.0.1").evictions.empty());
  }
  room.shown(1, Role::viewer);
  // The ninth pushes out the oldest that never showed a token: 2, not the viewer 1.
  const Admission ninth = room.arrive(9, "10.0.0.1", t0 + 1s);
  ASSERT_TRUE(ninth.admitted);
  ASSERT_EQ(ids(ninth.evictions), (std::vector<ConnectionId>{2}));
  EXPECT_EQ(ninth.evictions[0].reason, "made room for a newer connection from 10.0.0.1");
  // Another peer is not touched by this one's share.
  EXPECT_TRUE(socket(room, 10, "10.0.0.2").evictions.empty());
}

TEST(ConnectionRoom, APeerWhoseConnectionsAllShowedATokenGetsOnlyAProbationSeat) {
  ConnectionRoom room(RoomLimits{}, true);
  for (ConnectionId id = 1; id <= 8; ++id) {
    ASSERT_TRUE(socket(room, id, "10.0.0.1").admitted);
    room.shown(id, Role::viewer);
  }
  const Admission ninth = socket(room, 9, "10.0.0.1", t0 + 1s);
  ASSERT_TRUE(ninth.admitted);
  EXPECT_TRUE(ninth.evictions.empty());
  // Not the operator within 2 s: closed; the viewers stay.
  const std::vector<Closing> closed = room.due(t0 + 3s + 1ms);
  ASSERT_EQ(ids(closed), (std::vector<ConnectionId>{9}));
  EXPECT_EQ(closed[0].reason, "no operator token within 2 s on a seat kept for the operator");
  // The operator on probation is kept, and does not count against its peer's share.
  ASSERT_TRUE(socket(room, 10, "10.0.0.1", t0 + 4s).admitted);
  room.shown(10, Role::operator_);
  EXPECT_TRUE(room.due(t0 + 9s).empty());
  EXPECT_EQ(room.open(), 9U);
}

TEST(ConnectionRoom, ViewersNeverTakeTheReservedSeatsAndTheOperatorAlwaysGetsOne) {
  RoomLimits limits;
  limits.per_peer = 100;
  ConnectionRoom room(limits, false);  // 14 seats, 2 kept
  for (ConnectionId id = 1; id <= 12; ++id) {
    ASSERT_TRUE(socket(room, id, peer(static_cast<int>(id))).admitted);
    room.shown(id, Role::viewer);
  }
  // Seats 13 and 14 are on probation; a fifteenth pushes out the oldest of them.
  ASSERT_TRUE(socket(room, 13, "10.0.1.13", t0 + 100ms).evictions.empty());
  ASSERT_TRUE(socket(room, 14, "10.0.1.14", t0 + 200ms).evictions.empty());
  const Admission fifteenth = socket(room, 15, "10.0.1.15", t0 + 300ms);
  ASSERT_TRUE(fifteenth.admitted);
  ASSERT_EQ(ids(fifteenth.evictions), (std::vector<ConnectionId>{13}));
  EXPECT_EQ(fifteenth.evictions[0].reason, "made room on a seat kept for the operator");
  // A viewer's token does not keep a reserved seat.
  room.shown(14, Role::viewer);
  room.shown(15, Role::operator_);
  EXPECT_EQ(ids(room.due(t0 + 2300ms)), (std::vector<ConnectionId>{14}));
  // The operator keeps its seat; the viewers theirs.
  EXPECT_TRUE(room.due(t0 + 60s).empty());
  EXPECT_EQ(room.open(), 13U);
}

TEST(ConnectionRoom, WithEverySeatTheOperatorsANewSocketIsRefused) {
  RoomLimits limits;
  limits.seats = 3;
  limits.reserve = 1;
  ConnectionRoom room(limits, false);
  for (ConnectionId id = 1; id <= 3; ++id) {
    ASSERT_TRUE(socket(room, id, "10.0.0.1").admitted);
    room.shown(id, Role::operator_);
  }
  const Admission fourth = socket(room, 4, "10.0.0.1");
  EXPECT_FALSE(fourth.admitted);
  EXPECT_EQ(fourth.refusal, "every seat is taken by the operator");
  EXPECT_EQ(room.open(), 3U);
  // A page is still served.
  ASSERT_TRUE(room.arrive(5, "10.0.0.1", t0).admitted);
  EXPECT_TRUE(room.request(5, false, t0).admitted);
}

TEST(ConnectionRoom, ASocketWithoutATokenIsClosedOnlyWhereViewingNeedsOne) {
  ConnectionRoom open_view(RoomLimits{}, false);
  ConnectionRoom closed_view(RoomLimits{}, true);
  for (ConnectionRoom* room : {&open_view, &closed_view}) {
    ASSERT_TRUE(socket(*room, 1, "10.0.0.1").admitted);
    room->heard(1, t0 + 9s);
  }
  EXPECT_TRUE(open_view.due(t0 + 10001ms).empty());
  const std::vector<Closing> closed = closed_view.due(t0 + 10001ms);
  ASSERT_EQ(ids(closed), (std::vector<ConnectionId>{1}));
  EXPECT_EQ(closed[0].reason, "no token within 10 s");
}

TEST(ConnectionRoom, ASilentSocketIsClosedEvenTheOperatorsAndHearingKeepsItOpen) {
  ConnectionRoom room(RoomLimits{}, false);
  ASSERT_TRUE(socket(room, 1, "10.0.0.1").admitted);
  ASSERT_TRUE(socket(room, 2, "10.0.0.2").admitted);
  room.shown(1, Role::operator_);
  room.heard(2, t0 + 60s);
  const std::vector<Closing> closed = room.due(t0 + 65001ms);
  ASSERT_EQ(ids(closed), (std::vector<ConnectionId>{1}));
  EXPECT_EQ(closed[0].reason, "nothing heard for 65 s");
  EXPECT_EQ(ids(room.due(t0 + 125001ms)), (std::vector<ConnectionId>{2}));
}

TEST(ConnectionRoom, AtItsMostConnectionsTheOldestWithoutARequestMakesRoom) {
  RoomLimits limits;
  limits.connections = 3;
  ConnectionRoom room(limits, false);
  ASSERT_TRUE(socket(room, 1, "10.0.0.1").admitted);
  ASSERT_TRUE(room.arrive(2, "10.0.0.2", t0).admitted);
  ASSERT_TRUE(room.arrive(3, "10.0.0.3", t0).admitted);
  const Admission fourth = room.arrive(4, "10.0.0.4", t0);
  ASSERT_TRUE(fourth.admitted);
  EXPECT_EQ(ids(fourth.evictions), (std::vector<ConnectionId>{2}));
  ASSERT_TRUE(room.request(3, true, t0).admitted);
  ASSERT_TRUE(room.request(4, true, t0).admitted);
  const Admission fifth = room.arrive(5, "10.0.0.5", t0);
  EXPECT_FALSE(fifth.admitted);
  EXPECT_EQ(fifth.refusal, "the HMI holds 3 connections, its most");
}

}  // namespace
}  // namespace mcnc::hmi
