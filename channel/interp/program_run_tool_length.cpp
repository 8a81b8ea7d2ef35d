// The mill's tool words (gsk B.1, B.3): T selects a tool (M06 changes it, the PLC's), H the
// length offset of G43/G44 and D the radius offset of G41/G42. Both offsets come from the
// one tool offset table the lathe's T uses (G10, #2001+): H its Z length, D its radius.
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

#include <cmath>

namespace mcnc::interp {

namespace {

// An offset number 0-64 (0: none); false when `w` holds something else.
bool offset_number(const BlockWord& w, int& n) {
  if (w.value < 0.0 || w.value > kMaxToolOffsets || w.value != std::floor(w.value)) {
    return false;
  }
  n = static_cast<int>(w.value);
  return true;
}

}  // namespace

int ProgramRun::radius_offset() const {
  return config_.dialect == Dialect::fanuc_mill ? tools_.radius_offset : tools_.offset;
}

bool ProgramRun::run_length_compensation(GFunction f, double value) {
  tools_.length_sign = f == GFunction::length_plus ? 1 : f == GFunction::length_minus ? -1 : 0;
  modal_.codes[8] = value;
  apply_tool_offset(tools_.offset);  // the frame follows the new offset; nothing moves yet
  return true;
}

bool ProgramRun::run_mill_tool_words() {
  if (BlockWord* t = word('T')) {
    t->used = true;
    if (t->value < 0.0 || t->value > config_.max_tool || t->value != std::floor(t->value)) {
      return fail(alarm::kBadWordValue,
                  "T needs a tool number 0-" + std::to_string(config_.max_tool), t->column);
    }
    // The tool to change to with M06; the offsets are H's and D's.
    tools_.tool = static_cast<int>(t->value);
    tools_.t_value = t->value;
    Command& c = emit(Op::tool);
    c.tool = tools_.tool;
    c.offset = 0;
  }
  // H and D: an offset number of the table; the number is kept when the word is valid.
  const auto offset_word = [&](char letter, const char* what, int& number) {
    BlockWord* w = word(letter);
    if (w == nullptr) {
      return true;
    }
    w->used = true;
    if (!offset_number(*w, number)) {
      return fail(alarm::kBadWordValue,
                  std::string(1, letter) + " needs a " + what + " offset number 0-" +
                      std::to_string(kMaxToolOffsets),
                  w->column);
    }
    return true;
  };
  const int length_before = tools_.length_offset;
  if (!offset_word('H', "tool length", tools_.length_offset) ||
      !offset_word('D', "cutter radius", tools_.radius_offset)) {
    return false;
  }
  if (tools_.length_offset != length_before) {
    // Like the lathe's T offset: the position shown changes at once, the next move of Z goes
    // to the compensated position (G43 H alone does not move).
    apply_tool_offset(tools_.offset);
  }
  return true;
}

}  // namespace mcnc::interp
