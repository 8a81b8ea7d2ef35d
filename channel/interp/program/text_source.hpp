#pragma once
// The bytes of a program file, or of a text given whole (MDI blocks, a program a test writes),
// read by range: a program is never held whole in memory, however long its file (issue 23,
// "programs stream"). LineReader reads a range line by line through a buffer of its own.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace mcnc::interp::program {

class TextSource {
 public:
  // A text held in memory.
  static std::shared_ptr<const TextSource> of_text(std::string text);
  // A file, kept open: what is read later is what the file holds then (ParsedProgram checks
  // that it is what was checked). nullptr, with `error` set, when it cannot be opened.
  static std::shared_ptr<const TextSource> open_file(const std::string& path, std::string& error);

  ~TextSource();
  TextSource(const TextSource&) = delete;
  TextSource& operator=(const TextSource&) = delete;

  // Its size when it was opened.
  [[nodiscard]] std::uint64_t size() const noexcept { return size_; }
  // `out` becomes bytes [offset, offset + length). False when they cannot all be read (the
  // file shrank, or a read failed). Safe from several threads at once.
  bool read(std::uint64_t offset, std::size_t length, std::string& out) const;

 private:
  TextSource() = default;
  std::string text_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

// One line of a text: its 1-based line number, its text without the terminator (and without
// the '\r' of CRLF), and the byte offsets of its start and of the next line's.
struct RawLine {
  int line = 0;
  std::string_view text;
  std::uint64_t offset = 0;
  std::uint64_t next = 0;
};

// The lines of bytes [begin, end) of a source in order, the first numbered `first_line`. A line
// ends at '\n'; text after the last '\n' is a line when it is not empty.
class LineReader {
 public:
  LineReader(const TextSource& source, std::uint64_t begin, std::uint64_t end, int first_line);
  // The next line; its text is valid until the next call. False at the end of the range, or
  // when the source could not be read (failed()).
  bool next(RawLine& out);
  [[nodiscard]] bool failed() const noexcept { return failed_; }

 private:
  bool fill();

  static constexpr std::size_t kBlock = std::size_t{1} << 16;
  const TextSource& source_;
  std::uint64_t read_at_;  // next source byte to read into the buffer
  std::uint64_t end_;
  std::uint64_t buffer_at_;  // source offset of buffer_[0]
  std::string buffer_;
  std::string block_;
  std::size_t pos_ = 0;  // next line's start in buffer_
  int line_;
  bool failed_ = false;
};

}  // namespace mcnc::interp::program
