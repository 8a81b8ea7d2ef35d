#include "launch/machine_clock.hpp"

#include "common/clock/cycle_clock.hpp"
#include "common/process/thread_name.hpp"

namespace mcnc::launch {

MachineClockReference::MachineClockReference(dds::Participant& participant, const std::string& host)
    : echo_writer_(participant),
      clock_writer_(participant),
      probe_reader_(participant, [this](const ClockProbe& probe, const dds::WriterId&) {
        const std::int64_t received = clock::monotonic_ns();
        ClockEcho echo;
        echo.host(probe.host());
        echo.seq(probe.seq());
        echo.t1_ns(probe.t1_ns());
        echo.t2_ns(received);
        echo.t3_ns(clock::monotonic_ns());
        echo_writer_.write(echo);
      }) {
  HostClock own;
  own.host(host);
  own.offset_ns(0);
  own.error_ns(0);
  own.samples(0);
  clock_writer_.write(own);
}

HostClockEstimator::HostClockEstimator(dds::Participant& participant, std::string host)
    : host_(std::move(host)),
      probe_writer_(participant),
      clock_writer_(participant),
      echo_reader_(participant, [this](const ClockEcho& echo, const dds::WriterId&) {
        const std::int64_t received = clock::monotonic_ns();
        std::optional<HostClock> announce;
        {
          std::lock_guard<std::mutex> lock(mutex_);
          if (echo.host() != host_ || echo.seq() != seq_ || echo.t1_ns() != sent_ns_) {
            return;  // another host's, or an answer that came after its probe's successor
          }
          filter_.add({echo.t1_ns(), echo.t2_ns(), echo.t3_ns(), received});
          const auto estimate = filter_.estimate();
          if (estimate && (!announced_ || announced_->offset_ns != estimate->offset_ns ||
                           announced_->error_ns != estimate->error_ns)) {
            announced_ = estimate;
            HostClock hc;
            hc.host(host_);
            hc.offset_ns(estimate->offset_ns);
            hc.error_ns(estimate->error_ns);
            hc.samples(estimate->samples);
            announce = hc;
          }
        }
        if (announce) {
          clock_writer_.write(*announce);
        }
      }) {
  thread_ = std::thread([this] {
    process::name_this_thread("clock");
    probe_until_stopped();
  });
}

HostClockEstimator::~HostClockEstimator() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  stop_cv_.notify_all();
  thread_.join();
}

std::optional<clock::ClockOffset> HostClockEstimator::estimate() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return filter_.estimate();
}

void HostClockEstimator::probe_until_stopped() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    ClockProbe probe;
    probe.host(host_);
    probe.seq(++seq_);
    sent_ns_ = clock::monotonic_ns();
    probe.t1_ns(sent_ns_);
    lock.unlock();
    probe_writer_.write(probe);
    lock.lock();
    stop_cv_.wait_for(lock, kProbePeriod, [this] { return stop_; });
  }
}

HostClocks::HostClocks(dds::Participant& participant)
    : reader_(participant, [this](const HostClock& hc, const dds::WriterId&) {
        std::lock_guard<std::mutex> lock(mutex_);
        latest_[hc.host()] = hc;
      }) {}

std::optional<HostClock> HostClocks::of(const std::string& host) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = latest_.find(host);
  if (it == latest_.end()) {
    return std::nullopt;
  }
  return it->second;
}

}  // namespace mcnc::launch
