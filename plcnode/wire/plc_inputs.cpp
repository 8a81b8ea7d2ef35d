#include "plcnode/wire/plc_inputs.hpp"

#include "common/config/cyclic_routes.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mcnc::plc {

std::vector<int> PlcInputs::watched_axes(const config::MachineConfig& machine) {
  std::vector<int> axes;
  auto watch = [&](int id) {
    if (id != 0 && std::find(axes.begin(), axes.end(), id) == axes.end()) {
      axes.push_back(id);
    }
  };
  for (const config::PlcMCode& m : machine.plc.m_codes) {
    watch(m.spindle_stopped);
  }
  for (const config::PlcSignal& s : machine.plc.signals) {
    watch(s.at_axis);  // a sensor the axis reaches
  }
  // A pair in phase may open a chuck while it turns.
  for (const config::SpindleSyncGroup& g : machine.spindle_sync) {
    if (std::find(axes.begin(), axes.end(), g.master) != axes.end() ||
        std::find(axes.begin(), axes.end(), g.slave) != axes.end()) {
      watch(g.master);
      watch(g.slave);
    }
  }
  return axes;
}

namespace {

std::vector<std::string> axis_names(const config::MachineConfig& machine,
                                    const std::vector<int>& ids) {
  std::vector<std::string> names;
  for (const int id : ids) {
    names.push_back(machine.axes[static_cast<std::size_t>(id - 1)].name);
  }
  return names;
}

}  // namespace

PlcInputs::PlcInputs(process::ProcessNode& node, const config::MachineConfig& machine)
    : node_(node),
      channels_(machine.channels.size()),
      axes_(watched_axes(machine)),
      gate_(channels_ + axes_.size()),
      // Made before the readers, whose callbacks may come at once.
      status_(cycle::tracked_inputs<::mcnc::ChannelStatus>(0, channels_)),
      feedback_(cycle::tracked_inputs<::mcnc::AxisFeedback>(channels_, axes_.size())),
      status_reader_(
          node.participant(), dds::Keys::of(config::channel_names(machine)),
          [this](const ::mcnc::ChannelStatus& s, const dds::WriterId& writer) {
            if (s.channel() >= 1 && s.channel() <= channels_) {
              node_.wakeup().update([&] {
                status_[s.channel() - 1].on_sample(s, s.cycle(), s.event_seq(), writer, gate_);
              });
            }
          },
          [this](const dds::WriterId& writer, bool matched) {
            if (!matched) {
              node_.wakeup().update([&] {
                for (auto& input : status_) {
                  input.on_unmatched(writer, gate_);  // a channel gone: the others go on
                }
              });
            }
          }),
      event_reader_(node.participant(),
                    [this](const ::mcnc::CoordinationEvent& e, const dds::WriterId&) {
                      if (e.channel() < 1 || e.channel() > channels_) {
                        return;
                      }
                      node_.wakeup().update([&] {
                        status_[e.channel() - 1].on_event(e.seq(), gate_);
                        if (e.kind() != COORD_AUX_REQUEST) {
                          return;
                        }
                        if (queued_ == kQueue) {
                          ++dropped_;
                          return;
                        }
                        requests_[queued_++] =
                            AuxRequest{e.channel(),
                                       e.aux_id(),
                                       e.aux_kind() == AUX_T ? AuxKind::t_code : AuxKind::m_code,
                                       static_cast<int>(e.aux_code()),
                                       static_cast<int>(e.aux_spindle()),
                                       e.cycle()};
                      });
                    }),
      feedback_reader_(
          node.participant(), dds::Keys::of(axis_names(machine, axes_)),
          [this](const ::mcnc::AxisFeedback& fb, const dds::WriterId& writer) {
            for (std::size_t k = 0; k < axes_.size(); ++k) {
              if (static_cast<int>(fb.axis()) == axes_[k]) {
                node_.wakeup().update(
                    [&] { feedback_[k].on_sample(fb, fb.cycle(), 0, writer, gate_); });
              }
            }
          },
          [this](const dds::WriterId& writer, bool matched) {
            if (!matched) {
              node_.wakeup().update([&] {
                for (auto& input : feedback_) {
                  input.on_unmatched(writer, gate_);  // not known to stand: its interlocks hold
                }
              });
            }
          }) {}

bool PlcInputs::discovered() const noexcept {
  const int channels = static_cast<int>(channels_);
  return status_reader_.matched_writers() >= channels &&
         event_reader_.matched_writers() >= channels &&
         feedback_reader_.matched_writers() >= static_cast<int>(axes_.size());
}

bool PlcInputs::may_run(std::uint64_t cycle) const noexcept {
  return cycle == 0 || gate_.may_run(cycle);
}

void PlcInputs::apply(std::uint64_t cycle, bool lockstep, MachinePlc& plc,
                      std::span<AxisView> views) {
  node_.wakeup().with_lock([&] {
    for (std::size_t i = 0; i < queued_; ++i) {
      plc.request(requests_[i]);
    }
    queued_ = 0;
    for (std::size_t k = 0; k < axes_.size() && k < views.size(); ++k) {
      const cycle::TrackedInput<::mcnc::AxisFeedback>& input = feedback_[k];
      const ::mcnc::AxisFeedback* fb = input.for_cycle(cycle, lockstep);
      // Turning: more than a tenth of a revolution per second either way; without feedback
      // (or with its node gone) not known to stand.
      const bool known = fb != nullptr && !input.lost();
      views[k] = AxisView{axes_[k],
                          !known || std::abs(fb->vel()) > 36.0,
                          known ? static_cast<int>(fb->coupled_to()) : 0,
                          known && fb->coupling_locked(),
                          known,
                          known ? fb->act() : 0.0};
    }
  });
}

}  // namespace mcnc::plc
