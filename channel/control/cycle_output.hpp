#pragma once
// What the channel's cyclic core yields each cycle (ChannelController::cycle): one setpoint per
// axis, the channel's state and block, the events of the cycle in order, and what goes to the
// other channels, the axis nodes and the PLC in this cycle. Fixed size: it is built on the
// cyclic path.
#include "channel/control/read_ahead_stop.hpp"
#include "channel/coordination/aux_handshake.hpp"
#include "channel/coordination/axis_exchange.hpp"
#include "channel/coordination/channel_axes.hpp"
#include "channel/coordination/channel_state.hpp"
#include "channel/coordination/coupling_request.hpp"
#include "channel/coordination/sub_call.hpp"
#include "channel/coordination/sync_barrier.hpp"
#include "channel/interp/axis_vector.hpp"
#include "channel/interp/command.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace mcnc::channel {

using interp::AxisVector;
using interp::kMaxChannelAxes;

// The coordination state machines' vocabulary, as the channel's adapters and tests name it.
using coordination::AuxKind;
using coordination::AuxOutcome;
using coordination::AuxRequestOut;
using coordination::AxisFeedbackView;
using coordination::AxisRequestKind;
using coordination::AxisRequestOut;
using coordination::AxisSlot;
using coordination::AxisSyncOut;
using coordination::CallOutcome;
using coordination::CallRelease;
using coordination::CallRequest;
using coordination::CamOut;
using coordination::ChannelState;
using coordination::EgbOut;
using coordination::MachineAxis;
using coordination::MachineAxisKind;
using coordination::PartnerStatus;
using coordination::PlcAnswer;
using coordination::PolygonOut;
using coordination::ProbeSeen;
using coordination::SpindleGroupSetup;
using coordination::SpindleSyncOut;
using coordination::to_string;

struct CommandedAxis {
  double pos = 0.0;
  double vel = 0.0;
  double acc = 0.0;
  bool valid = false;              // false: the axis node holds its position
  ProbeArm probe = ProbeArm::off;  // G31: arm the drive's touch probe; G160: the torque skip
  // G160: the drive's torque limit (percent of the rated torque, 0: none) and the following
  // error beyond which the torque skip latches (units), for as long as the limit stands.
  double torque_limit = 0.0;
  double skip_deviation = 0.0;
  // G10 L14 P10: the axis held in torque mode at `torque` percent of the rated torque (signed),
  // its motor within `torque_speed` rpm; pos is where the channel last knew it.
  bool torque_mode = false;
  double torque = 0.0;
  double torque_speed = 0.0;
};

enum class ChannelEventKind : std::uint8_t {
  state_changed,
  block_started,  // command.line / command.block
  block_ended,    // the path passed the block's end (an exact stop: and every axis is in position)
  alarm,          // alarm_number / alarm text via last_alarm()
  program_end,    // end_code
  mdi_end,        // MDI blocks ended (end_code: 0 at their text's end, else 30, 2 or 99)
  sync_arrive,    // G04.1 P: the channel arrived at the mark (CycleOutput::arrival)
  sync_release,   // every participant arrived: the channel goes on
  subcall,        // G144: this channel sent CycleOutput::call
  subcall_release,  // this channel released the caller of the call it runs (call_id)
};

struct ChannelEvent {
  ChannelEventKind kind = ChannelEventKind::state_changed;
  ChannelState state = ChannelState::reset;
  int line = 0;
  const std::string* file = nullptr;  // the block's file (nullptr: the main program's)
  std::string_view text;              // block_started: the block's line as written (the file's)
  std::size_t block = 0;
  int end_code = 0;
  int alarm_number = 0;
  AxisVector pos{};           // block_ended: the commanded end point of the block
  std::uint64_t call_id = 0;  // subcall_release
  CallOutcome call_outcome = CallOutcome::released;
};

// A file name as the cycle keeps it: fixed, so that keeping it never allocates.
using FileName = std::array<char, 128>;

struct ChannelAlarm {
  int number = 0;
  std::array<char, 192> text{};  // fixed: alarms are raised from the cyclic path
  // The file the alarm is in (a called program's, an MDI's, ...) as the interpreter names it;
  // empty: the main program's.
  FileName file{};
  int line = 0;
  int column = 0;
  int axis = 0;  // channel axis index + 1 when an axis is concerned
};

struct CycleOutput {
  std::array<CommandedAxis, kMaxChannelAxes> setpoints{};
  ChannelState state = ChannelState::reset;
  std::size_t block = 0;
  int line = 0;
  FileName file{};           // the file of the block under way (empty: the main program's)
  interp::ModalState modal;  // of the block under way (of the last one, between runs)
  bool program_end = false;
  int end_code = -1;
  std::uint64_t run_start_cycle = 0;  // cycle the program started (valid once it has run)
  std::uint64_t end_cycle = 0;        // cycle of its program end (valid when program_end)
  // The channel's spindle (S1) as its program commands it: speed and direction (+1 M03,
  // -1 M04, 0 stopped). Stopped whenever no program runs (reset, idle, alarm, end).
  double spindle_rpm = 0.0;
  int spindle_direction = 0;
  // The spindle is under position control (M18): its setpoint is setpoints[spindle_c_slot],
  // in the spindle's degrees.
  bool spindle_position = false;
  // A G04.1 arrival to send to every other channel this cycle (sync_arrive event).
  bool arrival_due = false;
  coordination::SyncArrival arrival{};
  // A G144 call to send this cycle (subcall event), and the releases of calls to send.
  bool call_due = false;
  CallRequest call{};
  static constexpr std::size_t kMaxReleases = 8;
  std::array<CallRelease, kMaxReleases> releases{};
  std::size_t release_count = 0;
  // G140/G141/G142 requests to send to the axis nodes this cycle.
  static constexpr std::size_t kMaxAxisRequests = coordination::AxisExchange::kMaxRequests;
  std::array<AxisRequestOut, kMaxAxisRequests> axis_requests{};
  std::size_t axis_request_count = 0;
  // An M or T code for the PLC node, sent this cycle.
  bool aux_due = false;
  AuxRequestOut aux{};
  // G114.1 / G113 to the slave spindles' axis nodes, sent this cycle.
  bool spindle_sync_due = false;
  SpindleSyncOut spindle_sync{};
  // G51.4 / G50.4 to a slave axis's node, sent this cycle.
  bool axis_sync_due = false;
  AxisSyncOut axis_sync{};
  // G51.2 / G50.2 to the polygon axis's node, sent this cycle.
  bool polygon_sync_due = false;
  PolygonOut polygon_sync{};
  // G51.8 / G50.8 to the cam slave's node, sent this cycle (nullptr: none); the table stays the
  // coordination's.
  const CamOut* cam_sync = nullptr;
  // G81.4 / G80.4 (a reset's stop, the hand-over of the reached angle) to the EGB work axis's
  // node, sent this cycle.
  bool egb_sync_due = false;
  EgbOut egb_sync{};
  static constexpr std::size_t kMaxEvents = 64;  // many short blocks may pass in one cycle
  std::array<ChannelEvent, kMaxEvents> events{};
  std::size_t event_count = 0;
  // Events beyond kMaxEvents are dropped (the controller keeps room for a program end).
  void add_event(const ChannelEvent& event) noexcept {
    if (event.kind == ChannelEventKind::block_started) {
      keep_file(event.file);
    }
    if (event_count < kMaxEvents) {
      events[event_count++] = event;
    }
  }
  void keep_file(const std::string* name) noexcept {
    const std::size_t n = name == nullptr ? 0 : std::min(name->size(), file.size() - 1);
    if (n > 0) {
      std::copy_n(name->data(), n, file.begin());
    }
    file[n] = '\0';
  }
};

}  // namespace mcnc::channel
