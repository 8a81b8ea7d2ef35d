#include "channel/interp/program/text_source.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>

namespace mcnc::interp::program {

std::shared_ptr<const TextSource> TextSource::of_text(std::string text) {
  std::shared_ptr<TextSource> s(new TextSource());
  s->size_ = text.size();
  s->text_ = std::move(text);
  return s;
}

std::shared_ptr<const TextSource> TextSource::open_file(const std::string& path,
                                                        std::string& error) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
    error = fd < 0 ? std::strerror(errno) : "not a regular file";
    if (fd >= 0) {
      ::close(fd);
    }
    return nullptr;
  }
  std::shared_ptr<TextSource> s(new TextSource());
  s->fd_ = fd;
  s->size_ = static_cast<std::uint64_t>(st.st_size);
  return s;
}

TextSource::~TextSource() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

bool TextSource::read(std::uint64_t offset, std::size_t length, std::string& out) const {
  if (offset > size_ || length > size_ - offset) {
    return false;
  }
  if (fd_ < 0) {
    out.assign(text_, static_cast<std::size_t>(offset), length);
    return true;
  }
  out.resize(length);
  std::size_t done = 0;
  while (done < length) {
    const ssize_t n =
        ::pread(fd_, out.data() + done, length - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) {
      continue;
    }
    if (n <= 0) {
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  return true;
}

LineReader::LineReader(const TextSource& source, std::uint64_t begin, std::uint64_t end,
                       int first_line)
    : source_(source), read_at_(begin), end_(end), buffer_at_(begin), line_(first_line) {}

bool LineReader::fill() {
  if (read_at_ >= end_) {
    return false;
  }
  // What is left of the buffer moves to its front; the next block goes after it.
  buffer_.erase(0, pos_);
  buffer_at_ += pos_;
  pos_ = 0;
  const auto length = static_cast<std::size_t>(std::min<std::uint64_t>(kBlock, end_ - read_at_));
  if (!source_.read(read_at_, length, block_)) {
    failed_ = true;
    return false;
  }
  buffer_ += block_;
  read_at_ += length;
  return true;
}

bool LineReader::next(RawLine& out) {
  if (failed_) {
    return false;
  }
  std::size_t newline = buffer_.find('\n', pos_);
  while (newline == std::string::npos && fill()) {
    newline = buffer_.find('\n', pos_);
  }
  if (failed_) {
    return false;
  }
  std::size_t stop = newline;
  std::size_t after = newline + 1;
  if (newline == std::string::npos) {
    if (pos_ >= buffer_.size()) {
      return false;  // the range ended with its last line's terminator
    }
    stop = buffer_.size();
    after = buffer_.size();
  }
  std::string_view text(buffer_.data() + pos_, stop - pos_);
  if (!text.empty() && text.back() == '\r') {
    text.remove_suffix(1);
  }
  out.line = line_++;
  out.text = text;
  out.offset = buffer_at_ + pos_;
  out.next = buffer_at_ + after;
  pos_ = after;
  return true;
}

}  // namespace mcnc::interp::program
