#include "launch/trace_shipping.hpp"

#include <filesystem>
#include <sstream>
#include <thread>

namespace mcnc::launch {

namespace {
// A piece's text: well below what one RTPS sample carries comfortably.
constexpr std::size_t kChunkBytes = 32 * 1024;
}  // namespace

TracePartSender::TracePartSender(dds::Participant& participant, std::string host)
    : host_(std::move(host)),
      writer_(participant),
      receipts_(participant, [this](const TraceReceipt& r, const dds::WriterId&) {
        if (r.host() == host_) {
          std::lock_guard<std::mutex> lock(mutex_);
          confirmed_ = true;
          confirmed_cv_.notify_all();
        }
      }) {}

bool TracePartSender::send(const std::vector<std::string>& paths, std::chrono::seconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  // A reliable writer whose history is full of pieces not yet acknowledged refuses the next
  // one after a while: it is written again, since a lost piece would cut a part short.
  const auto write = [&](const TraceChunk& chunk) {
    while (!writer_.write(chunk)) {
      if (std::chrono::steady_clock::now() > deadline) {
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
  };
  for (const std::string& path : paths) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream all;
    all << in.rdbuf();
    const std::string text = all.str();
    const std::string part = std::filesystem::path(path).filename().string();
    std::uint32_t seq = 0;
    std::size_t at = 0;
    do {
      TraceChunk chunk;
      chunk.host(host_);
      chunk.part(part);
      chunk.seq(seq++);
      chunk.text(text.substr(at, kChunkBytes));
      if (!write(chunk)) {
        return false;
      }
      at += kChunkBytes;
    } while (at < text.size());
  }
  TraceChunk end;
  end.host(host_);
  end.seq(0);
  if (!write(end)) {
    return false;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  return confirmed_cv_.wait_until(lock, deadline, [this] { return confirmed_; });
}

TracePartReceiver::TracePartReceiver(dds::Participant& participant, std::string parts_dir)
    : parts_dir_(std::move(parts_dir)),
      receipt_writer_(participant),
      reader_(participant, [this](const TraceChunk& chunk, const dds::WriterId&) {
        std::lock_guard<std::mutex> lock(mutex_);
        if (chunk.part().empty()) {
          open_.clear();  // closes (flushes) every part written so far
          done_.insert(chunk.host());
          TraceReceipt receipt;
          receipt.host(chunk.host());
          receipt_writer_.write(receipt);
          done_cv_.notify_all();
          return;
        }
        // A part's name is a file name of the parts directory, nothing else.
        if (chunk.part().find('/') != std::string::npos || chunk.part() == "..") {
          return;
        }
        auto& out = open_[chunk.part()];
        if (chunk.seq() == 0 || !out.is_open()) {
          out.close();
          out.open(parts_dir_ + "/" + chunk.part(), chunk.seq() == 0
                                                        ? std::ios::binary | std::ios::trunc
                                                        : std::ios::binary | std::ios::app);
        }
        out << chunk.text();
      }) {}

std::vector<std::string> TracePartReceiver::wait_for(const std::vector<std::string>& hosts,
                                                     std::chrono::seconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  const auto all_done = [&] {
    for (const auto& h : hosts) {
      if (done_.count(h) == 0) {
        return false;
      }
    }
    return true;
  };
  done_cv_.wait_for(lock, timeout, all_done);
  std::vector<std::string> missing;
  for (const auto& h : hosts) {
    if (done_.count(h) == 0) {
      missing.push_back(h);
    }
  }
  return missing;
}

}  // namespace mcnc::launch
