#include "channel/interp/minimal_interpreter.hpp"

#include "channel/interp/block_lexer.hpp"
#include "channel/interp/program_alarms.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string_view>

namespace mcnc::interp {

namespace {

// Spec §1.10: coordinates ±999999.999; N up to 8 digits; O 4 digits; G 3 digits plus `.d`.
constexpr double kMaxCoordinate = 999999.999;
constexpr double kMaxSequence = 99999999.0;
constexpr double kMaxProgramNumber = 9999.0;
constexpr double kMaxGCode = 999.9;
constexpr double kMaxMCode = 999.0;
constexpr double kMaxDwellMs = 99999999.0;

// G codes carry one decimal digit (G04.1), so they are compared as tenths.
constexpr int kG00 = 0;
constexpr int kG01 = 10;
constexpr int kG04 = 40;

std::string letter_text(char c) {
  return std::string(1, c);
}

std::string g_name(int tenths) {
  char buf[24];
  if (tenths % 10 == 0) {
    std::snprintf(buf, sizeof buf, "G%02d", tenths / 10);
  } else {
    std::snprintf(buf, sizeof buf, "G%02d.%d", tenths / 10, tenths % 10);
  }
  return buf;
}

std::string m_name(int code) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "M%02d", code);
  return buf;
}

bool is_unsigned_integer(const LexWord& w) {
  return !w.has_sign && !w.has_point;
}

bool is_g04(const LexWord& w) {
  return w.letter == 'G' && !w.has_sign && w.value == 4.0;
}

}  // namespace

// Modal state carried from block to block while loading.
struct MinimalInterpreter::Modal {
  CommandKind motion = CommandKind::rapid;  // group 01 at power-on: G00
  double feed = 0.0;                        // units/min; 0 = never set
};

MinimalInterpreter::MinimalInterpreter(std::vector<AxisAddress> axes) : axes_(std::move(axes)) {
  if (axes_.size() > kMaxChannelAxes) {
    throw std::invalid_argument("MinimalInterpreter: more axes than kMaxChannelAxes");
  }
  const std::string_view reserved = "NOGMFP";
  std::string used;
  for (auto& a : axes_) {
    for (char* c : {&a.absolute, &a.incremental}) {
      if (*c >= 'a' && *c <= 'z') {
        *c = static_cast<char>(*c - 'a' + 'A');
      }
      if (*c < 'A' || *c > 'Z' || reserved.find(*c) != std::string_view::npos ||
          used.find(*c) != std::string::npos) {
        throw std::invalid_argument(std::string("MinimalInterpreter: bad axis address '") + *c +
                                    "'");
      }
      used.push_back(*c);
    }
  }
}

std::optional<ProgramAlarm> MinimalInterpreter::load(const std::string& program_text,
                                                     const std::string& program_name) {
  steps_.clear();
  block_count_ = 0;
  cursor_ = 0;
  position_ = AxisVector{};
  load_alarm_.reset();
  program_name_ = program_name;

  Modal modal;
  bool ended = false;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos < program_text.size() && !ended) {
    std::size_t eol = program_text.find('\n', pos);
    if (eol == std::string::npos) {
      eol = program_text.size();
    }
    ++line_no;
    const LexedLine lexed = lex_line(std::string_view(program_text).substr(pos, eol - pos));
    pos = eol + 1;
    if (lexed.ignored) {
      continue;
    }
    if (auto alarm = parse_block(lexed, line_no, modal, ended)) {
      load_alarm_ = std::move(alarm);
      break;
    }
  }
  if (!load_alarm_ && !ended) {
    load_alarm_ = ProgramAlarm{alarm::kProgramEndMissing, "program end M30 or M02 missing",
                               program_name_, line_no > 0 ? line_no : 1, 0};
  }
  if (load_alarm_) {
    // A program with an alarm runs no block at all.
    steps_.clear();
    block_count_ = 0;
  }
  return load_alarm_;
}

std::optional<ProgramAlarm> MinimalInterpreter::parse_block(const LexedLine& lexed, int line,
                                                            Modal& modal, bool& ended) {
  auto fail = [&](int number, std::string text, int column) {
    return std::optional<ProgramAlarm>(
        ProgramAlarm{number, std::move(text), program_name_, line, column});
  };

  // G04 changes the meaning of X and U wherever they stand in the block, so look for it first.
  bool dwell_block = false;
  for (const auto& w : lexed.words) {
    dwell_block = dwell_block || is_g04(w);
  }

  const LexWord* seen[26] = {};
  const LexWord* group1 = nullptr;
  const LexWord* group0 = nullptr;
  const LexWord* m_word = nullptr;
  const LexWord* f_word = nullptr;
  const LexWord* time_word = nullptr;
  const LexWord* first_axis = nullptr;
  Step motion;
  int group1_code = 0;
  bool has_axis = false;

  for (const auto& w : lexed.words) {
    const std::string name = letter_text(w.letter);
    if (w.letter != 'G') {
      const LexWord*& slot = seen[w.letter - 'A'];
      if (slot != nullptr) {
        return fail(alarm::kDuplicateAddress, "address " + name + " appears twice in the block",
                    w.column);
      }
      slot = &w;
    }
    const double mag = std::fabs(w.value);
    switch (w.letter) {
      case 'N':
      case 'O':
      case 'M': {
        if (!is_unsigned_integer(w)) {
          return fail(alarm::kIntegerExpected, name + " needs an unsigned integer value", w.column);
        }
        const double limit = w.letter == 'N'   ? kMaxSequence
                             : w.letter == 'O' ? kMaxProgramNumber
                                               : kMaxMCode;
        if (mag > limit) {
          return fail(alarm::kValueOutOfRange, "value of " + name + " out of range", w.column);
        }
        if (w.letter == 'M') {
          const int code = static_cast<int>(w.value);
          if (code != 30 && code != 2) {
            return fail(alarm::kUnsupportedM, m_name(code) + " is not supported yet", w.column);
          }
          m_word = &w;
        }
        continue;
      }
      case 'G': {
        if (w.has_sign || w.frac_digits > 1) {
          return fail(alarm::kIntegerExpected,
                      "G needs an unsigned code number with at most one decimal", w.column);
        }
        if (mag > kMaxGCode) {
          return fail(alarm::kValueOutOfRange, "value of G out of range", w.column);
        }
        const int code = static_cast<int>(std::lround(w.value * 10.0));
        if (code != kG00 && code != kG01 && code != kG04) {
          return fail(alarm::kUnsupportedG, g_name(code) + " is not supported yet", w.column);
        }
        const LexWord*& group = code == kG04 ? group0 : group1;
        if (group != nullptr) {
          return fail(
              alarm::kGroupConflict,
              std::string("two G codes of group ") + (code == kG04 ? "00" : "01") + " in one block",
              w.column);
        }
        group = &w;
        if (code != kG04) {
          group1_code = code;
        }
        continue;
      }
      case 'F':
        if (mag > kMaxCoordinate) {
          return fail(alarm::kValueOutOfRange, "value of F out of range", w.column);
        }
        if (w.value < 0.0) {
          return fail(alarm::kNegativeFeed, "feed F must not be negative", w.column);
        }
        f_word = &w;
        continue;
      case 'P':
        if (!dwell_block) {
          return fail(alarm::kPWithoutDwell, "P is only allowed with G04", w.column);
        }
        break;
      default:
        break;
    }

    if (dwell_block && (w.letter == 'P' || w.letter == 'X' || w.letter == 'U')) {
      if (w.value < 0.0) {
        return fail(alarm::kNegativeDwell, "G04 dwell time must not be negative", w.column);
      }
      if (w.letter == 'P' && w.has_point) {
        return fail(alarm::kIntegerExpected, "G04 P is milliseconds without a decimal point",
                    w.column);
      }
      if (mag > (w.letter == 'P' ? kMaxDwellMs : kMaxCoordinate)) {
        return fail(alarm::kValueOutOfRange, "value of " + name + " out of range", w.column);
      }
      if (time_word != nullptr) {
        return fail(alarm::kDwellTimeTwice, "G04 dwell time given more than once", w.column);
      }
      time_word = &w;
      continue;
    }

    std::size_t axis = 0;
    while (axis < axes_.size() && axes_[axis].absolute != w.letter &&
           axes_[axis].incremental != w.letter) {
      ++axis;
    }
    if (axis == axes_.size()) {
      return fail(alarm::kUnknownAddress, "unknown word address " + name, w.column);
    }
    if (mag > kMaxCoordinate) {
      return fail(alarm::kValueOutOfRange, "value of " + name + " out of range", w.column);
    }
    if (dwell_block) {
      return fail(alarm::kAxisInDwell, name + " is not allowed in a G04 block", w.column);
    }
    const AxisAddress& address = axes_[axis];
    AxisWord& slot = motion.axes[axis];
    if (slot.mode != AxisMode::unchanged) {
      return fail(alarm::kAbsoluteAndIncremental,
                  std::string("absolute ") + address.absolute + " and incremental " +
                      address.incremental + " of one axis in one block",
                  w.column);
    }
    slot.mode = w.letter == address.absolute ? AxisMode::absolute : AxisMode::incremental;
    // Diameter programming: X/U are diameters; the canonical command is physical (radius).
    slot.value = address.diameter ? w.value / 2.0 : w.value;
    has_axis = true;
    if (first_axis == nullptr) {
      first_axis = &w;
    }
  }

  if (lexed.error) {
    return fail(lexed.error->number, lexed.error->text, lexed.error->column);
  }

  if (group1 != nullptr) {
    modal.motion = group1_code == kG01 ? CommandKind::linear : CommandKind::rapid;
  }
  if (f_word != nullptr) {
    modal.feed = f_word->value;
  }

  const std::size_t block = block_count_ + 1;
  const std::size_t steps_before = steps_.size();
  auto push = [&](Step step) {
    step.command.line = line;
    step.command.block = block;
    steps_.push_back(step);
  };

  if (group0 != nullptr) {
    if (time_word == nullptr) {
      return fail(alarm::kDwellTimeMissing, "G04 without dwell time (P, X or U)", group0->column);
    }
    Step dwell;
    dwell.command.kind = CommandKind::dwell;
    dwell.command.dwell_s = time_word->letter == 'P' ? time_word->value / 1000.0 : time_word->value;
    push(dwell);
  } else if (has_axis) {
    if (modal.motion == CommandKind::linear && !(modal.feed > 0.0)) {
      const LexWord* at = f_word != nullptr ? f_word : group1 != nullptr ? group1 : first_axis;
      return fail(alarm::kFeedMissing, "G01 without feed: program F greater than 0", at->column);
    }
    motion.command.kind = modal.motion;
    motion.command.feed = modal.motion == CommandKind::linear ? modal.feed : 0.0;
    push(motion);
  }
  if (m_word != nullptr) {
    Step end;
    end.command.kind = CommandKind::program_end;
    end.command.end_code = static_cast<int>(m_word->value);
    push(end);
    ended = true;
  }
  if (steps_.size() != steps_before) {
    block_count_ = block;
  }
  return std::nullopt;
}

void MinimalInterpreter::rewind(const AxisVector& current) {
  cursor_ = 0;
  position_ = current;
}

std::optional<PullResult> MinimalInterpreter::next() {
  if (load_alarm_) {
    // The program stops at its alarm: it keeps answering with it until a good program is loaded.
    return PullResult{*load_alarm_};
  }
  if (cursor_ >= steps_.size()) {
    return std::nullopt;
  }
  const Step& step = steps_[cursor_++];
  CanonicalCommand command = step.command;
  for (std::size_t i = 0; i < axes_.size(); ++i) {
    const AxisWord& w = step.axes[i];
    if (w.mode == AxisMode::absolute) {
      position_[i] = w.value;
    } else if (w.mode == AxisMode::incremental) {
      position_[i] += w.value;
    }
  }
  command.target = position_;
  return PullResult{command};
}

std::size_t MinimalInterpreter::block_count() const noexcept {
  return block_count_;
}

}  // namespace mcnc::interp
