// NC blocks: words, G and M codes, spindles, tools, calls and the multi-channel words.
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mcnc::interp {

namespace {

// The largest whole number of a coupling's ratio: G51.2's P and Q, G81.4's T and L.
constexpr std::int64_t kMaxRatio = 9999;

bool whole_number(double v, std::int64_t& out) {
  const double r = std::round(v);
  if (std::fabs(v - r) > 1e-6 || std::fabs(r) > 1e15) {
    return false;
  }
  out = static_cast<std::int64_t>(r);
  return true;
}

std::string g_name(int code10) {
  char buf[24];
  if (code10 % 10 == 0) {
    std::snprintf(buf, sizeof buf, "G%02d", code10 / 10);
  } else {
    std::snprintf(buf, sizeof buf, "G%02d.%d", code10 / 10, code10 % 10);
  }
  return buf;
}

std::string address_name(const parse::Address& a) {
  std::string n;
  if (a.comma) {
    n += ',';
  }
  n += a.first;
  if (a.second != 0) {
    n += a.second;
  }
  return n;
}

// G65 type I argument addresses -> local variable (spec dafeng L7393-7415); 0 = not an argument.
int type_one_variable(char letter) {
  switch (letter) {
    case 'A':
      return 1;
    case 'B':
      return 2;
    case 'C':
      return 3;
    case 'I':
      return 4;
    case 'J':
      return 5;
    case 'K':
      return 6;
    case 'D':
      return 7;
    case 'E':
      return 8;
    case 'F':
      return 9;
    case 'H':
      return 11;
    case 'M':
      return 13;
    case 'N':
      return 14;
    case 'P':
      return 16;
    case 'Q':
      return 17;
    case 'R':
      return 18;
    case 'S':
      return 19;
    case 'T':
      return 20;
    case 'U':
      return 21;
    case 'V':
      return 22;
    case 'W':
      return 23;
    case 'X':
      return 24;
    case 'Y':
      return 25;
    case 'Z':
      return 26;
    default:
      return 0;
  }
}

// The P words of these codes are theirs, not the `S_ Paab` spindle address: an S beside them
// is a speed of the channel's spindle (G71-G73 take F, S and T on their P block, spec dafeng
// §2.5, syntax ②).
bool takes_p(GFunction f) {
  switch (f) {
    case GFunction::finishing_cycle:
    case GFunction::rough_turning:
    case GFunction::rough_facing:
    case GFunction::pattern_repeat:
    case GFunction::face_grooving:
    case GFunction::od_grooving:
    case GFunction::multiple_thread:
    case GFunction::extended_thread:
    case GFunction::dwell:
    case GFunction::channel_sync:
    case GFunction::data_input:
    case GFunction::reference_2_4:
    case GFunction::work_system:
    case GFunction::work_system_ext:
    case GFunction::axis_sync_on:
    case GFunction::axis_sync_off:
    case GFunction::axis_acquire:
    case GFunction::spindle_sync_on:
    case GFunction::polygon_on:
    case GFunction::polygon_off:
    case GFunction::cam_on:
    case GFunction::egb_on:
    case GFunction::egb_off:
    case GFunction::stroke_check_on:
    case GFunction::chip_break_per_min:
    case GFunction::chip_break_per_rev:
    case GFunction::skip:
    case GFunction::multi_skip:
    case GFunction::torque_skip:
      return true;
    default:
      return false;
  }
}

struct BlockG {
  int code10 = 0;
  GCodeInfo info;
  int column = 0;
};

}  // namespace

// ---------------------------------------------------------------------------------------------
// Words

void ProgramRun::index_word(std::size_t k) {
  const parse::Address& a = words_[k].address;
  if (a.second != 0 && !a.comma) {
    ++two_letter_words_;
    return;
  }
  if (a.first < 'A' || a.first > 'Z') {
    return;
  }
  std::uint32_t& first = (a.comma ? first_comma_word_ : first_letter_word_)[a.first - 'A'];
  if (first == 0) {
    first = static_cast<std::uint32_t>(k + 1);
  }
}

void ProgramRun::index_words() {
  first_letter_word_.fill(0);
  first_comma_word_.fill(0);
  two_letter_words_ = 0;
  for (std::size_t k = 0; k < words_.size(); ++k) {
    index_word(k);
  }
}

BlockWord* ProgramRun::word(char letter) {
  if (letter >= 'A' && letter <= 'Z') {
    const std::uint32_t first = first_letter_word_[letter - 'A'];
    return first == 0 ? nullptr : &words_[first - 1];
  }
  for (BlockWord& w : words_) {
    if (w.address.is(letter)) {
      return &w;
    }
  }
  return nullptr;
}

BlockWord* ProgramRun::word(char a, char b) {
  if (two_letter_words_ == 0 && b != 0) {
    return nullptr;
  }
  for (BlockWord& w : words_) {
    if (w.address.is(a, b)) {
      return &w;
    }
  }
  return nullptr;
}

BlockWord* ProgramRun::comma_word(char letter) {
  if (letter >= 'A' && letter <= 'Z') {
    const std::uint32_t first = first_comma_word_[letter - 'A'];
    return first == 0 ? nullptr : &words_[first - 1];
  }
  for (BlockWord& w : words_) {
    if (w.address.comma && w.address.first == letter) {
      return &w;
    }
  }
  return nullptr;
}

int ProgramRun::count_words(char letter) const {
  int n = 0;
  for (const BlockWord& w : words_) {
    n += w.address.is(letter) ? 1 : 0;
  }
  return n;
}

double ProgramRun::length_increment() const {
  // IS-B inputs 0.001 mm or 0.0001 inch: the inch increment is a tenth of the metric one's
  // number, in every increment system.
  return modal_.metric ? config_.least_increment : config_.least_increment / 10.0;
}

double ProgramRun::scaled(const BlockWord& w, bool length) const {
  double v = w.value;
  // Angles and times keep the metric increment's number in G20 (0.001 degree, 0.001 s).
  const double inc = length ? length_increment() : config_.least_increment;
  if (w.literal) {
    if (!w.has_point && config_.decimal_point == DecimalPoint::increment) {
      v *= inc;
    }
    return v;
  }
  // A variable value is cut to the least increment: truncated (Dafeng L6671-6676) or rounded
  // (GSK, the FANUC mill: gsk B.4 item 6). Values a hair below a multiple of the increment
  // (0.3 / 0.001) count as on it.
  const double units = v / inc;
  const double nearest = std::round(units);
  if (std::fabs(units - nearest) < 1e-6) {
    return nearest * inc;
  }
  return (config_.dialect != Dialect::dafeng ? nearest : std::trunc(units)) * inc;
}

double ProgramRun::length_of(const BlockWord& w) const {
  return scaled(w, true) * (modal_.metric ? 1.0 : 25.4);
}

double ProgramRun::scaled_axis_word(int axis, const BlockWord& w) const {
  return scaled(w, !config_.axes[static_cast<std::size_t>(axis)].rotary);
}

bool ProgramRun::evaluate_words(const parse::Statement& s) {
  words_.clear();
  index_words();
  const parse::Arena& arena = *line_->arena;
  for (std::uint32_t k = 0; k < s.word_count; ++k) {
    const parse::Word& pw = arena.words[s.first_word + k];
    BlockWord w;
    w.address = pw.address;
    w.index = pw.index;
    w.column = pw.column;
    w.literal = pw.literal;
    w.has_point = pw.has_point;
    if (pw.literal) {
      w.value = pw.value;
    } else {
      macro::MacroValue v;
      if (!evaluate(s, pw.expression, v)) {
        return false;
      }
      if (v.is_null()) {
        continue;  // a word whose value is null disappears (spec dafeng L6437-6445)
      }
      w.value = v.number();
      w.has_point = true;
    }
    words_.push_back(w);
    index_word(words_.size() - 1);
  }
  return true;
}

bool ProgramRun::check_unused_words() {
  for (const BlockWord& w : words_) {
    if (w.used) {
      continue;
    }
    const std::string name = address_name(w.address);
    if (w.address.second == 0 && !w.address.comma && w.address.first != 'U' &&
        w.address.first != 'W' && w.address.first != 'V' && w.address.first != 'H') {
      bool axis_letter = false;
      for (char c : {'X', 'Y', 'Z', 'A', 'B', 'C'}) {
        axis_letter = axis_letter || w.address.first == c;
      }
      if (axis_letter) {
        return fail(alarm::kWordNotAllowed,
                    name + " is not an axis of channel " + std::to_string(config_.channel) +
                        " or not used by this block",
                    w.column);
      }
    }
    if (w.address.comma) {
      return fail(alarm::kWordNotAllowed,
                  name + " belongs to a G01 (,A ,C ,R) or G02/G03 (,C ,R) move", w.column);
    }
    return fail(alarm::kWordNotAllowed, name + " is not used by this block", w.column);
  }
  return true;
}

bool ProgramRun::collect_macro_args(std::array<macro::MacroValue, 33>& args, bool type_one_only,
                                    bool reserve_p) {
  args.fill(macro::MacroValue::null());
  int group = 1;  // type II: I/J/K groups, a repeated letter starts the next group
  std::array<bool, 3> in_group{};
  for (BlockWord& w : words_) {
    if (w.used) {
      continue;
    }
    if (w.address.second != 0 || w.address.comma || w.index >= 0) {
      return fail(alarm::kWordNotAllowed, address_name(w.address) + " cannot be a macro argument",
                  w.column);
    }
    const char c = w.address.first;
    if (c == 'G' || c == 'L' || c == 'O' || (c == 'P' && reserve_p)) {
      continue;  // the caller takes them
    }
    int var = type_one_variable(c);
    if (!type_one_only && (c == 'I' || c == 'J' || c == 'K')) {
      const int k = c - 'I';
      bool later_set = false;
      for (int j = k; j < 3; ++j) {
        later_set = later_set || in_group[static_cast<std::size_t>(j)];
      }
      if (later_set) {
        ++group;
        in_group.fill(false);
      }
      if (group > 10) {
        return fail(alarm::kWordNotAllowed, "more than 10 I/J/K argument groups", w.column);
      }
      in_group[static_cast<std::size_t>(k)] = true;
      var = 4 + 3 * (group - 1) + k;
    }
    if (var == 0) {
      return fail(alarm::kWordNotAllowed, address_name(w.address) + " cannot be a macro argument",
                  w.column);
    }
    args[static_cast<std::size_t>(var - 1)] = macro::MacroValue::of(w.value);
    w.used = true;
  }
  return true;
}

bool ProgramRun::repeat_word(std::int64_t& repeat) {
  repeat = 1;
  BlockWord* l = word('L');
  if (l == nullptr) {
    return true;
  }
  l->used = true;
  if (!whole_number(l->value, repeat) || repeat < 0) {
    return fail(alarm::kBadWordValue, "L (repeat count) must be a whole number >= 0", l->column);
  }
  return true;
}

bool ProgramRun::program_word(const char* code, int column, std::int64_t& program) {
  BlockWord* p = word('P');
  if (p == nullptr || !whole_number(p->value, program) || program < 0 || program > 9999) {
    return fail(alarm::kBadWordValue, std::string(code) + " needs P<program number 0-9999>",
                p != nullptr ? p->column : column);
  }
  p->used = true;
  return true;
}

bool ProgramRun::call_with_arguments(int program, int column, bool p_is_program) {
  std::int64_t repeat = 1;
  std::array<macro::MacroValue, 33> args{};
  if (!repeat_word(repeat) || !collect_macro_args(args, false, p_is_program)) {
    return false;
  }
  return call_macro(program, static_cast<int>(repeat), args, column, false);
}

// ---------------------------------------------------------------------------------------------
// The block

bool ProgramRun::execute_block(const parse::Line& /*line*/, const parse::Statement& s) {
  if (!evaluate_words(s)) {
    return false;
  }
  if (words_.empty()) {
    return true;
  }
  if (!contour_.active()) {
    block_start_ = machine_;  // a G70-G73 contour's blocks belong to their cycle's block
  }
  block_barrier_ = false;
  block_moved_ = false;
  block_exact_stop_ = false;
  if (frame_active() && !contour_.active()) {
    // Offsets written since the last block (G10, #2001, #5221 ...); not inside a G70-G73
    // contour, whose moves are read back in the frame before they go out.
    rebuild_frame();
  }

  // G codes of the block.
  std::array<BlockG, 8> gs{};
  int ng = 0;
  for (BlockWord& w : words_) {
    if (!w.address.is('G')) {
      continue;
    }
    w.used = true;
    std::int64_t code10 = 0;
    if (w.index >= 0 || !whole_number(w.value * 10.0, code10) || code10 < 0 || code10 > 9999) {
      return fail(alarm::kUnsupportedG, "G needs a code such as G01 or G04.1", w.column);
    }
    const int c = static_cast<int>(code10);
    // G codes that call macros (spec dafeng §4.13): the block is a call, like G65.
    int program = 0;
    for (const auto& [g, p] : config_.calls.g_macro) {
      program = g == c ? p : program;
    }
    const MacroCallTables& t = config_.calls;
    if (program == 0 && t.g_range_count > 0 && c % 10 == 0 && c / 10 >= t.g_range_first &&
        c / 10 < t.g_range_first + t.g_range_count) {
      program = t.g_range_program + (c / 10 - t.g_range_first);
    }
    if (program != 0) {
      return call_with_arguments(program, w.column, false);  // P is #16 here
    }
    const GCodeInfo info = lookup_gcode(c, config_.system, config_.dialect);
    if (info.function == GFunction::unknown) {
      return fail(alarm::kUnsupportedG, g_name(c) + " is not a G code of this dialect", w.column);
    }
    if (info.function == GFunction::not_in_this_version) {
      return fail(alarm::kNotInThisVersion, g_name(c) + ": " + info.topic, w.column);
    }
    if (!polar_allows(info.function, c, w.column)) {
      return false;
    }
    for (int i = 0; i < ng; ++i) {
      BlockG& other = gs[static_cast<std::size_t>(i)];
      if (other.info.group == info.group) {
        if (config_.dialect != Dialect::dafeng && info.group != 0) {
          // GSK and the mill: the last code of a group wins (gsk A.1 item 10, B.2 rule 5).
          other = BlockG{c, info, w.column};
          goto next_word;  // NOLINT(cppcoreguidelines-avoid-goto)
        }
        char group[8];
        std::snprintf(group, sizeof group, "%02d",
                      config_.dialect == Dialect::fanuc_mill ? mill_group(info.group) : info.group);
        return fail(alarm::kGroupConflict,
                    "two G codes of group " + std::string(group) + " in one block (" +
                        g_name(other.code10) + ", " + g_name(c) + ")",
                    w.column);
      }
    }
    if (ng == static_cast<int>(gs.size())) {
      return fail(alarm::kGroupConflict, "too many G codes in one block", w.column);
    }
    gs[static_cast<std::size_t>(ng++)] = BlockG{c, info, w.column};
  next_word:;
  }

  // Duplicate addresses (G, M and the argument letters of calls may repeat).
  bool call_block = false;
  for (int i = 0; i < ng; ++i) {
    const GFunction f = gs[static_cast<std::size_t>(i)].info.function;
    call_block = call_block || f == GFunction::macro_call || f == GFunction::modal_call ||
                 f == GFunction::channel_sync;
  }
  for (std::size_t i = 0; i < words_.size(); ++i) {
    const BlockWord& a = words_[i];
    if (a.address.is('G') || a.address.is('M')) {
      continue;
    }
    if (call_block &&
        (a.address.is('I') || a.address.is('J') || a.address.is('K') || a.address.is('Q'))) {
      continue;
    }
    for (std::size_t j = i + 1; j < words_.size(); ++j) {
      if (words_[j].address == a.address) {
        return fail(alarm::kDuplicateAddress,
                    address_name(a.address) + " appears twice in one block", words_[j].column);
      }
    }
  }

  GFunction motion = GFunction::unknown;   // group 01 in this block
  GFunction primary = GFunction::unknown;  // the one-shot code that takes the words
  int primary_code = 0;
  int primary_column = 0;
  bool frame_primary = false;  // the primary is G68.1/G69.1/G51.1/G50.1/G12.1/G13.1/G22/G23
  for (int i = 0; i < ng; ++i) {
    const BlockG& g = gs[static_cast<std::size_t>(i)];
    if (g.info.group == 1) {
      motion = g.info.function;
      continue;
    }
    if (g.info.function == GFunction::exact_stop) {
      block_exact_stop_ = true;
      continue;
    }
    // Modal codes that take the block's axis words as their data, not as a move.
    const bool frame_code =
        g.info.function == GFunction::rotation_on || g.info.function == GFunction::rotation_off ||
        g.info.function == GFunction::mirror_on || g.info.function == GFunction::mirror_off ||
        g.info.function == GFunction::polar_on || g.info.function == GFunction::polar_off ||
        g.info.function == GFunction::stroke_check_on ||
        g.info.function == GFunction::stroke_check_off ||
        g.info.function == GFunction::normal_off || g.info.function == GFunction::normal_left ||
        g.info.function == GFunction::normal_right ||
        g.info.function == GFunction::oscillation_on ||
        g.info.function == GFunction::oscillation_off;
    if (g.info.group == 0 || frame_code) {
      if (primary != GFunction::unknown && (frame_code || frame_primary)) {
        // G68.1, G51.1 and G22 take the axis words as their data: no other code may want them.
        return fail(alarm::kGroupConflict,
                    g_name(primary_code) + " and " + g_name(g.code10) + " in one block", g.column);
      }
      frame_primary = frame_primary || frame_code;
      primary = g.info.function;
      primary_code = g.code10;
      primary_column = g.column;
      continue;
    }
  }

  // Macro calls take every other word as an argument.
  if (primary == GFunction::macro_call) {
    if (words_.front().address != parse::Address{'G', 0, false} || words_.front().value != 65.0) {
      return fail(alarm::kWordNotAllowed, "G65 must come first in its block (only N before it)",
                  words_.front().column);
    }
    std::int64_t program = 0;
    if (!program_word("G65", primary_column, program)) {
      return false;
    }
    if (modal_call_.active) {
      modal_call_.active = false;  // G65 cancels a modal G66 call (gsk D2-37)
      modal_.codes[12] = 67;
    }
    return call_with_arguments(static_cast<int>(program), primary_column, true);
  }
  for (int i = 0; i < ng; ++i) {
    const BlockG& g = gs[static_cast<std::size_t>(i)];
    if (g.info.function == GFunction::modal_call) {
      std::int64_t program = 0;
      std::int64_t repeat = 1;
      if (!program_word("G66", g.column, program) || !repeat_word(repeat)) {
        return false;
      }
      ModalCall m;
      m.active = true;
      m.program = static_cast<int>(program);
      m.repeat = static_cast<int>(repeat);
      m.frame_depth = frames_.size();
      if (!collect_macro_args(m.args, false, true)) {
        return false;
      }
      modal_call_ = m;
      modal_.codes[12] = 66;
      return check_unused_words();
    }
    if (g.info.function == GFunction::modal_call_cancel) {
      modal_call_.active = false;
      modal_.codes[12] = 67;
    }
  }
  if (primary == GFunction::channel_call) {
    return run_channel_call(primary_column);
  }

  // M codes that call programs (spec dafeng §4.13): M98-like or G65-like.
  for (BlockWord& w : words_) {
    if (!w.address.is('M')) {
      continue;
    }
    std::int64_t m = 0;
    if (!whole_number(w.value, m) || m < 0 || m > 9999) {
      return fail(alarm::kBadWordValue, "M needs a whole number 0-9999", w.column);
    }
    const MacroCallTables& t = config_.calls;
    int program = 0;
    bool as_macro = false;
    for (const auto& [code, p] : t.m_subprogram) {
      program = code == m ? p : program;
    }
    for (const auto& [code, p] : t.m_macro) {
      if (code == m) {
        program = p;
        as_macro = true;
      }
    }
    if (program == 0 && t.m_sub_range_count > 0 && m >= t.m_sub_range_first &&
        m < t.m_sub_range_first + t.m_sub_range_count) {
      program = t.m_sub_range_program + static_cast<int>(m - t.m_sub_range_first);
    }
    if (program == 0 && t.m_macro_range_count > 0 && m >= t.m_macro_range_first &&
        m < t.m_macro_range_first + t.m_macro_range_count) {
      program = t.m_macro_range_program + static_cast<int>(m - t.m_macro_range_first);
      as_macro = true;
    }
    if (program == 0) {
      continue;
    }
    w.used = true;
    if (as_macro) {
      return call_with_arguments(program, w.column, false);
    }
    return call_subprogram(program, -1, 1, w.column, false) && check_unused_words();
  }

  // Modal codes, in the order a control applies them before the block's motion.
  // GSK: a G50 block ignores a work-system code beside it (gsk D2-16).
  const bool ignore_work_system =
      config_.dialect == Dialect::gsk && primary == GFunction::coordinate_set;
  for (int i = 0; i < ng; ++i) {
    const BlockG& g = gs[static_cast<std::size_t>(i)];
    if (ignore_work_system && g.info.group == 14) {
      continue;
    }
    if (contour_.capturing() && g.info.group == 2) {
      continue;  // G96/G97 in a G71-G73 contour are the finishing pass's (spec L1527)
    }
    if (g.info.group != 0 && g.info.group != 1 && g.info.function != primary &&
        !apply_modal(g.info.function, g.code10, g.column)) {
      return false;
    }
  }
  block_motion_code_ = motion != GFunction::unknown;
  bool group10 = false;
  for (int i = 0; i < ng; ++i) {
    group10 = group10 || gs[static_cast<std::size_t>(i)].info.group == 10;
  }
  if (motion != GFunction::unknown && !group10 && hole_.active()) {
    hole_ = state::HoleMode{};  // a group 01 code ends the hole cycle (spec L1938)
    modal_.codes[10] = 80.0;
  }
  // A hole block: the cycle's code, or positioning words while the cycle is modal.
  bool hole_block = group10 && hole_.active();
  if (!hole_block && hole_.active() && motion == GFunction::unknown &&
      primary == GFunction::unknown) {
    for (std::size_t i = 0; i < config_.axes.size() && !hole_block; ++i) {
      const AxisWords aw = axis_words(static_cast<int>(i));
      if (aw.error) {
        return false;
      }
      hole_block = aw.word != nullptr;
    }
  }
  if (hole_block && !take_hole_words(0)) {
    return false;
  }
  if (motion != GFunction::unknown) {
    modal_.motion = motion;
    for (int i = 0; i < ng; ++i) {
      if (gs[static_cast<std::size_t>(i)].info.group == 1) {
        modal_.codes[1] = static_cast<double>(gs[static_cast<std::size_t>(i)].code10) / 10.0;
      }
    }
  }
  // G71-G73 read the contour's geometry only: its F, S, T and M codes are the finishing pass's
  // (spec L1524-1530); the calls among them are refused by the calls themselves.
  if (contour_.capturing()) {
    for (BlockWord& w : words_) {
      const char c = w.address.first;
      if (w.address.second == 0 && !w.address.comma && (c == 'F' || c == 'S' || c == 'T')) {
        w.used = true;
      }
      if (w.address.is('M')) {
        if (w.value == 98.0 || w.value == 99.0) {
          return contour_forbids(w.value == 98.0 ? "M98" : "M99", w.column);
        }
        w.used = true;
      }
    }
  }
  // G81.1's F is the oscillation's speed, not the path's feed (L2460).
  if (BlockWord* f = word('F'); f != nullptr && !f->used && primary != GFunction::oscillation_on) {
    f->used = true;
    // A signed lead's sign is the thread's hand (thread_lead), not a direction of the feed.
    if (f->value < 0.0 && !signed_lead()) {
      return fail(alarm::kNegativeFeed, "feed F must not be negative", f->column);
    }
    modal_.feed = std::fabs(f->value) * (modal_.metric ? 1.0 : 25.4);
  }

  // Spindles, tool and the M codes that go out before the motion.
  // A hole-cycle block keeps P as its dwell (take_hole_words has it).
  bool p_is_spindle_address = word('S') != nullptr && !hole_block;
  for (int i = 0; i < ng; ++i) {
    p_is_spindle_address =
        p_is_spindle_address && !takes_p(gs[static_cast<std::size_t>(i)].info.function);
  }
  for (const BlockWord& w : words_) {
    if (w.address.is('M') && (w.value == 98.0 || w.value == 99.0)) {
      p_is_spindle_address = false;
    }
  }
  bool spindle_words = false;
  bool m_words = false;
  const bool capture = contour_.capturing();
  for (const BlockWord& w : words_) {
    if (capture) {
      break;
    }
    const char c = w.address.first;
    spindle_words = spindle_words || c == 'S' || c == 'M';
    m_words = m_words || w.address.is('M');
  }
  if (spindle_words && !run_spindle_words(p_is_spindle_address)) {
    return false;
  }
  // G81.4's T is the work's number of teeth, not a tool (spec dafeng L3236-3238).
  const bool t_is_teeth = primary == GFunction::egb_on;
  if (BlockWord* t = word('T'); interpolation_mode() && t != nullptr && !t_is_teeth) {
    return fail(alarm::kInterpolationModeRestriction,
                "the tool and its offset do not change in polar or cylindrical interpolation "
                "(spec L711-849)",
                t->column);
  }
  if (!capture && !t_is_teeth &&
      !(config_.dialect == Dialect::fanuc_mill ? run_mill_tool_words() : run_tool_word())) {
    return false;
  }
  if (m_words && !run_m_codes(false)) {
    return false;
  }

  // The one-shot code, or the motion of the modal group 01 code.
  if (primary != GFunction::unknown && primary != GFunction::machine_position) {
    if (!run_one_shot(primary, primary_code, primary_column)) {
      return false;
    }
  } else {
    const bool g53 = primary == GFunction::machine_position;
    GFunction m = modal_.motion;
    if (g53) {
      block_barrier_ = true;
      m = motion == GFunction::linear ? GFunction::linear : GFunction::rapid;
      if (motion != GFunction::unknown && motion != GFunction::rapid &&
          motion != GFunction::linear) {
        return fail(alarm::kWordNotAllowed, "G53 moves with G00 or G01 only", primary_column);
      }
    }
    if (hole_block && interpolation_mode()) {
      return fail(alarm::kInterpolationModeRestriction,
                  "no hole cycle in polar or cylindrical interpolation: G80 first", 0);
    }
    if (hole_block && !g53) {
      if (!run_hole_cycle(0)) {
        return false;
      }
    } else if (!run_motion(m, g53, g53 ? primary_column : 0)) {
      return false;
    }
  }

  if (block_barrier_ && !out_.empty() && out_.size() > block_out_start_) {
    out_.back().barrier = true;
  }
  if (!check_unused_words()) {
    return false;
  }
  // An angle-only G01 waits for the next block's end point: one block without motion may come
  // between them (gsk A.6.11 rule 7), nothing that stops the read-ahead.
  if (angle_start_.active && line_ != nullptr && angle_start_.line != line_->line &&
      !block_moved_) {
    if (++angle_start_.idle_blocks > 1 || block_barrier_ ||
        (!out_.empty() && out_.back().barrier)) {
      return fail(alarm::kAngleProgramming,
                  "the angle-only G01 of line " + std::to_string(angle_start_.line) +
                      " needs the next move block right after it",
                  0);
    }
  }
  // Under compensation the look-ahead needs moves: too many blocks in a row without one leave
  // it blind (spec L3735-3740: 4 of 5; gsk A.6.22 rule 1: 7).
  if (compensation_ != Command::Compensation::off && !contour_.capturing()) {
    idle_blocks_ = block_moved_ ? 0 : idle_blocks_ + 1;
    const int limit = config_.compensation_idle_blocks > 0 ? config_.compensation_idle_blocks
                      : config_.dialect == Dialect::gsk    ? 7
                                                           : 4;
    if (idle_blocks_ >= limit) {
      return fail(alarm::kCompensationLookahead,
                  std::to_string(idle_blocks_) +
                      " blocks in a row without a move under G41/G42: the compensation cannot "
                      "see where the path goes",
                  0);
    }
  } else {
    idle_blocks_ = 0;
  }
  // A modal G66 call follows every block that moved an axis, outside the called macro.
  if (block_moved_ && modal_call_.active) {
    bool inside = false;
    for (const Frame& f : frames_) {
      inside = inside || f.modal_call;
    }
    if (!inside &&
        !call_macro(modal_call_.program, modal_call_.repeat, modal_call_.args, 0, true)) {
      return false;
    }
  }
  return !m_words || run_m_codes(true);
}

// ---------------------------------------------------------------------------------------------
// Modal codes

bool ProgramRun::apply_modal(GFunction f, int code10, int column) {
  const double value = static_cast<double>(code10) / 10.0;
  if (!frame_allows(f, code10, column)) {
    return false;
  }
  switch (f) {
    case GFunction::plane_xy:
      modal_.plane = Plane::xy;
      modal_.codes[16] = value;
      return true;
    case GFunction::plane_zx:
      modal_.plane = Plane::zx;
      modal_.codes[16] = value;
      return true;
    case GFunction::plane_yz:
      modal_.plane = Plane::yz;
      modal_.codes[16] = value;
      return true;
    case GFunction::inch:
    case GFunction::metric:
      modal_.metric = f == GFunction::metric;
      modal_.codes[6] = value;
      return true;
    case GFunction::tnrc_cancel:
      compensation_ = Command::Compensation::off;
      modal_.codes[7] = value;
      return true;
    case GFunction::drill_cancel:
      hole_ = state::HoleMode{};
      modal_.codes[10] = value;
      return true;
    case GFunction::work_system:
    case GFunction::work_system_ext: {
      BlockWord* p = word('P');
      if (f == GFunction::work_system_ext || (code10 == 540 && p != nullptr)) {
        std::int64_t n = 0;
        if (p == nullptr || !whole_number(p->value, n) || n < 1 || n > kExtendedWorkSystems) {
          return fail(alarm::kBadWordValue, "G54.1 needs P1-P99",
                      p != nullptr ? p->column : column);
        }
        p->used = true;
        coordinates_.select(6 + static_cast<int>(n));
        modal_.codes[14] = 54.1;
        return true;
      }
      coordinates_.select((code10 - 540) / 10 + 1);
      modal_.codes[14] = value;
      return true;
    }
    case GFunction::exact_stop_mode:
    case GFunction::cutting_mode:
      modal_.exact_stop = f == GFunction::exact_stop_mode;
      modal_.codes[15] = value;
      return true;
    case GFunction::turret_mirror_on:
    case GFunction::turret_mirror_off:
      modal_.turret_mirror = f == GFunction::turret_mirror_on;
      modal_.codes[4] = value;
      return true;
    case GFunction::css_on:
    case GFunction::css_off:
      spindles_.css = f == GFunction::css_on;
      modal_.codes[2] = value;
      return true;
    case GFunction::feed_per_min:
    case GFunction::feed_per_rev:
      modal_.feed_mode = f == GFunction::feed_per_min ? FeedMode::per_min : FeedMode::per_rev;
      modal_.codes[5] = value;
      chip_ = ChipBreaking{};  // G98/G99 end chip breaking (spec L2568)
      modal_.codes[13] = 0;
      return true;
    case GFunction::absolute:
    case GFunction::incremental:
      modal_.incremental = f == GFunction::incremental;
      modal_.codes[3] = value;
      return true;
    case GFunction::return_initial:
    case GFunction::return_r_level:
      modal_.codes[11] = value;
      return true;
    case GFunction::polar_coords_on:
    case GFunction::polar_coords_off:
      for (const BlockWord& w : words_) {
        if (config_.dialect == Dialect::gsk && w.column != column) {
          return fail(alarm::kMustBeAlone,
                      g_name(code10) + " stands alone in its block (gsk rule 12, L393)", w.column);
        }
      }
      polar_coords_ = f == GFunction::polar_coords_on;
      polar_command_.reset();
      modal_.codes[18] = value;
      return true;
    case GFunction::modal_call:
    case GFunction::modal_call_cancel:
      return true;
    case GFunction::length_plus:
    case GFunction::length_minus:
    case GFunction::length_cancel:
      return run_length_compensation(f, value);
    case GFunction::tnrc_left:
    case GFunction::tnrc_right:
      compensation_ =
          f == GFunction::tnrc_left ? Command::Compensation::left : Command::Compensation::right;
      modal_.codes[7] = value;
      return true;
    case GFunction::drill_face:
    case GFunction::drill_side:
    case GFunction::tap_face:
    case GFunction::tap_side:
    case GFunction::bore_face:
    case GFunction::bore_side:
    case GFunction::mill_drill:
    case GFunction::mill_drill_dwell:
    case GFunction::mill_peck_deep:
    case GFunction::mill_peck_high_speed:
    case GFunction::mill_tap:
    case GFunction::mill_tap_left:
    case GFunction::mill_bore:
    case GFunction::mill_bore_stop:
    case GFunction::mill_back_bore:
    case GFunction::mill_bore_manual:
    case GFunction::mill_bore_dwell:
    case GFunction::mill_fine_bore:
      hole_.function = f;
      hole_.code10 = code10;
      modal_.codes[10] = value;
      return true;
    default:
      return fail(alarm::kUnsupportedG, g_name(code10) + " cannot be used here", column);
  }
}

// ---------------------------------------------------------------------------------------------
// Spindles and tools

bool ProgramRun::run_spindle_words(bool p_is_spindle_address) {
  // SPaab: the reference spindle of G96/G99/threading (spec dafeng L2662-2746).
  if (BlockWord* sp = word('S', 'P')) {
    sp->used = true;
    std::int64_t v = 0;
    if (!whole_number(sp->value, v) || v < 1 || v > 649) {
      return fail(alarm::kBadWordValue, "SP needs aab: channel aa (0-64) and spindle b (1-9)",
                  sp->column);
    }
    const int channel = static_cast<int>(v / 10);
    const int spindle = static_cast<int>(v % 10);
    if (spindle == 0) {
      return fail(alarm::kBadWordValue, "SP needs a spindle number b of 1-9", sp->column);
    }
    if ((channel == 0 || channel == config_.channel) &&
        !own_spindle(spindle, "SP" + std::to_string(v), sp->column)) {
      return false;
    }
    Command& c = emit(Op::spindle_select);
    c.channel = channel == config_.channel ? 0 : channel;
    c.spindle = spindle;
    if (c.channel == 0) {
      spindles_.reference = spindle;
    }
  }

  // Which spindle the S word and the spindle M codes address.
  int channel = 0;  // 0: this channel
  int addressed = 0;
  BlockWord* s = word('S');
  BlockWord* p = p_is_spindle_address ? word('P') : nullptr;
  if (p != nullptr) {
    std::int64_t v = 0;
    if (!whole_number(p->value, v) || v < 1 || v > 999) {
      return fail(alarm::kBadWordValue, "S_ P: P needs aab: channel aa and spindle b (1-9)",
                  p->column);
    }
    p->used = true;
    channel = static_cast<int>(v / 10);
    channel = channel == config_.channel ? 0 : channel;
    addressed = static_cast<int>(v % 10);
    if (addressed == 0) {
      return fail(alarm::kBadWordValue, "S_ P: the spindle number b must be 1-9", p->column);
    }
    if (channel == 0 && !own_spindle(addressed, "S_ P" + std::to_string(v), p->column)) {
      return false;
    }
  }
  bool surface_changed = false;
  bool clamp_changed = false;
  std::array<bool, 10> speed_changed{};
  double remote_rpm = -1.0;
  if (s != nullptr) {
    s->used = true;
    if (s->value < 0.0) {
      return fail(alarm::kBadWordValue, "S must not be negative", s->column);
    }
    int spindle = s->index >= 0 ? s->index : (addressed != 0 ? addressed : 1);
    if (spindle < 1 || spindle > 9) {
      return fail(alarm::kBadWordValue, "Sn=: spindle n must be 1-9", s->column);
    }
    if (addressed != 0 && s->index >= 0 && s->index != addressed) {
      return fail(alarm::kBadWordValue, "Sn= and P name different spindles", s->column);
    }
    if (s->index >= 0 && channel == 0 &&
        !own_spindle(spindle, "S" + std::to_string(spindle) + "=", s->column)) {
      return false;
    }
    addressed = spindle;
    bool clamp = false;
    for (const BlockWord& w : words_) {
      if (w.address.is('G')) {
        const GCodeInfo info = lookup_gcode(static_cast<int>(std::lround(w.value * 10)),
                                            config_.system, config_.dialect);
        clamp = clamp || info.function == GFunction::coordinate_set;
      }
    }
    if (channel != 0) {
      remote_rpm = s->value;
    } else if (clamp) {
      spindles_.clamp_rpm = s->value;  // G50 S (G92 S in system B): the G96 maximum
      clamp_changed = true;
    } else if (spindles_.css && s->index < 0 && p == nullptr) {
      spindles_.surface =
          s->value * (modal_.metric ? 1.0 : 0.3048);  // G96 S: m/min (ft/min in G20)
      surface_changed = true;
    } else {
      spindles_.rpm[static_cast<std::size_t>(spindle)] = s->value;
      speed_changed[static_cast<std::size_t>(spindle)] = true;
    }
  }

  auto spindle_command = [this](int spindle, SpindleDirection dir) -> Command& {
    Command& c = emit(Op::spindle);
    c.spindle = spindle;
    c.spindle_direction = dir;
    c.rpm = spindles_.rpm[static_cast<std::size_t>(spindle)];
    if (spindles_.surface_speed_on(spindle) && dir != SpindleDirection::stop &&
        dir != SpindleDirection::orient) {
      c.css = true;
      c.surface = spindles_.surface;
      c.max_rpm = spindles_.clamp_rpm;
    }
    return c;
  };

  bool commanded = false;
  std::uint32_t commanded_spindles = 0;
  for (BlockWord& w : words_) {
    if (!w.address.is('M')) {
      continue;
    }
    std::int64_t m = 0;
    if (!whole_number(w.value, m)) {
      return fail(alarm::kBadWordValue, "M needs a whole number", w.column);
    }
    const int base = static_cast<int>(m % 100);
    int spindle = static_cast<int>(m / 100) + 1;
    const int control = control_code(m, spindle);
    if (control < 0 && (m >= 1000 || (base != 3 && base != 4 && base != 5 && base != 19))) {
      continue;
    }
    w.used = true;
    if (spindle > 9) {
      return fail(alarm::kBadWordValue,
                  "M" + std::to_string(m) + " would address spindle " + std::to_string(spindle) +
                      "; spindles are 1-9",
                  w.column);
    }
    if (m >= 100 && channel == 0 && !own_spindle(spindle, "M" + std::to_string(m), w.column)) {
      return false;
    }
    if (addressed != 0 && addressed != spindle &&
        (p != nullptr || (s != nullptr && s->index >= 0))) {
      return fail(alarm::kBadWordValue,
                  "M" + std::to_string(m) + " is spindle " + std::to_string(spindle) +
                      " but the S word addresses spindle " + std::to_string(addressed),
                  w.column);
    }
    if (control >= 0) {
      if (channel != 0) {
        return fail(
            alarm::kNotInThisVersion,
            "M" + std::to_string(m) + " for another channel's spindle is not in this version",
            w.column);
      }
      if (commanded_spindles & (1U << spindle)) {
        return fail(alarm::kGroupConflict,
                    "two M codes for spindle " + std::to_string(spindle) + " in one block",
                    w.column);
      }
      commanded_spindles |= 1U << spindle;
      const auto s_index = static_cast<std::size_t>(spindle);
      const SpindleDirection turning = spindles_.direction[s_index];
      if (control == 1 && (turning == SpindleDirection::cw || turning == SpindleDirection::ccw)) {
        return fail(alarm::kSpindleControl,
                    "M" + std::to_string(m) + ": spindle " + std::to_string(spindle) +
                        " turns; stop it (M05) before position control",
                    w.column);
      }
      // The channel takes C over from where the spindle stands once the block runs: an axis
      // word beside it would be computed from where C was before.
      for (std::size_t i = 0; i < config_.axes.size(); ++i) {
        const AxisWords aw = axis_words(static_cast<int>(i));
        if (aw.error) {
          return false;
        }
        if (aw.word != nullptr) {
          return fail(alarm::kMustBeAlone,
                      "M" + std::to_string(m) + " stands in a block without axis words (" +
                          std::string(1, config_.axes[i].name) + " here)",
                      aw.word->column);
        }
      }
      spindles_.position_control[s_index] = control == 1;
      Command& c = emit(Op::spindle_mode);
      c.spindle = spindle;
      c.position_control = control == 1;
      c.barrier = true;  // the blocks after it start from where the spindle stands
      commanded = true;
      continue;
    }
    const SpindleDirection dir = base == 3   ? SpindleDirection::cw
                                 : base == 4 ? SpindleDirection::ccw
                                 : base == 5 ? SpindleDirection::stop
                                             : SpindleDirection::orient;
    if (dir != SpindleDirection::stop && channel == 0 && spindle <= 9 &&
        spindles_.position_control[static_cast<std::size_t>(spindle)]) {
      return fail(alarm::kSpindleControl,
                  "M" + std::to_string(m) + ": spindle " + std::to_string(spindle) +
                      " is under position control; " + position_code(spindle, false) +
                      " returns it to speed control first",
                  w.column);
    }
    if (channel != 0) {
      Command& c = emit(Op::spindle);
      c.channel = channel;
      c.spindle = spindle;
      c.spindle_direction = dir;
      c.rpm = remote_rpm >= 0.0 ? remote_rpm : 0.0;
      commanded = true;
      continue;
    }
    if (commanded_spindles & (1U << spindle)) {
      return fail(alarm::kGroupConflict,
                  "two M codes for spindle " + std::to_string(spindle) + " in one block", w.column);
    }
    commanded_spindles |= 1U << spindle;
    if (dir != SpindleDirection::orient) {
      spindles_.direction[static_cast<std::size_t>(spindle)] = dir;
    }
    Command& c = spindle_command(spindle, dir);
    if (dir == SpindleDirection::stop) {
      if (BlockWord* pa = word('P', 'A')) {
        pa->used = true;
        c.has_angle = true;
        c.angle = pa->value;
      }
      if (BlockWord* pn = word('P', 'N')) {
        pn->used = true;
        std::int64_t n = 0;
        if (!whole_number(pn->value, n) || n < 1 || n > 360) {
          return fail(alarm::kBadWordValue, "PN needs a number of divisions 1-360", pn->column);
        }
        c.divisions = static_cast<int>(n);
      }
    }
    speed_changed[static_cast<std::size_t>(spindle)] = false;
    if (spindle == spindles_.reference) {
      surface_changed = false;
      clamp_changed = false;
    }
    commanded = true;
  }
  if (channel != 0 && !commanded && remote_rpm >= 0.0) {
    Command& c = emit(Op::spindle);  // a speed for another channel's spindle: direction kept
    c.channel = channel;
    c.spindle = addressed;
    c.spindle_direction = SpindleDirection::keep;
    c.rpm = remote_rpm;
  }
  // A new speed, surface speed or clamp for a turning spindle goes out at once.
  for (int sp = 1; sp <= 9; ++sp) {
    const SpindleDirection dir = spindles_.direction[static_cast<std::size_t>(sp)];
    const bool turning = dir == SpindleDirection::cw || dir == SpindleDirection::ccw;
    const bool css_here = spindles_.surface_speed_on(sp);
    const bool changed =
        css_here ? (surface_changed || clamp_changed) : speed_changed[static_cast<std::size_t>(sp)];
    if (turning && changed) {
      spindle_command(sp, dir);
    }
  }
  return true;
}

bool ProgramRun::own_spindle(int spindle, const std::string& what, int column) {
  if (config_.spindles == kSpindlesUnknown || spindle <= config_.spindles) {
    return true;
  }
  const std::string has = config_.spindles == 0 ? "none"
                          : config_.spindles == 1
                              ? "spindle 1 only"
                              : "spindles 1-" + std::to_string(config_.spindles);
  return fail(alarm::kNoSuchSpindle,
              what + " names spindle " + std::to_string(spindle) +
                  ", which this channel does not have (it has " + has + ")",
              column);
}

int ProgramRun::control_code(std::int64_t m, int& spindle) const {
  int addressed = 1;
  int control = -1;
  if (config_.dialect == Dialect::fanuc_mill) {
    return -1;  // the mill's M18/M19 orient the spindle (gsk B.3), the PLC's
  }
  if (config_.dialect == Dialect::gsk) {
    control = m == 14 ? 1 : m == 15 ? 0 : -1;
  } else if (m < 1000 && (m % 100 == 17 || m % 100 == 18)) {
    addressed = static_cast<int>(m / 100) + 1;
    control = m % 100 == 18 ? 1 : 0;
  }
  // Without a C axis (c_axis in the machine file) the code stays the PLC's, as on a machine
  // whose spindle has no position control.
  const bool has_c = std::any_of(config_.axes.begin(), config_.axes.end(),
                                 [&](const AxisConfig& a) { return a.spindle == addressed; });
  if (control < 0 || !has_c) {
    return -1;
  }
  spindle = addressed;
  return control;
}

std::string ProgramRun::position_code(int spindle, bool position) const {
  if (config_.dialect == Dialect::gsk) {
    return position ? "M14" : "M15";
  }
  return "M" + std::to_string((spindle - 1) * 100 + (position ? 18 : 17));
}

bool ProgramRun::run_tool_word() {
  BlockWord* t = word('T');
  if (t == nullptr) {
    return true;
  }
  t->used = true;
  std::int64_t v = 0;
  if (!whole_number(t->value, v) || v < 0 || v > 9999) {
    return fail(alarm::kBadWordValue, "T needs TAABB: tool AA and offset BB as a whole number",
                t->column);
  }
  bool in_t_call = false;
  for (const Frame& f : frames_) {
    in_t_call = in_t_call || f.t_call;
  }
  if (config_.calls.t_program != 0 && !in_t_call) {
    // The T code calls the tool-change program like M98, with #149 = the T value (L7549-7566).
    vars_.write(149, macro::MacroValue::of(static_cast<double>(v)));
    return call_subprogram(config_.calls.t_program, -1, 1, t->column, true);
  }
  const int tool = static_cast<int>(v / 100);
  const int offset = static_cast<int>(v % 100);
  if (tool > config_.max_tool) {
    return fail(alarm::kBadWordValue,
                "tool number " + std::to_string(tool) + " beyond the " +
                    std::to_string(config_.max_tool) + " tools of this machine",
                t->column);
  }
  if (offset > kMaxToolOffsets) {
    return fail(alarm::kBadWordValue, "offset number " + std::to_string(offset) + " beyond 64",
                t->column);
  }
  if (compensation_ != Command::Compensation::off) {
    // A T command cancels tool-nose radius compensation (spec L3789).
    compensation_ = Command::Compensation::off;
    modal_.codes[7] = 40;
  }
  Command& c = emit(Op::tool);
  c.tool = tool;
  c.offset = offset;
  tools_.tool = tool;
  tools_.t_value = static_cast<double>(v);
  apply_tool_offset(offset);
  return true;
}

// ---------------------------------------------------------------------------------------------
// M codes

bool ProgramRun::run_m_codes(bool after_motion) {
  for (BlockWord& w : words_) {
    if (!w.address.is('M') || (w.used && !after_motion)) {
      continue;
    }
    std::int64_t m = 0;
    if (!whole_number(w.value, m) || m < 0 || m > 9999) {
      return fail(alarm::kBadWordValue, "M needs a whole number 0-9999", w.column);
    }
    const bool flow =
        m == 0 || m == 1 || m == 2 || m == 30 || m == 98 || m == 99 || m == 92 || m == 91;
    if (!after_motion) {
      if (flow) {
        w.used = true;  // runs after the motion; its words are checked then
        const char* words = m == 98 ? "PQL" : m == 99 ? "P" : m == 92 ? "NL" : "";
        for (const char* c = words; *c != 0; ++c) {
          if (BlockWord* x = word(*c)) {
            x->used = true;
          }
        }
        if (m == 91) {
          return fail(alarm::kNotInThisVersion,
                      "M91 (jump on an input) needs the PLC inputs of a later release", w.column);
        }
        continue;
      }
      w.used = true;
      emit(Op::aux).code = static_cast<int>(m);
      continue;
    }
    if (!flow) {
      continue;
    }
    switch (m) {
      case 0:
      case 1: {
        Command& c = emit(Op::stop);
        c.code = static_cast<int>(m);
        c.barrier = true;
        break;
      }
      case 2:
      case 30:
        if (angle_start_.active) {
          return fail(alarm::kAngleProgramming,
                      "the angle-only G01 of line " + std::to_string(angle_start_.line) +
                          " has no end point before the program end",
                      w.column);
        }
        if (!oscillation_ended()) {
          return false;
        }
        end_program(static_cast<int>(m));
        return true;
      case 98: {
        BlockWord* p = word('P');
        BlockWord* q = word('Q');
        BlockWord* l = word('L');
        std::int64_t program = -1;
        std::int64_t start = -1;
        std::int64_t repeat = 1;
        if (p != nullptr) {
          p->used = true;
          if (!whole_number(p->value, program) || program < 0 || program > 99999999) {
            return fail(alarm::kBadWordValue, "M98 P needs a program number", p->column);
          }
          if (program > 9999) {
            if (l != nullptr) {
              return fail(alarm::kBadWordValue,
                          "M98 P<count><program> and L together: give the count once", p->column);
            }
            repeat = program / 10000;  // P30010: O0010 three times (gsk D2-20, decision D24)
            program %= 10000;
          }
        }
        if (q != nullptr) {
          q->used = true;
          if (!whole_number(q->value, start) || start < 0) {
            return fail(alarm::kBadWordValue, "M98 Q needs a sequence number", q->column);
          }
        }
        if (l != nullptr) {
          l->used = true;
          if (!whole_number(l->value, repeat) || repeat < 0 || repeat > 999999) {
            return fail(alarm::kBadWordValue, "M98 L needs a repeat count 0-999999", l->column);
          }
        }
        if (p == nullptr && q == nullptr) {
          return fail(alarm::kBadWordValue, "M98 needs P<program> or Q<sequence number>", w.column);
        }
        return call_subprogram(static_cast<int>(program), static_cast<int>(start),
                               static_cast<int>(repeat), w.column, false);
      }
      case 99: {
        BlockWord* p = word('P');
        std::int64_t target = -1;
        if (p != nullptr) {
          p->used = true;
          if (!whole_number(p->value, target) || target < 0) {
            return fail(alarm::kBadWordValue, "M99 P needs a sequence number", p->column);
          }
        }
        return return_from_subprogram(target, w.column);
      }
      case 92: {
        // M92 N L: jump back to N; L = total passes (decision D23), no L = endless.
        BlockWord* n = word('N');
        BlockWord* l = word('L');
        std::int64_t target = 0;
        std::int64_t passes = -1;
        if (n == nullptr || !whole_number(n->value, target) || target < 0) {
          return fail(alarm::kBadWordValue, "M92 needs N<sequence number>", w.column);
        }
        n->used = true;
        if (l != nullptr) {
          l->used = true;
          if (!whole_number(l->value, passes)) {
            return fail(alarm::kBadWordValue, "M92 L needs a whole number", l->column);
          }
          passes = passes < 1 ? 1 : passes;
        }
        const auto key = std::make_pair(frames_.size(), line_);
        auto it = loop_counters_.find(key);
        if (it == loop_counters_.end()) {
          it = loop_counters_.emplace(key, passes < 0 ? -1 : passes - 1).first;
        }
        if (it->second == 0) {
          loop_counters_.erase(it);
          break;
        }
        if (it->second > 0) {
          --it->second;
        }
        return jump_to_sequence(target, parse::GotoDirection::backward, n->column);
      }
      default:
        break;
    }
  }
  return true;
}

// ---------------------------------------------------------------------------------------------
// One-shot codes

bool ProgramRun::run_one_shot(GFunction f, int code10, int column) {
  if (!frame_allows(f, code10, column)) {
    return false;
  }
  switch (f) {
    case GFunction::polar_on:
    case GFunction::polar_off:
      return run_polar(f, column);
    case GFunction::cylindrical:
      return run_cylindrical(column);
    case GFunction::rotation_on:
    case GFunction::rotation_off:
      return run_rotation(f, column);
    case GFunction::mirror_on:
    case GFunction::mirror_off:
      return run_mirror(f, column);
    case GFunction::dwell:
      return run_dwell(column);
    case GFunction::channel_sync:
      return run_channel_sync(column);
    case GFunction::data_input:
      return run_data_input(column);
    case GFunction::radius_switch:
      return run_radius_switch(column);
    case GFunction::stroke_check_on:
    case GFunction::stroke_check_off:
      return run_stroke_check(f, column);
    case GFunction::chip_break_per_min:
    case GFunction::chip_break_per_rev:
      return run_chip_breaking(f, column);
    case GFunction::normal_off:
    case GFunction::normal_left:
    case GFunction::normal_right:
      return run_normal_direction(f, column);
    case GFunction::oscillation_on:
    case GFunction::oscillation_off:
      return run_oscillation(f, column);
    case GFunction::skip:
      return run_skip(column);
    case GFunction::multi_skip:
      return run_multi_skip(column);
    case GFunction::torque_skip:
      return run_torque_skip(column);
    case GFunction::reference_return:
    case GFunction::reference_2_4:
      return run_reference_return(f, column);
    case GFunction::reference_check:
      return run_reference_check(column);
    case GFunction::return_from_reference:
      return run_return_from_reference(column);
    case GFunction::single_direction:
      return run_single_direction(column);
    case GFunction::coordinate_set:
      return run_coordinate_set(column);
    case GFunction::restore_origin:
      return run_restore_origin(column);
    case GFunction::local_system:
      return run_local_system(column);
    case GFunction::axis_release:
    case GFunction::axis_acquire:
    case GFunction::axis_restore:
      return run_axis_exchange(f, column);
    case GFunction::channel_release:
      emit(Op::subcall_release);
      return true;
    case GFunction::axis_sync_on:
    case GFunction::axis_sync_off:
      return run_axis_sync(f, column);
    case GFunction::spindle_sync_on:
    case GFunction::spindle_sync_off:
      return run_spindle_sync(f);
    case GFunction::polygon_on:
    case GFunction::polygon_off:
      return run_polygon(f, column);
    case GFunction::cam_on:
    case GFunction::cam_off:
      return run_cam(f, column);
    case GFunction::egb_on:
    case GFunction::egb_off:
      return run_gear_box(f);
    case GFunction::finishing_cycle:
      return run_finishing_cycle(column);
    case GFunction::rough_turning:
    case GFunction::rough_facing:
      return run_rough_cycle(f, column);
    case GFunction::pattern_repeat:
      return run_pattern_cycle(column);
    case GFunction::face_grooving:
    case GFunction::od_grooving:
      return run_groove_cycle(f, column);
    case GFunction::multiple_thread:
      return run_multiple_thread(column);
    case GFunction::extended_thread:
      return run_extended_thread(column);
    default:
      return fail(alarm::kUnsupportedG, g_name(code10) + " cannot be used here", column);
  }
}

bool ProgramRun::run_dwell(int column) {
  BlockWord* p = word('P');
  BlockWord* x = word('X');
  BlockWord* u = word('U');
  BlockWord* i = word('I');
  BlockWord* ps = word('P', 'S');
  if (ps != nullptr && i != nullptr) {
    return fail(alarm::kGroupConflict, "G04 PS and G04 I cannot wait in one block", i->column);
  }
  const bool gsk = config_.dialect == Dialect::gsk;
  const int given = (p != nullptr) + (x != nullptr) + (u != nullptr);
  if (given > 1 && !gsk) {
    BlockWord* second = p != nullptr ? (x != nullptr ? x : u) : u;
    return fail(alarm::kDwellTimeTwice, "G04 dwell time given more than once (P, X, U)",
                second->column);
  }
  double seconds = 0.0;
  bool has_time = false;
  // GSK (D2-7): P wins over X, X over U.
  if (u != nullptr) {
    u->used = true;
    seconds = scaled(*u, false);
    has_time = true;
  }
  if (x != nullptr) {
    x->used = true;
    seconds = scaled(*x, false);
    has_time = true;
  }
  if (p != nullptr) {
    p->used = true;
    seconds = p->value / 1000.0;
    has_time = true;
  }
  if (seconds < 0.0) {
    if (!gsk) {
      return fail(alarm::kNegativeDwell, "G04 dwell time must not be negative",
                  (p != nullptr ? p : (x != nullptr ? x : u))->column);
    }
    seconds = 0.0;
  }
  if (i != nullptr) {
    i->used = true;
    std::int64_t input = 0;
    if (!whole_number(i->value, input)) {
      return fail(alarm::kBadWordValue, "G04 I needs an input number", i->column);
    }
    block_barrier_ = true;
    if (input == 0) {
      Command& c = emit(Op::sync);  // G04 I0: the read-ahead barrier (spec L6918-6921)
      c.barrier = true;
      if (has_time) {
        Command& d = emit(Op::dwell);
        d.seconds = seconds;
      }
      return true;
    }
    Command& c = emit(Op::wait_input);
    c.input = static_cast<int>(input < 0 ? -input : input);
    c.input_on = input > 0;
    if (BlockWord* j = word('J')) {
      j->used = true;
      c.timeout_s = j->value;
    }
    if (BlockWord* k = word('K')) {
      k->used = true;
      c.width_s = k->value;
    }
    c.dwell_s = has_time ? seconds : -1.0;
    return true;
  }
  if (ps != nullptr) {
    // G04 PSn=r (dafeng L2747-2782): n omitted is spindle 1; r in rpm, 0 waits for the stop.
    ps->used = true;
    const int spindle = ps->index < 0 ? 1 : ps->index;
    if (spindle < 1 || spindle > 9) {
      return fail(alarm::kBadWordValue, "G04 PS names spindle 1-9", ps->column);
    }
    if (ps->value < 0.0) {
      return fail(alarm::kBadWordValue, "G04 PS: the speed (rpm) must not be negative", ps->column);
    }
    if (!own_spindle(spindle, "G04 PS", ps->column)) {
      return false;
    }
    block_barrier_ = true;
    Command& c = emit(Op::wait_spindle);
    c.spindle = spindle;
    c.rpm = ps->value;
    c.dwell_s = has_time ? seconds : -1.0;
    return true;
  }
  Command& c = emit(Op::dwell);
  if (config_.dwell_in_revs_with_g99 && modal_.feed_mode == FeedMode::per_rev) {
    c.in_revs = true;
  }
  c.seconds = seconds;
  (void)column;
  return true;
}

bool ProgramRun::run_channel_sync(int column) {
  BlockWord* p = word('P');
  Command& c = emit(Op::sync);
  c.barrier = true;
  block_barrier_ = true;
  bool any_q = false;
  for (BlockWord& w : words_) {
    if (!w.address.is('Q')) {
      continue;
    }
    w.used = true;
    any_q = true;
    std::int64_t v = 0;
    if (!whole_number(w.value, v)) {
      return fail(alarm::kSyncForm, "G04.1 Q needs whole numbers", w.column);
    }
    if (w.index < 0 && v == -1) {
      c.all_channels = true;
      continue;
    }
    if (v <= 0 || (w.index >= 0 && (w.index < 1 || w.index > 25))) {
      return fail(alarm::kSyncForm,
                  "G04.1 Q: write channels as digits (Q123, 0 = channel 10), Qt=d for channel "
                  "10t+d, or Q-1 for all",
                  w.column);
    }
    // Each digit is a channel; digit 0 is channel 10. Qt=d... names channels 10t+d (D6).
    for (std::int64_t rest = v; rest > 0; rest /= 10) {
      const int d = static_cast<int>(rest % 10);
      const int channel = w.index >= 0 ? 10 * w.index + d : (d == 0 ? 10 : d);
      if (channel < 1 || channel > 255) {
        return fail(alarm::kSyncForm,
                    "G04.1 Q names channel " + std::to_string(channel) + " (channels are 1-255)",
                    w.column);
      }
      c.set_channel(channel);
    }
  }
  if (p == nullptr) {
    if (any_q) {
      return fail(alarm::kSyncForm, "G04.1 with Q needs P (the synchronisation number)", column);
    }
    return true;  // neither P nor Q: the read-ahead barrier of G04 I0 (spec L5445)
  }
  p->used = true;
  std::int64_t v = 0;
  if (!whole_number(p->value, v) || v < 1 || v > 99999999) {
    return fail(alarm::kSyncForm, "G04.1 P needs a positive whole number", p->column);
  }
  c.has_p = true;
  c.p = static_cast<int>(v);
  if (!any_q) {
    c.all_channels = true;  // P without Q: all channels (decision D5)
  }
  if (c.all_channels) {
    c.channels = {};
  } else if (!c.has_channel(config_.channel)) {
    return fail(alarm::kSyncForm,
                "G04.1 Q does not include this channel (" + std::to_string(config_.channel) + ")",
                column);
  }
  return true;
}

bool ProgramRun::run_channel_call(int column) {
  BlockWord* n = word('N');
  BlockWord* p = word('P');
  BlockWord* h = word('H');
  BlockWord* l = word('L');
  std::int64_t channel = 0;
  std::int64_t program = 0;
  std::int64_t wait = 1;
  std::int64_t repeat = 1;
  if (n == nullptr || !whole_number(n->value, channel) || channel < 1 || channel > 255) {
    return fail(alarm::kBadWordValue, "G144 needs N<channel 1-255>",
                n != nullptr ? n->column : column);
  }
  if (channel == config_.channel) {
    return fail(alarm::kBadWordValue, "G144 N names this channel itself", n->column);
  }
  if (p == nullptr || !whole_number(p->value, program) || program < 0 || program > 9999) {
    return fail(alarm::kBadWordValue, "G144 needs P<program number 0-9999>",
                p != nullptr ? p->column : column);
  }
  if (h != nullptr && (!whole_number(h->value, wait) || (wait != 0 && wait != 1))) {
    return fail(alarm::kBadWordValue, "G144 H must be 0 (no wait) or 1 (wait)", h->column);
  }
  if (l != nullptr) {
    if (wait == 0) {
      return fail(alarm::kWordNotAllowed, "G144 L (repeat count) is only valid with H1", l->column);
    }
    if (!whole_number(l->value, repeat) || repeat < 1) {
      return fail(alarm::kBadWordValue, "G144 L needs a repeat count of at least 1", l->column);
    }
    l->used = true;
  }
  n->used = true;
  p->used = true;
  if (h != nullptr) {
    h->used = true;
  }
  Command& c = emit(Op::subcall);
  c.channel = static_cast<int>(channel);
  c.program = static_cast<int>(program);
  c.wait = wait == 1;
  c.repeat = static_cast<int>(repeat);
  for (BlockWord& w : words_) {
    if (w.used) {
      continue;
    }
    const char letter = w.address.first;
    const int var = w.address.second == 0 && !w.address.comma && w.index < 0 && letter != 'N' &&
                            letter != 'P' && letter != 'H' && letter != 'L' && letter != 'O'
                        ? type_one_variable(letter)
                        : 0;
    if (var == 0 || var > kSubcallArgs) {
      return fail(alarm::kWordNotAllowed, address_name(w.address) + " cannot be a G144 argument",
                  w.column);
    }
    c.args.emplace_back(var, w.value);
    w.used = true;
  }
  std::sort(c.args.begin(), c.args.end());
  c.barrier = c.wait;
  return true;
}

bool ProgramRun::run_axis_exchange(GFunction f, int column) {
  if (f == GFunction::axis_restore) {
    Command& c = emit(Op::axis_restore);
    c.barrier = true;
    released_.fill(false);
    return true;
  }
  bool force = false;
  if (f == GFunction::axis_acquire) {
    if (BlockWord* p = word('P')) {
      std::int64_t v = 0;
      if (!whole_number(p->value, v) || (v != 0 && v != 1)) {
        return fail(alarm::kBadWordValue, "G141 P must be 0 (wait for release) or 1 (force)",
                    p->column);
      }
      p->used = true;
      force = v == 1;
    }
  }
  int count = 0;
  for (BlockWord& w : words_) {
    if (w.used || w.address.second != 0 || w.address.comma) {
      continue;
    }
    const char letter = w.address.first;
    if (letter != 'X' && letter != 'Y' && letter != 'Z' && letter != 'A' && letter != 'B' &&
        letter != 'C') {
      continue;
    }
    std::int64_t exchange = 0;
    if (!whole_number(w.value, exchange) || exchange < 1 || exchange > 9999) {
      return fail(alarm::kBadWordValue,
                  std::string(1, letter) +
                      "n: n is the axis exchange number (parameter 5660), a positive whole number",
                  w.column);
    }
    int axis = -1;
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      axis = config_.axes[i].name == letter ? static_cast<int>(i) : axis;
    }
    if (axis < 0) {
      return fail(alarm::kWordNotAllowed,
                  std::string(1, letter) + " is not an axis (or placeholder axis) of channel " +
                      std::to_string(config_.channel),
                  w.column);
    }
    if (!inclined_allows(axis, "it cannot be exchanged", w.column)) {
      return false;
    }
    if (oscillating_[static_cast<std::size_t>(axis)]) {
      return fail(alarm::kOscillation,
                  std::string(1, letter) + " oscillates (G81.1): G80.1 before it is exchanged",
                  w.column);
    }
    const int own = config_.axes[static_cast<std::size_t>(axis)].exchange;
    if (own != 0 && own != exchange) {
      return fail(alarm::kBadWordValue,
                  std::string(1, letter) + std::to_string(exchange) + ": the exchange number of " +
                      letter + " in this channel is " + std::to_string(own),
                  w.column);
    }
    w.used = true;
    Command& c = emit(f == GFunction::axis_release ? Op::axis_release : Op::axis_acquire);
    c.axis = letter;
    c.exchange = static_cast<int>(exchange);
    c.force = force;
    c.barrier = true;
    released_[static_cast<std::size_t>(axis)] = f == GFunction::axis_release;
    ++count;
  }
  if (count == 0) {
    return fail(alarm::kBadWordValue,
                std::string(f == GFunction::axis_release ? "G140" : "G141") +
                    " needs an axis with its exchange number, e.g. A14",
                column);
  }
  return true;
}

bool ProgramRun::run_axis_sync(GFunction f, int column) {
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  std::int64_t master = 0;
  std::int64_t slave = 0;
  if (q == nullptr || !whole_number(q->value, slave) || slave < 1 || slave > 255) {
    return fail(alarm::kBadWordValue,
                std::string(f == GFunction::axis_sync_on ? "G51.4" : "G50.4") +
                    " needs Q<slave axis number>",
                q != nullptr ? q->column : column);
  }
  q->used = true;
  if (p != nullptr) {
    p->used = true;  // G50.4 accepts and ignores P (spec L5580)
    if (f == GFunction::axis_sync_on &&
        (!whole_number(p->value, master) || master < 1 || master > 255 || master == slave)) {
      return fail(alarm::kBadWordValue, "G51.4 P needs a master axis number other than Q",
                  p->column);
    }
  }
  if (f == GFunction::axis_sync_on) {
    for (std::size_t i = 0; i < config_.axes.size(); ++i) {
      if (config_.axes[i].id == slave &&
          !inclined_allows(static_cast<int>(i), "it cannot be a G51.4 slave (it may be the master)",
                           q->column)) {
        return false;
      }
    }
  }
  Command& c = emit(f == GFunction::axis_sync_on ? Op::axis_couple : Op::axis_decouple);
  c.master = f == GFunction::axis_sync_on ? static_cast<int>(master) : 0;
  c.slave = static_cast<int>(slave);
  c.barrier = true;
  return true;
}

bool ProgramRun::run_spindle_sync(GFunction f) {
  if (f == GFunction::spindle_sync_off) {
    Command& c = emit(Op::spindle_unsync);
    c.barrier = true;
    return true;
  }
  Command& c = emit(Op::spindle_sync);
  std::int64_t v = 0;
  if (BlockWord* p = word('P')) {
    p->used = true;
    if (!whole_number(p->value, v) || v < 1) {
      return fail(alarm::kBadWordValue, "G114.1 P (master ratio) must be a positive whole number",
                  p->column);
    }
    c.sync_p = static_cast<int>(v);
  }
  if (BlockWord* q = word('Q')) {
    q->used = true;
    if (!whole_number(q->value, v) || v == 0) {
      return fail(alarm::kBadWordValue, "G114.1 Q (slave ratio) must be a non-zero whole number",
                  q->column);
    }
    c.sync_q = static_cast<int>(v);
  }
  if (BlockWord* k = word('K')) {
    k->used = true;
    if (!whole_number(k->value, v) || v < 1 || v > 3) {
      return fail(alarm::kBadWordValue, "G114.1 K (synchronisation group) must be 1-3", k->column);
    }
    c.sync_k = static_cast<int>(v);
  }
  if (BlockWord* r = word('R')) {
    r->used = true;
    if (r->value < 0.0 || r->value >= 360.0) {
      return fail(alarm::kBadWordValue, "G114.1 R (phase) must be 0-359.999 degrees", r->column);
    }
    c.sync_r = r->value;
  }
  c.barrier = true;
  return true;
}

// G50.2 P / G80.4 P: a coupling ends, the block waiting for its axis to stop with P1 or no P,
// not with P0 (spec dafeng L2925-2927, L3245-3249).
bool ProgramRun::run_coupling_off(Op op, const char* code, const char* axis) {
  Command& c = emit(op);
  c.wait = true;
  c.barrier = true;
  if (BlockWord* p = word('P')) {
    p->used = true;
    std::int64_t v = 0;
    if (!whole_number(p->value, v) || (v != 0 && v != 1)) {
      return fail(
          alarm::kBadWordValue,
          std::string(code) + " P must be 0 (do not wait for the " + axis + " to stop) or 1 (wait)",
          p->column);
    }
    c.wait = v == 1;
  }
  return true;
}

// G51.2 P Q R / G50.2 P (spec dafeng §2.6.6, L2847-2870): the ratios are whole numbers, P
// unsigned and Q signed (its sign turns the slave the other way), R the master's start angle.
bool ProgramRun::run_polygon(GFunction f, int column) {
  std::int64_t v = 0;
  if (f == GFunction::polygon_off) {
    return run_coupling_off(Op::polygon_off, "G50.2", "polygon axis");
  }
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  if (p == nullptr || q == nullptr) {
    return fail(alarm::kBadWordValue,
                "G51.2 needs P (master spindle ratio) and Q (polygon axis ratio)", column);
  }
  Command& c = emit(Op::polygon);
  p->used = true;
  if (!whole_number(p->value, v) || v < 1 || v > kMaxRatio) {
    return fail(alarm::kBadWordValue, "G51.2 P (master ratio) must be a whole number 1-9999",
                p->column);
  }
  c.sync_p = static_cast<int>(v);
  q->used = true;
  if (!whole_number(q->value, v) || v == 0 || v < -kMaxRatio || v > kMaxRatio) {
    return fail(alarm::kBadWordValue,
                "G51.2 Q (polygon axis ratio) must be a non-zero whole number, -9999 to 9999",
                q->column);
  }
  c.sync_q = static_cast<int>(v);
  c.sync_r = 0.0;
  if (BlockWord* r = word('R')) {
    r->used = true;
    if (!(r->value >= 0.0 && r->value <= 360.0)) {
      return fail(alarm::kBadWordValue, "G51.2 R (master start angle) must be 0-360 degrees",
                  r->column);
    }
    c.sync_r = r->value;
  }
  c.barrier = true;
  return true;
}

// G51.8 P L R / H1 A B R / H2 D P R and G50.8 (spec dafeng §2.6.7-2.6.10, L3013-3230): the
// channel's cam slave follows a lift per master spindle angle. The table is read from #P to
// #P+L-1 when the block runs, so the program fills it before (L3067-3085); a vacant point is an
// alarm, not a lift of 0: a table with a hole would move the axis by what nobody wrote.
bool ProgramRun::run_cam(GFunction f, int column) {
  if (f == GFunction::cam_off) {
    emit(Op::cam_off).barrier = true;
    return true;
  }
  Command& c = emit(Op::cam);
  c.barrier = true;
  c.sync_r = 0.0;
  if (BlockWord* r = word('R')) {
    r->used = true;
    if (!(r->value >= 0.0 && r->value <= 360.0)) {
      return fail(alarm::kBadWordValue, "G51.8 R (start angle) must be 0-360 degrees", r->column);
    }
    c.sync_r = r->value;
  }
  std::int64_t h = 0;
  if (BlockWord* hw = word('H')) {
    hw->used = true;
    if (!whole_number(hw->value, h) || (h != 1 && h != 2)) {
      return fail(alarm::kBadWordValue,
                  "G51.8 H must be 1 (ellipse) or 2 (eccentric circle); a table takes P and L",
                  hw->column);
    }
  }
  if (h == 0) {
    return run_cam_table(c, column);
  }
  c.cam_shape = static_cast<int>(h);
  const char first = h == 1 ? 'A' : 'D';
  const char second = h == 1 ? 'B' : 'P';
  BlockWord* a = word(first);
  BlockWord* b = word(second);
  if (a == nullptr || b == nullptr) {
    return fail(alarm::kBadWordValue,
                h == 1 ? "G51.8 H1 needs A (semi-major axis) and B (semi-minor axis)"
                       : "G51.8 H2 needs D (circle diameter) and P (eccentricity)",
                column);
  }
  a->used = true;
  b->used = true;
  if (!(a->value > 0.0)) {
    return fail(alarm::kBadWordValue,
                h == 1 ? "G51.8 H1 A (semi-major axis) must be greater than 0"
                       : "G51.8 H2 D (circle diameter) must be greater than 0",
                a->column);
  }
  if (h == 1 && !(b->value > 0.0)) {
    return fail(alarm::kBadWordValue, "G51.8 H1 B (semi-minor axis) must be greater than 0",
                b->column);
  }
  // The spindle's axis must lie inside the circle, or the lift has no value at some angles.
  if (h == 2 && !(b->value >= 0.0 && b->value < a->value / 2.0)) {
    return fail(alarm::kBadWordValue, "G51.8 H2 P (eccentricity) must be 0 or more and below D/2",
                b->column);
  }
  c.cam_a = a->value;
  c.cam_b = b->value;
  return true;
}

bool ProgramRun::run_cam_table(Command& c, int column) {
  BlockWord* p = word('P');
  BlockWord* l = word('L');
  if (p == nullptr || l == nullptr) {
    return fail(alarm::kBadWordValue,
                "G51.8 needs P (the table's first variable) and L (its number of points)", column);
  }
  p->used = true;
  l->used = true;
  std::int64_t first = 0;
  std::int64_t points = 0;
  if (!whole_number(p->value, first) || first < 1 || first > 999) {
    return fail(alarm::kBadWordValue, "G51.8 P (the table's first variable) must be #1-#999",
                p->column);
  }
  if (!whole_number(l->value, points) || points < 1 || first + points - 1 > 999) {
    return fail(alarm::kBadWordValue,
                "G51.8 L (number of points) must be 1 or more, the table within #1-#999",
                l->column);
  }
  c.cam_first = static_cast<int>(first);
  c.cam_lift.reserve(static_cast<std::size_t>(points));
  for (std::int64_t n = first; n < first + points; ++n) {
    const macro::VariableRead v = vars_.read(n);
    if (v.alarm.number != 0 || v.value.is_null() || !std::isfinite(v.value.number())) {
      return fail(alarm::kBadWordValue,
                  "G51.8: #" + std::to_string(n) + " of the cam table is vacant", p->column);
    }
    c.cam_lift.push_back(v.value.number());
  }
  return true;
}

// G81.4 T L P Q R / G80.4 P, the electronic gear box (spec dafeng §2.6.11, L3231-3374): the
// channel's EGB work axis follows its tool spindle until G80.4. T and L take the whole numbers of
// G51.2's ratios (decision 133).
bool ProgramRun::run_gear_box(GFunction f) {
  std::int64_t v = 0;
  if (f == GFunction::egb_off) {
    return run_coupling_off(Op::egb_off, "G80.4", "work axis");
  }
  Command& c = emit(Op::egb);
  c.barrier = true;
  if (BlockWord* t = word('T')) {
    t->used = true;
    if (!whole_number(t->value, v) || v < 1 || v > kMaxRatio) {
      return fail(alarm::kBadWordValue,
                  "G81.4 T (number of teeth of the work) must be a whole number 1-9999", t->column);
    }
    c.egb_teeth = static_cast<int>(v);
  }
  if (BlockWord* l = word('L')) {
    l->used = true;
    if (!whole_number(l->value, v) || v == 0 || v < -kMaxRatio || v > kMaxRatio) {
      return fail(alarm::kBadWordValue,
                  "G81.4 L (number of threads of the hob) must be a non-zero whole number, -9999 "
                  "to 9999",
                  l->column);
    }
    c.egb_threads = static_cast<int>(v);
  }
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  if (p != nullptr) {
    p->used = true;
    if (!(p->value >= -90.0 && p->value <= 90.0)) {
      return fail(alarm::kBadWordValue, "G81.4 P (helix angle) must be -90 to 90 degrees",
                  p->column);
    }
    c.egb_helix = p->value;
  }
  if (q != nullptr) {
    q->used = true;
    // The sign reverses the helical term (L3349), so the range is the module's magnitude.
    if (!(std::fabs(q->value) >= 0.1 && std::fabs(q->value) <= 25.0)) {
      return fail(alarm::kBadWordValue,
                  "G81.4 Q (module) must be 0.1-25 mm (its sign: the "
                  "helical term's direction)",
                  q->column);
    }
    c.egb_module = q->value;
  }
  // A helical gear's term divides by the module: a helix angle without it has no value.
  if (c.egb_helix != 0.0 && q == nullptr) {
    return fail(alarm::kBadWordValue, "G81.4 P (helix angle) needs Q (module)", p->column);
  }
  if (BlockWord* r = word('R')) {
    r->used = true;
    if (!(r->value >= 0.0 && r->value < 360.0)) {
      return fail(alarm::kBadWordValue, "G81.4 R (work phase) must be 0-359.999 degrees",
                  r->column);
    }
    c.sync_r = r->value;
    c.egb_phase = true;
  }
  return true;
}

bool ProgramRun::run_data_input(int column) {
  BlockWord* l = word('L');
  BlockWord* p = word('P');
  std::int64_t lv = 0;
  std::int64_t pv = 0;
  if (p == nullptr || !whole_number(p->value, pv)) {
    return fail(alarm::kBadWordValue, "G10 needs P (which offset)", column);
  }
  p->used = true;
  if (l != nullptr) {
    l->used = true;
    if (whole_number(l->value, lv) && lv == 14) {
      return run_torque_data(column);
    }
    if (!whole_number(l->value, lv) || (lv != 2 && lv != 20)) {
      return fail(alarm::kNotInThisVersion,
                  "G10 L" + std::to_string(lv) +
                      " is not implemented (work offsets: L2, L20; torque data: L14; tool "
                      "offsets: no L)",
                  l->column);
    }
    int system = 0;
    if (lv == 2) {
      if (pv < 0 || pv > 6 + kExtendedWorkSystems) {
        return fail(alarm::kBadWordValue, "G10 L2 P must be 0 (EXT), 1-6 (G54-G59) or 7-105",
                    p->column);
      }
      system = static_cast<int>(pv);
    } else {
      if (pv < 1 || pv > kExtendedWorkSystems) {
        return fail(alarm::kBadWordValue, "G10 L20 P must be 1-99 (G54.1 P1-P99)", p->column);
      }
      system = 6 + static_cast<int>(pv);
    }
    return for_each_axis_word([&](int axis, const BlockWord& w, bool incremental) {
      double& slot = coordinates_.offset(system, axis);
      const double v = data_to_physical(axis, scaled_axis_word(axis, w));
      slot = incremental ? slot + v : v;
      return true;
    });
  }
  // Tool offsets: P1-P64 wear, P10001-P10064 geometry (spec dafeng L3620-3669).
  const bool geometry = pv >= 10001 && pv <= 10000 + kMaxToolOffsets;
  if (!geometry && (pv < 1 || pv > kMaxToolOffsets)) {
    return fail(alarm::kBadWordValue, "G10 P must be 1-64 (wear) or 10001-10064 (geometry)",
                p->column);
  }
  ToolOffsetValues& t = tools_.values(geometry, static_cast<int>(geometry ? pv - 10000 : pv));
  struct Field {
    char abs;
    char inc;
    double* value;
  };
  const double inch = modal_.metric ? 1.0 : 25.4;
  for (const Field& fd : {Field{'X', 'U', &t.x}, Field{'Z', 'W', &t.z}, Field{'Y', 'V', &t.y}}) {
    BlockWord* a = word(fd.abs);
    BlockWord* i = word(fd.inc);
    if (a != nullptr && i != nullptr) {
      return fail(alarm::kAbsoluteAndIncremental,
                  std::string(1, fd.abs) + " and " + fd.inc + " in one block", i->column);
    }
    if (a != nullptr) {
      a->used = true;
      *fd.value = scaled(*a, true) * inch;
    }
    if (i != nullptr) {
      i->used = true;
      *fd.value += scaled(*i, true) * inch;
    }
  }
  if (BlockWord* r = word('R')) {
    r->used = true;
    t.radius = scaled(*r, true) * inch;
  }
  if (BlockWord* ur = word('U', 'R')) {
    ur->used = true;
    t.radius += scaled(*ur, true) * inch;
  }
  if (BlockWord* q = word('Q')) {
    q->used = true;
    std::int64_t tip = 0;
    if (!whole_number(q->value, tip) || tip < 0 || tip > 9) {
      return fail(alarm::kBadWordValue, "G10 Q (imaginary tool tip) must be 0-9", q->column);
    }
    // One imaginary tip per offset number, read as #2301+: kept with the geometry.
    tools_.values(true, static_cast<int>(geometry ? pv - 10000 : pv)).tip = static_cast<int>(tip);
  }
  apply_tool_offset(tools_.offset);  // the active offset takes the new values at once
  return true;
}

}  // namespace mcnc::interp
