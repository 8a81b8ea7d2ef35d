#include "tools/mcnc/interp_params.hpp"

#include "channel/interp/dialect.hpp"
#include "common/config/dialect_names.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <optional>
#include <set>
#include <utility>

namespace mcnc::tools {

namespace {

using interp::InterpreterConfig;

[[noreturn]] void bad(const std::string& key, const std::string& why) {
  throw ParamError(key + ": " + why);
}

void only_keys(const YAML::Node& node, const std::string& where,
               std::initializer_list<const char*> keys) {
  if (!node.IsMap()) {
    bad(where, "must be a mapping");
  }
  const std::set<std::string> allowed(keys.begin(), keys.end());
  for (const auto& kv : node) {
    const auto k = kv.first.as<std::string>();
    if (allowed.count(k) == 0) {
      bad(where.empty() ? k : where + "." + k, "unknown key");
    }
  }
}

template <typename T>
T get(const YAML::Node& n, const std::string& key) {
  try {
    return n.as<T>();
  } catch (const YAML::Exception&) {
    bad(key, "wrong type");
  }
}

// The canned cycles' parameters (interp::CycleDefaults), lengths in mm (radius).
void cycle_defaults(const YAML::Node& node, interp::CycleDefaults& d) {
  only_keys(node, "cycles",
            {"rough_depth",        "rough_retract",        "rough_retract_along_contour",
             "pattern_relief_x",   "pattern_relief_z",     "pattern_passes",
             "groove_retract",     "thread_finish_passes", "thread_chamfer",
             "thread_angle",       "thread_min_depth",     "thread_allowance",
             "thread_alternating", "drill_high_speed",     "drill_retract",
             "drill_clearance",    "drill_full_retract",   "tap_high_speed",
             "tap_retract",        "bore_shift_direction", "drill_overload",
             "tap_overload"});
  const auto length = [&](const char* k, double& v) {
    if (node[k]) {
      v = get<double>(node[k], std::string("cycles.") + k);
      if (v < 0.0) {
        bad(std::string("cycles.") + k, "must be >= 0");
      }
    }
  };
  const auto count = [&](const char* k, int& v, int low, int high) {
    if (node[k]) {
      v = get<int>(node[k], std::string("cycles.") + k);
      if (v < low || v > high) {
        bad(std::string("cycles.") + k, std::to_string(low) + "-" + std::to_string(high));
      }
    }
  };
  const auto flag = [&](const char* k, bool& v) {
    if (node[k]) {
      v = get<bool>(node[k], std::string("cycles.") + k);
    }
  };
  length("rough_depth", d.rough_depth);
  length("rough_retract", d.rough_retract);
  flag("rough_retract_along_contour", d.rough_retract_along_contour);
  if (node["pattern_relief_x"]) {
    d.pattern_relief_x = get<double>(node["pattern_relief_x"], "cycles.pattern_relief_x");
  }
  if (node["pattern_relief_z"]) {
    d.pattern_relief_z = get<double>(node["pattern_relief_z"], "cycles.pattern_relief_z");
  }
  count("pattern_passes", d.pattern_passes, 1, 999);
  length("groove_retract", d.groove_retract);
  count("thread_finish_passes", d.thread_finish_passes, 0, 99);
  count("thread_chamfer", d.thread_chamfer, 0, 99);
  count("thread_angle", d.thread_angle, 0, 99);
  length("thread_min_depth", d.thread_min_depth);
  length("thread_allowance", d.thread_allowance);
  flag("thread_alternating", d.thread_alternating);
  flag("drill_high_speed", d.drill_high_speed);
  length("drill_retract", d.drill_retract);
  length("drill_clearance", d.drill_clearance);
  length("drill_full_retract", d.drill_full_retract);
  flag("tap_high_speed", d.tap_high_speed);
  length("tap_retract", d.tap_retract);
  count("bore_shift_direction", d.bore_shift_direction, 0, 3);
  // G10 L14 P7/P8 on an overload: params 5100.2-5100.4 and 5113, 5200.4-5200.6 and 5251.
  const auto overload = [&](const char* k, interp::OverloadParams& o) {
    const YAML::Node n = node[k];
    if (!n) {
      return;
    }
    const std::string at = std::string("cycles.") + k;
    only_keys(n, at, {"retract", "retry", "alarm", "variable"});
    const auto bit = [&](const char* b, bool& v) {
      if (n[b]) {
        v = get<bool>(n[b], at + "." + b);
      }
    };
    bit("retract", o.retract);
    bit("retry", o.retry);
    bit("alarm", o.alarm);
    if (n["variable"]) {
      o.variable = get<int>(n["variable"], at + ".variable");
      if (o.variable < 0 || o.variable > 999) {
        bad(at + ".variable", "0-999");
      }
    }
  };
  overload("drill_overload", d.drill_overload);
  overload("tap_overload", d.tap_overload);
}

char axis_letter(const std::string& s, const std::string& key) {
  if (s.size() != 1 || std::string("XYZABC").find(s[0]) == std::string::npos) {
    bad(key, "an axis is one of X, Y, Z, A, B, C");
  }
  return s[0];
}

// Per-axis values keyed by letter, in programmed units (X as a diameter on diameter axes).
void axis_values(const YAML::Node& node, const std::string& key, const InterpreterConfig& c,
                 std::array<double, interp::kMaxChannelAxes>& out) {
  if (!node.IsMap()) {
    bad(key, "must map axis letters to values");
  }
  for (const auto& kv : node) {
    const std::string k = key + "." + kv.first.as<std::string>();
    const char letter = axis_letter(kv.first.as<std::string>(), k);
    bool found = false;
    for (std::size_t i = 0; i < c.axes.size(); ++i) {
      if (c.axes[i].name == letter) {
        found = true;
        out[i] = get<double>(kv.second, k) / (c.axes[i].diameter ? 2.0 : 1.0);
      }
    }
    if (!found) {
      bad(k, "not an axis of this channel");
    }
  }
}

void tool_table(const YAML::Node& node, const std::string& key,
                std::array<interp::ToolOffsetValues, interp::kMaxToolOffsets + 1>& table) {
  if (!node.IsMap()) {
    bad(key, "must map offset numbers to values");
  }
  for (const auto& kv : node) {
    const int n = get<int>(kv.first, key);
    const std::string k = key + "." + std::to_string(n);
    if (n < 1 || n > interp::kMaxToolOffsets) {
      bad(k, "offset numbers are 1-64");
    }
    only_keys(kv.second, k, {"X", "Z", "Y", "R", "tip"});
    interp::ToolOffsetValues& t = table[static_cast<std::size_t>(n)];
    if (kv.second["X"]) {
      t.x = get<double>(kv.second["X"], k + ".X");
    }
    if (kv.second["Z"]) {
      t.z = get<double>(kv.second["Z"], k + ".Z");
    }
    if (kv.second["Y"]) {
      t.y = get<double>(kv.second["Y"], k + ".Y");
    }
    if (kv.second["R"]) {
      t.radius = get<double>(kv.second["R"], k + ".R");
    }
    if (kv.second["tip"]) {
      t.tip = get<int>(kv.second["tip"], k + ".tip");
    }
  }
}

std::vector<std::pair<int, int>> code_map(const YAML::Node& node, const std::string& key,
                                          int scale) {
  std::vector<std::pair<int, int>> out;
  if (!node.IsMap()) {
    bad(key, "must map codes to program numbers");
  }
  for (const auto& kv : node) {
    const double code = get<double>(kv.first, key);
    out.emplace_back(static_cast<int>(code * scale + 0.5), get<int>(kv.second, key));
  }
  return out;
}

void range(const YAML::Node& node, const std::string& key, int& count, int& program, int& first) {
  only_keys(node, key, {"count", "program", "first"});
  count = get<int>(node["count"], key + ".count");
  program = get<int>(node["program"], key + ".program");
  first = get<int>(node["first"], key + ".first");
}

}  // namespace

void load_interp_params(const std::string& path, InterpreterConfig& c) {
  YAML::Node root;
  try {
    root = YAML::LoadFile(path);
  } catch (const YAML::Exception& e) {
    throw ParamError(path + ": " + e.what());
  }
  if (root.IsNull()) {
    return;
  }
  only_keys(root, "",
            {"system",
             "dialect",
             "channel",
             "spindles",
             "decimal_point",
             "least_increment",
             "feed_mode",
             "arc_check",
             "arc_tolerance",
             "dwell_in_revs_with_g99",
             "thread_chamfer_leads",
             "thread_repair",
             "chamfer_is_length",
             "compensation_idle_blocks",
             "stroke_inside_forbidden",
             "skip_input",
             "torque_skip",
             "polar",
             "cylindrical_parallel",
             "normal",
             "inclined",
             "cycles",
             "block_skip",
             "max_tool",
             "statement_limit",
             "retained_file",
             "program_dir",
             "axes",
             "work_offsets",
             "tool_geometry",
             "tool_wear",
             "macro_calls",
             "macro"});
  if (root["system"]) {
    const auto s = get<std::string>(root["system"], "system");
    if (s != "A" && s != "B") {
      bad("system", "A or B");
    }
    c.system = s == "A" ? interp::GCodeSystem::a : interp::GCodeSystem::b;
  }
  if (root["dialect"]) {
    const auto s = get<std::string>(root["dialect"], "dialect");
    const std::optional<interp::Dialect> d = interp::dialect_named(s);
    if (!d) {
      bad("dialect", config::dialect_choices());
    }
    if (*d == interp::Dialect::fanuc_mill && c.system == interp::GCodeSystem::a && root["system"]) {
      bad("system", "B in the mill dialect (G90/G91, G92 and G98/G99 as the mill spells them)");
    }
    interp::select_dialect(c, *d);
  }
  if (root["channel"]) {
    c.channel = get<int>(root["channel"], "channel");
    if (c.channel < 1 || c.channel > 255) {
      bad("channel", "1-255");
    }
  }
  if (root["spindles"]) {
    c.spindles = get<int>(root["spindles"], "spindles");
    if (c.spindles < 0 || c.spindles > 9) {
      bad("spindles", "0-9");
    }
  }
  if (root["decimal_point"]) {
    const auto s = get<std::string>(root["decimal_point"], "decimal_point");
    if (s != "calculator" && s != "increment") {
      bad("decimal_point", "calculator or increment");
    }
    c.decimal_point =
        s == "calculator" ? interp::DecimalPoint::calculator : interp::DecimalPoint::increment;
  }
  if (root["least_increment"]) {
    c.least_increment = get<double>(root["least_increment"], "least_increment");
    if (!(c.least_increment >= 1e-6 && c.least_increment <= 0.001)) {
      bad("least_increment", "0.000001-0.001 mm");
    }
  }
  if (root["feed_mode"]) {
    const auto s = get<std::string>(root["feed_mode"], "feed_mode");
    if (s != "per_min" && s != "per_rev") {
      bad("feed_mode", "per_min or per_rev");
    }
    c.power_on_feed_mode = s == "per_min" ? interp::FeedMode::per_min : interp::FeedMode::per_rev;
  }
  if (root["arc_check"]) {
    c.arc_check = get<bool>(root["arc_check"], "arc_check");
  }
  if (root["stroke_inside_forbidden"]) {
    c.stroke_inside_forbidden =
        get<bool>(root["stroke_inside_forbidden"], "stroke_inside_forbidden");
  }
  if (root["skip_input"]) {  // G31 / G31.8 without L, K or I (param 5510)
    c.skip_input = get<int>(root["skip_input"], "skip_input");
    if (c.skip_input < 0 || c.skip_input > 99) {
      bad("skip_input", "0 to 99");
    }
  }
  if (root["torque_skip"]) {  // G160 without P / Q (params 5515, 5516)
    const YAML::Node& t = root["torque_skip"];
    only_keys(t, "torque_skip", {"limit", "deviation"});
    if (t["limit"]) {
      c.torque_skip_percent = get<double>(t["limit"], "torque_skip.limit");
      if (!(c.torque_skip_percent >= 0.0 && c.torque_skip_percent <= 1000.0)) {
        bad("torque_skip.limit", "0 to 1000 %");
      }
    }
    if (t["deviation"]) {
      c.torque_skip_deviation = get<double>(t["deviation"], "torque_skip.deviation");
      if (!(c.torque_skip_deviation >= 0.0)) {
        bad("torque_skip.deviation", "0 mm or more");
      }
    }
  }
  if (root["arc_tolerance"]) {
    c.arc_tolerance = get<double>(root["arc_tolerance"], "arc_tolerance");
  }
  if (root["polar"]) {
    // Polar interpolation G12.1 (params 5530/5531); the axes are checked when G12.1 runs.
    const YAML::Node& p = root["polar"];
    only_keys(p, "polar", {"linear", "rotary", "tolerance"});
    c.polar_linear = axis_letter(get<std::string>(p["linear"], "polar.linear"), "polar.linear");
    c.polar_rotary = axis_letter(get<std::string>(p["rotary"], "polar.rotary"), "polar.rotary");
    if (p["tolerance"]) {
      c.polar_tolerance = get<double>(p["tolerance"], "polar.tolerance");
      if (!(c.polar_tolerance >= 1e-6 && c.polar_tolerance <= 1.0)) {
        bad("polar.tolerance", "0.000001 to 1 mm");
      }
    }
  }
  if (root["normal"]) {
    // G41.1/G42.1 (params 5550/5551): the rotary axis and its speed between blocks (deg/min);
    // the axis is checked when G41.1 runs.
    const YAML::Node& n = root["normal"];
    only_keys(n, "normal", {"axis", "feed"});
    c.normal_axis = axis_letter(get<std::string>(n["axis"], "normal.axis"), "normal.axis");
    if (n["feed"]) {
      c.normal_feed = get<double>(n["feed"], "normal.feed");
      if (!(c.normal_feed > 0.0)) {
        bad("normal.feed", "more than 0 degrees per minute");
      }
    }
  }
  if (root["cylindrical_parallel"]) {
    // G07.1 (param 0016): the linear axis whose place the rotary axis takes in the plane.
    c.cylindrical_parallel =
        axis_letter(get<std::string>(root["cylindrical_parallel"], "cylindrical_parallel"),
                    "cylindrical_parallel");
  }
  if (root["thread_repair"]) {
    // GSK thread repair (№174.4 on) and what the position page's soft key recorded: Z in the
    // work coordinates (mm) and the spindle's angle (degrees), both or neither.
    const YAML::Node& n = root["thread_repair"];
    only_keys(n, "thread_repair", {"z", "angle"});
    c.thread_repair = true;
    if (n["z"] || n["angle"]) {
      c.thread_repair_recorded = true;
      c.thread_repair_z = get<double>(n["z"], "thread_repair.z");
      c.thread_repair_degrees = get<double>(n["angle"], "thread_repair.angle");
    }
  }
  if (root["thread_chamfer_leads"]) {
    c.thread_chamfer_leads = get<double>(root["thread_chamfer_leads"], "thread_chamfer_leads");
    if (c.thread_chamfer_leads < 0.0 || c.thread_chamfer_leads > 9.9) {
      bad("thread_chamfer_leads", "0-9.9 (leads)");
    }
  }
  if (root["chamfer_is_length"]) {
    c.chamfer_is_length = get<bool>(root["chamfer_is_length"], "chamfer_is_length");
  }
  if (root["compensation_idle_blocks"]) {
    c.compensation_idle_blocks =
        get<int>(root["compensation_idle_blocks"], "compensation_idle_blocks");
    if (c.compensation_idle_blocks < 0 || c.compensation_idle_blocks > 99) {
      bad("compensation_idle_blocks", "0 (the dialect's) to 99");
    }
  }
  if (root["cycles"]) {
    cycle_defaults(root["cycles"], c.cycles);
  }
  if (root["dwell_in_revs_with_g99"]) {
    c.dwell_in_revs_with_g99 = get<bool>(root["dwell_in_revs_with_g99"], "dwell_in_revs_with_g99");
  }
  if (root["block_skip"]) {
    for (const auto& n : root["block_skip"]) {
      const int level = get<int>(n, "block_skip");
      if (level < 1 || level > 9) {
        bad("block_skip", "levels are 1-9");
      }
      c.block_skip[static_cast<std::size_t>(level)] = true;
    }
  }
  if (root["max_tool"]) {
    c.max_tool = get<int>(root["max_tool"], "max_tool");
  }
  if (root["statement_limit"]) {
    c.statement_limit = get<std::uint64_t>(root["statement_limit"], "statement_limit");
  }
  if (root["retained_file"]) {
    c.retained_file = get<std::string>(root["retained_file"], "retained_file");
  }
  if (root["program_dir"]) {
    c.program_dir = get<std::string>(root["program_dir"], "program_dir");
  }
  if (root["axes"]) {
    c.axes.clear();
    int i = 0;
    for (const auto& a : root["axes"]) {
      const std::string k = "axes[" + std::to_string(i++) + "]";
      only_keys(a, k,
                {"name", "diameter", "rotary", "start", "reference", "exchange", "approach",
                 "stroke", "oscillation", "skip_load", "torque_mode_speed"});
      interp::AxisConfig ax;
      ax.name = axis_letter(get<std::string>(a["name"], k + ".name"), k + ".name");
      for (const auto& other : c.axes) {
        if (other.name == ax.name) {
          bad(k + ".name", "axis named twice");
        }
      }
      ax.diameter = a["diameter"] && get<bool>(a["diameter"], k + ".diameter");
      ax.rotary = a["rotary"] && get<bool>(a["rotary"], k + ".rotary");
      const double unit = ax.diameter ? 2.0 : 1.0;
      if (a["start"]) {
        ax.start = get<double>(a["start"], k + ".start") / unit;
      }
      if (a["reference"]) {
        std::size_t r = 0;
        for (const auto& v : a["reference"]) {
          if (r >= ax.reference.size()) {
            bad(k + ".reference", "at most 4 reference points");
          }
          ax.reference[r++] = get<double>(v, k + ".reference") / unit;
        }
      }
      if (a["exchange"]) {
        ax.exchange = get<int>(a["exchange"], k + ".exchange");
      }
      ax.oscillation = a["oscillation"] && get<bool>(a["oscillation"], k + ".oscillation");
      if (a["skip_load"]) {  // G31 P98/P99 without G10 L14 P6 (param 5511)
        ax.skip_load = get<double>(a["skip_load"], k + ".skip_load");
        if (!(ax.skip_load >= 0.0 && ax.skip_load <= 1000.0)) {
          bad(k + ".skip_load", "0 to 1000 %");
        }
      }
      if (a["torque_mode_speed"]) {  // G10 L14 P10 without P11 (param 5521)
        ax.torque_mode_speed = get<double>(a["torque_mode_speed"], k + ".torque_mode_speed");
        if (!(ax.torque_mode_speed >= 0.0 && ax.torque_mode_speed <= 100000.0)) {
          bad(k + ".torque_mode_speed", "0 to 100000 rpm");
        }
      }
      if (a["approach"]) {
        ax.approach = get<double>(a["approach"], k + ".approach") / unit;
      }
      if (a["stroke"]) {
        // G22 without words (params 0512/0513): [- limit, + limit], machine positions.
        const YAML::Node& st = a["stroke"];
        if (!st.IsSequence() || st.size() != 2) {
          bad(k + ".stroke", "[- limit, + limit]");
        }
        ax.stroke_minus = get<double>(st[0], k + ".stroke") / unit;
        ax.stroke_plus = get<double>(st[1], k + ".stroke") / unit;
        if (!(ax.stroke_minus < ax.stroke_plus)) {
          bad(k + ".stroke", "the - limit below the + limit");
        }
      }
      c.axes.push_back(ax);
    }
    if (c.axes.empty() || c.axes.size() > interp::kMaxChannelAxes) {
      bad("axes", "1-8 axes");
    }
  }
  if (root["inclined"]) {
    // Inclined-axis control (params 5680.1, 5690-5692): two linear axes of `axes` and the angle.
    const YAML::Node& n = root["inclined"];
    only_keys(n, "inclined", {"axis", "orthogonal", "angle"});
    c.inclined_axis = axis_letter(get<std::string>(n["axis"], "inclined.axis"), "inclined.axis");
    c.inclined_orthogonal = axis_letter(get<std::string>(n["orthogonal"], "inclined.orthogonal"),
                                        "inclined.orthogonal");
    c.inclined_degrees = get<double>(n["angle"], "inclined.angle");
    for (const auto& [key, name] : {std::pair{"inclined.axis", c.inclined_axis},
                                    std::pair{"inclined.orthogonal", c.inclined_orthogonal}}) {
      const auto axis = std::find_if(c.axes.begin(), c.axes.end(),
                                     [&](const interp::AxisConfig& a) { return a.name == name; });
      if (axis == c.axes.end() || axis->rotary) {
        bad(key, "a linear axis of axes");
      }
    }
    if (c.inclined_axis == c.inclined_orthogonal) {
      bad("inclined.orthogonal", "another axis than inclined.axis");
    }
    if (!(std::fabs(c.inclined_degrees) < 90.0)) {
      bad("inclined.angle", "more than -90 and less than 90 degrees");
    }
  }
  if (root["work_offsets"]) {
    const YAML::Node& w = root["work_offsets"];
    if (!w.IsMap()) {
      bad("work_offsets", "must be a mapping");
    }
    for (const auto& kv : w) {
      const auto name = kv.first.as<std::string>();
      int system = -1;
      if (name == "EXT") {
        system = 0;
      } else if (name.size() == 3 && name.rfind("G5", 0) == 0 && name[2] >= '4' && name[2] <= '9') {
        system = name[2] - '4' + 1;
      } else if (name.rfind("G54.1 P", 0) == 0) {
        system = 6 + std::atoi(name.c_str() + 7);
        if (system < 7 || system > interp::kWorkSystems) {
          system = -1;
        }
      }
      if (system < 0) {
        bad("work_offsets." + name, "EXT, G54-G59 or \"G54.1 P1\"-\"G54.1 P99\"");
      }
      axis_values(kv.second, "work_offsets." + name, c,
                  c.work_offsets[static_cast<std::size_t>(system)]);
    }
  }
  if (root["tool_geometry"]) {
    tool_table(root["tool_geometry"], "tool_geometry", c.tool_geometry);
  }
  if (root["tool_wear"]) {
    tool_table(root["tool_wear"], "tool_wear", c.tool_wear);
  }
  if (root["macro_calls"]) {
    const YAML::Node& m = root["macro_calls"];
    only_keys(m, "macro_calls",
              {"t_program", "g_macro", "g_range", "m_subprogram", "m_subprogram_range", "m_macro",
               "m_macro_range"});
    interp::MacroCallTables& t = c.calls;
    if (m["t_program"]) {
      t.t_program = get<int>(m["t_program"], "macro_calls.t_program");
    }
    if (m["g_macro"]) {
      t.g_macro = code_map(m["g_macro"], "macro_calls.g_macro", 10);
    }
    if (m["g_range"]) {
      range(m["g_range"], "macro_calls.g_range", t.g_range_count, t.g_range_program,
            t.g_range_first);
    }
    if (m["m_subprogram"]) {
      t.m_subprogram = code_map(m["m_subprogram"], "macro_calls.m_subprogram", 1);
    }
    if (m["m_subprogram_range"]) {
      range(m["m_subprogram_range"], "macro_calls.m_subprogram_range", t.m_sub_range_count,
            t.m_sub_range_program, t.m_sub_range_first);
    }
    if (m["m_macro"]) {
      t.m_macro = code_map(m["m_macro"], "macro_calls.m_macro", 1);
    }
    if (m["m_macro_range"]) {
      range(m["m_macro_range"], "macro_calls.m_macro_range", t.m_macro_range_count,
            t.m_macro_range_program, t.m_macro_range_first);
    }
  }
  if (root["macro"]) {
    const YAML::Node& m = root["macro"];
    only_keys(m, "macro", {"locals", "commons", "vacant_ordering"});
    if (m["locals"]) {
      c.macro.local_last = get<int>(m["locals"], "macro.locals");
      if (c.macro.local_last != 33 && c.macro.local_last != 99) {
        bad("macro.locals", "33 or 99");
      }
    }
    if (m["commons"]) {
      c.macro.common_last = get<int>(m["commons"], "macro.commons");
      if (c.macro.common_last != 199 && c.macro.common_last != 499) {
        bad("macro.commons", "199 or 499");
      }
    }
    if (m["vacant_ordering"]) {
      const auto s = get<std::string>(m["vacant_ordering"], "macro.vacant_ordering");
      if (s != "as_zero" && s != "gsk_table") {
        bad("macro.vacant_ordering", "as_zero or gsk_table");
      }
      c.macro.vacant_ordering = s == "as_zero" ? interp::macro::VacantOrdering::kAsZero
                                               : interp::macro::VacantOrdering::kLiteralGskTable;
    }
  }
}

}  // namespace mcnc::tools
