#pragma once
// Writes this process's part of the event trace (one JSON object per line, see docs/trace.md).
// emit() formats into a preallocated slot and returns at once; a background thread writes the
// slots to the file, so the cyclic path never waits for the disk. `mcnc run` merges the parts
// of all processes into one file ordered by cycle.
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace mcnc::trace {

// Escapes `in` as the inside of a JSON string into `out` (always terminated, cut if too long).
void json_escape(std::string_view in, char* out, std::size_t out_size) noexcept;

class TraceWriter {
 public:
  // An empty path makes a writer that drops everything (tracing off).
  TraceWriter(const std::string& path, std::string src);
  ~TraceWriter();
  TraceWriter(const TraceWriter&) = delete;
  TraceWriter& operator=(const TraceWriter&) = delete;

  [[nodiscard]] bool enabled() const noexcept { return file_ != nullptr; }
  // One event: {"cycle":cycle,"src":src,"ev":ev,<fields>}. `fields_fmt` is printf-style and
  // yields the remaining members without braces, e.g. "\"ch\":\"%s\",\"state\":\"%s\"".
  void emit(std::uint64_t cycle, const char* ev, const char* fields_fmt, ...) noexcept
      __attribute__((format(printf, 4, 5)));
  // Blocks until everything emitted so far is in the file.
  void flush();
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_.load(); }

 private:
  void run();

  static constexpr std::size_t kSlotSize = 768;
  static constexpr std::size_t kSlots = 8192;
  std::string src_;
  std::FILE* file_ = nullptr;
  std::vector<char> slots_;
  std::atomic<std::uint64_t> head_{0};  // next slot to fill (producers, under mutex_)
  std::atomic<std::uint64_t> tail_{0};  // next slot to write (writer thread)
  std::atomic<std::uint64_t> dropped_{0};
  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable drained_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace mcnc::trace
