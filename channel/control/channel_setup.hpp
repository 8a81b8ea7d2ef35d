#pragma once
// How a channel's cyclic core is set up from the machine file (channel/setup/ builds it): its
// axes and spindles, cycle, PLC, exchangeable slots, couplings, probes and inputs.
#include "channel/control/shared_write_log.hpp"
#include "channel/coordination/axis_exchange.hpp"
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/coupling_request.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mcnc::channel {

struct ChannelSetup {
  std::size_t axis_count = 0;
  std::vector<double> in_position;  // per axis, units
  double cycle_s = 0.001;
  std::size_t pulls_per_cycle = 64;  // commands pulled into the look-ahead per cycle at most
  // Past this many a cycle, the channel pulls on only while the window's end holds down what
  // the planner's next cycle may do (MotionPlanner::window_end_binds): a refill after a
  // read-ahead stop is spread over cycles without changing the motion.
  std::size_t pulls_before_settled = 16;
  // Spindles whose feedback follows the axes' in cycle()'s `feedback`: their alarms stop the
  // channel too, and a channel comes to idle only with them enabled.
  std::size_t spindle_count = 0;
  std::uint32_t channel_id = 1;  // the channel's number (CHn), as G04.1 Q names it
  // The writes to shared variables not yet sent (null: none kept): the channel arrives at a
  // G04.1 and calls with G144 only once they are out.
  const SharedWriteLog* shared_writes = nullptr;
  // Per axis: what the channel may do with it (G140/G141/G142). Empty: every axis is the
  // channel's own for good (no exchange; feedback owner not looked at).
  std::vector<coordination::AxisSlot> slots{};
  // A PLC node runs M and T codes: each is a block that ends with its answer; a spindle
  // start (M03/M04) waits for the PLC's consent.
  bool plc = false;
  // G114.1 groups this channel commands (its spindle is their master).
  std::vector<coordination::SpindleGroupSetup> spindle_groups{};
  // G51.2: the channel's polygon axis and its master spindle (master 0: none).
  coordination::PolygonSetup polygon{};
  // G51.8: the channel's cam master spindle and slave axis (master 0: none).
  coordination::CamSetup cam{};
  // G81.4: the channel's gear box's tool spindle and work axis (tool 0: none).
  coordination::EgbSetup egb{};
  // G144: how many cycles a call waits for its target to become free (0: as long as it takes).
  std::uint64_t call_wait_cycles = 0;
  // The channel's first spindle is the slave of a G114.1 group: a start waits until the blocks
  // before it ended and is an alarm while the spindle follows its master.
  bool spindle_may_follow = false;
  // Every axis of the machine, by system number - 1: what G51.4 P may name.
  std::vector<coordination::MachineAxis> machine_axes{};
  // The slot of the first spindle's C axis (C1 mode), if it has one: its feedback is the
  // spindle's, and it is commanded only while M18 (GSK M14) holds the spindle under position
  // control.
  std::optional<std::size_t> spindle_c_slot{};
  // Per axis: the skip input its drive's touch probe is wired to (G31; 0: none). Empty: none.
  std::vector<int> probe_inputs{};
  // Per axis: its drive takes a torque limit and reports its torque (G160; torque_skip).
  std::vector<bool> torque_axes{};
  // Per axis: its drive switches to torque mode (G10 L14 P10; torque_mode), and its motor speed
  // there where no P11 set one (param 5521, rpm; 0: none). Empty: none.
  std::vector<bool> torque_mode_axes{};
  std::vector<double> torque_mode_speeds{};
  // Param 5520.1: a reset puts the axes in torque mode back in position mode where they stand
  // (false: they keep their torque).
  bool reset_leaves_torque_mode = false;
  // G31: a touch probe that does not report itself armed within this many cycles is an alarm.
  std::uint64_t probe_arm_cycles = 200;
  // G04 I: per input port (the index), the bit of the PLC's inputs it reads (-1: none).
  std::vector<int> input_ports{};
  // G31 P1-P8: per skip signal P-1 (G0014.0-7), the bit of the PLC's inputs it is (-1: none).
  std::array<int, 8> skip_signals{-1, -1, -1, -1, -1, -1, -1, -1};
  // G04 PS: reached within this many rpm (param 1057); an alarm after this long (param 1059).
  double speed_arrival_rpm = 10.0;
  double speed_arrival_timeout_s = 10.0;
};

}  // namespace mcnc::channel
