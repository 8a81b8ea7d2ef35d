#include "channel/interp/program_run.hpp"

#include "channel/interp/program/program_format_alarms.hpp"
#include "channel/interp/program/program_store.hpp"
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/transform/inclined_axis.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <utility>

namespace mcnc::interp {

namespace {

macro::MacroDialect dialect_of(const InterpreterConfig& c) {
  macro::MacroDialect d = c.macro;
  d.channel = c.channel;
  return d;
}

std::string label(int number) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "O%04d", number);
  return buf;
}

// A value that must be a whole number (N targets, program numbers, counts).
bool whole(double v, std::int64_t& out) {
  const double r = std::round(v);
  if (std::fabs(v - r) > 1e-9 || std::fabs(r) > 9.2e18) {
    return false;
  }
  out = static_cast<std::int64_t>(r);
  return true;
}

}  // namespace

ProgramRun::ProgramRun(const InterpreterConfig& config, const InterpreterEnvironment* environment)
    : config_(config),
      environment_(environment != nullptr ? environment : &default_environment_),
      vars_(dialect_of(config)),
      tools_(config.tool_geometry, config.tool_wear),
      coordinates_(config.work_offsets) {
  vars_.add_provider(macro::MathConstantsProvider::kFirst, macro::MathConstantsProvider::kLast,
                     constants_);
  vars_.share(config_.shared_variables, config_.shared_sink);
  vars_.add_writable_provider(2001, 2999, *this);
  vars_.add_writable_provider(3000, 3100, *this);
  vars_.add_writable_provider(3901, 3902, *this);
  vars_.add_writable_provider(4000, 4399, *this);
  vars_.add_writable_provider(5001, 5399, *this);
  vars_.add_writable_provider(7001, 7999, *this);
  vars_.add_writable_provider(10001, 19999, *this);
  for (std::size_t i = 0; i < config_.axes.size() && i < kMaxChannelAxes; ++i) {
    machine_[i] = config_.axes[i].start;
    diameter_[i] = config_.axes[i].diameter;
    if (config_.normal_axis != 0 && config_.axes[i].name == config_.normal_axis &&
        config_.axes[i].rotary) {
      normal_axis_ = static_cast<int>(i);
    }
  }
  released_at_ = machine_;  // the machine's position, inclined
  for (std::size_t i = 0; i < config_.axes.size() && i < kMaxChannelAxes; ++i) {
    const bool linear = !config_.axes[i].rotary && config_.axes[i].spindle == 0;
    if (linear && config_.inclined_axis != 0 && config_.axes[i].name == config_.inclined_axis) {
      inclined_axes_[0] = static_cast<int>(i);
    }
    if (linear && config_.inclined_orthogonal != 0 &&
        config_.axes[i].name == config_.inclined_orthogonal) {
      inclined_axes_[1] = static_cast<int>(i);
    }
  }
  // The configuration's loaders refuse an incomplete or impossible pair; here it stays off.
  if (inclined_axes_[0] >= 0 && inclined_axes_[1] >= 0 && inclined_axes_[0] != inclined_axes_[1] &&
      std::fabs(config_.inclined_degrees) < 90.0) {
    inclined_.then(
        transform::InclinedAxis{inclined_axes_[0], inclined_axes_[1], config_.inclined_degrees});
    machine_ = from_inclined(machine_);
  } else {
    inclined_axes_ = {-1, -1};
  }
  // GSK and the FANUC mill start the compensation on G00 too; Dafeng on the first G01.
  lookahead_ = BlockLookahead(BlockLookahead::Settings{config_.dialect != Dialect::dafeng});
  lookahead_.reset(machine_);
  normal_ = NormalDirection(NormalDirection::Settings{normal_axis_, config_.normal_feed});
  normal_.reset(machine_);
  cycle_memory_ = config_.cycles;  // the first blocks of G71-G76 change them from here
  extended_thread_.angle = config_.cycles.thread_angle;
  extended_thread_.min_depth = config_.cycles.thread_min_depth;
  extended_thread_.allowance = config_.cycles.thread_allowance;
  extended_thread_.finish_passes = config_.cycles.thread_finish_passes;
  // #4001-#4030 at power-on.
  modal_ = state::ModalState::power_on(config_.system, config_.dialect, config_.power_on_feed_mode);
  timer_ms_base_ = environment_->milliseconds();
}

// ---------------------------------------------------------------------------------------------
// Programs

parse::StructureLimits ProgramRun::structure_limits() const {
  parse::StructureLimits limits;
  if (config_.dialect != Dialect::dafeng) {
    limits.max_loop_label = 3;  // GSK and FANUC: DO1-DO3 (gsk D2-38)
  }
  return limits;
}

program::ProgramStore& ProgramRun::store() {
  if (!store_) {
    store_ = config_.program_store ? config_.program_store
                                   : std::make_shared<program::ProgramStore>(config_.program_dir);
  }
  return *store_;
}

std::optional<ProgramAlarm> ProgramRun::start_text(std::string text, const std::string& file_name) {
  return start_programs(
      program::split_programs(program::TextSource::of_text(std::move(text)), file_name), file_name);
}

std::optional<ProgramAlarm> ProgramRun::start_file(const std::string& path,
                                                   const std::string& file_name) {
  std::string error;
  std::shared_ptr<const program::TextSource> text = program::TextSource::open_file(path, error);
  if (!text) {
    return ProgramAlarm{program::alarm::kFileUnreadable,
                        "cannot read program file " + file_name + ": " + error, file_name, 0, 0};
  }
  return start_programs(program::split_programs(std::move(text), file_name), file_name);
}

std::optional<ProgramAlarm> ProgramRun::start_programs(program::SplitResult split,
                                                       const std::string& file_name) {
  if (split.alarm) {
    return split.alarm;
  }
  if (split.programs.empty()) {
    return ProgramAlarm{alarm::kProgramEndMissing, "the file holds no program", file_name, 0, 0};
  }
  for (const program::Program& p : split.programs) {
    parse::ParsedProgramResult parsed = parse::parse_program(p, structure_limits());
    if (parsed.alarm) {
      return parsed.alarm;
    }
    file_programs_.push_back(std::make_unique<parse::ParsedProgram>(std::move(*parsed.program)));
  }
  if (!config_.retained_file.empty()) {
    std::ifstream probe(config_.retained_file);
    if (probe.good()) {
      const macro::MacroAlarm a = vars_.load_retained_file(config_.retained_file);
      if (a) {
        return ProgramAlarm{a.number, std::string(a.text()), config_.retained_file, 0, 0};
      }
    }
  }
  const parse::ParsedProgram* main = file_programs_.front().get();
  main_number_ = main->number.value_or(0);
  frames_.push_back(Frame{main, 0, 0, 0, CallKind::main, false, false});
  started_ = true;
  return std::nullopt;
}

std::optional<ProgramAlarm> ProgramRun::start_number(int number) {
  program::ProgramResult found = store().find(number);
  if (found.alarm) {
    return found.alarm;
  }
  parse::ParsedProgramResult parsed = parse::parse_program(*found.program, structure_limits());
  if (parsed.alarm) {
    return parsed.alarm;
  }
  file_programs_.push_back(std::make_unique<parse::ParsedProgram>(std::move(*parsed.program)));
  main_number_ = number;
  frames_.push_back(Frame{file_programs_.back().get(), 0, 0, 0, CallKind::main, false, false});
  started_ = true;
  return std::nullopt;
}

std::optional<ProgramAlarm> ProgramRun::start_called(int number,
                                                     std::span<const std::pair<int, double>> args) {
  if (auto alarm = start_number(number)) {
    return alarm;
  }
  called_ = true;
  for (const auto& [var, value] : args) {
    vars_.write(var, macro::MacroValue::of(value));
  }
  return std::nullopt;
}

std::optional<ProgramAlarm> ProgramRun::start_mdi(std::string text) {
  if (auto alarm = start_text(std::move(text), std::string(kMdiName))) {
    return alarm;
  }
  mdi_ = true;
  return std::nullopt;
}

const parse::ParsedProgram* ProgramRun::find_program(int number, int column) {
  for (const auto& p : file_programs_) {
    if (p->number && *p->number == number) {
      return p.get();
    }
  }
  if (auto it = directory_programs_.find(number); it != directory_programs_.end()) {
    return it->second.get();
  }
  if (config_.program_dir.empty()) {
    fail(program::alarm::kProgramNotFound,
         "program " + label(number) + " not found (not in this file, and no program directory)",
         column);
    return nullptr;
  }
  program::ProgramResult found = store().find(number);
  if (found.alarm) {
    fail(found.alarm->number, found.alarm->text, column);
    return nullptr;
  }
  parse::ParsedProgramResult parsed = parse::parse_program(*found.program, structure_limits());
  if (parsed.alarm) {
    alarm_ = parsed.alarm;  // points into the called file
    return nullptr;
  }
  auto& slot = directory_programs_[number];
  slot = std::make_unique<parse::ParsedProgram>(std::move(*parsed.program));
  return slot.get();
}

// ---------------------------------------------------------------------------------------------
// Pulling

std::optional<InterpResult> ProgramRun::next() {
  // The command is moved once, straight into the result.
  auto pop = [this]() {
    std::optional<InterpResult> r(std::in_place, std::in_place_type<Command>,
                                  std::move(ready_[ready_head_++]));
    std::get<Command>(*r).n = ++sequence_;
    if (ready_head_ == ready_.size()) {
      ready_.clear();  // keeps the capacity: no allocation per command
      ready_head_ = 0;
    }
    return r;
  };
  if (ready_head_ < ready_.size()) {
    return pop();
  }
  if (!started_ || ended_ || alarm_) {
    if (alarm_ && !alarm_reported_) {
      alarm_reported_ = true;
      return *alarm_;
    }
    return std::nullopt;
  }
  std::uint64_t statements = 0;
  while (ready_.empty() && !ended_ && !alarm_) {
    if (++statements > config_.statement_limit) {
      fail(alarm::kStatementLimit,
           "more than " + std::to_string(config_.statement_limit) +
               " statements without a command: an endless macro loop?",
           0);
      break;
    }
    step();
    if (!out_.empty() && !alarm_) {
      release_block();
    }
  }
  if (alarm_) {
    out_.clear();
    ready_.clear();
    ready_head_ = 0;
    alarm_reported_ = true;
    return *alarm_;
  }
  if (!ready_.empty()) {
    return pop();
  }
  return std::nullopt;
}

void ProgramRun::release_block() {
  if (!tag_normal_direction() || !mark_chip_breaking()) {
    return;
  }
  map_to_machine();
  framed_commands_ = 0;  // out_ is emptied below
  const std::size_t from = ready_.size();
  release_through_lookahead();
  expand_modes(ready_, from);
  turn_normal_direction(from);
  split_chip_breaking(from);
  expand_inclined(ready_, from);
  check_stroke(from);
  check_oscillation(from);
  if (ended_) {
    end_polar();  // the end resets the modes, after their last moves went out
    end_cylindrical();
  }
}

void ProgramRun::release_through_lookahead() {
  bool needed = lookahead_.holding();
  for (const Command& c : out_) {
    needed =
        needed || c.corner != Command::Corner::none || c.compensation != Command::Compensation::off;
  }
  if (!needed) {
    for (auto c = out_.rbegin(); c != out_.rend(); ++c) {
      if (c->op == Op::rapid || c->op == Op::linear || c->op == Op::arc || c->op == Op::thread) {
        lookahead_.passed(c->to);
        break;
      }
    }
    std::swap(ready_, out_);  // nothing waits: the block's commands are ready as they are
    out_.clear();
    return;
  }
  const std::array<int, 2> axes = plane_axis_indices();
  if (axes[0] >= 0 && axes[1] >= 0) {
    lookahead_.set_plane(axes, modal_.plane);
  }
  path::PathResult e;
  for (Command& c : out_) {
    e = lookahead_.push(std::move(c), ready_);
    if (e) {
      break;
    }
  }
  out_.clear();
  if (!e && ended_) {
    e = lookahead_.flush(ready_);
  }
  if (e) {
    fail(e->alarm, e->text, 0);
  }
}

bool ProgramRun::step() {
  Frame& f = frames_.back();
  const parse::ParsedProgram& p = *f.program;
  if (f.pc >= p.size()) {
    file_ = &p.file;
    line_ = p.line(p.size() - 1);
    if (f.kind == CallKind::main && frames_.size() == 1 && mdi_) {
      if (!oscillation_ended()) {
        return false;
      }
      end_program(0);  // MDI blocks end with their text
      return true;
    }
    if (f.kind == CallKind::main && frames_.size() == 1) {
      return fail(alarm::kProgramEndMissing, "program end M30 or M02 missing", 0);
    }
    return fail(alarm::kSubprogramEndMissing,
                "subprogram " + label(p.number.value_or(0)) + " ends without M99", 0);
  }
  const int index = f.pc++;
  const parse::Line* read = p.line(index);
  if (read == nullptr) {
    alarm_ = p.read_alarm();
    return false;
  }
  const parse::Line& line = *read;
  if (line.skip_level > 0 && config_.block_skip[static_cast<std::size_t>(line.skip_level)]) {
    return true;
  }
  line_ = &line;
  file_ = &p.file;
  block_out_start_ = out_.size();
  return execute(line, index, line.statement);
}

// ---------------------------------------------------------------------------------------------
// Macro statements

// Expressions live in the arena of the line being executed, which holds `s`.
bool ProgramRun::evaluate(const parse::Statement& /*s*/, int expression, macro::MacroValue& out) {
  const macro::EvalResult r =
      macro::evaluate(line_->arena->expressions[static_cast<std::size_t>(expression)], vars_);
  if (r.alarm) {
    return fail_macro(r.alarm);
  }
  out = r.value;
  return true;
}

bool ProgramRun::condition(const parse::Statement& s, int expression, bool& out) {
  macro::MacroValue v;
  if (!evaluate(s, expression, v)) {
    return false;
  }
  out = !v.is_null() && v.number() != 0.0;
  return true;
}

bool ProgramRun::execute(const parse::Line& line, int index, const parse::Statement& s) {
  const parse::ParsedProgram& p = *frames_.back().program;
  switch (s.kind) {
    case parse::StatementKind::empty:
    case parse::StatementKind::endif:
      return true;
    case parse::StatementKind::block:
      return execute_block(line, s);
    case parse::StatementKind::assignment:
      return assign(line, s);
    case parse::StatementKind::go_to: {
      macro::MacroValue v;
      if (!evaluate(s, s.target, v)) {
        return false;
      }
      std::int64_t n = 0;
      if (v.is_null() || !whole(v.number(), n) || n < 0) {
        return fail(alarm::kBadWordValue, "GOTO needs a sequence number (a whole number >= 0)",
                    s.column);
      }
      return jump_to_sequence(n, s.direction, s.column);
    }
    case parse::StatementKind::if_then: {
      bool c = false;
      if (!condition(s, s.condition, c)) {
        return false;
      }
      return c ? execute(line, index, *s.then) : true;
    }
    case parse::StatementKind::if_block: {
      bool c = false;
      if (!condition(s, s.condition, c)) {
        return false;
      }
      if (c) {
        return true;
      }
      for (int j = p.partner(index); j >= 0;) {
        const parse::Line* read = p.line(j);
        if (read == nullptr) {
          alarm_ = p.read_alarm();
          return false;
        }
        const parse::Line& branch = *read;
        if (branch.statement.kind == parse::StatementKind::elif) {
          line_ = &branch;
          bool taken = false;
          if (!condition(branch.statement, branch.statement.condition, taken)) {
            return false;
          }
          if (taken) {
            frames_.back().pc = j + 1;
            return true;
          }
          j = p.partner(j);
          continue;
        }
        frames_.back().pc = j + 1;  // ELSE body, or past ENDIF
        return true;
      }
      return true;
    }
    case parse::StatementKind::elif:
    case parse::StatementKind::else_branch:
      // Reached in sequence: the branch before it ran; continue after ENDIF.
      frames_.back().pc = p.endif_of(index) + 1;
      return true;
    case parse::StatementKind::while_do: {
      bool c = false;
      if (!condition(s, s.condition, c)) {
        return false;
      }
      if (!c) {
        frames_.back().pc = p.partner(index) + 1;
      }
      return true;
    }
    case parse::StatementKind::loop_end:
      frames_.back().pc = p.partner(index);
      return true;
    case parse::StatementKind::loop_break:
    case parse::StatementKind::loop_continue: {
      const int w = p.loop_of(index);
      if (w < 0) {
        return fail(alarm::kLoopControl,
                    s.kind == parse::StatementKind::loop_break ? "BREAK outside a WHILE loop"
                                                               : "CONTINUE outside a WHILE loop",
                    s.column);
      }
      frames_.back().pc = s.kind == parse::StatementKind::loop_break ? p.partner(w) + 1 : w;
      return true;
    }
    case parse::StatementKind::channel_only:
      if (s.label != config_.channel) {
        return fail(alarm::kWrongChannel,
                    "this program may only run in channel " + std::to_string(s.label) + " (CH" +
                        std::to_string(s.label) + "), not in channel " +
                        std::to_string(config_.channel),
                    s.column);
      }
      return true;
  }
  return true;
}

const std::string& ProgramRun::message_of(const parse::Line& line) const {
  return line.arena->messages[static_cast<std::size_t>(line.message)];
}

bool ProgramRun::assign(const parse::Line& line, const parse::Statement& s) {
  const macro::Assignment& a = *s.assignment;
  std::int64_t target = a.target;
  if (target < 0) {
    const macro::EvalResult r = macro::evaluate(a.target_index, vars_);
    if (r.alarm) {
      return fail_macro(r.alarm);
    }
    if (!whole(r.value.number(), target)) {
      target = -1;  // execute() reports the bad number
    }
  }
  if (target == 3000 || target == 3006) {
    const macro::EvalResult r = macro::evaluate(a.value, vars_);
    if (r.alarm) {
      return fail_macro(r.alarm);
    }
    std::int64_t n = 0;
    if (target == 3000) {
      if (!whole(r.value.number(), n) || n < 0 || n > alarm::kUserAlarmMaxN) {
        return fail(
            alarm::kUserAlarmRange,
            "#3000 = n: n must be a whole number 0-" + std::to_string(alarm::kUserAlarmMaxN),
            a.target_column);
      }
      return fail(alarm::kUserAlarmBase + static_cast<int>(n),
                  line.message < 0 ? std::string("macro alarm") : message_of(line),
                  a.target_column);
    }
    emit(Op::message).text = line.message < 0 ? std::string() : message_of(line);
    Command& stop = emit(Op::stop);
    stop.code = 0;
    stop.barrier = true;
    return true;
  }
  const macro::MacroAlarm m = macro::execute(a, vars_);
  if (m) {
    return fail_macro(m);
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// Jumps and calls

int ProgramRun::find_sequence(const parse::ParsedProgram& p, std::int64_t n, int from,
                              parse::GotoDirection direction, int column) {
  const int found = p.find_sequence(n, from, direction);
  if (found >= 0) {
    return found;
  }
  if (p.read_alarm()) {
    alarm_ = p.read_alarm();
    return -1;
  }
  fail(alarm::kSequenceNotFound,
       "sequence number N" + std::to_string(n) + " not found in " +
           (p.number ? label(*p.number) : p.file) +
           (direction == parse::GotoDirection::forward    ? " after this block"
            : direction == parse::GotoDirection::backward ? " before this block"
                                                          : ""),
       column);
  return -1;
}

bool ProgramRun::jump_to_sequence(std::int64_t n, parse::GotoDirection direction, int column) {
  Frame& f = frames_.back();
  const int target = find_sequence(*f.program, n, f.pc - 1, direction, column);
  if (target < 0) {
    return false;
  }
  f.pc = target;
  return true;
}

bool ProgramRun::call_subprogram(int program, int start_sequence, int repeat, int column,
                                 bool t_call) {
  if (contour_.active()) {
    return contour_forbids("a subprogram call (M98, T or M code)", column);  // gsk A.6.30 rule 4
  }
  if (config_.dialect == Dialect::gsk && compensation_ != Command::Compensation::off && !t_call) {
    // GSK: compensation is cancelled before M98 and set up again inside (gsk A.6.22 rule 4).
    return fail(alarm::kCompensationStart,
                "cancel the tool-nose compensation (G40) before calling a subprogram", column);
  }
  if (static_cast<int>(frames_.size()) > config_.max_subprogram_nesting) {
    return fail(
        alarm::kCallNestingTooDeep,
        "subprogram calls nested deeper than " + std::to_string(config_.max_subprogram_nesting),
        column);
  }
  const parse::ParsedProgram* p =
      program < 0 ? frames_.back().program : find_program(program, column);
  if (p == nullptr) {
    return false;
  }
  int start = 0;
  if (start_sequence >= 0) {
    start = find_sequence(*p, start_sequence, -1, parse::GotoDirection::forward, column);
    if (start < 0) {
      return false;
    }
  }
  if (repeat <= 0) {
    return true;
  }
  frames_.push_back(Frame{p, start, start, repeat - 1, CallKind::subprogram, false, t_call});
  return true;
}

bool ProgramRun::call_macro(int program, int repeat, const std::array<macro::MacroValue, 33>& args,
                            int column, bool modal) {
  if (contour_.active()) {
    return contour_forbids("a macro call (G65, G66, G/M-code macros)", column);
  }
  if (macro_depth_ >= config_.max_macro_nesting) {
    return fail(alarm::kCallNestingTooDeep,
                "macro calls (G65, G66, macro-type G/M codes) nested deeper than " +
                    std::to_string(config_.max_macro_nesting),
                column);
  }
  if (static_cast<int>(frames_.size()) > config_.max_subprogram_nesting) {
    return fail(
        alarm::kCallNestingTooDeep,
        "subprogram calls nested deeper than " + std::to_string(config_.max_subprogram_nesting),
        column);
  }
  const parse::ParsedProgram* p = find_program(program, column);
  if (p == nullptr || repeat <= 0) {
    return p != nullptr;
  }
  const macro::MacroAlarm pushed = vars_.push_level();
  if (pushed) {
    return fail(alarm::kCallNestingTooDeep, std::string(pushed.text()), column);
  }
  for (int i = 1; i <= 33 && i <= config_.macro.local_last; ++i) {
    if (!args[static_cast<std::size_t>(i - 1)].is_null()) {
      vars_.write(i, args[static_cast<std::size_t>(i - 1)]);
    }
  }
  ++macro_depth_;
  frames_.push_back(Frame{p, 0, 0, repeat - 1, CallKind::macro, modal, false});
  return true;
}

bool ProgramRun::return_from_subprogram(std::int64_t return_sequence, int column) {
  if (contour_.active()) {
    return contour_forbids("M99", column);
  }
  if (frames_.size() == 1 && (called_ || mdi_)) {
    if (!oscillation_ended()) {
      return false;
    }
    end_program(99);  // a program called by G144 ends at its M99 (spec dafeng §3.4 decide 4)
    return true;
  }
  if (frames_.size() == 1) {
    // M99 in the main program: back to its start (spec dafeng L6348-6350), or to N P.
    Frame& f = frames_.back();
    if (return_sequence >= 0) {
      const int t =
          find_sequence(*f.program, return_sequence, -1, parse::GotoDirection::forward, column);
      if (t < 0) {
        return false;
      }
      f.pc = t;
    } else {
      f.pc = 0;
    }
    return true;
  }
  Frame& f = frames_.back();
  if (f.repeats_left > 0) {
    --f.repeats_left;
    f.pc = f.start_pc;
    return true;
  }
  if (f.kind == CallKind::macro) {
    vars_.pop_level();
    --macro_depth_;
  }
  frames_.pop_back();
  if (return_sequence >= 0) {
    Frame& caller = frames_.back();
    const int t =
        find_sequence(*caller.program, return_sequence, -1, parse::GotoDirection::forward, column);
    if (t < 0) {
      return false;
    }
    caller.pc = t;
  }
  return true;
}

void ProgramRun::end_program(int code) {
  Command& c = emit(Op::end);
  c.code = code;
  c.barrier = true;
  ended_ = true;
  // The end resets what a reset cancels: the rotation (spec L4552) and the mirror (polar and
  // cylindrical interpolation in release_block, after their last moves).
  rotated_ = false;
  program_mirror_ = transform::AxisMirror{};
  for (std::size_t i = 0; i < config_.axes.size() && i < kMaxChannelAxes; ++i) {
    diameter_[i] = config_.axes[i].diameter;  // G10.9 ends with the program (L3981)
  }
  polar_coords_ = false;
  modal_.codes[17] = 69.1;
  modal_.codes[18] = 15;
  modal_.codes[22] = 50.1;
  rebuild_frame();
  save_retained();
}

std::size_t ProgramRun::main_block_count() const {
  if (frames_.empty()) {
    return 0;
  }
  return frames_.front().program->block_count();
}

std::optional<ProgramAlarm> ProgramRun::save_retained() {
  if (config_.retained_file.empty()) {
    return std::nullopt;
  }
  const macro::MacroAlarm a = vars_.save_retained_file(config_.retained_file);
  if (a) {
    return ProgramAlarm{a.number, std::string(a.text()), config_.retained_file, 0, 0};
  }
  return std::nullopt;
}

// ---------------------------------------------------------------------------------------------
// Output and alarms

Command& ProgramRun::emit(Op op) {
  Command& c = out_.emplace_back();
  c.op = op;
  last_op_ = op;
  if (compensation_ != Command::Compensation::off && !cycle_output_ &&
      (op == Op::rapid || op == Op::linear || op == Op::arc)) {
    c.compensation = compensation_;
    if (radius_offset() > 0) {
      const int o = radius_offset();
      c.nose_radius = tools_.radius(o);
      // A milling cutter is compensated about its centre (tip 0).
      c.nose_tip = config_.dialect == Dialect::fanuc_mill ? 0 : tools_.tip(o);
    }
  }
  c.line = line_ != nullptr ? line_->line : 0;
  c.block_text = line_ != nullptr ? line_->text : std::string_view();
  c.file = file_;
  for (std::size_t k = 0; k < kShownModalGroups.size(); ++k) {
    // A G code is >= 0 with at most one decimal: adding a half and truncating rounds it as
    // std::lround would, without a library call per group and command.
    const double g = modal_.codes[static_cast<std::size_t>(kShownModalGroups[k])];
    c.modal.g[k] = static_cast<std::uint16_t>(g * 10.0 + 0.5);
  }
  c.modal.feed = modal_.feed;
  c.to = machine_;
  return c;
}

bool ProgramRun::fail(int number, std::string text, int column) {
  if (alarm_) {
    return false;
  }
  while (out_.size() > block_out_start_) {
    out_.pop_back();  // nothing of the failing block is emitted
  }
  alarm_ = ProgramAlarm{number, std::move(text), file_ != nullptr ? *file_ : std::string(),
                        line_ != nullptr ? line_->line : 0, column};
  save_retained();
  return false;
}

void ProgramRun::warn(std::string text, int column) {
  // A program that repeats the block in a loop must not grow the list without end: nobody
  // needs the ten-thousandth copy of a warning.
  constexpr std::size_t kMaxWarnings = 100;
  if (warning_count_++ < kMaxWarnings) {
    warnings_.push_back(ProgramAlarm{0, std::move(text), file_ != nullptr ? *file_ : std::string(),
                                     line_ != nullptr ? line_->line : 0, column});
  }
}

std::vector<ProgramAlarm> ProgramRun::take_warnings() {
  return std::exchange(warnings_, {});
}

bool ProgramRun::fail_macro(const macro::MacroAlarm& a) {
  return fail(a.number, std::string(a.text()), a.column);
}

}  // namespace mcnc::interp
