#pragma once
// What the PLC node hears, as lockstep inputs (docs/plc.md): every channel's cyclic status with
// the events it announces (the aux requests among them), and the feedback of the axes it
// watches (the spindles an interlock looks at, the axes of position inputs). An adapter: DDS
// callbacks fill it under the node's wake-up lock; apply() hands MachinePlc, in the cycle, the
// requests received and what each watched axis does.
#include "common/config/machine_config.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/cycle/tracked_input.hpp"
#include "common/process/process_node.hpp"
#include "plcnode/logic/machine_plc.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mcnc::plc {

class PlcInputs {
 public:
  explicit PlcInputs(process::ProcessNode& node, const config::MachineConfig& machine);
  PlcInputs(const PlcInputs&) = delete;
  PlcInputs& operator=(const PlcInputs&) = delete;

  // Every channel's status and event writers and every watched axis's feedback writer matched.
  [[nodiscard]] bool discovered() const noexcept;
  [[nodiscard]] bool may_run(std::uint64_t cycle) const noexcept;
  // The axes watched (ids): the spindles an interlock looks at and the G114.1 partners of
  // those, and the axes that switch a position input of the simulated machine.
  [[nodiscard]] std::span<const int> axes() const noexcept { return axes_; }

  // Before the PLC's cycle `cycle`, under no lock: the requests received go to `plc` (which
  // takes each in the cycle after the one it was sent in), and `views` (one per axes()) say
  // what each watched axis does at cycle-1 (realtime: as last heard). No allocation.
  void apply(std::uint64_t cycle, bool lockstep, MachinePlc& plc, std::span<AxisView> views);
  // Requests that did not fit the receive queue: counted, never silent.
  [[nodiscard]] std::uint64_t dropped() const noexcept { return dropped_; }

 private:
  static constexpr std::size_t kQueue = 256;
  static std::vector<int> watched_axes(const config::MachineConfig& machine);

  process::ProcessNode& node_;
  std::size_t channels_;
  std::vector<int> axes_;
  cycle::LockstepGate gate_;
  std::vector<cycle::TrackedInput<::mcnc::ChannelStatus>> status_;
  std::vector<cycle::TrackedInput<::mcnc::AxisFeedback>> feedback_;  // per axes_
  std::array<AuxRequest, kQueue> requests_{};
  std::size_t queued_ = 0;
  std::uint64_t dropped_ = 0;
  dds::Reader<::mcnc::ChannelStatus> status_reader_;
  dds::Reader<::mcnc::CoordinationEvent> event_reader_;
  dds::Reader<::mcnc::AxisFeedback> feedback_reader_;
};

}  // namespace mcnc::plc
