#pragma once
// What a channel knows of the axes it programs, as its coordination state machines read it:
// the feedback of one axis at cycle N (stamped N-1), how the machine file sets up each axis slot
// and what the channel may do with it now. Plain values.
#include <cstddef>
#include <cstdint>

namespace mcnc::coordination {

// G31 skip: what the axis node says of the touch probe of an axis's drive.
enum class ProbeSeen : std::uint8_t { off = 0, armed = 1, latched = 2 };

// What the channel knows of one of its axes at cycle N (the feedback stamped N-1).
struct AxisFeedbackView {
  double cmd = 0.0;      // position the axis node commands its drive
  double act = 0.0;      // actual position
  bool enabled = false;  // drive in operation and following this channel
  bool alarm = false;    // the axis node holds an alarm
  bool present = false;  // feedback received at all
  // G140/G141: the channel that owns the axis now (0: nobody) and the one that released it
  // (or had it taken) to that owner, 0 in the configured assignment.
  std::uint32_t owner = 0;
  std::uint32_t released_by = 0;
  // G114.1: a slave spindle's master (axis id, 0: none) and whether it is in phase; G51.4: a
  // slave axis's master.
  std::uint32_t coupled_to = 0;
  bool coupling_locked = false;
  // G140-G142: the node refused this channel's latest request, or could not keep it.
  bool request_refused = false;
  bool request_full = false;
  // G31: the axis's touch probe, and where it latched (units, as act).
  ProbeSeen probe = ProbeSeen::off;
  double probe_pos = 0.0;
  double vel = 0.0;  // actual velocity, units/s (a spindle's degrees/s: G04 PS)
  // The drive's torque (0x6077) in percent of the motor's rated torque, when it reports it
  // (G10 L14 P0/P1).
  bool load_known = false;
  double load = 0.0;
  // G31.8: the edges the drive latched since its probe was armed continuously (probe_pos: the
  // last one's position).
  std::uint32_t probe_count = 0;
  // G51.8: the cam's lift in cmd (and act) that the node lays over what the channel commands.
  double superimposed = 0.0;

  // Where the channel commands the axis: cmd without the lift of a cam.
  [[nodiscard]] double channel_cmd() const noexcept { return cmd - superimposed; }
};

// One axis the channel programs. The channel's own axes belong to it at start; an exchange
// slot (another channel's exchangeable axis: the spec's virtual axis, dafeng §3.3) moves
// nothing physical until the channel acquires the axis (G141).
struct AxisSlot {
  char address = 'X';
  bool exchange_slot = false;
  std::uint32_t home = 0;  // the channel that owns the axis in the configured assignment
  std::uint32_t id = 0;    // the axis's system number (G51.4 P and Q name axes by it)
  // G51.4 (params 5600, 5610): it may follow another axis, its master when G51.4 has no P (0:
  // none), and whether it follows that master from power-on (a gantry's second drive).
  bool may_follow = false;
  std::uint32_t default_master = 0;
  bool follows_at_start = false;
  // G51.2: the channel's polygon axis, a rotary servo axis that follows the master spindle
  // instead of the program between G51.2 and G50.2 (params 5310/5311).
  bool polygon = false;
};

// G51.4: an axis of the machine as a possible master (spec dafeng §3.2: of the same kind as
// the slave, and here never a slave itself, so that no slave follows a slave).
enum class MachineAxisKind : std::uint8_t { linear, rotary, spindle };
struct MachineAxis {
  MachineAxisKind kind = MachineAxisKind::linear;
  bool may_follow = false;
};

// What the channel does with a slot now: commands it (owned, its position taken over), a
// virtual axis (an exchange slot the channel does not own: moves nothing physical), away
// (given to or taken by another channel, or back but not taken over yet: a block moving it is
// an alarm), follows (G51.4: it moves with its master, not with this channel's program) or
// speed_control (the first spindle's C axis while the spindle is under speed control).
enum class SlotUse : std::uint8_t { commanded, virtual_axis, away, follows, speed_control };

// A request an axis node answers in its feedback: sent at N, taken at N+1 (ARCHITECTURE.md §4),
// seen in the feedback at N+2. Before that the feedback cannot show the answer.
[[nodiscard]] constexpr bool answer_visible(std::uint64_t sent_cycle,
                                            std::uint64_t cycle) noexcept {
  return cycle >= sent_cycle + 2;
}

}  // namespace mcnc::coordination
