// The simulated drive's object dictionary: the master's start-up against it over SDO, and the
// CiA 301 rules of PDO mapping.
#include "axisnode/drivesim/drive_objects.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/cia402/node_startup.hpp"
#include "canopen/frames.hpp"
#include "canopen/sdo_abort.hpp"
#include "canopen/sdo_server.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <deque>
#include <string>

namespace mcnc::drivesim {
namespace {

namespace abort = canopen::sdo_abort;

std::uint32_t write_u(DriveObjects& od, std::uint16_t index, std::uint8_t sub, std::uint32_t v,
                      std::size_t size) {
  const std::uint8_t bytes[4] = {static_cast<std::uint8_t>(v), static_cast<std::uint8_t>(v >> 8),
                                 static_cast<std::uint8_t>(v >> 16),
                                 static_cast<std::uint8_t>(v >> 24)};
  return od.write(index, sub, bytes, size);
}

// The master's start-up of node 2 against the drive, frame by frame.
canopen::NodeStartup::Status start(DriveObjects& od, canopen::NodeStartup& s) {
  canopen::SdoServer server(2, od);
  std::deque<can::CanFrame> to_master{canopen::encode_heartbeat(2, canopen::NmtState::bootup)};
  can::CanFrame out;
  std::uint64_t now = 0;
  s.begin(now, out);
  while (!to_master.empty() && s.status() == canopen::NodeStartup::Status::running) {
    now += 500;
    const can::CanFrame in = to_master.front();
    to_master.pop_front();
    if (s.on_frame(in, now, out)) {
      can::CanFrame resp;
      if (server.on_frame(out, resp)) {
        to_master.push_back(resp);
      }
    }
  }
  return s.status();
}

TEST(DriveObjects, TheMastersStartupConfiguresTheDrive) {
  DriveObjects od(2);
  canopen::NodeStartupConfig c{2};
  c.pdos = canopen::axis_pdos(false, true, true);
  c.heartbeat_ms = 50;
  canopen::NodeStartup s(c);
  ASSERT_EQ(start(od, s), canopen::NodeStartup::Status::done) << s.error();
  EXPECT_EQ(od.mode(), 8);
  EXPECT_EQ(od.heartbeat_ms(), 50);
  EXPECT_TRUE(od.rpdo(0).valid());
  EXPECT_EQ(od.rpdo(0).cob_id, 0x202U);
  EXPECT_TRUE(od.tpdo(1).valid());
  EXPECT_EQ(od.tpdo(1).count, 2);
  EXPECT_EQ(od.tpdo(1).entries[0], 0x606C0020U);
  EXPECT_EQ(od.tpdo(1).entries[1], 0x60F40020U);
}

TEST(DriveObjects, TheTorqueGoesInTpdo2InPerMilleOfTheRatedTorque) {
  DriveObjects od(2);
  canopen::NodeStartupConfig c{2};
  c.pdos = canopen::spindle_pdos();
  c.pdos.tpdo2.objects[c.pdos.tpdo2.count++] = canopen::MappedObject{0x6077, 0, 16};
  canopen::NodeStartup s(c);
  ASSERT_EQ(start(od, s), canopen::NodeStartup::Status::done) << s.error();
  od.live.torque = -1234;  // -123.4 % of the rated torque: braking
  od.live.rated_torque = 3000;
  can::CanFrame f;
  ASSERT_TRUE(od.encode_tpdo(1, f));
  EXPECT_EQ(f.id, 0x282U);
  ASSERT_EQ(f.dlc, 2);
  EXPECT_EQ(static_cast<std::int16_t>(f.data[0] | f.data[1] << 8), -1234);
  canopen::SdoValue v;
  ASSERT_EQ(od.read(0x6076, 0, v), 0U);
  EXPECT_EQ(v.size, 4U);
  EXPECT_EQ(write_u(od, 0x6077, 0, 0, 2), abort::kReadOnly);
}

TEST(DriveObjects, TheLayoutTheMasterMapsIsTheOneBothEndsPackBy) {
  // Not a layout of the project's: the objects in an order of their own, both TPDOs filled.
  canopen::PdoLayout layout = canopen::spindle_pdos();
  std::swap(layout.rpdo1.objects[0], layout.rpdo1.objects[2]);  // mode, target, controlword
  layout.tpdo1.objects[0] = canopen::MappedObject{0x6064, 0, 32};
  layout.tpdo1.objects[1] = canopen::MappedObject{0x6061, 0, 8};
  layout.tpdo1.objects[2] = canopen::MappedObject{0x6041, 0, 16};
  layout.tpdo2.objects[layout.tpdo2.count++] = canopen::MappedObject{0x6077, 0, 16};
  layout.tpdo2.objects[layout.tpdo2.count++] = canopen::MappedObject{0x606C, 0, 32};
  DriveObjects od(2);
  canopen::NodeStartupConfig c{2};
  c.pdos = layout;
  c.mode = 9;
  canopen::NodeStartup s(c);
  ASSERT_EQ(start(od, s), canopen::NodeStartup::Status::done) << s.error();

  // The master's command, as the drive reads it.
  const canopen::DriveCommand command{0x000F, -4000000, -250000, 8};
  RpdoValues got;
  for (std::size_t n = 0; n < 2; ++n) {
    can::CanFrame frame;
    ASSERT_TRUE(canopen::pack_command(n == 0 ? layout.rpdo1 : layout.rpdo2, 2, command, frame));
    RpdoValues values;
    ASSERT_TRUE(od.decode_rpdo(n, frame, values)) << n;
    got.merge(values);
  }
  EXPECT_EQ(got.controlword, 0x000F);
  EXPECT_EQ(got.target_position, -4000000);
  EXPECT_EQ(got.target_velocity, -250000);
  EXPECT_EQ(got.mode, 8);

  // The drive's answer, as the master reads it.
  od.live.statusword = 0x1237;
  od.live.position = -987654;
  od.live.velocity = -31000;
  od.live.torque = -12;
  canopen::DriveFeedback feedback;
  for (std::size_t n = 0; n < 2; ++n) {
    can::CanFrame frame;
    ASSERT_TRUE(od.encode_tpdo(n, frame)) << n;
    ASSERT_TRUE(canopen::unpack_feedback(n == 0 ? layout.tpdo1 : layout.tpdo2, frame, feedback))
        << n;
  }
  EXPECT_EQ(feedback.statusword, 0x1237);
  EXPECT_EQ(feedback.position_actual, -987654);
  EXPECT_EQ(feedback.mode_display, 9);
  EXPECT_EQ(feedback.velocity_actual, -31000);
  EXPECT_EQ(feedback.torque_actual, -12);
}

TEST(DriveObjects, AnInjectedRefusalStopsTheStartupNamingTheObject) {
  DriveObjects od(2);
  od.refuse(0x6060, abort::kDeviceState);
  canopen::NodeStartup s(canopen::NodeStartupConfig{2});
  ASSERT_EQ(start(od, s), canopen::NodeStartup::Status::failed);
  EXPECT_EQ(std::string(s.error()),
            "node 2: writing 0x6060:00 (modes of operation) was refused: data cannot be "
            "transferred or stored because of the present device state (SDO abort 0x08000022)");
}

TEST(DriveObjects, MappingFollowsTheRulesOfCia301) {
  DriveObjects od(2);
  // TPDO1 is valid: its mapping cannot change.
  EXPECT_EQ(write_u(od, 0x1A00, 0, 0, 1), abort::kDeviceState);
  EXPECT_EQ(write_u(od, 0x1800, 1, 0x80000182U, 4), 0U);                   // invalidate
  EXPECT_EQ(write_u(od, 0x1A00, 1, 0x60640020U, 4), abort::kDeviceState);  // count still 2
  EXPECT_EQ(write_u(od, 0x1A00, 0, 0, 1), 0U);
  EXPECT_EQ(write_u(od, 0x1A00, 1, 0x607A0020U, 4), abort::kNotMappable);  // not a TPDO object
  EXPECT_EQ(write_u(od, 0x1A00, 1, 0x60410010U, 4), 0U);
  EXPECT_EQ(write_u(od, 0x1A00, 2, 0x60640020U, 4), 0U);
  EXPECT_EQ(write_u(od, 0x1A00, 3, 0x606C0020U, 4), 0U);
  EXPECT_EQ(write_u(od, 0x1A00, 0, 3, 1), abort::kPdoTooLong);  // 80 bits
  EXPECT_EQ(write_u(od, 0x1A00, 0, 2, 1), 0U);
  EXPECT_EQ(write_u(od, 0x1A00, 9, 0x60410010U, 4), abort::kNoSubindex);
  EXPECT_EQ(write_u(od, 0x1800, 2, 250, 1), abort::kInvalidValue);  // reserved type
}

TEST(DriveObjects, AccessRules) {
  DriveObjects od(2);
  canopen::SdoValue v;
  EXPECT_EQ(write_u(od, 0x6041, 0, 0, 2), abort::kReadOnly);
  EXPECT_EQ(write_u(od, 0x1000, 0, 0, 4), abort::kReadOnly);
  EXPECT_EQ(write_u(od, 0x6060, 0, 3, 1), abort::kInvalidValue);  // profile velocity: not here
  EXPECT_EQ(write_u(od, 0x6060, 0, 9, 2), abort::kLengthTooHigh);
  EXPECT_EQ(write_u(od, 0x6060, 0, 9, 1), 0U);
  ASSERT_EQ(od.read(0x6061, 0, v), 0U);
  EXPECT_EQ(v.size, 1U);
  EXPECT_EQ(v.bytes[0], 9);
  EXPECT_EQ(od.read(0x2000, 0, v), abort::kNoObject);
  EXPECT_EQ(od.read(0x6064, 1, v), abort::kNoSubindex);
  od.live.position = -12345;
  ASSERT_EQ(od.read(0x6064, 0, v), 0U);
  std::int32_t pos = 0;
  std::memcpy(&pos, v.bytes.data(), 4);
  EXPECT_EQ(pos, -12345);
  ASSERT_EQ(od.read(0x1008, 0, v), 0U);
  EXPECT_EQ(std::string(v.bytes.begin(), v.bytes.begin() + static_cast<std::ptrdiff_t>(v.size)),
            "mcnc drivesim");
}

}  // namespace
}  // namespace mcnc::drivesim
