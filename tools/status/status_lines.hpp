#pragma once
// `mcnc status`: what a live machine's status topics say, as one line per channel and per axis
// (docs/operations.md). Pure: the command fills a StatusSnapshot from DDS and prints these lines.
#include "channel/control/channel_controller.hpp"
#include "common/config/machine_config.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mcnc::status {

using channel::ChannelState;  // ChannelStatus carries it in the same order

// The last ChannelStatus of one channel.
struct ChannelView {
  ChannelState state = ChannelState::reset;
  std::uint32_t block = 0;
  std::uint32_t block_total = 0;
  std::int32_t line = 0;
  std::uint32_t alarms = 0;
  bool program_end = false;
  std::int32_t sync_p = 0;             // G04.1 mark it waits at (state waiting)
  std::uint64_t sync_waiting_for = 0;  // bit c-1: channel c has not arrived yet
  std::uint32_t call_caller = 0;       // G144: the channel whose call it runs, 0: none
  // For the HMI (docs/hmi.md).
  std::uint64_t cycle = 0;
  std::int32_t end_code = -1;
  std::uint64_t sync_channels = 0;     // the mark's participants, bit c-1 for channel c
  std::uint32_t call_waiting_for = 0;  // G144 H1: the called channel, 0: none
  double feed_override = 100.0;        // percent
  double rapid_override = 100.0;
  double spindle_override = 100.0;
  bool single_block = false;
  double spindle_rpm = 0.0;                // commanded, M04 negative
  std::string program;                     // the file of the executing block
  std::int32_t waiting_m = -1;             // the M code whose FIN it waits for, -1: none
  std::int32_t waiting_t = -1;             // the T code whose FIN it waits for, -1: none
  std::int16_t waiting_exchange = 0;       // G140/G141/G142 it waits for, 0: none
  std::uint32_t waiting_axis = 0;          // that exchange's axis (machine number), 0: every axis
  std::array<std::uint16_t, 8> modal_g{};  // ChannelStatus.modal_g
  double modal_feed = 0.0;
};

// The last AxisFeedback of one axis or spindle.
struct AxisView {
  double cmd = 0.0;
  double act = 0.0;
  double vel = 0.0;  // units/s (a spindle: degrees/s)
  double following_error = 0.0;
  bool enabled = false;
  bool alarm = false;
  std::uint32_t owner = 0;        // channel id, 0: nobody
  std::uint32_t released_by = 0;  // G140: the channel that gave it to its owner
  std::uint32_t coupled_to = 0;   // G114.1 / G51.4: the master's axis id
  bool coupling_locked = false;
  std::int16_t mode_display = 0;  // a spindle: 8 CSP, 9 CSV
  std::uint64_t cycle = 0;
  std::uint8_t drive_state = 0;  // the wire's DriveState, in its order (drive_state_name)
  bool load_known = false;       // the drive sends its torque (TPDO2)
  double load = 0.0;             // percent of the motor's rated torque
};

// The CiA 402 state of the wire's DriveState number: "operation_enabled", "fault", ...
const char* drive_state_name(std::uint8_t drive_state) noexcept;

// By channel id and by axis id (the machine file's 1-based positions).
// The run as the launcher commands it (RunControl): `starting` until a start is heard.
enum class RunPhase : std::uint8_t { starting, running, stopped, estop };
struct RunView {
  RunPhase phase = RunPhase::starting;
  std::string reason;  // why it stopped (an E-stop's cause)
};

// A host's clock against machine time, as its launcher announces it (HostClock).
struct HostClockView {
  std::int64_t offset_ns = 0;
  std::int64_t error_ns = 0;
  std::uint32_t samples = 0;  // 0: the coordinating host, whose clock is machine time
};

struct StatusSnapshot {
  std::map<std::uint32_t, ChannelView> channels;
  std::map<std::uint32_t, AxisView> axes;
  RunView run;
  std::map<std::string, HostClockView> host_clocks;  // by host name
};

// One line per channel, then one per axis and spindle, in the machine file's order; a channel
// or axis not heard from says so. A machine of several hosts then has a line per host with its
// clock's offset against machine time and the offset's error.
std::vector<std::string> status_lines(const config::MachineConfig& machine,
                                      const StatusSnapshot& snapshot);

// The channels and axes of the machine that the snapshot lacks, by name.
std::vector<std::string> missing(const config::MachineConfig& machine,
                                 const StatusSnapshot& snapshot);

}  // namespace mcnc::status
