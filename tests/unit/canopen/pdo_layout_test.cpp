// One PDO layout: what the start-up maps is what the frames are packed and unpacked by, and a
// mapping a classic CAN frame cannot carry is refused, saying why.
#include "canopen/pdo_layout.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/cia402/node_startup.hpp"

#include <gtest/gtest.h>

#include <string>

namespace mcnc::canopen {
namespace {

TEST(PdoLayout, FramesArePackedAndUnpackedInTheOrderOfTheMapping) {
  const PdoLayout spindle = spindle_pdos();
  const DriveCommand command{0x001F, -123456, 3600000, -1};
  can::CanFrame rpdo1;
  ASSERT_TRUE(pack_command(spindle.rpdo1, 4, command, rpdo1));
  EXPECT_EQ(rpdo1.id, 0x204U);
  ASSERT_EQ(rpdo1.dlc, 7);  // 16 + 32 + 8 bits
  const std::array<std::uint8_t, 8> bytes{0x1F, 0x00, 0xC0, 0x1D, 0xFE, 0xFF, 0xFF, 0x00};
  EXPECT_EQ(rpdo1.data, bytes);
  can::CanFrame rpdo2;
  ASSERT_TRUE(pack_command(spindle.rpdo2, 4, command, rpdo2));
  EXPECT_EQ(rpdo2.id, 0x304U);
  EXPECT_EQ(rpdo2.dlc, 4);

  // The same objects in another order: the frame follows the mapping.
  PdoMapping swapped = spindle.rpdo1;
  std::swap(swapped.objects[0], swapped.objects[2]);
  can::CanFrame f;
  ASSERT_TRUE(pack_command(swapped, 4, command, f));
  EXPECT_EQ(f.data[0], 0xFF) << "the mode first";
  EXPECT_EQ(f.data[5], 0x1F) << "the controlword last";

  // A drive's answer, unpacked by the TPDO's mapping; sign extended where the object is signed.
  PdoMapping tpdo2;
  tpdo2.receive = false;
  tpdo2.number = 2;
  tpdo2.objects[tpdo2.count++] = MappedObject{0x60F4, 0, 32};
  tpdo2.objects[tpdo2.count++] = MappedObject{0x6077, 0, 16};
  const auto value_of = [](std::uint16_t index, std::uint8_t) -> std::uint32_t {
    return index == 0x60F4 ? static_cast<std::uint32_t>(-70000) : static_cast<std::uint16_t>(-5);
  };
  ASSERT_TRUE(pack(tpdo2, 4, value_of, f));
  EXPECT_EQ(f.id, 0x284U);
  DriveFeedback feedback;
  ASSERT_TRUE(unpack_feedback(tpdo2, f, feedback));
  EXPECT_EQ(feedback.following_error, -70000);
  EXPECT_EQ(feedback.torque_actual, -5);
  EXPECT_EQ(feedback.velocity_actual, 0) << "not mapped: left as it was";
  f.dlc = 5;
  feedback = DriveFeedback{};
  EXPECT_FALSE(unpack_feedback(tpdo2, f, feedback)) << "not the mapped length";
  EXPECT_EQ(feedback.following_error, 0) << "nothing taken from a frame of the wrong length";
}

TEST(PdoLayout, AMappingBeyondEightBytesIsRefusedWithTheReason) {
  PdoLayout layout = axis_pdos(false, true, true);  // TPDO2: 8 bytes, full
  EXPECT_EQ(layout_error(layout), nullptr);
  layout.tpdo2.objects[layout.tpdo2.count++] = MappedObject{0x6077, 0, 16};  // 10 bytes
  ASSERT_NE(pdo_error(layout.tpdo2), nullptr);
  EXPECT_STREQ(layout_error(layout),
               "the mapping is longer than the 8 bytes a classic CAN frame carries");
  can::CanFrame f;
  EXPECT_FALSE(pack(
      layout.tpdo2, 3, [](std::uint16_t, std::uint8_t) { return 0U; }, f));
  SdoWriteList writes;
  EXPECT_FALSE(pdo_configuration(3, layout.tpdo2, writes));
  PdoMapping odd = layout.rpdo1;
  odd.objects[0].bits = 12;
  EXPECT_STREQ(pdo_error(odd), "a mapped object is 8, 16 or 32 bits long");

  // The start-up refuses it before anything goes on the bus, naming the PDO.
  NodeStartupConfig config{3};
  config.pdos = layout;
  NodeStartup startup(config);
  can::CanFrame out;
  EXPECT_FALSE(startup.begin(0, out));
  EXPECT_EQ(startup.status(), NodeStartup::Status::failed);
  EXPECT_EQ(std::string(startup.error()),
            "node 3: TPDO2 cannot be mapped: the mapping is longer than the 8 bytes a classic CAN "
            "frame carries");
}

}  // namespace
}  // namespace mcnc::canopen
