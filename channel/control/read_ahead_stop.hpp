#pragma once
// The blocks that stop the channel's read-ahead (spec dafeng §3.0, spec L6907): G04.1, G144,
// G145, G140-G142, aux codes the PLC answers (and spindle starts it allows), G114.1/G113,
// G51.4/G50.4, M18/M17, G31, G04 I/PS, G10 L14 P0-P5/P9-P12/P20-P51 and the in-feeds G10 L14
// P7/P8 watch. Such a block is pulled and held until every block before it ended, then run by its
// coordination machine; nothing after it is read meanwhile. "The block that stops read-ahead" is
// one std::variant, and read_ahead_stop() is the one place that says which commands are one and
// what each carries. Pure: no allocation beyond the command copies the G31, G10 L14 P7/P8 and aux
// blocks keep (made while reading ahead, as before), nothing throws but a copy of a command.
#include "channel/coordination/aux_handshake.hpp"
#include "channel/coordination/axis_exchange.hpp"
#include "channel/coordination/condition_block.hpp"
#include "channel/coordination/coupling_request.hpp"
#include "channel/coordination/sub_call.hpp"
#include "channel/coordination/sync_barrier.hpp"
#include "channel/interp/command.hpp"

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>

namespace mcnc::channel {

// G31 skip: the touch probe the channel asks an axis's drive to arm (latch where its input
// goes on, or off); what the axis node says of it is ProbeSeen (the values the wire carries).
// G160 (torque): the axis node latches where the axis's torque is at its limit and its
// following error beyond the skip deviation.
// What the setpoint asks of an axis's probe: G31's first edge, G160's torque skip, G31.8's every
// edge (the drive's continuous latching).
enum class ProbeArm : std::uint8_t {
  off = 0,
  rising = 1,
  falling = 2,
  torque = 3,
  every_rising = 4,
  every_falling = 5
};

// Where a block that stops read-ahead stands in the program.
struct HeldBlock {
  std::uint64_t n = 0;
  int line = 0;
  const std::string* file = nullptr;
  std::string_view text;
  bool started = false;  // its block_started event is out
  interp::ModalState modal;
};

struct SyncStop {  // G04.1 [P]
  HeldBlock block;
  bool has_p = false;
  std::int32_t p = 0;
  coordination::ChannelSet participants;
  bool all_channels = false;
};
struct CallStop {  // G144
  HeldBlock block;
  coordination::CallRequest call;  // call_id set when it is sent
};
struct ReleaseStop {  // G145
  HeldBlock block;
};
struct ExchangeStop {  // G140 / G141 / G142
  HeldBlock block;
  coordination::AxisRequestKind kind = coordination::AxisRequestKind::restore;
  std::size_t slot = 0;
  bool force = false;  // G141 P1
};
struct AuxStop {  // an M or T code for the PLC, or a spindle start it must allow
  HeldBlock block;
  coordination::AuxKind kind = coordination::AuxKind::m_code;
  int code = 0;
  bool spindle_start = false;
  interp::Command command;  // a spindle start: goes to the planner once allowed
};
// G114.1 / G113 (spindle), G51.4 / G50.4 (axis), G51.2 / G50.2 (polygon), G51.8 / G50.8 (cam),
// G81.4 / G80.4 (electronic gear box)
struct CouplingStop {
  HeldBlock block;
  bool axis = false;
  coordination::SpindleSyncOut spindle{};
  bool on = false;           // axis: G51.4
  std::uint32_t master = 0;  // axis: P (0: the slave's default)
  std::uint32_t slave = 0;   // axis: Q
  bool polygon = false;      // G51.2 / G50.2
  coordination::PolygonOut polygon_sync{};
  bool cam = false;  // G51.8 / G50.8
  coordination::CamOut cam_sync{};
  bool egb = false;  // G81.4 / G80.4
  coordination::EgbOut egb_sync{};
};
struct ModeStop {  // M18 / M17
  HeldBlock block;
  bool position = false;
};
// G31: the move waits until the touch probes on its input are armed, runs until one latches
// (then stops at the planner's reset deceleration) or it ends, and the source learns where.
// G160 and G31 P98/P99 arm the torque skips of the axes whose torque they limit (`torque`).
struct SkipStop {
  interp::Command command;          // the move, queued once the probes are armed
  ProbeArm arm = ProbeArm::rising;  // the touch probes' edge, or `torque` alone (G160, P98)
  bool at_front = false;            // its torque limits stand from when it reached the front
};
// G04 I / G04 PS: the block waits until its condition holds, its dwell time ends or it times
// out.
struct WaitStop {
  HeldBlock block;
  coordination::ConditionBlock condition;
};

// G10 L14 P9 (`limit`), P0/P1 and P2-P5: the drives' torque limits, the loads watched or a
// load timer change once every block before it ended, so that a move runs under one setting
// from start to end.
struct TorqueDataStop {
  HeldBlock block;
  bool limit = true;            // P9; else P0/P1 or P2-P5
  std::uint32_t axes = 0;       // bit i: channel axis i's value is set
  interp::AxisVector values{};  // percent of the rated torque: the limit (0: cancelled) or load
  bool every_move = false;      // P0 (every move) or P1 (G01 moves)
  double filter_s = 0.0;        // J
  int timer = 0;                // P2-P5: the load timer it starts (0: P0/P1)
};
// G10 L14 P20-P51: load timer `timer` compared with `seconds` once every block before it ended;
// the axes that meet it go back to the interpreter (#R), or are an alarm without R.
struct LoadTimerStop {
  HeldBlock block;
  int timer = 2;
  bool longer = false;           // P21/P31/P41/P51: more than `seconds`; else less
  std::uint32_t axes = 0;        // bit i: channel axis i is compared
  interp::AxisVector seconds{};  // per axis
  bool variable = false;         // R given
};
// G10 L14 P10/P11/P12 once every block before it ended: P10 puts the axes named in torque mode
// (α0: back to position mode), P11 sets their motor speed in it, P12 puts them back in position
// mode with a torque limit.
struct TorqueModeStop {
  HeldBlock block;
  int p = 10;                   // 10, 11 or 12
  std::uint32_t axes = 0;       // bit i: channel axis i is named
  interp::AxisVector values{};  // P10: % of the rated torque; P11: rpm; P12: the limit (0: none)
};
// The cutting block after a G51.2 or G81.4 that did not wait for its slave to lock (params
// 5300.5 / 5320.5 = 1): queued once the slave is locked (spec dafeng L2917-2919, L3331-3333).
struct LockWaitStop {
  interp::Command command;
};
// G10 L14 P7/P8 (decision 162): a drilling or tapping cycle's in-feed watched for overload,
// queued once every block before it ended. While it moves, the loads of its axes are watched
// as G10 L14 P0's; on an overload the move stops, the tool goes back along it to the hole's R
// point, and then the cycle alarms, goes on with the next block (the source drops the rest of
// this one) or feeds in again from R, as Command::overload_outcome says.
enum class OverloadPhase : std::uint8_t {
  start,       // not queued yet
  feeding,     // the in-feed moves, its load watched
  stopping,    // overloaded: the move decelerates (the planner's reset deceleration)
  retracting,  // back to R
};
struct OverloadStop {
  interp::Command command;  // the in-feed
  OverloadPhase phase = OverloadPhase::start;
  interp::AxisVector start{};  // where the in-feed starts (a retry starts there again)
  std::uint32_t overloads = 0;
  coordination::CoordinationAlarm alarm;  // the last overload's (number 1282)
};
// The block held, std::monostate when none.
using ReadAheadStop = std::variant<std::monostate, SyncStop, CallStop, ReleaseStop, ExchangeStop,
                                   AuxStop, CouplingStop, ModeStop, SkipStop, WaitStop,
                                   TorqueDataStop, LoadTimerStop, TorqueModeStop, LockWaitStop,
                                   OverloadStop>;

// What decides which commands stop read-ahead in a channel.
struct StopRules {
  std::uint32_t channel_id = 1;
  std::span<const coordination::AxisSlot> slots;  // G140/G141 name a slot by its address
  bool plc = false;                               // M and T codes go to a PLC node
  bool spindle_may_follow = false;                // the first spindle may follow (G114.1 slave)
  coordination::ConditionSetup conditions{};      // G04 PS: speed arrival width and timeout
};

// The stop that command `c` (pulled in program order) makes, or std::monostate when it goes to
// the planner. `spindle_queued` is the first spindle's direction as the pulled blocks leave it
// (+1 M03, -1 M04, 0 stopped): a spindle start or reversal asks the PLC, a speed change of a
// turning spindle does not; it is kept up to date. A G140/G141 of an axis that is not exchanged
// sets `alarm` (raised when the blocks before it ran).
ReadAheadStop read_ahead_stop(const interp::Command& c, const StopRules& rules, int& spindle_queued,
                              std::optional<interp::ProgramAlarm>& alarm);

}  // namespace mcnc::channel
