#include "axisnode/drivesim/drive_bus_simulator.hpp"

#include "canopen/sdo_abort.hpp"
#include "canopen/sdo_client.hpp"

#include <stdexcept>
#include <string>
#include <utility>

namespace mcnc::drivesim {

using canopen::CanFrame;
using canopen::FrameKind;
using canopen::NmtCommand;
using canopen::NmtState;

DriveBusSimulator::DriveBusSimulator(const std::vector<DriveParams>& drives, double cycle_s) {
  index_by_node_.fill(kNoDrive);
  drives_.reserve(drives.size());
  for (const DriveParams& params : drives) {
    if (params.node_id < 1 || params.node_id > 127) {
      throw std::invalid_argument("drive node id " + std::to_string(params.node_id) +
                                  " is outside 1..127");
    }
    if (index_by_node_[params.node_id] != kNoDrive) {
      throw std::invalid_argument("drive node id " + std::to_string(params.node_id) +
                                  " is used twice on one bus");
    }
    index_by_node_[params.node_id] = static_cast<std::int16_t>(drives_.size());
    drives_.emplace_back(params, cycle_s);
  }
  sdo_.reserve(drives_.size());
  for (SimulatedDrive& drive : drives_) {
    sdo_.emplace_back(drive.node_id(), drive.objects());
  }
  rpdos_got_.assign(drives_.size(), 0);
  rpdos_awaited_.assign(drives_.size(), 0);
}

bool DriveBusSimulator::schedule_fault(std::uint8_t node, DriveFault fault,
                                       std::uint64_t at_sync) noexcept {
  SimulatedDrive* drive = find_mutable(node);
  if (drive == nullptr) {
    return false;
  }
  drive->schedule_fault(fault, at_sync);
  return true;
}

bool DriveBusSimulator::refuse_sdo(std::uint8_t node, std::uint16_t index) noexcept {
  SimulatedDrive* drive = find_mutable(node);
  if (drive == nullptr) {
    return false;
  }
  drive->objects().refuse(index, canopen::sdo_abort::kDeviceState);
  return true;
}

std::size_t DriveBusSimulator::handle_sdo(const CanFrame& in, std::span<CanFrame> out) noexcept {
  const auto node = static_cast<std::uint8_t>(in.id - canopen::kSdoRequestBase);
  if (node >= index_by_node_.size() || index_by_node_[node] == kNoDrive || out.empty()) {
    return 0;
  }
  const auto i = static_cast<std::size_t>(index_by_node_[node]);
  if (drives_[i].nmt_state() == NmtState::bootup || drives_[i].nmt_state() == NmtState::stopped) {
    return 0;  // no SDO before the boot-up, nor in stopped (CiA 301)
  }
  return sdo_[i].on_frame(in, out[0]) ? 1 : 0;
}

std::size_t DriveBusSimulator::power_on(std::span<CanFrame> out) noexcept {
  std::size_t written = 0;
  for (SimulatedDrive& drive : drives_) {
    drive.power_on();
    if (written < out.size()) {
      out[written++] = canopen::encode_heartbeat(drive.node_id(), NmtState::bootup);
    }
  }
  return written;
}

std::size_t DriveBusSimulator::handle(const CanFrame& in, std::span<CanFrame> out) noexcept {
  const canopen::FrameClass cls = canopen::classify(in);
  switch (cls.kind) {
    case FrameKind::nmt:
      return handle_nmt(in, out);
    case FrameKind::sync:
      return handle_sync(in, out);
    case FrameKind::rpdo1:
      handle_rpdo(in, cls.node, 0);
      return 0;
    case FrameKind::rpdo2:
      handle_rpdo(in, cls.node, 1);
      return 0;
    default:
      if (in.id > canopen::kSdoRequestBase && in.id < canopen::kSdoRequestBase + 0x80) {
        return handle_sdo(in, out);
      }
      return 0;
  }
}

std::size_t DriveBusSimulator::handle_nmt(const CanFrame& in, std::span<CanFrame> out) noexcept {
  const auto nmt = canopen::decode_nmt(in);
  if (!nmt) {
    ++malformed_;
    return 0;
  }
  const bool resets =
      nmt->command == NmtCommand::reset_node || nmt->command == NmtCommand::reset_communication;
  std::size_t written = 0;
  auto apply = [&](SimulatedDrive& drive) {
    if (drive.nmt_state() == NmtState::bootup) {
      return;  // not powered yet: no CANopen stack running
    }
    drive.on_nmt(nmt->command);
    if (drive.nmt_state() != NmtState::operational) {
      // Its RPDOs are ignored now: not awaited until it is fed again.
      const auto i = static_cast<std::size_t>(&drive - drives_.data());
      rpdos_got_[i] = 0;
      rpdos_awaited_[i] = 0;
    }
    if (resets && written < out.size()) {
      out[written++] = canopen::encode_heartbeat(drive.node_id(), NmtState::bootup);
    }
  };
  if (nmt->node == 0) {
    for (SimulatedDrive& drive : drives_) {
      apply(drive);
    }
  } else if (SimulatedDrive* drive = find_mutable(nmt->node)) {
    apply(*drive);
  }
  return written;
}

std::size_t DriveBusSimulator::handle_sync(const CanFrame& in, std::span<CanFrame> out) noexcept {
  if (!canopen::decode_sync(in)) {
    ++malformed_;
    return 0;
  }
  std::size_t written = 0;
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    SimulatedDrive& drive = drives_[i];
    rpdos_awaited_[i] = rpdos_got_[i];
    rpdos_got_[i] = 0;
    if (drive.nmt_state() != NmtState::operational) {
      continue;
    }
    drive.on_sync();
    const canopen::Emcy emcy = drive.take_emcy();
    if (emcy.error_code != 0 && written < out.size()) {
      out[written++] = canopen::encode_emcy(drive.node_id(), emcy);
    }
    for (std::size_t n = 0; n < 2; ++n) {
      CanFrame tpdo;
      if (written < out.size() && drive.objects().encode_tpdo(n, tpdo)) {
        out[written++] = tpdo;
      }
    }
    CanFrame heartbeat;
    if (written < out.size() && drive.heartbeat(heartbeat)) {
      out[written++] = heartbeat;
    }
  }
  return written;
}

std::size_t DriveBusSimulator::heartbeats_out_of_operation(std::uint64_t now_us,
                                                           std::span<CanFrame> out) noexcept {
  std::size_t written = 0;
  for (SimulatedDrive& drive : drives_) {
    if (written < out.size() && drive.heartbeat_out_of_operation(now_us, out[written])) {
      ++written;
    }
  }
  return written;
}

bool DriveBusSimulator::rpdos_complete() const noexcept {
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    if (drives_[i].nmt_state() == NmtState::operational &&
        (rpdos_got_[i] & rpdos_awaited_[i]) != rpdos_awaited_[i]) {
      return false;
    }
  }
  return true;
}

void DriveBusSimulator::stop_awaiting_silent_drives() noexcept {
  for (std::size_t i = 0; i < drives_.size(); ++i) {
    rpdos_awaited_[i] &= rpdos_got_[i];
  }
}

void DriveBusSimulator::handle_rpdo(const CanFrame& in, std::uint8_t node, std::size_t n) noexcept {
  SimulatedDrive* drive = find_mutable(node);
  if (drive == nullptr) {
    return;  // another node's RPDO: not ours to judge
  }
  RpdoValues values;
  if (!drive->objects().decode_rpdo(n, in, values)) {
    ++malformed_;  // not mapped, or not the mapped length
    return;
  }
  if (drive->nmt_state() == NmtState::operational) {
    drive->on_rpdo(values);
    rpdos_got_[static_cast<std::size_t>(index_by_node_[node])] |=
        static_cast<std::uint8_t>(1U << n);
  }
}

const SimulatedDrive* DriveBusSimulator::find(std::uint8_t node_id) const noexcept {
  if (node_id >= index_by_node_.size() || index_by_node_[node_id] == kNoDrive) {
    return nullptr;
  }
  return &drives_[static_cast<std::size_t>(index_by_node_[node_id])];
}

SimulatedDrive* DriveBusSimulator::find_mutable(std::uint8_t node_id) noexcept {
  return const_cast<SimulatedDrive*>(std::as_const(*this).find(node_id));
}

unsigned long DriveBusSimulator::malformed_count() const noexcept {
  return malformed_;
}

}  // namespace mcnc::drivesim
