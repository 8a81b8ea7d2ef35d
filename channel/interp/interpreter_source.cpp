#include "channel/interp/interpreter_source.hpp"

#include "channel/interp/program_alarms.hpp"

#include <algorithm>

namespace mcnc::interp {

namespace {

const char* what_is_missing(Op op, FeedMode mode, bool in_revs) {
  switch (op) {
    case Op::arc:
    case Op::linear:
      return mode == FeedMode::per_rev
                 ? "feed per revolution (G99) needs the spindle's feedback in the channel"
                 : nullptr;
    case Op::dwell:
      return in_revs ? "a dwell in spindle revolutions needs the spindle's feedback in the channel"
                     : nullptr;
    case Op::spindle:
    case Op::spindle_select:
    case Op::tool:
    case Op::aux:
    case Op::stop:
      return "spindle, tool, M-code and input commands need the PLC node";
    case Op::axis_release:
    case Op::axis_acquire:
    case Op::axis_restore:
    case Op::axis_couple:
    case Op::axis_decouple:
    case Op::spindle_sync:
    case Op::spindle_unsync:
    case Op::polygon:
    case Op::polygon_off:
    case Op::cam:
    case Op::cam_off:
    case Op::egb:
    case Op::egb_off:
      return "multi-channel commands need the channel coordination runtime";
    case Op::message:
      return "#3006 messages need the HMI";
    case Op::thread:
      return "threading needs the spindle's feedback in the channel";
    default:
      return nullptr;
  }
}

// A G31's input is the input of a drive's touch probe of the channel (touch_probe in the machine
// file).
bool skip_wired(const Command& c, const InterpreterConfig& config) {
  if (c.skip_signal != 0) {  // G31 P: an input of the PLC
    return config.skip_signals[static_cast<std::size_t>(c.skip_signal - 1)];
  }
  if (c.multi_skip) {  // G31.8 stores its own axis's positions: that drive's probe latches them
    return c.skip_axis < config.axes.size() && config.axes[c.skip_axis].probe_input == c.input;
  }
  for (const AxisConfig& a : config.axes) {
    if (a.probe_input == c.input) {
      return true;
    }
  }
  return false;
}

// G31 P98/P99: an axis it watches whose drive takes no torque limit (nullptr: none).
const AxisConfig* unlimited_load_axis(const Command& c, const InterpreterConfig& config) {
  for (std::size_t a = 0; a < config.axes.size(); ++a) {
    if (c.load_ratio[a] > 0.0 && !config.axes[a].torque_skip) {
      return &config.axes[a];
    }
  }
  return nullptr;
}

// G10 L14 P9 / P0 / P1: an axis it names whose drive takes no torque limit nor reports its
// torque (nullptr: none).
const AxisConfig* unlimited_torque_axis(const Command& c, const InterpreterConfig& config) {
  for (std::size_t a = 0; a < config.axes.size(); ++a) {
    if (((c.torque_data_axes >> a) & 1U) != 0 && !config.axes[a].torque_skip) {
      return &config.axes[a];
    }
  }
  return nullptr;
}

// G10 L14 P10-P12: an axis it names whose drive has no torque mode (nullptr: none).
const AxisConfig* axis_without_torque_mode(const Command& c, const InterpreterConfig& config) {
  for (std::size_t a = 0; a < config.axes.size(); ++a) {
    if (((c.torque_data_axes >> a) & 1U) != 0 && !config.axes[a].torque_mode) {
      return &config.axes[a];
    }
  }
  return nullptr;
}

// A command the channel refuses: a G04.1 naming a channel the machine lacks is a program error;
// anything else is not in this version.
int alarm_for(const Command& c, const InterpreterConfig& config) {
  if (c.torque_skip || (c.load_skip && unlimited_load_axis(c, config) != nullptr) ||
      c.op == Op::torque_limit || c.op == Op::load_watch || c.op == Op::torque_mode ||
      c.overload_axes != 0) {
    return alarm::kSkipInput;
  }
  if (c.op == Op::sync) {
    return alarm::kSyncForm;
  }
  if (c.op == Op::spindle_mode) {
    return alarm::kSpindleControl;
  }
  if (c.skip && !skip_wired(c, config)) {
    return alarm::kSkipInput;
  }
  if (c.op == Op::wait_input) {
    return alarm::kInputPort;
  }
  if (c.op == Op::wait_spindle) {
    return alarm::kNoSuchSpindle;
  }
  const bool bad_word = c.op == Op::subcall || c.op == Op::axis_release ||
                        c.op == Op::axis_acquire || c.op == Op::axis_couple ||
                        c.op == Op::axis_decouple;
  return bad_word ? alarm::kBadWordValue : alarm::kNotInThisVersion;
}

// Room each kept block text has from the start, so that keeping one allocates only for a
// longer line.
constexpr std::size_t kTypicalLine = 128;

}  // namespace

InterpreterSource::InterpreterSource(InterpreterConfig config, std::size_t texts_kept)
    : config_(std::move(config)), texts_(std::max<std::size_t>(texts_kept, 1)) {
  for (std::string& t : texts_) {
    t.reserve(kTypicalLine);
  }
}

InterpreterSource::~InterpreterSource() = default;

InterpreterConfig InterpreterSource::dry_config(const InterpreterConfig& config) {
  InterpreterConfig dry = config;
  dry.retained_file.clear();       // a dry run must not write the retained variables
  dry.shared_variables = nullptr;  // nor tell the other channels of its writes
  dry.shared_sink = nullptr;
  return dry;
}

void InterpreterSource::dry_run(const InterpreterConfig& config, Interpreter& probe,
                                CheckedProgram& checked) {
  std::optional<ProgramAlarm>& alarm = checked.alarm;
  checked.block_count = alarm ? 0 : probe.main_block_count();
  for (int i = 0; i < kDryRunCommands && !alarm; ++i) {
    std::optional<InterpResult> r = probe.next();
    if (!r) {
      break;
    }
    if (const auto* a = std::get_if<ProgramAlarm>(&*r)) {
      alarm = *a;
      break;
    }
    const Command& c = std::get<Command>(*r);
    std::string why;
    if (!for_channel(c, why, config)) {
      alarm = ProgramAlarm{alarm_for(c, config), why, c.file != nullptr ? *c.file : checked.name,
                           c.line, 0};
    } else if (c.op == Op::end) {
      break;
    }
  }
}

CheckedProgram InterpreterSource::check(const InterpreterConfig& config, std::string text,
                                        std::string name, bool mdi) {
  CheckedProgram checked{std::move(name), std::move(text), std::string(), 0, std::nullopt};
  Interpreter probe(dry_config(config));
  checked.alarm = mdi ? probe.start_mdi(checked.text) : probe.start(checked.text, checked.name);
  dry_run(config, probe, checked);
  return checked;
}

CheckedProgram InterpreterSource::check_file(const InterpreterConfig& config, std::string path,
                                             std::string name) {
  CheckedProgram checked{std::move(name), std::string(), std::move(path), 0, std::nullopt};
  Interpreter probe(dry_config(config));
  checked.alarm = probe.start_file(checked.path, checked.name);
  dry_run(config, probe, checked);
  return checked;
}

std::optional<ProgramAlarm> InterpreterSource::load(const std::string& program_text,
                                                    const std::string& program_name) {
  adopt(check(config_, program_text, program_name, false));
  return load_alarm_;
}

std::optional<ProgramAlarm> InterpreterSource::load_file(const std::string& path,
                                                         const std::string& program_name) {
  adopt(check_file(config_, path, program_name));
  return load_alarm_;
}

void InterpreterSource::adopt(CheckedProgram program) noexcept {
  text_ = std::move(program.text);
  path_ = std::move(program.path);
  name_ = std::move(program.name);
  block_count_ = program.block_count;
  run_blocks_ = block_count_;  // adopted while no run is under way: the status shows its count
  load_alarm_ = std::move(program.alarm);
  loaded_ = true;
}

void InterpreterSource::prepare_mdi(CheckedProgram blocks) noexcept {
  mdi_text_ = std::move(blocks.text);
  mdi_blocks_ = blocks.block_count;
}

void InterpreterSource::start_interpreter(const AxisVector& current) {
  InterpreterConfig c = config_;
  for (std::size_t i = 0; i < c.axes.size() && i < kMaxChannelAxes; ++i) {
    c.axes[i].start = current[i];
  }
  interpreter_ = std::make_unique<Interpreter>(c);
  run_alarm_.reset();
}

void InterpreterSource::rewind(const AxisVector& current) {
  interpreter_.reset();
  run_alarm_.reset();
  calling_ = false;
  run_blocks_ = block_count_;
  if (!loaded_ || load_alarm_) {
    return;
  }
  start_interpreter(current);
  run_alarm_ =
      path_.empty() ? interpreter_->start(text_, name_) : interpreter_->start_file(path_, name_);
}

std::optional<ProgramAlarm> InterpreterSource::call(int number,
                                                    std::span<const std::pair<int, double>> args,
                                                    const AxisVector& current) {
  start_interpreter(current);
  calling_ = true;
  run_alarm_ = interpreter_->start_called(number, args);
  run_blocks_ = run_alarm_ ? 0 : interpreter_->main_block_count();
  if (run_alarm_) {
    interpreter_.reset();
  }
  return run_alarm_;
}

std::optional<ProgramAlarm> InterpreterSource::start_mdi(const AxisVector& current) {
  if (mdi_text_.empty()) {
    interpreter_.reset();
    calling_ = true;
    run_alarm_ = ProgramAlarm{1100, "no MDI blocks to run", std::string(kMdiName), 0, 0};
    return run_alarm_;
  }
  start_interpreter(current);
  calling_ = true;
  run_blocks_ = mdi_blocks_;
  run_alarm_ = interpreter_->start_mdi(mdi_text_);
  if (run_alarm_) {
    interpreter_.reset();
  }
  return run_alarm_;
}

bool InterpreterSource::for_channel(const Command& c, std::string& why,
                                    const InterpreterConfig& config) {
  if (c.op == Op::sync) {
    for (int ch = config.channel_count + 1; c.has_p && config.channel_count > 0 && ch <= 255;
         ++ch) {
      if (c.has_channel(ch)) {
        why = "G04.1 Q names channel " + std::to_string(ch) + ", which this machine does not have";
        return false;
      }
    }
    return true;
  }
  if (c.op == Op::subcall) {
    if (config.channel_count > 0 && c.channel > config.channel_count) {
      why = "G144 N names channel " + std::to_string(c.channel) +
            ", which this machine does not have";
      return false;
    }
    return true;
  }
  if (c.op == Op::subcall_release || c.op == Op::axis_restore || c.op == Op::spindle_sync ||
      c.op == Op::spindle_unsync || c.op == Op::polygon || c.op == Op::polygon_off ||
      c.op == Op::cam || c.op == Op::cam_off || c.op == Op::load_timer_check || c.op == Op::egb ||
      c.op == Op::egb_off) {
    return true;
  }
  if (c.op == Op::axis_couple || c.op == Op::axis_decouple) {
    // Q names the slave by its system number: one of this channel's axes that may follow
    // (param 5600.1). The master is checked when the block runs (it may be any channel's).
    const char* g = c.op == Op::axis_couple ? "G51.4" : "G50.4";
    for (const AxisConfig& a : config.axes) {
      if (a.id == c.slave) {
        if (a.may_follow) {
          return true;
        }
        why = std::string(g) + " Q" + std::to_string(c.slave) + ": axis " + a.name +
              " cannot follow another axis (axis_sync in the machine file, parameter 5600.1)";
        return false;
      }
    }
    why = std::string(g) + " Q" + std::to_string(c.slave) + ": axis " + std::to_string(c.slave) +
          " is not one of this channel's axes";
    return false;
  }
  if (config.plc && (c.op == Op::aux || c.op == Op::tool)) {
    return true;  // the PLC node answers them (an unknown M code is its alarm)
  }
  if (c.op == Op::axis_release || c.op == Op::axis_acquire) {
    // The exchange number names a physical axis: the slot's axis must have one (param 5660).
    for (const AxisConfig& a : config.axes) {
      if (a.name == c.axis && a.exchange == 0) {
        why = std::string(c.op == Op::axis_release ? "G140 " : "G141 ") + c.axis +
              std::to_string(c.exchange) + ": axis " + c.axis +
              " of this channel has no exchange number (exchange: in the machine file)";
        return false;
      }
    }
    return true;
  }
  if (c.op == Op::spindle_mode) {
    // Position control drives the spindle as the channel's C axis (c_axis in the machine file).
    for (const AxisConfig& a : config.axes) {
      if (a.spindle == c.spindle) {
        return true;
      }
    }
    why = "spindle " + std::to_string(c.spindle) +
          " has no axis for position control on this machine (c_axis of the spindle in the "
          "machine file)";
    return false;
  }
  if (c.op == Op::spindle && config.spindles > 0) {
    if (c.channel != 0 || c.spindle > 1) {
      why = "only the channel's first spindle can be commanded in this version";
      return false;
    }
    if (c.spindle_direction == SpindleDirection::orient) {
      why = "spindle orientation (M19) needs spindle positioning, not in this version";
      return false;
    }
    return true;
  }
  if (c.op == Op::wait_input) {
    // G04 I n waits on the PLC input whose port is n (plc.signals), as the PLC reports it.
    for (const int port : config.input_ports) {
      if (port == c.input) {
        return true;
      }
    }
    why = "G04 I" + std::string(c.input_on ? "" : "-") + std::to_string(c.input) +
          ": the machine's PLC has no input with port " + std::to_string(c.input) +
          " (port of an input in plc.signals)";
    return false;
  }
  if (c.op == Op::wait_spindle) {
    // The spindle's actual speed comes from its axis node's feedback.
    if (c.spindle >= 1 && c.spindle <= config.spindles) {
      return true;
    }
    why = "G04 PS" + std::to_string(c.spindle) + "=: this channel has no spindle " +
          std::to_string(c.spindle) + " whose actual speed it reads (spindles in the machine file)";
    return false;
  }
  if (c.multi_skip && !skip_wired(c, config)) {
    const char axis = c.skip_axis < config.axes.size() ? config.axes[c.skip_axis].name : '?';
    why = "G31.8: the touch probe of axis " + std::string(1, axis) +
          ", whose positions it stores, is not wired to input " + std::to_string(c.input) +
          " (touch_probe of the axis in the machine file)";
    return false;
  }
  if (c.torque_skip && c.torque_limit > 0.0 &&
      !(c.skip_axis < config.axes.size() && config.axes[c.skip_axis].torque_skip)) {
    why = "G160: the drive of axis " +
          std::string(1, c.skip_axis < config.axes.size() ? config.axes[c.skip_axis].name : '?') +
          " takes no torque limit (torque_skip of the axis in the machine file)";
    return false;
  }
  if (c.load_skip) {
    if (const AxisConfig* a = unlimited_load_axis(c, config)) {
      why = std::string(c.skip ? "G31 P99" : "G31 P98") + ": the drive of axis " + a->name +
            " takes no torque limit (torque_skip of the axis in the machine file)";
      return false;
    }
  }
  if (c.op == Op::torque_limit || c.op == Op::load_watch) {
    if (const AxisConfig* a = unlimited_torque_axis(c, config)) {
      const bool limit = c.op == Op::torque_limit;
      const int p = limit ? 9 : c.load_timer != 0 ? c.load_timer : c.every_move ? 0 : 1;
      why = "G10 L14 P" + std::to_string(p) + ": the drive of axis " + a->name +
            (limit ? " takes no torque limit" : " does not report its torque") +
            " (torque_skip of the axis in the machine file)";
      return false;
    }
    return true;
  }
  if (c.op == Op::torque_mode) {
    if (const AxisConfig* a = axis_without_torque_mode(c, config)) {
      why = "G10 L14 P" + std::to_string(c.torque_mode_p) + ": the drive of axis " + a->name +
            " has no torque mode (torque_mode of the axis in the machine file)";
      return false;
    }
    return true;
  }
  for (std::size_t a = 0; c.overload_axes != 0 && a < config.axes.size(); ++a) {
    // G10 L14 P7/P8 watch the loads the drives report (0x6077), as P0/P1.
    if (((c.overload_axes >> a) & 1U) != 0 && !config.axes[a].torque_skip) {
      why = "G10 L14 P" + std::to_string(c.overload_p) + ": the drive of axis " +
            config.axes[a].name + " does not report its torque (torque_skip of the axis in the " +
            "machine file)";
      return false;
    }
  }
  if (c.skip && !skip_wired(c, config)) {
    why = c.skip_signal != 0
              ? "G31 P" + std::to_string(c.skip_signal) +
                    ": the machine's PLC has no input for G0014." +
                    std::to_string(c.skip_signal - 1) + " (skip " + std::to_string(c.skip_signal) +
                    " of an input in plc.signals)"
              : "G31: no touch probe of this channel's axes is wired to input " +
                    std::to_string(c.input) + " (touch_probe of an axis in the machine file)";
    return false;
  }
  if (const char* missing = what_is_missing(c.op, c.feed_mode, c.in_revs)) {
    why = missing;
    return false;
  }
  switch (c.op) {
    case Op::rapid:
    case Op::linear:
    case Op::arc:
    case Op::dwell:
    case Op::oscillate:
    case Op::oscillate_end:
    case Op::end:
      return true;
    default:
      why = "this command cannot run in the channel yet";
      return false;
  }
}

void InterpreterSource::adopt_position(const AxisVector& at) {
  if (interpreter_) {
    interpreter_->set_machine_position(at);
  }
}

void InterpreterSource::skip_result(bool skipped, const AxisVector& skip_at,
                                    const AxisVector& stop_at) {
  if (interpreter_) {
    interpreter_->skip_result(skipped, skip_at, stop_at);
  }
}

void InterpreterSource::load_timer_result(std::uint32_t axes) {
  if (interpreter_) {
    interpreter_->load_timer_result(axes);
  }
}

void InterpreterSource::overload_result(std::uint32_t overloads, std::uint64_t dropped_block,
                                        const AxisVector& stop_at) {
  if (interpreter_) {
    interpreter_->overload_result(overloads, dropped_block, stop_at);
  }
}

void InterpreterSource::multi_skip_result(std::span<const double> latched,
                                          const AxisVector& stop_at) {
  if (interpreter_) {
    interpreter_->multi_skip_result(latched, stop_at);
  }
}

std::optional<PullResult> InterpreterSource::next() {
  if (run_alarm_) {
    return PullResult{*run_alarm_};  // the program stays stopped at its alarm
  }
  if (load_alarm_ && !calling_) {
    return PullResult{*load_alarm_};  // the channel's own program cannot run
  }
  if (!interpreter_) {
    return std::nullopt;
  }
  std::optional<InterpResult> r = interpreter_->next();
  if (!r) {
    return std::nullopt;
  }
  if (const auto* alarm = std::get_if<ProgramAlarm>(&*r)) {
    run_alarm_ = *alarm;
    return PullResult{*alarm};
  }
  Command& c = std::get<Command>(*r);
  std::string why;
  if (for_channel(c, why, config_)) {
    keep_text(c);
    return PullResult{std::move(c)};
  }
  run_alarm_ =
      ProgramAlarm{alarm_for(c, config_), why, c.file != nullptr ? *c.file : name_, c.line, 0};
  return PullResult{*run_alarm_};
}

void InterpreterSource::keep_text(Command& c) {
  std::string& kept = texts_[next_text_];
  next_text_ = (next_text_ + 1) % texts_.size();
  kept.assign(c.block_text);
  c.block_text = kept;
}

}  // namespace mcnc::interp
