#pragma once
// The machine's PLC program (ARCHITECTURE.md §5, docs/plc.md): the I/O image of a simulated
// machine, the M codes of the machine file's table with their FIN conditions, interlocks and
// time-outs, the spindle start interlocks and T codes (the turret's index time). Channels ask
// with aux requests; each request ends in exactly one answer: done (FIN), refused (an
// interlock, an unknown code) or timed out. Pure and deterministic: requests sent before a
// cycle are taken in that cycle, in the order (cycle sent, channel); fixed-size, no allocation
// after construction, no exceptions.
#include "common/config/plc_config.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace mcnc::plc {

enum class AuxKind : std::uint8_t { m_code, t_code };
enum class AuxOutcome : std::uint8_t { done, refused, timed_out };
const char* to_string(AuxOutcome outcome) noexcept;

struct AuxRequest {
  std::uint32_t channel = 0;
  std::uint64_t id = 0;  // unique per channel and run: the answer names it
  AuxKind kind = AuxKind::m_code;
  int code = 0;     // M number (3/4: a spindle start), or the T word (e.g. 101)
  int spindle = 0;  // M03/M04: the axis id of the spindle it starts
  std::uint64_t sent_cycle = 0;
};

struct AuxResult {
  AuxRequest request;
  AuxOutcome outcome = AuxOutcome::done;
  std::array<char, 96> reason{};  // why it was refused or timed out
};

// An axis the PLC watches, as its feedback (stamped N-1) shows it: a spindle an interlock looks
// at, or an axis a sensor input of the simulated machine is switched by.
struct AxisView {
  int axis = 0;         // axis id
  bool turning = true;  // unknown (no feedback): counts as turning
  int coupled_to = 0;   // G114.1: the master this slave follows (axis id), 0: none
  bool locked = false;  // ... in phase
  bool known = false;   // its feedback is there: `position` is its actual position
  double position = 0.0;
};

struct PlcOutput {
  static constexpr std::size_t kMaxEvents = 64;
  std::array<AuxRequest, kMaxEvents> started{};  // requests taken this cycle (trace `aux`)
  std::size_t started_count = 0;
  std::array<AuxResult, kMaxEvents> answers{};  // requests ended this cycle
  std::size_t answer_count = 0;
  std::uint64_t outputs = 0;  // bit k: signal k (an output) on
  std::uint64_t inputs = 0;   // bit k: signal k (an input) on
  std::size_t busy = 0;       // requests under way
};

class MachinePlc {
 public:
  static constexpr std::size_t kMaxQueued = 256;
  static constexpr std::size_t kMaxActive = 64;  // one per channel: a channel waits for each

  MachinePlc(const config::PlcConfig& config, int cycle_us) noexcept;

  // A request to take at the first cycle after `sent_cycle`. A full queue refuses it in that
  // cycle's answers.
  void request(const AuxRequest& request) noexcept;
  // A spindle allowed to start counts as turning for this many cycles even before its feedback
  // says so (the start reaches the drive and comes back as feedback a few cycles later).
  static constexpr std::uint64_t kStartBridgeCycles = 16;
  // One cycle: the simulated inputs follow the outputs or the axes they watch, queued requests
  // start (or are refused), running ones end on their FIN condition or time out. `axes`: the
  // watched axes (spindles and the axes of position inputs).
  const PlcOutput& cycle(std::uint64_t cycle, std::span<const AxisView> axes) noexcept;
  [[nodiscard]] const PlcOutput& output() const noexcept { return out_; }
  [[nodiscard]] bool signal(int index) const noexcept { return (state_ >> index) & 1U; }

 private:
  struct Active {
    AuxRequest request;
    const config::PlcMCode* entry = nullptr;  // nullptr: a T code
    std::uint64_t started = 0;
  };
  void start(const AuxRequest& r, std::uint64_t cycle, std::span<const AxisView> spindles) noexcept;
  void answer(const AuxRequest& r, AuxOutcome outcome, const char* reason) noexcept;
  [[nodiscard]] bool holds(std::span<const config::PlcCondition> conditions) const noexcept;
  // The first condition that does not hold, as text ("chuck1_closed=1"), or nullptr.
  [[nodiscard]] const char* unmet(std::span<const config::PlcCondition> conditions,
                                  std::array<char, 64>& text) const noexcept;
  void update_inputs(std::uint64_t cycle, std::span<const AxisView> axes) noexcept;

  const config::PlcConfig& config_;
  int cycle_us_;
  std::uint64_t state_ = 0;  // bit per signal
  // Per signal: an output's last change, an input's value due at a cycle (following).
  std::array<std::uint64_t, config::kMaxPlcSignals> changed_at_{};
  std::array<AuxRequest, kMaxQueued> queue_{};
  std::size_t queue_count_ = 0;
  std::array<Active, kMaxActive> active_{};
  std::size_t active_count_ = 0;
  std::array<AuxRequest, kMaxQueued> overflow_{};  // refused for want of room, answered next
  std::size_t overflow_count_ = 0;
  struct Start {
    int spindle = 0;
    std::uint64_t cycle = 0;
  };
  std::array<Start, 16> starts_{};  // the last start allowed per spindle
  [[nodiscard]] bool turning(int spindle, std::uint64_t cycle,
                             std::span<const AxisView> spindles) const noexcept;
  // Master or slave of a G114.1 pair in phase: a part held by both chucks turns with both.
  [[nodiscard]] static bool synchronised(int spindle, std::span<const AxisView> spindles) noexcept;
  PlcOutput out_{};
};

}  // namespace mcnc::plc
