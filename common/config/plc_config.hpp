#pragma once
// The `plc:` section of a machine file: the machine's PLC (mcnc-plcnode, docs/plc.md). Its I/O
// image (outputs it sets, inputs it reads; an input of this simulated machine follows an output
// after a delay), the M codes it runs with their completion (FIN) conditions and interlocks,
// the spindle start interlocks and the turret's index time for T codes.
#include <cstddef>
#include <string>
#include <vector>

namespace mcnc::config {

// The I/O image travels as 64-bit masks (PlcStatus).
inline constexpr std::size_t kMaxPlcSignals = 64;

struct PlcSignal {
  std::string name;
  bool output = false;
  // An input: the output it follows (the simulated machine), inverted or not, this long after
  // the output changed. Empty: it keeps `initial`.
  std::string follows;
  int follows_index = -1;  // the signal `follows` names
  bool invert = false;
  int delay_ms = 0;
  bool initial = false;
  int index = 0;  // position in `signals`
  // An input: the port number G04 I names it by (1-99; 0: none).
  int port = 0;
  // An input: the skip signal G31 P names it by, 1-8 for G0014.0-G0014.7 (0: none).
  int skip = 0;
  // An input of the simulated machine that is on while axis `at_axis` (its id; 0: none) stands
  // at or beyond `at` on the side `at_side` (+1 above, -1 below): a sensor the axis reaches.
  int at_axis = 0;
  int at_side = 0;
  double at = 0.0;
};

// `name` or `name=1`: the signal on; `name=0`: off.
struct PlcCondition {
  int signal = 0;  // index into PlcConfig::signals
  bool on = true;
};

struct PlcMCode {
  int code = 0;
  std::vector<int> channels;            // channel ids it applies to; empty: every channel
  std::vector<PlcCondition> set;        // outputs written when the code starts
  std::vector<PlcCondition> wait;       // inputs that complete it (FIN); none: FIN at once
  std::vector<PlcCondition> requires_;  // inputs that must hold before it starts (interlock)
  int spindle_stopped = 0;              // axis id of a spindle that must stand (0: none)
  int timeout_ms = 5000;                // FIN not reached within: alarm
};

struct PlcSpindleStart {
  int spindle = 0;                      // axis id
  std::vector<PlcCondition> requires_;  // M03/M04 only with these inputs
};

struct PlcConfig {
  bool present = false;
  std::string middleware;  // the PLC node's DDS implementation; empty: the machine's
  std::vector<PlcSignal> signals;
  std::vector<PlcMCode> m_codes;
  std::vector<PlcSpindleStart> spindle_start;
  int tool_change_ms = 0;  // T codes: FIN this long after the request (the turret indexes)

  // The entry for M`code` in channel `channel`, or nullptr.
  [[nodiscard]] const PlcMCode* find_m_code(int code, int channel) const noexcept;
  [[nodiscard]] const PlcSignal* find_signal(const std::string& name) const noexcept;
};

}  // namespace mcnc::config
