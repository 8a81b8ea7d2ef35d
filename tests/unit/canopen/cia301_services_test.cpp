// Heartbeat, EMCY codes and PDO mapping, against what CiA 301 / CiA 402 specify.
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/emcy_codes.hpp"
#include "canopen/heartbeat.hpp"
#include "canopen/sdo_client.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mcnc::canopen {
namespace {

can::CanFrame heartbeat_frame(std::uint8_t node, std::uint8_t state, std::uint8_t dlc = 1) {
  can::CanFrame f;
  f.id = 0x700U + node;
  f.dlc = dlc;
  f.data[0] = state;
  return f;
}

TEST(Heartbeat, ConsumerReportsBootupHeardAndLostOnce) {
  HeartbeatConsumer c(4, 100000);                                // 100 ms
  EXPECT_EQ(c.on_time(500000), HeartbeatConsumer::Event::none);  // not monitored before one
  EXPECT_EQ(c.on_frame(heartbeat_frame(4, 0x00), 1000), HeartbeatConsumer::Event::bootup);
  EXPECT_EQ(c.on_frame(heartbeat_frame(4, 0x7F), 50000), HeartbeatConsumer::Event::heard);
  EXPECT_EQ(c.state(), NmtState::preoperational);
  EXPECT_EQ(c.on_frame(heartbeat_frame(5, 0x05), 60000), HeartbeatConsumer::Event::none);
  EXPECT_EQ(c.on_time(150000), HeartbeatConsumer::Event::none);  // exactly 100 ms: not yet
  EXPECT_EQ(c.on_time(150001), HeartbeatConsumer::Event::lost);
  EXPECT_EQ(c.on_time(300000), HeartbeatConsumer::Event::none);  // once
  EXPECT_FALSE(c.alive());
  EXPECT_EQ(c.on_frame(heartbeat_frame(4, 0x05), 310000), HeartbeatConsumer::Event::heard);
  EXPECT_TRUE(c.alive());
  EXPECT_EQ(c.state(), NmtState::operational);
  // A heartbeat of the wrong length is counted, not believed.
  EXPECT_EQ(c.on_frame(heartbeat_frame(4, 0x05, 2), 320000), HeartbeatConsumer::Event::none);
  EXPECT_EQ(c.malformed(), 1U);
}

TEST(Heartbeat, ProducerKeepsItsPeriod) {
  HeartbeatProducer p(7, 10000);
  can::CanFrame f;
  ASSERT_TRUE(p.due(0, NmtState::operational, f));
  EXPECT_EQ(f.id, 0x707U);
  EXPECT_EQ(f.dlc, 1);
  EXPECT_EQ(f.data[0], 0x05);
  EXPECT_FALSE(p.due(9999, NmtState::operational, f));
  EXPECT_TRUE(p.due(10500, NmtState::operational, f));   // late
  EXPECT_FALSE(p.due(19999, NmtState::operational, f));  // the next is still due at 20000
  EXPECT_TRUE(p.due(20000, NmtState::operational, f));
  HeartbeatProducer off(7, 0);
  EXPECT_FALSE(off.due(0, NmtState::operational, f));
}

TEST(Emcy, CodesInWords) {
  EXPECT_STREQ(emcy_text(0x8611), "following error");
  EXPECT_STREQ(emcy_text(0x2310), "continuous over-current");
  EXPECT_STREQ(emcy_text(0x8130), "life guard or heartbeat error");
  EXPECT_STREQ(emcy_text(0x0000), "error reset or no error");
  EXPECT_STREQ(emcy_text(0x2399), "current, device output side");  // by its class
  EXPECT_STREQ(emcy_text(0x5123), "device hardware");
  EXPECT_STREQ(emcy_text(0xFF42), "device specific");
}

TEST(PdoMapping, RpdoOfACspAxisInTheOrderTheStandardRequires) {
  const PdoLayout pdos = axis_pdos(false, false, false);
  SdoWriteList w;
  ASSERT_TRUE(pdo_configuration(3, pdos.rpdo1, w));
  const std::vector<std::tuple<int, int, std::uint32_t, int>> expected{
      {0x1400, 1, 0x80000203U, 4},                          // invalidate
      {0x1400, 2, 1, 1},                                    // synchronous
      {0x1600, 0, 0, 1},                                    // no entries while mapping
      {0x1600, 1, 0x60400010U, 4},                          // controlword, 16 bits
      {0x1600, 2, 0x607A0020U, 4},                          // target position, 32 bits
      {0x1600, 0, 2, 1},           {0x1400, 1, 0x203U, 4},  // valid again
  };
  ASSERT_EQ(w.count, expected.size());
  for (std::size_t i = 0; i < w.count; ++i) {
    EXPECT_EQ(w.writes[i].index, std::get<0>(expected[i])) << i;
    EXPECT_EQ(w.writes[i].sub, std::get<1>(expected[i])) << i;
    EXPECT_EQ(w.writes[i].value, std::get<2>(expected[i])) << i;
    EXPECT_EQ(w.writes[i].size, std::get<3>(expected[i])) << i;
  }
  // The first write as it goes on the bus: an expedited 4-byte download to node 3.
  SdoClient client(3, 100000);
  can::CanFrame f;
  const std::uint32_t v = w.writes[0].value;
  const std::uint8_t bytes[4] = {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                 static_cast<std::uint8_t>(v >> 16),
                                 static_cast<std::uint8_t>(v >> 24)};
  ASSERT_TRUE(client.download(w.writes[0].index, w.writes[0].sub, bytes, 4, 0, f));
  EXPECT_EQ(f.id, 0x603U);
  const std::array<std::uint8_t, 8> on_bus{0x23, 0x00, 0x14, 0x01, 0x03, 0x02, 0x00, 0x80};
  EXPECT_EQ(f.data, on_bus);
}

TEST(PdoMapping, TpdosAndLimits) {
  const PdoLayout csv = axis_pdos(true, true, true);
  EXPECT_EQ(csv.rpdo1.objects[1].index, 0x60FF);
  SdoWriteList w;
  ASSERT_TRUE(pdo_configuration(3, csv.tpdo2, w));
  EXPECT_EQ(w.writes[0].index, 0x1801);  // TPDO2 communication
  EXPECT_EQ(w.writes[0].value, 0x80000283U);
  EXPECT_EQ(w.writes[3].index, 0x1A01);
  EXPECT_EQ(w.writes[3].value, 0x606C0020U);
  EXPECT_EQ(w.writes[4].value, 0x60F40020U);
  EXPECT_EQ(pdo_cob_id(csv.tpdo1, 3), 0x183U);
  // 16 + 32 + 32 bits do not fit in one PDO.
  PdoMapping big = csv.tpdo1;
  big.objects[big.count++] = MappedObject{0x606C, 0, 32};
  EXPECT_FALSE(pdo_configuration(3, big, w));
  PdoMapping empty;
  EXPECT_FALSE(pdo_configuration(3, empty, w));
  EXPECT_EQ(axis_pdos(false, false, false).tpdo2.count, 0U);  // no second TPDO unless asked
}

}  // namespace
}  // namespace mcnc::canopen
