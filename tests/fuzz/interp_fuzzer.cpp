// libFuzzer target over the ISO lathe interpreter (channel/interp/): loads the input as a program
// file and pulls commands until the program ends, raises an alarm or the pull budget is spent.
// Every command and alarm is also rendered as JSON, so the output code runs on fuzzed values.
// Besides the sanitizers it checks that after an alarm next() returns nothing (interpreter.hpp)
// and that every number a command carries is finite (the planner and JSON need it).
//
// Input: byte 0 selects the configuration, the rest is the program text. The flags are byte 0
// minus '0', so a seed file starts with a readable character: '0' defaults, '1' system B, '2'
// gsk, '4' increment, '8' block skip, '@' axes and call tables, 'P' channel 2, 'p' per rev:
//   bit 0  system B (else A)
//   bit 1  dialect gsk, with the GSK macro ranges (#1-#33, #100-#199, GSK vacant ordering);
//          and thread repair on with a groove recorded at Z-10, 90 degrees; with bit 0
//          ('3'): the mill dialect fanuc-mill (its system B and axes X Y Z)
//   bit 2  decimal_point increment (else calculator)
//   bit 3  block skip levels 1 and 3 switched on
//   bit 4  axes X Z C Y with exchange numbers, X and C as the polar interpolation's axes (G12.1,
//          G16), C the normal direction control's (G41.1), Z's G22 limits, and the macro-call
//          tables of
//          docs/canonical-commands.md (T -> O9010, G120 -> O9010, M60 -> O9001, M78 -> O9030,
//          G200-G298 -> O9200-, M500-M598 -> O9500-, M800-M898 -> O9800-)
//   bit 5  channel 2 (else 1)
//   bit 6  power-on G99 (feed per revolution), arc_check off, dwell in revolutions with G99,
//          inclined-axis control of X on Z at -30 degrees
//   bit 7  least increment 0.0001 mm, 4 call levels fewer (max_subprogram_nesting 12)
//
// Bounds: M99 in a main program loops forever by design, and a pull may evaluate up to
// `statement_limit` steps, so both the pulls and the steps per pull are limited; their product
// bounds the work per input (kMaxPulls * kStatementLimit = 10^6 steps, about 2 s under
// ASan+UBSan for a loop that spends the whole statement limit on every pull; 4*10^7 steps took
// 63 s, far beyond -timeout=10).
#include "channel/interp/dialect.hpp"
#include "channel/interp/interpreter.hpp"
#include "channel/interp/output/command_json.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <variant>

namespace {

using namespace mcnc::interp;

constexpr std::uint64_t kStatementLimit = 5'000;
constexpr int kMaxPulls = 200;

InterpreterConfig make_config(std::uint8_t flags) {
  InterpreterConfig c;
  c.statement_limit = kStatementLimit;
  c.retained_file.clear();  // no file I/O: #500-#999 stay in memory
  c.program_dir.clear();    // no directory lookups: only the programs of the input
  if (flags & 0x01) {
    c.system = GCodeSystem::b;
  }
  if ((flags & 0x03) == 0x03) {
    select_dialect(c, Dialect::fanuc_mill);
  } else if (flags & 0x02) {
    select_dialect(c, Dialect::gsk);
    // Thread repair on (№174.4) with a recorded groove, so that G92/G92.1 P1 get past it.
    c.thread_repair = true;
    c.thread_repair_recorded = true;
    c.thread_repair_z = -10.0;
    c.thread_repair_degrees = 90.0;
  }
  if (flags & 0x04) {
    c.decimal_point = DecimalPoint::increment;
  }
  if (flags & 0x08) {
    c.block_skip[1] = true;
    c.block_skip[3] = true;
  }
  if (flags & 0x10) {
    AxisConfig x{'X', true};
    x.start = 100.0;
    x.reference = {0.0, 150.0, 10.0, -5.0};
    x.exchange = 1;
    AxisConfig z{'Z', false};
    z.start = 50.0;
    z.reference = {0.0, 200.0, 0.0, 0.0};
    z.exchange = 2;
    AxisConfig cax{'C', false, true};
    cax.exchange = 14;
    AxisConfig y{'Y', false};
    c.axes = {x, z, cax, y};
    c.polar_linear = 'X';
    c.polar_rotary = 'C';
    c.normal_axis = 'C';              // G41.1/G42.1 turn C outside polar interpolation
    c.axes[1].stroke_minus = -400.0;  // G22 without words: Z -400..-350
    c.axes[1].stroke_plus = -350.0;
    c.calls.t_program = 9010;
    c.calls.g_macro = {{1200, 9010}};
    c.calls.g_range_count = 99;
    c.calls.g_range_program = 9200;
    c.calls.g_range_first = 200;
    c.calls.m_subprogram = {{60, 9001}};
    c.calls.m_sub_range_count = 99;
    c.calls.m_sub_range_program = 9500;
    c.calls.m_sub_range_first = 500;
    c.calls.m_macro = {{78, 9030}};
    c.calls.m_macro_range_count = 99;
    c.calls.m_macro_range_program = 9800;
    c.calls.m_macro_range_first = 800;
    c.tool_geometry[1] = ToolOffsetValues{0.5, 1.2, 0.0, 0.4, 3};
    c.tool_wear[1] = ToolOffsetValues{-0.02, 0.0, 0.0, 0.0, 0};
    c.work_offsets[1][1] = -300.0;  // G54 Z
  }
  if (flags & 0x20) {
    c.channel = 2;
  }
  if (flags & 0x40) {
    c.power_on_feed_mode = FeedMode::per_rev;
    c.arc_check = false;
    c.dwell_in_revs_with_g99 = true;
    c.inclined_axis = 'X';
    c.inclined_orthogonal = 'Z';
    c.inclined_degrees = -30.0;
  }
  if (flags & 0x80) {
    c.least_increment = 0.0001;
    c.max_subprogram_nesting = 12;
    c.max_macro_nesting = 4;
  }
  return c;
}

// Every number a command carries reaches the planner or the trace: it must be finite.
void check_finite(const Command& c) {
  bool ok = std::isfinite(c.feed) && std::isfinite(c.seconds) && std::isfinite(c.rpm) &&
            std::isfinite(c.surface) && std::isfinite(c.max_rpm) && std::isfinite(c.angle) &&
            std::isfinite(c.timeout_s) && std::isfinite(c.width_s) && std::isfinite(c.dwell_s) &&
            std::isfinite(c.sync_r) && std::isfinite(c.center[0]) && std::isfinite(c.center[1]);
  for (const double v : c.to) {
    ok = ok && std::isfinite(v);
  }
  for (const auto& a : c.args) {
    ok = ok && std::isfinite(a.second);
  }
  if (!ok) {
    std::fprintf(stderr,
                 "interp_fuzzer: command %llu (line %d) carries a value that is not finite\n",
                 static_cast<unsigned long long>(c.n), c.line);
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) {
    return -1;  // not added to the corpus
  }
  const auto flags = static_cast<std::uint8_t>(data[0] - '0');
  const InterpreterConfig config = make_config(flags);
  std::string text(reinterpret_cast<const char*>(data + 1), size - 1);
  const std::string file = "fuzz.nc";

  Interpreter interp(config);
  std::string json;
  if (auto alarm = interp.start(std::move(text), file)) {
    output::append_json(json, *alarm);
    return 0;
  }
  for (int pulls = 0; pulls < kMaxPulls; ++pulls) {
    auto r = interp.next();
    if (!r) {
      break;
    }
    json.clear();
    if (const auto* c = std::get_if<Command>(&*r)) {
      check_finite(*c);
      output::append_json(json, *c, config.axes, file);
    } else {
      output::append_json(json, std::get<ProgramAlarm>(*r));
      // After an alarm the interpreter must stay stopped.
      if (interp.next()) {
        std::fprintf(stderr, "interp_fuzzer: next() returned a result after an alarm\n");
        std::abort();
      }
      break;
    }
  }
  // The state readers a channel uses after a run.
  volatile double sink = 0.0;
  for (std::size_t i = 0; i < config.axes.size(); ++i) {
    sink = sink + interp.machine_position()[i] + interp.program_position(static_cast<int>(i));
  }
  (void)sink;
  return 0;
}
