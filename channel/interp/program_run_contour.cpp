// The finishing contour N(P)..N(Q) of G70-G73 (spec dafeng §2.5 L1421-1708, gsk A.6.30): G70
// runs its blocks, G71-G73 read their geometry. The blocks run inline, inside the cycle block:
// nothing in the contour may call, return, end the program or stop the read-ahead.
#include "channel/interp/program_alarms.hpp"
#include "channel/interp/program_run.hpp"

namespace mcnc::interp {

namespace {

// A bound on the blocks one contour may run (loops in it included).
constexpr int kContourStepLimit = 100000;

}  // namespace

ProgramRun::BlockContext ProgramRun::save_block() const {
  return BlockContext{line_,
                      file_,
                      words_,
                      block_out_start_,
                      block_barrier_,
                      block_moved_,
                      block_exact_stop_,
                      block_motion_code_};
}

void ProgramRun::restore_block(BlockContext&& b) {
  line_ = b.line;
  file_ = b.file;
  words_ = std::move(b.words);
  index_words();
  block_out_start_ = b.out_start;
  block_barrier_ = b.barrier;
  block_moved_ = b.moved;
  block_exact_stop_ = b.exact_stop;
  block_motion_code_ = b.motion_code;
}

bool ProgramRun::contour_forbids(const char* what, int column) {
  return fail(alarm::kContourForbidden,
              std::string(what) + " is not allowed inside the contour of G70-G73", column);
}

bool ProgramRun::find_contour(const char* code, int& first, int& last, int column) {
  BlockWord* p = word('P');
  BlockWord* q = word('Q');
  if (p == nullptr || q == nullptr) {
    return fail(alarm::kContourMissing,
                std::string(code) +
                    " needs P and Q, the sequence numbers of the contour's first "
                    "and last block",
                column);
  }
  p->used = true;
  q->used = true;
  const Frame& f = frames_.back();
  const parse::ParsedProgram& program = *f.program;
  const auto n_p = static_cast<std::int64_t>(p->value);
  const auto n_q = static_cast<std::int64_t>(q->value);
  if (p->value != static_cast<double>(n_p) || q->value != static_cast<double>(n_q) || n_p < 0 ||
      n_q < 0) {
    return fail(alarm::kContourMissing, "P and Q must be sequence numbers", p->column);
  }
  // The contour normally follows the cycle block; G70 may also name one before it or after M30
  // (spec L1456-1473): the first N(P) after this block, else from the program's start.
  first = find_sequence(program, n_p, f.pc - 1, parse::GotoDirection::wrap, p->column);
  if (first < 0) {
    return false;
  }
  last = find_sequence(program, n_q, first - 1, parse::GotoDirection::forward, q->column);
  if (last < 0) {
    return false;
  }
  if (program.sequence_repeats(n_p)) {
    return fail(alarm::kContourMissing,
                "N" + std::to_string(n_p) +
                    " appears more than once in this program (gsk A.6.30 "
                    "rule 6)",
                p->column);
  }
  if (last - first + 1 > 100 * 8) {
    // The block count is checked on the motions; this only bounds absurd ranges early.
    return fail(alarm::kContourTooLong, "the contour N(P)..N(Q) is too long", q->column);
  }
  return true;
}

bool ProgramRun::run_contour(int first, int last, ContourMode mode, int column) {
  const std::size_t depth = frames_.size();
  const int resume = frames_.back().pc;
  BlockContext saved = save_block();
  const ContourMode outer = contour_.mode;
  if (outer != ContourMode::none) {
    return contour_forbids("a G70-G73 cycle", column);
  }
  contour_.begin(mode);
  frames_.back().pc = first;
  bool ok = true;
  for (int steps = 0; ok && !alarm_; ++steps) {
    const int pc = frames_.back().pc;
    if (pc > last) {
      break;
    }
    if (pc < first) {
      ok = contour_forbids("a jump out of the contour", 0);
      break;
    }
    if (steps > kContourStepLimit) {
      ok = fail(alarm::kStatementLimit, "the contour does not end: a loop inside N(P)..N(Q)?", 0);
      break;
    }
    block_barrier_ = false;
    const std::size_t before = out_.size();
    step();
    if (frames_.size() != depth) {
      ok = contour_forbids("a subprogram or macro call", 0);
      break;
    }
    bool barrier = block_barrier_;
    for (std::size_t k = before; k < out_.size(); ++k) {
      barrier = barrier || out_[k].barrier;
    }
    if (ended_) {
      ok = contour_forbids("the program end", 0);
      break;
    }
    if (barrier) {
      // The read-ahead would run past the stop: the cycle's blocks run as one.
      ok = contour_forbids("a block that stops the read-ahead (G04.1, M00, G53 ...)", 0);
      break;
    }
  }
  contour_.mode = outer;
  if (alarm_) {
    return false;
  }
  frames_.back().pc = resume;
  restore_block(std::move(saved));
  return ok;
}

bool ProgramRun::run_finishing_cycle(int column) {
  int first = 0;
  int last = 0;
  if (!find_contour("G70", first, last, column)) {
    return false;
  }
  std::int64_t repeat = 1;
  if (!repeat_word(repeat)) {
    return false;
  }
  std::array<int, 2> axes{};
  if (!require_plane_axes(axes, column)) {
    return false;
  }
  const AxisVector start = machine_;
  for (std::int64_t i = 0; i < repeat; ++i) {
    if (!run_contour(first, last, ContourMode::finish, column)) {
      return false;
    }
    // Back to the start point at rapid (FANUC; the spec does not say, L1421-1479).
    AxisVector back = machine_;
    back[static_cast<std::size_t>(axes[0])] = start[static_cast<std::size_t>(axes[0])];
    back[static_cast<std::size_t>(axes[1])] = start[static_cast<std::size_t>(axes[1])];
    emit(Op::rapid).to = back;
    machine_ = back;
  }
  block_moved_ = true;
  return true;
}

bool ProgramRun::capture_contour(const char* code, const std::array<int, 2>& axes,
                                 path::PlanePath& contour, bool& type2, int column) {
  int first = 0;
  int last = 0;
  if (!find_contour(code, first, last, column)) {
    return false;
  }
  contour_.first = first;
  contour_.last = last;
  const AxisVector start = machine_;
  const GFunction motion = modal_.motion;
  const double motion_code = modal_.codes[1];
  const std::size_t from = out_.size();
  if (!run_contour(first, last, ContourMode::capture, column)) {
    return false;
  }
  type2 = contour_.type2();
  const auto a = static_cast<std::size_t>(axes[0]);
  const auto b = static_cast<std::size_t>(axes[1]);
  contour.clear();
  contour_.lines.clear();
  // Nose compensation of the contour (spec L3743: active in G70-G73): the side, radius and tip
  // in effect at the cycle, or of the first compensated contour block.
  Command::Compensation side = compensation_;
  double radius = 0.0;
  int tip = 0;
  if (tools_.offset > 0) {
    radius = tools_.radius(tools_.offset);
    tip = tools_.tip(tools_.offset);
  }
  for (std::size_t k = from; k < out_.size() && side == Command::Compensation::off; ++k) {
    side = out_[k].compensation;
    radius = out_[k].nose_radius;
    tip = out_[k].nose_tip;
  }
  for (std::size_t k = from; k < out_.size(); ++k) {
    const Command& c = out_[k];
    path::PlaneMove m;
    switch (c.op) {
      case Op::rapid:
        m.kind = path::MoveKind::rapid;
        break;
      case Op::linear:
        m.kind = path::MoveKind::feed;
        break;
      case Op::arc:
        m.kind = path::MoveKind::arc;
        m.ccw = c.direction == ArcDirection::ccw;
        m.center = {c.center[0], c.center[1]};
        if (c.plane != modal_.plane) {
          return fail(alarm::kContourStart, "an arc of another plane in the contour", column);
        }
        break;
      case Op::thread:
        return contour_forbids("threading", column);
      default:
        continue;  // dwells and the like do not shape the contour
    }
    m.to = {c.to[a], c.to[b]};
    m.feed = c.feed;
    m.source = static_cast<int>(contour.size());
    contour.push_back(m);
    contour_.lines.push_back(c.line);
  }
  out_.resize(from);
  machine_ = start;
  modal_.motion = motion;
  modal_.codes[1] = motion_code;
  if (contour.empty()) {
    return fail(alarm::kContourMissing, std::string(code) + " contour N(P)..N(Q) has no motion",
                column);
  }
  // GSK: G71-G73 cancel the compensation (gsk A.6.22 rule 6); Dafeng roughs the compensated
  // contour, so the passes and the semi-finishing pass keep the nose radius off the part.
  if (side == Command::Compensation::off || radius <= 0.0 || config_.dialect == Dialect::gsk) {
    return true;
  }
  path::NoseCompensation nose;
  nose.start({machine_[a], machine_[b]},
             side == Command::Compensation::left ? path::CompensationSide::left
                                                 : path::CompensationSide::right,
             radius, tip);
  path::PlanePath compensated;
  for (const path::PlaneMove& m : contour) {
    if (const path::PathResult e = nose.push(m, compensated)) {
      return fail_path(*e, column);
    }
  }
  if (const path::PathResult e = nose.cancel(nullptr, compensated)) {
    return fail_path(*e, column);
  }
  // The first move stays the approach to B, with the first block's speed type.
  if (!compensated.empty()) {
    compensated.front().kind = contour.front().kind;
  }
  contour = std::move(compensated);
  return true;
}

}  // namespace mcnc::interp
