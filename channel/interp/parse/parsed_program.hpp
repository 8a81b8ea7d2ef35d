#pragma once
// A program ready to run, read as a stream (issue 23, "programs stream"). Loading reads every
// line once, in order: each line is parsed (those past the window only checked, as they are
// parsed again when the run reaches them), so that a syntax error is an alarm before the
// program moves anything, and the block structure is matched (WHILE-DO m with END m, IF with
// ELIF/ELSE/ENDIF, within the nesting limits). What is kept of the whole program is what a jump
// needs: where each chunk of kChunkLines lines is in the file, which N numbers it may hold, and
// the partners of the structure lines. The parsed lines themselves are kept for a window of
// kWindowChunks chunks, and parsed again from the file when the run comes back to a chunk that
// left the window: memory is bounded by the window, not by the program.
#include "channel/interp/parse/statement.hpp"
#include "channel/interp/program/program_text.hpp"
#include "channel/interp/program_alarm.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace mcnc::interp::parse {

struct StructureLimits {
  int max_while_nesting = 5;  // spec dafeng L7133
  int max_if_nesting = 10;    // spec dafeng L7035
  int max_loop_label = 0;     // DO m: m up to this (GSK and FANUC: 3); 0 = any positive m
};

class ParsedProgram {
 public:
  static constexpr int kChunkLines = 256;
  static constexpr std::size_t kWindowChunks = 64;

  ParsedProgram();
  ~ParsedProgram();
  ParsedProgram(ParsedProgram&&) noexcept;
  ParsedProgram& operator=(ParsedProgram&&) noexcept;

  std::optional<int> number;
  std::string file;

  // Its lines, blank and comment lines included.
  [[nodiscard]] int size() const noexcept { return line_count_; }
  // Its lines that are not empty (blank, comment only, the O line).
  [[nodiscard]] std::size_t block_count() const noexcept { return block_count_; }

  // Line `index` (0-based). It stays valid until lines of kWindowChunks - 1 other chunks have
  // been asked for. nullptr when it cannot be read again because the file no longer holds what
  // was loaded: read_alarm() says so.
  const Line* line(int index) const;
  [[nodiscard]] const std::optional<ProgramAlarm>& read_alarm() const noexcept {
    return read_alarm_;
  }

  // WHILE <-> its END; IF, ELIF, ELSE -> the next branch line of the same IF (ELIF, ELSE or
  // ENDIF); -1 for any other line.
  [[nodiscard]] int partner(int index) const noexcept;
  // ELIF, ELSE: the ENDIF of their IF; -1 for any other line.
  [[nodiscard]] int endif_of(int index) const noexcept;
  // A line with BREAK or CONTINUE (after an IF too): the innermost WHILE around it; -1 when
  // none, and for any other line.
  [[nodiscard]] int loop_of(int index) const noexcept;

  // The line with N number `n` that a jump from line `from` reaches: `wrap`, the first after
  // `from`, else the first of the program; `forward`, the first after `from`; `backward`, the
  // last at or before `from`. -1 when there is none, or when a chunk could not be read again
  // (read_alarm()).
  int find_sequence(std::int64_t n, int from, GotoDirection direction) const;
  // Whether more than one line has N number `n`.
  bool sequence_repeats(std::int64_t n) const;

 private:
  friend struct ParsedProgramLoader;
  struct Chunk;
  struct ChunkInfo {
    std::uint64_t offset = 0;  // in the file
    std::uint64_t bytes = 0;
    int first_line = 0;  // the file's line number of its first line
    int lines = 0;
    std::int64_t min_n = -1;  // N numbers of its lines: the least and greatest (-1: none)
    std::int64_t max_n = -1;
    std::uint64_t n_bits = 0;  // bit n % 64 for each of them
    std::uint64_t checksum = 0;
  };
  using Pairs = std::vector<std::pair<int, int>>;  // line -> line, sorted

  // The window's slot holding chunk `k`, loading it (and evicting the least recently used) when
  // it is not there; nullptr when it cannot be read.
  const Chunk* resident(std::size_t k) const;
  // Reads and parses chunk `k` into `into`; false (read_alarm_ set) when the file no longer
  // holds what was loaded.
  bool read_chunk(std::size_t k, Chunk& into) const;
  // Chunk `k`'s lines, for a search: from the window when it is there, else parsed into a
  // scratch chunk that does not enter the window (a search does not evict the run's lines).
  const Chunk* for_search(std::size_t k) const;
  static int lookup(const Pairs& pairs, int index) noexcept;

  int line_count_ = 0;
  std::size_t block_count_ = 0;
  std::shared_ptr<const program::TextSource> text_;
  std::vector<ChunkInfo> chunks_;
  Pairs partner_;
  Pairs endif_of_;
  Pairs loop_of_;

  // The window.
  mutable std::vector<std::unique_ptr<Chunk>> slots_;
  mutable std::vector<std::uint64_t> slot_used_;     // when each slot was last asked for
  mutable std::vector<std::int32_t> slot_of_chunk_;  // per chunk: its slot, -1 when none
  mutable std::vector<std::size_t> chunk_of_slot_;
  mutable std::uint64_t uses_ = 0;
  mutable std::unique_ptr<Chunk> scratch_;
  mutable std::optional<ProgramAlarm> read_alarm_;
};

struct ParsedProgramResult {
  std::optional<ParsedProgram> program;
  std::optional<ProgramAlarm> alarm;
};

// Reads `program` from its file, line by line (program::Program: where it is).
ParsedProgramResult parse_program(const program::Program& program, StructureLimits limits = {});

}  // namespace mcnc::interp::parse
