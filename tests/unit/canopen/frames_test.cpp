#include "canopen/frames.hpp"
#include "canopen/cia402/drive_pdos.hpp"

#include <gtest/gtest.h>

namespace mcnc::canopen {
namespace {

TEST(CanopenFrames, NmtLayoutAndRoundTrip) {
  const CanFrame frame = encode_nmt(NmtCommand::reset_node, 5);
  EXPECT_EQ(frame.id, 0x000U);
  ASSERT_EQ(frame.dlc, 2);
  EXPECT_EQ(frame.data[0], 0x81);
  EXPECT_EQ(frame.data[1], 5);
  const auto decoded = decode_nmt(frame);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->command, NmtCommand::reset_node);
  EXPECT_EQ(decoded->node, 5);
  EXPECT_EQ(classify(frame).kind, FrameKind::nmt);
}

TEST(CanopenFrames, NmtRejects) {
  CanFrame frame = encode_nmt(NmtCommand::start, 0);
  frame.dlc = 1;
  EXPECT_FALSE(decode_nmt(frame));
  frame = encode_nmt(NmtCommand::start, 0);
  frame.data[0] = 0x03;  // not an NMT command
  EXPECT_FALSE(decode_nmt(frame));
  frame = encode_nmt(NmtCommand::start, 0);
  frame.data[1] = 128;  // node out of range
  EXPECT_FALSE(decode_nmt(frame));
  frame = encode_nmt(NmtCommand::start, 0);
  frame.id = 0x001;
  EXPECT_FALSE(decode_nmt(frame));
}

TEST(CanopenFrames, SyncWithAndWithoutCounter) {
  const CanFrame plain = encode_sync(0);
  EXPECT_EQ(plain.id, 0x080U);
  EXPECT_EQ(plain.dlc, 0);
  EXPECT_EQ(decode_sync(plain), std::uint8_t{0});

  const CanFrame counted = encode_sync(240);
  EXPECT_EQ(counted.dlc, 1);
  EXPECT_EQ(decode_sync(counted), std::uint8_t{240});
  EXPECT_EQ(classify(counted).kind, FrameKind::sync);
  EXPECT_EQ(classify(counted).node, 0);

  CanFrame bad = counted;
  bad.data[0] = 241;
  EXPECT_FALSE(decode_sync(bad));
  bad.data[0] = 0;
  EXPECT_FALSE(decode_sync(bad));
  bad = counted;
  bad.dlc = 2;
  EXPECT_FALSE(decode_sync(bad));
  bad = counted;
  bad.id = 0x081;
  EXPECT_FALSE(decode_sync(bad));
}

TEST(CanopenFrames, HeartbeatAndBootUp) {
  const CanFrame boot = encode_heartbeat(3, NmtState::bootup);
  EXPECT_EQ(boot.id, 0x703U);
  ASSERT_EQ(boot.dlc, 1);
  EXPECT_EQ(boot.data[0], 0x00);
  EXPECT_EQ(decode_heartbeat(boot), NmtState::bootup);
  EXPECT_EQ(classify(boot).kind, FrameKind::heartbeat);
  EXPECT_EQ(classify(boot).node, 3);

  const CanFrame op = encode_heartbeat(127, NmtState::operational);
  EXPECT_EQ(op.id, 0x77FU);
  EXPECT_EQ(decode_heartbeat(op), NmtState::operational);
  EXPECT_EQ(decode_heartbeat(encode_heartbeat(1, NmtState::preoperational)),
            NmtState::preoperational);
  EXPECT_EQ(decode_heartbeat(encode_heartbeat(1, NmtState::stopped)), NmtState::stopped);

  CanFrame bad = op;
  bad.dlc = 2;
  EXPECT_FALSE(decode_heartbeat(bad));
  bad = op;
  bad.data[0] = 0x06;
  EXPECT_FALSE(decode_heartbeat(bad));
  bad = op;
  bad.id = 0x700;  // node 0 is not a node
  EXPECT_FALSE(decode_heartbeat(bad));
  EXPECT_EQ(classify(bad).kind, FrameKind::other);
}

TEST(CanopenFrames, EmcyLayoutAndRoundTrip) {
  const CanFrame frame = encode_emcy(2, Emcy{0x7305, 0x81});
  EXPECT_EQ(frame.id, 0x082U);
  ASSERT_EQ(frame.dlc, 8);
  EXPECT_EQ(frame.data[0], 0x05);
  EXPECT_EQ(frame.data[1], 0x73);
  EXPECT_EQ(frame.data[2], 0x81);
  for (int i = 3; i < 8; ++i) {
    EXPECT_EQ(frame.data[static_cast<std::size_t>(i)], 0);
  }
  const auto decoded = decode_emcy(frame);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->error_code, 0x7305);
  EXPECT_EQ(decoded->error_register, 0x81);
  EXPECT_EQ(classify(frame).kind, FrameKind::emcy);
  EXPECT_EQ(classify(frame).node, 2);

  CanFrame bad = frame;
  bad.dlc = 7;
  EXPECT_FALSE(decode_emcy(bad));
  EXPECT_FALSE(decode_emcy(encode_sync(0)));
}

TEST(CanopenFrames, RpdoLayoutAndRoundTrip) {
  const CanFrame frame = encode_rpdo_csp(4, RxPdoCsp{0x000F, -2});
  EXPECT_EQ(frame.id, 0x204U);
  ASSERT_EQ(frame.dlc, 6);
  EXPECT_EQ(frame.data[0], 0x0F);
  EXPECT_EQ(frame.data[1], 0x00);
  EXPECT_EQ(frame.data[2], 0xFE);
  EXPECT_EQ(frame.data[3], 0xFF);
  EXPECT_EQ(frame.data[4], 0xFF);
  EXPECT_EQ(frame.data[5], 0xFF);
  const auto decoded = decode_rpdo_csp(frame);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->controlword, 0x000F);
  EXPECT_EQ(decoded->target_position, -2);
  EXPECT_EQ(classify(frame).kind, FrameKind::rpdo1);
  EXPECT_EQ(classify(frame).node, 4);

  for (const std::int32_t value : {0, 1, 0x12345678, -0x12345678, INT32_MIN, INT32_MAX}) {
    const auto back = decode_rpdo_csp(encode_rpdo_csp(1, RxPdoCsp{0xABCD, value}));
    ASSERT_TRUE(back);
    EXPECT_EQ(back->controlword, 0xABCD);
    EXPECT_EQ(back->target_position, value);
  }
}

TEST(CanopenFrames, TpdoLayoutAndRoundTrip) {
  const CanFrame frame = encode_tpdo_csp(4, TxPdoCsp{0x0637, 0x01020304});
  EXPECT_EQ(frame.id, 0x184U);
  ASSERT_EQ(frame.dlc, 6);
  EXPECT_EQ(frame.data[0], 0x37);
  EXPECT_EQ(frame.data[1], 0x06);
  EXPECT_EQ(frame.data[2], 0x04);
  EXPECT_EQ(frame.data[5], 0x01);
  const auto decoded = decode_tpdo_csp(frame);
  ASSERT_TRUE(decoded);
  EXPECT_EQ(decoded->statusword, 0x0637);
  EXPECT_EQ(decoded->position_actual, 0x01020304);
  EXPECT_EQ(classify(frame).kind, FrameKind::tpdo1);
}

TEST(CanopenFrames, PdoRejectsWrongLengthAndWrongId) {
  CanFrame rpdo = encode_rpdo_csp(4, RxPdoCsp{6, 100});
  rpdo.dlc = 5;
  EXPECT_FALSE(decode_rpdo_csp(rpdo));
  rpdo.dlc = 8;
  EXPECT_FALSE(decode_rpdo_csp(rpdo));
  EXPECT_FALSE(decode_rpdo_csp(encode_tpdo_csp(4, TxPdoCsp{})));
  EXPECT_FALSE(decode_tpdo_csp(encode_rpdo_csp(4, RxPdoCsp{})));
  CanFrame tpdo = encode_tpdo_csp(4, TxPdoCsp{});
  tpdo.dlc = 4;
  EXPECT_FALSE(decode_tpdo_csp(tpdo));
  // An extended or remote frame with the same low bits is not CANopen traffic.
  CanFrame extended = encode_rpdo_csp(4, RxPdoCsp{});
  extended.id |= can::kEffFlag;
  EXPECT_FALSE(decode_rpdo_csp(extended));
  EXPECT_EQ(classify(extended).kind, FrameKind::other);
  CanFrame remote = encode_tpdo_csp(4, TxPdoCsp{});
  remote.id |= can::kRtrFlag;
  EXPECT_EQ(classify(remote).kind, FrameKind::other);
}

TEST(CanopenFrames, ClassifyRanges) {
  CanFrame frame;
  frame.id = 0x280;  // RPDO2 of node 0: not one of ours
  EXPECT_EQ(classify(frame).kind, FrameKind::other);
  frame.id = 0x1FF;
  EXPECT_EQ(classify(frame).kind, FrameKind::tpdo1);
  EXPECT_EQ(classify(frame).node, 127);
  frame.id = 0x180;
  EXPECT_EQ(classify(frame).kind, FrameKind::other);
  frame.id = 0x600;  // SDO request
  EXPECT_EQ(classify(frame).kind, FrameKind::other);
}

}  // namespace
}  // namespace mcnc::canopen
