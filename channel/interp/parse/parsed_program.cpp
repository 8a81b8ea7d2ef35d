#include "channel/interp/parse/parsed_program.hpp"

#include "channel/interp/parse/line_parser.hpp"
#include "channel/interp/program/program_format_alarms.hpp"
#include "channel/interp/program_alarms.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <string>

namespace mcnc::interp::parse {

// kChunkLines lines parsed, with their text: `text` holds each line followed by '\n', and each
// Line's `text` is a view into it.
struct ParsedProgram::Chunk {
  std::string text;
  Arena arena;
  std::vector<Line> lines;
  std::vector<std::size_t> lengths;  // of each line's text, while the chunk is filled

  void clear() {
    text.clear();
    arena.words.clear();
    arena.expressions.clear();
    arena.messages.clear();
    lines.clear();
    lengths.clear();
  }
  // The lines' views into `text` and `arena`: set once every line is in (`text` grows while
  // it is filled).
  void seal() {
    std::size_t at = 0;
    for (std::size_t j = 0; j < lines.size(); ++j) {
      lines[j].text = std::string_view(text).substr(at, lengths[j]);
      lines[j].arena = &arena;
      at += lengths[j] + 1;
    }
  }
};

namespace {

constexpr std::uint64_t kFnvOffset = 14695981039346656037ULL;
constexpr std::uint64_t kFnvPrime = 1099511628211ULL;

// FNV-1a over the line eight bytes at a time (then its last bytes one by one): each step is a
// bijection of the hash for a given word, so a chunk whose one word changed never checks the
// same, and a line costs a few steps rather than one per byte.
std::uint64_t checksum_line(std::uint64_t h, std::string_view text) {
  std::size_t i = 0;
  for (; i + sizeof(std::uint64_t) <= text.size(); i += sizeof(std::uint64_t)) {
    std::uint64_t word = 0;
    std::memcpy(&word, text.data() + i, sizeof word);
    h = (h ^ word) * kFnvPrime;
  }
  for (; i < text.size(); ++i) {
    h = (h ^ static_cast<unsigned char>(text[i])) * kFnvPrime;
  }
  return (h ^ static_cast<unsigned char>('\n')) * kFnvPrime;
}

// The block structure, matched line by line: WHILE-DO m with END m, IF with ELIF/ELSE/ENDIF.
class StructureMatch {
 public:
  StructureMatch(StructureLimits limits, const std::string& file) : limits_(limits), file_(file) {}

  // Line `index` of the program; its first structure error.
  std::optional<ProgramAlarm> feed(int index, const Line& line) {
    const Statement& s = line.statement;
    if (leaves_loop(s)) {
      for (auto it = open_.rbegin(); it != open_.rend(); ++it) {
        if (it->kind == StatementKind::while_do) {
          loop_of.emplace_back(index, it->index);
          break;
        }
      }
    }
    switch (s.kind) {
      case StatementKind::while_do:
        if (++whiles_ > limits_.max_while_nesting) {
          return alarm(
              line, alarm::kNestingTooDeep,
              "WHILE loops nested deeper than " + std::to_string(limits_.max_while_nesting));
        }
        for (const Open& o : open_) {
          if (o.kind == StatementKind::while_do && o.label == s.label) {
            return alarm(
                line, alarm::kStructureMismatch,
                "WHILE ... DO" + std::to_string(s.label) + " inside a loop with the same label");
          }
        }
        if (limits_.max_loop_label > 0 && s.label > limits_.max_loop_label) {
          return alarm(line, alarm::kBadWordValue,
                       "DO" + std::to_string(s.label) + ": loop labels are 1-" +
                           std::to_string(limits_.max_loop_label));
        }
        open_.push_back(Open{index, line.line, s.column, StatementKind::while_do, s.label, {}});
        return std::nullopt;
      case StatementKind::loop_end: {
        if (open_.empty() || open_.back().kind != StatementKind::while_do ||
            open_.back().label != s.label) {
          const bool in_if = !open_.empty() && open_.back().kind == StatementKind::if_block;
          return alarm(line, alarm::kStructureMismatch,
                       "END" + std::to_string(s.label) +
                           (in_if ? " inside an IF block that is not closed"
                                  : " without a matching WHILE ... DO" + std::to_string(s.label)));
        }
        partner.emplace_back(open_.back().index, index);
        partner.emplace_back(index, open_.back().index);
        open_.pop_back();
        --whiles_;
        return std::nullopt;
      }
      case StatementKind::if_block:
        if (++ifs_ > limits_.max_if_nesting) {
          return alarm(line, alarm::kNestingTooDeep,
                       "IF blocks nested deeper than " + std::to_string(limits_.max_if_nesting));
        }
        open_.push_back(Open{index, line.line, s.column, StatementKind::if_block, 0, {}});
        return std::nullopt;
      case StatementKind::elif:
      case StatementKind::else_branch: {
        const char* name = s.kind == StatementKind::elif ? "ELIF" : "ELSE";
        if (open_.empty() || open_.back().kind != StatementKind::if_block) {
          return alarm(line, alarm::kStructureMismatch,
                       std::string(name) + " without an open IF block");
        }
        Open& o = open_.back();
        if (o.seen_else) {
          return alarm(line, alarm::kStructureMismatch, std::string(name) + " after ELSE");
        }
        partner.emplace_back(o.branches.empty() ? o.index : o.branches.back(), index);
        o.branches.push_back(index);
        o.seen_else = s.kind == StatementKind::else_branch;
        return std::nullopt;
      }
      case StatementKind::endif: {
        if (open_.empty() || open_.back().kind != StatementKind::if_block) {
          return alarm(line, alarm::kStructureMismatch, "ENDIF without an open IF block");
        }
        const Open& o = open_.back();
        partner.emplace_back(o.branches.empty() ? o.index : o.branches.back(), index);
        // Every ELIF/ELSE of this IF jumps to this ENDIF when reached in sequence.
        for (const int b : o.branches) {
          endif_of.emplace_back(b, index);
        }
        open_.pop_back();
        --ifs_;
        return std::nullopt;
      }
      default:
        return std::nullopt;
    }
  }

  // After the last line: a structure left open.
  std::optional<ProgramAlarm> finish() {
    if (open_.empty()) {
      return std::nullopt;
    }
    const Open& o = open_.back();
    return ProgramAlarm{
        alarm::kStructureMismatch,
        o.kind == StatementKind::while_do
            ? "WHILE ... DO" + std::to_string(o.label) + " without END" + std::to_string(o.label)
            : std::string("IF block without ENDIF"),
        file_, o.line, o.column};
  }

  std::vector<std::pair<int, int>> partner;
  std::vector<std::pair<int, int>> endif_of;
  std::vector<std::pair<int, int>> loop_of;

 private:
  struct Open {
    int index = 0;  // line index in the program
    int line = 0;   // in the file
    int column = 0;
    StatementKind kind = StatementKind::empty;
    int label = 0;
    std::vector<int> branches;  // IF: its ELIF and ELSE lines so far
    bool seen_else = false;
  };

  // BREAK or CONTINUE, alone or after an IF.
  static bool leaves_loop(const Statement& s) {
    return s.kind == StatementKind::loop_break || s.kind == StatementKind::loop_continue ||
           (s.then != nullptr && leaves_loop(*s.then));
  }

  ProgramAlarm alarm(const Line& line, int number, std::string text) const {
    return ProgramAlarm{number, std::move(text), file_, line.line, line.statement.column};
  }

  StructureLimits limits_;
  const std::string& file_;
  std::vector<Open> open_;
  int whiles_ = 0;
  int ifs_ = 0;
};

}  // namespace

// Fills chunks line by line, the same way when a program is loaded and when a chunk is read
// again.
struct ParsedProgramLoader {
  // Adds line `raw` to `chunk`; its parse error, if any.
  static std::optional<ParseError> add(ParsedProgram::Chunk& chunk, const program::RawLine& raw,
                                       std::uint64_t& checksum) {
    Line& line = chunk.lines.emplace_back();
    if (std::optional<ParseError> error = parse_line_into(raw.text, raw.line, chunk.arena, line)) {
      chunk.lines.pop_back();
      return error;
    }
    chunk.text.append(raw.text);
    chunk.text.push_back('\n');
    chunk.lengths.push_back(raw.text.size());
    checksum = checksum_line(checksum, raw.text);
    return std::nullopt;
  }
  // Checks line `raw`, which the window does not keep, into `line`: its syntax error, if any.
  static std::optional<ParseError> check(const program::RawLine& raw, std::uint64_t& checksum,
                                         Line& line) {
    line = Line{};
    if (std::optional<ParseError> error = check_line_into(raw.text, raw.line, line)) {
      return error;
    }
    checksum = checksum_line(checksum, raw.text);
    return std::nullopt;
  }
  // parse_program().
  static ParsedProgramResult load(const program::Program& program, StructureLimits limits);
};

ParsedProgram::ParsedProgram() = default;
ParsedProgram::~ParsedProgram() = default;
ParsedProgram::ParsedProgram(ParsedProgram&&) noexcept = default;
ParsedProgram& ParsedProgram::operator=(ParsedProgram&&) noexcept = default;

int ParsedProgram::lookup(const Pairs& pairs, int index) noexcept {
  const auto it = std::lower_bound(pairs.begin(), pairs.end(), std::pair<int, int>{index, -1});
  return it != pairs.end() && it->first == index ? it->second : -1;
}

int ParsedProgram::partner(int index) const noexcept {
  return lookup(partner_, index);
}

int ParsedProgram::endif_of(int index) const noexcept {
  return lookup(endif_of_, index);
}

int ParsedProgram::loop_of(int index) const noexcept {
  return lookup(loop_of_, index);
}

bool ParsedProgram::read_chunk(std::size_t k, Chunk& into) const {
  const ChunkInfo& info = chunks_[k];
  into.clear();
  program::LineReader reader(*text_, info.offset, info.offset + info.bytes, info.first_line);
  program::RawLine raw;
  std::uint64_t checksum = kFnvOffset;
  bool parsed = true;
  while (parsed && reader.next(raw)) {
    parsed = !ParsedProgramLoader::add(into, raw, checksum);
  }
  if (!parsed || reader.failed() || static_cast<int>(into.lines.size()) != info.lines ||
      checksum != info.checksum) {
    into.clear();
    read_alarm_ = ProgramAlarm{program::alarm::kFileChanged,
                               "program file " + file + " changed while it runs (lines " +
                                   std::to_string(info.first_line) + "-" +
                                   std::to_string(info.first_line + info.lines - 1) + ")",
                               file, info.first_line, 0};
    return false;
  }
  into.seal();
  return true;
}

const ParsedProgram::Chunk* ParsedProgram::resident(std::size_t k) const {
  const std::int32_t at = slot_of_chunk_[k];
  if (at >= 0) {
    slot_used_[static_cast<std::size_t>(at)] = ++uses_;
    return slots_[static_cast<std::size_t>(at)].get();
  }
  std::size_t slot = slots_.size();
  if (slots_.size() < kWindowChunks) {
    slots_.push_back(std::make_unique<Chunk>());
    slot_used_.push_back(0);
    chunk_of_slot_.push_back(chunks_.size());
  } else {
    slot = static_cast<std::size_t>(std::min_element(slot_used_.begin(), slot_used_.end()) -
                                    slot_used_.begin());
    if (chunk_of_slot_[slot] < chunks_.size()) {
      slot_of_chunk_[chunk_of_slot_[slot]] = -1;
    }
  }
  chunk_of_slot_[slot] = chunks_.size();  // free until read
  slot_used_[slot] = ++uses_;
  if (!read_chunk(k, *slots_[slot])) {
    slot_used_[slot] = 0;
    return nullptr;
  }
  chunk_of_slot_[slot] = k;
  slot_of_chunk_[k] = static_cast<std::int32_t>(slot);
  return slots_[slot].get();
}

const ParsedProgram::Chunk* ParsedProgram::for_search(std::size_t k) const {
  const std::int32_t at = slot_of_chunk_[k];
  if (at >= 0) {
    return slots_[static_cast<std::size_t>(at)].get();
  }
  if (!scratch_) {
    scratch_ = std::make_unique<Chunk>();
  }
  return read_chunk(k, *scratch_) ? scratch_.get() : nullptr;
}

const Line* ParsedProgram::line(int index) const {
  if (index < 0 || index >= line_count_) {
    return nullptr;
  }
  const Chunk* chunk = resident(static_cast<std::size_t>(index / kChunkLines));
  return chunk == nullptr ? nullptr : &chunk->lines[static_cast<std::size_t>(index % kChunkLines)];
}

int ParsedProgram::find_sequence(std::int64_t n, int from, GotoDirection direction) const {
  const auto may_hold = [&](const ChunkInfo& c) {
    return c.min_n >= 0 && c.min_n <= n && n <= c.max_n &&
           ((c.n_bits >> (static_cast<std::uint64_t>(n) % 64)) & 1U) != 0;
  };
  // The first line with N`n` in lines [begin, end), in order; -1 when none (or unreadable).
  const auto first_in = [&](int begin, int end) {
    for (int k = std::max(begin, 0) / kChunkLines;
         k * kChunkLines < end && k < static_cast<int>(chunks_.size()); ++k) {
      if (!may_hold(chunks_[static_cast<std::size_t>(k)])) {
        continue;
      }
      const Chunk* c = for_search(static_cast<std::size_t>(k));
      if (c == nullptr) {
        return -1;
      }
      for (int j = 0; j < static_cast<int>(c->lines.size()); ++j) {
        const int index = k * kChunkLines + j;
        if (index >= begin && index < end && c->lines[static_cast<std::size_t>(j)].sequence == n) {
          return index;
        }
      }
    }
    return -1;
  };
  switch (direction) {
    case GotoDirection::wrap: {
      const int after = first_in(from + 1, line_count_);
      return after >= 0 || read_alarm_ ? after : first_in(0, from + 1);
    }
    case GotoDirection::forward:
      return first_in(from + 1, line_count_);
    case GotoDirection::backward:
      for (int k = std::min(from, line_count_ - 1) / kChunkLines; k >= 0 && from >= 0; --k) {
        if (!may_hold(chunks_[static_cast<std::size_t>(k)])) {
          continue;
        }
        const Chunk* c = for_search(static_cast<std::size_t>(k));
        if (c == nullptr) {
          return -1;
        }
        for (int j = static_cast<int>(c->lines.size()) - 1; j >= 0; --j) {
          const int index = k * kChunkLines + j;
          if (index <= from && c->lines[static_cast<std::size_t>(j)].sequence == n) {
            return index;
          }
        }
      }
      return -1;
  }
  return -1;
}

bool ParsedProgram::sequence_repeats(std::int64_t n) const {
  const int first = find_sequence(n, -1, GotoDirection::forward);
  return first >= 0 && find_sequence(n, first, GotoDirection::forward) >= 0;
}

ParsedProgramResult ParsedProgramLoader::load(const program::Program& program,
                                              StructureLimits limits) {
  ParsedProgramResult out;
  ParsedProgram p;
  p.number = program.number;
  p.file = program.file;
  p.text_ = program.text;
  StructureMatch match(limits, program.file);
  std::optional<ProgramAlarm> structure;  // reported when no line has a syntax error
  program::LineReader reader(*program.text, program.begin, program.end, program.first_line);
  program::RawLine raw;
  // The chunks past the window are checked, not kept: they are parsed again when the run
  // reaches them, so the load builds nothing of their lines.
  ParsedProgram::Chunk beyond_window;
  Line checked;
  ParsedProgram::Chunk* chunk = nullptr;
  ParsedProgram::ChunkInfo info;
  const auto close_chunk = [&] {
    if (chunk == nullptr) {
      return;
    }
    if (chunk == &beyond_window) {
      p.slot_of_chunk_.push_back(-1);
    } else {
      chunk->seal();
      p.slot_of_chunk_.push_back(static_cast<std::int32_t>(p.slots_.size() - 1));
      p.chunk_of_slot_.push_back(p.chunks_.size());
      p.slot_used_.push_back(++p.uses_);
    }
    p.chunks_.push_back(info);
    chunk = nullptr;
  };
  int index = 0;
  while (reader.next(raw)) {
    if (chunk == nullptr) {
      info = ParsedProgram::ChunkInfo{raw.offset, 0, raw.line, 0, -1, -1, 0, kFnvOffset};
      if (p.slots_.size() < ParsedProgram::kWindowChunks) {
        p.slots_.push_back(std::make_unique<ParsedProgram::Chunk>());
        chunk = p.slots_.back().get();
      } else {
        chunk = &beyond_window;
      }
    }
    const bool kept = chunk != &beyond_window;
    if (auto error = kept ? ParsedProgramLoader::add(*chunk, raw, info.checksum)
                          : ParsedProgramLoader::check(raw, info.checksum, checked)) {
      out.alarm = ProgramAlarm{error->number, error->text, program.file, raw.line, error->column};
      return out;
    }
    const Line& line = kept ? chunk->lines.back() : checked;
    if (line.sequence >= 0) {
      info.min_n = info.min_n < 0 ? line.sequence : std::min(info.min_n, line.sequence);
      info.max_n = std::max(info.max_n, line.sequence);
      info.n_bits |= std::uint64_t{1} << (static_cast<std::uint64_t>(line.sequence) % 64);
    }
    p.block_count_ += line.statement.kind != StatementKind::empty ? 1 : 0;
    if (!structure) {
      structure = match.feed(index, line);
    }
    info.bytes = raw.next - info.offset;
    ++info.lines;
    ++index;
    if (info.lines == ParsedProgram::kChunkLines) {
      close_chunk();
    }
  }
  close_chunk();
  if (reader.failed()) {
    out.alarm = ProgramAlarm{program::alarm::kFileUnreadable,
                             "cannot read program file " + program.file, program.file, 0, 0};
    return out;
  }
  if (!structure) {
    structure = match.finish();
  }
  if (structure) {
    out.alarm = std::move(structure);
    return out;
  }
  p.line_count_ = index;
  p.partner_ = std::move(match.partner);
  p.endif_of_ = std::move(match.endif_of);
  p.loop_of_ = std::move(match.loop_of);
  std::sort(p.partner_.begin(), p.partner_.end());
  std::sort(p.endif_of_.begin(), p.endif_of_.end());
  std::sort(p.loop_of_.begin(), p.loop_of_.end());
  out.program = std::move(p);
  return out;
}

ParsedProgramResult parse_program(const program::Program& program, StructureLimits limits) {
  return ParsedProgramLoader::load(program, limits);
}

}  // namespace mcnc::interp::parse
