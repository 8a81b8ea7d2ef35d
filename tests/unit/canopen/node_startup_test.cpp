// The master's start-up of one node against an SDO server: the order of what it writes, and a
// clear error naming the object when the node refuses or stays silent.
#include "canopen/cia402/node_startup.hpp"
#include "canopen/frames.hpp"
#include "canopen/sdo_abort.hpp"
#include "canopen/sdo_server.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace mcnc::canopen {
namespace {

// Accepts every write and records it; answers the device type; refuses one object if asked.
class RecordingDictionary final : public ObjectAccess {
 public:
  std::uint32_t read(std::uint16_t index, std::uint8_t sub, SdoValue& out) noexcept override {
    if (index == 0x1000 && sub == 0) {
      out.size = 4;
      out.bytes = {static_cast<std::uint8_t>(device_type),
                   static_cast<std::uint8_t>(device_type >> 8),
                   static_cast<std::uint8_t>(device_type >> 16),
                   static_cast<std::uint8_t>(device_type >> 24)};
      return 0;
    }
    return sdo_abort::kNoObject;
  }
  std::uint32_t write(std::uint16_t index, std::uint8_t sub, const std::uint8_t* data,
                      std::size_t size) noexcept override {
    if (index == refuse_index) {
      return refuse_code;
    }
    std::uint32_t v = 0;
    for (std::size_t i = 0; i < size; ++i) {
      v |= static_cast<std::uint32_t>(data[i]) << (8 * i);
    }
    writes.push_back({index, sub, v});
    return 0;
  }
  struct Write {
    std::uint16_t index;
    std::uint8_t sub;
    std::uint32_t value;
  };
  std::vector<Write> writes;
  std::uint32_t device_type = 0x00020192;
  std::uint16_t refuse_index = 0;
  std::uint32_t refuse_code = 0;
};

constexpr std::uint8_t kNode = 3;

can::CanFrame bootup() {
  return encode_heartbeat(kNode, NmtState::bootup);
}

// Runs the start-up against the dictionary behind an SDO server; a silent node answers
// nothing after its boot-up, and the bus loses the SDO requests numbered in `lost` (from 0;
// the master's aborts are not counted).
// Returns the frames the master sent.
std::vector<can::CanFrame> run_startup(NodeStartup& s, RecordingDictionary& od, bool silent,
                                       bool boots = true, const std::vector<int>& lost = {}) {
  SdoServer server(kNode, od);
  std::vector<can::CanFrame> sent;
  can::CanFrame out;
  std::uint64_t now = 0;
  s.begin(now, out);
  sent.push_back(out);
  std::vector<can::CanFrame> to_master;
  if (boots) {
    to_master.push_back(bootup());
  }
  int requests = 0;
  const auto to_node = [&](const can::CanFrame& frame) {
    sent.push_back(frame);
    if (frame.id != kSdoRequestBase + kNode || frame.data[0] == 0x80) {
      return;  // not a request, or the master's abort
    }
    const bool dropped = std::find(lost.begin(), lost.end(), requests++) != lost.end();
    can::CanFrame resp;
    if (!silent && !dropped && server.on_frame(frame, resp)) {
      to_master.push_back(resp);
    }
  };
  for (int step = 0; step < 100000 && s.status() == NodeStartup::Status::running; ++step) {
    now += 1000;
    if (!to_master.empty()) {
      const can::CanFrame in = to_master.front();
      to_master.erase(to_master.begin());
      if (s.on_frame(in, now, out)) {
        to_node(out);
      }
    } else if (s.on_time(now, out)) {
      to_node(out);
    }
  }
  return sent;
}

TEST(NodeStartup, ResetsChecksMapsSetsTheModeAndStarts) {
  RecordingDictionary od;
  NodeStartupConfig config{kNode};
  config.pdos = axis_pdos(false, true, false);  // with velocity actual in TPDO2
  NodeStartup s(config);
  const auto sent = run_startup(s, od, false);
  ASSERT_EQ(s.status(), NodeStartup::Status::done) << s.error();
  // NMT reset communication to node 3 first, NMT start last.
  EXPECT_EQ(sent.front().id, 0x000U);
  EXPECT_EQ(sent.front().data[0], 0x82);
  EXPECT_EQ(sent.front().data[1], kNode);
  EXPECT_EQ(sent.back().id, 0x000U);
  EXPECT_EQ(sent.back().data[0], 0x01);
  // The device type is read before anything is written.
  EXPECT_EQ(sent[1].id, 0x603U);
  EXPECT_EQ(sent[1].data[0], 0x40);
  EXPECT_EQ(sent[1].data[1], 0x00);
  EXPECT_EQ(sent[1].data[2], 0x10);
  // What the node got, in order: heartbeat time, RPDO1, TPDO1, TPDO2, then the mode.
  ASSERT_GE(od.writes.size(), 5U);
  EXPECT_EQ(od.writes.front().index, 0x1017);
  EXPECT_EQ(od.writes.front().value, 100U);
  EXPECT_EQ(od.writes[1].index, 0x1400);
  EXPECT_EQ(od.writes[1].value, 0x80000203U);
  EXPECT_EQ(od.writes.back().index, 0x6060);
  EXPECT_EQ(od.writes.back().value, 8U);
  std::size_t tpdo2_entries = 0;
  for (const auto& w : od.writes) {
    tpdo2_entries += (w.index == 0x1A01 && w.sub == 1 && w.value == 0x606C0020U) ? 1 : 0;
  }
  EXPECT_EQ(tpdo2_entries, 1U);
}

TEST(NodeStartup, AHomingAxisGetsItsMethodAndOffsetThenModeSix) {
  RecordingDictionary od;
  NodeStartupConfig config{kNode};
  config.pdos = homing_axis_pdos();
  config.mode = 6;
  config.homing_method = 37;
  config.home_offset = -5000;
  config.quick_stop_deceleration = 20000000;
  NodeStartup s(config);
  run_startup(s, od, false);
  ASSERT_EQ(s.status(), NodeStartup::Status::done) << s.error();
  ASSERT_GE(od.writes.size(), 3U);
  const auto n = od.writes.size();
  EXPECT_EQ(od.writes[n - 4].index, 0x6085);  // quick stop deceleration, counts/s^2
  EXPECT_EQ(od.writes[n - 4].value, 20000000U);
  EXPECT_EQ(od.writes[n - 3].index, 0x6098);
  EXPECT_EQ(od.writes[n - 3].value, 37U);
  EXPECT_EQ(od.writes[n - 2].index, 0x607C);
  EXPECT_EQ(od.writes[n - 2].value, static_cast<std::uint32_t>(-5000));
  EXPECT_EQ(od.writes[n - 1].index, 0x6060);
  EXPECT_EQ(od.writes[n - 1].value, 6U);
  // RPDO1 maps the modes of operation, TPDO1 its display.
  bool mode_in_rpdo = false;
  bool display_in_tpdo = false;
  for (const auto& w : od.writes) {
    mode_in_rpdo = mode_in_rpdo || (w.index == 0x1600 && w.value == 0x60600008U);
    display_in_tpdo = display_in_tpdo || (w.index == 0x1A00 && w.value == 0x60610008U);
  }
  EXPECT_TRUE(mode_in_rpdo);
  EXPECT_TRUE(display_in_tpdo);
}

TEST(NodeStartup, ARefusedWriteNamesTheObjectAndTheReason) {
  RecordingDictionary od;
  od.refuse_index = 0x6060;
  od.refuse_code = sdo_abort::kValueTooHigh;
  NodeStartup s(NodeStartupConfig{kNode});
  run_startup(s, od, false);
  ASSERT_EQ(s.status(), NodeStartup::Status::failed);
  EXPECT_EQ(s.abort_code(), sdo_abort::kValueTooHigh);
  EXPECT_EQ(std::string(s.error()),
            "node 3: writing 0x6060:00 (modes of operation) was refused: value of parameter "
            "written too high (SDO abort 0x06090031)");
}

TEST(NodeStartup, AWrongDeviceTypeIsNotConfigured) {
  RecordingDictionary od;
  od.device_type = 0x00000191;  // a CiA 401 I/O module
  NodeStartup s(NodeStartupConfig{kNode});
  run_startup(s, od, false);
  ASSERT_EQ(s.status(), NodeStartup::Status::failed);
  EXPECT_NE(std::string(s.error()).find("device type 0x1000 is 0x00000191"), std::string::npos);
  EXPECT_TRUE(od.writes.empty());
}

TEST(NodeStartup, SilenceAfterTheBootupTimesOutWithTheObject) {
  RecordingDictionary od;
  NodeStartup s(NodeStartupConfig{kNode});
  const auto sent = run_startup(s, od, true);
  ASSERT_EQ(s.status(), NodeStartup::Status::failed);
  EXPECT_EQ(std::string(s.error()),
            "node 3: reading 0x1000:00 (device type) failed: SDO protocol timed out (SDO abort "
            "0x05040000) 3 times");
  // Reset, then three times the request and its abort on the bus.
  ASSERT_EQ(sent.size(), 7U);
  for (std::size_t i = 1; i < sent.size(); i += 2) {
    EXPECT_EQ(sent[i].data[0], 0x40);      // initiate upload
    EXPECT_EQ(sent[i + 1].data[0], 0x80);  // abort
  }
}

TEST(NodeStartup, ALostRequestIsSentAgainAndTheStartupFinishes) {
  RecordingDictionary od;
  NodeStartup s(NodeStartupConfig{kNode});
  // The device-type read once, the first write twice, a later write once.
  const auto sent = run_startup(s, od, false, true, {0, 2, 3, 9});
  ASSERT_EQ(s.status(), NodeStartup::Status::done) << s.error();
  RecordingDictionary reference;
  NodeStartup clean(NodeStartupConfig{kNode});
  run_startup(clean, reference, false);
  ASSERT_EQ(od.writes.size(), reference.writes.size());  // each write landed once, in order
  for (std::size_t i = 0; i < od.writes.size(); ++i) {
    EXPECT_EQ(od.writes[i].index, reference.writes[i].index);
    EXPECT_EQ(od.writes[i].sub, reference.writes[i].sub);
    EXPECT_EQ(od.writes[i].value, reference.writes[i].value);
  }
}

TEST(NodeStartup, AWriteLostEveryTimeFailsNamingItAndTheTries) {
  RecordingDictionary od;
  NodeStartupConfig c{kNode};
  c.sdo_attempts = 2;
  NodeStartup s(c);
  // Request 0 reads the device type, 1 writes the heartbeat time, 2 is its retry.
  run_startup(s, od, false, true, {1, 2});
  ASSERT_EQ(s.status(), NodeStartup::Status::failed);
  EXPECT_EQ(std::string(s.error()),
            "node 3: writing 0x1017:00 (producer heartbeat time) failed: SDO protocol timed out "
            "(SDO abort 0x05040000) 2 times");
}

TEST(NodeStartup, NoBootupRetriesTheResetThenFails) {
  RecordingDictionary od;
  NodeStartupConfig c{kNode};
  c.bootup_attempts = 3;
  NodeStartup s(c);
  const auto sent = run_startup(s, od, false, /*boots=*/false);
  ASSERT_EQ(s.status(), NodeStartup::Status::failed);
  EXPECT_EQ(sent.size(), 3U);  // three resets of communication
  for (const auto& f : sent) {
    EXPECT_EQ(f.data[0], 0x82);
  }
  EXPECT_EQ(std::string(s.error()), "node 3: no boot-up after 3 NMT resets of communication");
}

}  // namespace
}  // namespace mcnc::canopen
