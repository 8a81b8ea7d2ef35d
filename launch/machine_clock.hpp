#pragma once
// The machine clock across hosts (docs/multichannel.md "One machine clock", decision 47).
// Machine time is the CLOCK_MONOTONIC of the host whose launcher coordinates the run. There,
// MachineClockReference answers every other host's probes with it and announces its own host's
// offset as 0. On every other host, HostClockEstimator probes the reference 20 times a second
// and announces its host's offset (HostClock) whenever the estimate changes; the host's
// processes start their cycles at machine time plus that offset (process::ProcessNode).
#include "common/clock/clock_offset.hpp"
#include "idl/dds_participant.hpp"

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

namespace mcnc::launch {

class MachineClockReference {
 public:
  MachineClockReference(dds::Participant& participant, const std::string& host);

 private:
  dds::Writer<ClockEcho> echo_writer_;
  dds::Writer<HostClock> clock_writer_;
  dds::Reader<ClockProbe> probe_reader_;
};

class HostClockEstimator {
 public:
  static constexpr std::chrono::milliseconds kProbePeriod{50};

  HostClockEstimator(dds::Participant& participant, std::string host);
  ~HostClockEstimator();
  HostClockEstimator(const HostClockEstimator&) = delete;
  HostClockEstimator& operator=(const HostClockEstimator&) = delete;

  [[nodiscard]] std::optional<clock::ClockOffset> estimate() const;

 private:
  void probe_until_stopped();

  std::string host_;
  mutable std::mutex mutex_;
  clock::ClockOffsetFilter filter_;  // under mutex_, as the three below
  std::uint64_t seq_ = 0;            // the latest probe's: only its answer counts
  std::int64_t sent_ns_ = 0;
  std::optional<clock::ClockOffset> announced_;
  dds::Writer<ClockProbe> probe_writer_;
  dds::Writer<HostClock> clock_writer_;
  dds::Reader<ClockEcho> echo_reader_;
  bool stop_ = false;  // under mutex_
  std::condition_variable stop_cv_;
  std::thread thread_;
};

// Every host's clock as its launcher announced it.
class HostClocks {
 public:
  explicit HostClocks(dds::Participant& participant);
  [[nodiscard]] std::optional<HostClock> of(const std::string& host) const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, HostClock> latest_;
  dds::Reader<HostClock> reader_;
};

}  // namespace mcnc::launch
