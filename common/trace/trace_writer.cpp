#include "common/trace/trace_writer.hpp"

#include "common/process/thread_name.hpp"

#include <cstdarg>
#include <cstring>
#include <stdexcept>

namespace mcnc::trace {

void json_escape(std::string_view in, char* out, std::size_t out_size) noexcept {
  if (out_size == 0) {
    return;
  }
  std::size_t o = 0;
  for (const char ch : in) {
    const auto c = static_cast<unsigned char>(ch);
    char escaped[8];
    int n = 0;
    switch (c) {
      case '"':
        n = std::snprintf(escaped, sizeof escaped, "\\\"");
        break;
      case '\\':
        n = std::snprintf(escaped, sizeof escaped, "\\\\");
        break;
      case '\n':
        n = std::snprintf(escaped, sizeof escaped, "\\n");
        break;
      case '\r':
        n = std::snprintf(escaped, sizeof escaped, "\\r");
        break;
      case '\t':
        n = std::snprintf(escaped, sizeof escaped, "\\t");
        break;
      default:
        n = c < 0x20 ? std::snprintf(escaped, sizeof escaped, "\\u%04x", c)
                     : std::snprintf(escaped, sizeof escaped, "%c", c);
    }
    // Cut before a character whose escape does not fit whole (room kept for the terminator).
    if (o + static_cast<std::size_t>(n) >= out_size) {
      break;
    }
    std::memcpy(out + o, escaped, static_cast<std::size_t>(n));
    o += static_cast<std::size_t>(n);
  }
  out[o] = '\0';
}

TraceWriter::TraceWriter(const std::string& path, std::string src) : src_(std::move(src)) {
  if (path.empty()) {
    return;
  }
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) {
    throw std::runtime_error("cannot write trace file " + path);
  }
  slots_.resize(kSlotSize * kSlots);
  thread_ = std::thread([this] {
    process::name_this_thread("trace");
    run();
  });
}

TraceWriter::~TraceWriter() {
  if (file_ == nullptr) {
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_one();
  thread_.join();
  std::fclose(file_);
}

void TraceWriter::emit(std::uint64_t cycle, const char* ev, const char* fields_fmt, ...) noexcept {
  if (file_ == nullptr) {
    return;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  const std::uint64_t head = head_.load();
  if (head - tail_.load() >= kSlots) {
    dropped_.fetch_add(1);
    return;
  }
  char* slot = &slots_[(head % kSlots) * kSlotSize];
  // An event that does not fit whole is dropped whole and counted, never written cut.
  constexpr std::size_t kRoom = kSlotSize - 3;  // the line without "}\n" and the terminator
  int n = std::snprintf(slot, kSlotSize, "{\"cycle\":%llu,\"src\":\"%s\",\"ev\":\"%s\"",
                        static_cast<unsigned long long>(cycle), src_.c_str(), ev);
  if (n < 0 || static_cast<std::size_t>(n) > kRoom) {
    dropped_.fetch_add(1);
    return;
  }
  if (fields_fmt != nullptr && fields_fmt[0] != '\0') {
    va_list args;
    va_start(args, fields_fmt);
    const int m =
        std::vsnprintf(slot + n + 1, kRoom - static_cast<std::size_t>(n), fields_fmt, args);
    va_end(args);
    if (m < 0 || static_cast<std::size_t>(n) + 1 + static_cast<std::size_t>(m) > kRoom) {
      dropped_.fetch_add(1);
      return;
    }
    if (m > 0) {  // fields that format to nothing add no comma
      slot[n] = ',';
      n += 1 + m;
    }
  }
  slot[n++] = '}';
  slot[n++] = '\n';
  slot[n] = '\0';
  head_.store(head + 1);
  lock.unlock();
  wake_.notify_one();
}

void TraceWriter::flush() {
  if (file_ == nullptr) {
    return;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.notify_one();
  drained_.wait(lock, [this] { return tail_.load() == head_.load(); });
}

void TraceWriter::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stop_ || tail_.load() != head_.load(); });
    while (tail_.load() != head_.load()) {
      const std::uint64_t tail = tail_.load();
      const char* slot = &slots_[(tail % kSlots) * kSlotSize];
      lock.unlock();  // the slot is ours until tail moves; producers never touch it
      std::fputs(slot, file_);
      lock.lock();
      tail_.store(tail + 1);
    }
    lock.unlock();  // producers never wait for the disk
    std::fflush(file_);
    lock.lock();
    drained_.notify_all();
    if (stop_ && tail_.load() == head_.load()) {
      return;  // only once drained: events may have come in while the disk was flushed
    }
  }
}

}  // namespace mcnc::trace
