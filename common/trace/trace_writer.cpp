#include "common/trace/trace_writer.hpp"

#include <cstdarg>
#include <stdexcept>

namespace mcnc::trace {

void json_escape(const char* in, char* out, std::size_t out_size) noexcept {
  std::size_t o = 0;
  auto put = [&](char c) {
    if (o + 1 < out_size) {
      out[o++] = c;
    }
  };
  for (const char* p = in; *p != '\0' && o + 7 < out_size; ++p) {
    const auto c = static_cast<unsigned char>(*p);
    switch (c) {
      case '"': put('\\'); put('"'); break;
      case '\\': put('\\'); put('\\'); break;
      case '\n': put('\\'); put('n'); break;
      case '\r': put('\\'); put('r'); break;
      case '\t': put('\\'); put('t'); break;
      default:
        if (c < 0x20) {
          o += static_cast<std::size_t>(std::snprintf(out + o, out_size - o, "\\u%04x", c));
        } else {
          put(static_cast<char>(c));
        }
    }
  }
  out[o < out_size ? o : out_size - 1] = '\0';
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
  thread_ = std::thread([this] { run(); });
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
  int n = std::snprintf(slot, kSlotSize, "{\"cycle\":%llu,\"src\":\"%s\",\"ev\":\"%s\"",
                        static_cast<unsigned long long>(cycle), src_.c_str(), ev);
  if (fields_fmt != nullptr && fields_fmt[0] != '\0' && n > 0 &&
      static_cast<std::size_t>(n) < kSlotSize - 3) {
    slot[n++] = ',';
    va_list args;
    va_start(args, fields_fmt);
    const int m = std::vsnprintf(slot + n, kSlotSize - static_cast<std::size_t>(n) - 2, fields_fmt, args);
    va_end(args);
    n = m > 0 ? n + m : n;
  }
  if (n < 0 || static_cast<std::size_t>(n) > kSlotSize - 3) {
    dropped_.fetch_add(1);  // an event that does not fit is dropped whole, never cut
    return;
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
    std::fflush(file_);
    drained_.notify_all();
    if (stop_) {
      return;
    }
  }
}

} // namespace mcnc::trace
