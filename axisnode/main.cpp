// mcnc-axisnode: one axis or spindle. DDS on one side (setpoints from its owner channel,
// operator commands, feedback out), CAN on the other (a CiA 402 drive in cyclic synchronous
// position, velocity for a spindle, homing at start-up). Wiring only: the behaviour is in
// AxisNodeController and DriveLink.
#include "axisnode/canopen/emcy_codes.hpp"
#include "axisnode/control/axis_node_controller.hpp"
#include "axisnode/coupling/axis_coupling.hpp"
#include "axisnode/coupling/master_history.hpp"
#include "axisnode/coupling/spindle_coupling.hpp"
#include "axisnode/link/drive_link.hpp"
#include "axisnode/ownership/axis_ownership.hpp"
#include "common/clock/cycle_clock.hpp"
#include "common/config/cyclic_routes.hpp"
#include "common/cycle/lockstep_gate.hpp"
#include "common/cycle/pending_events.hpp"
#include "common/cycle/tracked_input.hpp"
#include "common/log/logging.hpp"
#include "common/process/cycle_loop.hpp"
#include "common/process/process_node.hpp"
#include "common/process/startup.hpp"
#include "common/trace/trace_writer.hpp"

#include <spdlog/spdlog.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <thread>

using namespace std::chrono_literals;
using namespace mcnc;

namespace {

const char* drive_state_name(cia402::State state) {
  return cia402::to_string(state);
}

ownership::OwnershipRequestKind to_core(AxisRequestKind kind) {
  switch (kind) {
    case AXIS_RELEASE:
      return ownership::OwnershipRequestKind::release;
    case AXIS_ACQUIRE:
      return ownership::OwnershipRequestKind::acquire;
    case AXIS_RESTORE:
      return ownership::OwnershipRequestKind::restore;
    case AXIS_WITHDRAW:
      return ownership::OwnershipRequestKind::withdraw;
  }
  return ownership::OwnershipRequestKind::withdraw;
}

DriveState to_wire(cia402::State state) {
  static_assert(static_cast<int>(cia402::State::fault) == static_cast<int>(DRIVE_FAULT),
                "core and wire drive states must be in the same order");
  return static_cast<DriveState>(static_cast<int>(state));
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"mcnc axis node: one axis, CiA 402 drive over CAN, setpoints over DDS"};
  process::ShellOptions shell;
  std::string axis_name;
  std::string trace_path;
  int trace_pos_every = 10;
  int stall_ms = 2000;
  process::add_shell_options(app, shell);
  app.add_option("--axis", axis_name, "axis name from the machine file")->required();
  app.add_option("--trace", trace_path, "write this process's trace events to FILE");
  app.add_option("--trace-pos-every", trace_pos_every, "pos event every K cycles")
      ->check(CLI::PositiveNumber);
  app.add_option("--lockstep-stall-ms", stall_ms,
                 "lockstep: warn when the bus keeps a cycle waiting this long");
  CLI11_PARSE(app, argc, argv);

  const config::MachineConfig machine = process::load_machine_or_exit(shell.machine_path);
  const config::AxisConfig* axis = machine.find_axis(axis_name);
  if (axis == nullptr) {
    std::fprintf(stderr, "error: axis %s is not in machine file %s\n", axis_name.c_str(),
                 shell.machine_path.c_str());
    return 2;
  }
  if (!axis->spindle.empty()) {
    std::fprintf(stderr, "error: %s is spindle %s's C axis: the spindle's node drives it\n",
                 axis_name.c_str(), axis->spindle.c_str());
    return 2;
  }
  const config::BusConfig* bus = machine.find_bus(axis->bus);
  const config::ChannelConfig* owner = machine.find_channel(axis->channel);
  process::start_process(axis->name, shell);
  process::require_roudi_or_exit(machine, axis->name);

  std::vector<std::uint8_t> other_nodes;
  for (const auto& other : machine.axes) {
    if (other.bus == axis->bus && other.name != axis->name) {
      other_nodes.push_back(static_cast<std::uint8_t>(other.node_id));
    }
  }
  const bool sync_producer = bus->sync_producer == axis->name;
  const auto node_id = static_cast<std::uint8_t>(axis->node_id);

  try {
    process::ProcessNode node(process::resolve_domain(machine), axis->name,
                              process::cyclic_clock(shell),
                              process::resolve_middleware(machine, axis->name));
    trace::TraceWriter tracer(trace_path, axis->name);
    node.announce(PHASE_STARTING);

    // The channels that may own this axis: its home channel, then those that may acquire it
    // (G141). Each sends a setpoint every cycle, valid only while it commands the axis; the node
    // follows its owner's alone (ARCHITECTURE.md §5) and runs cycle N in lockstep once every
    // candidate's setpoint N-1 and the events it announces are in, so that a G140/G141/G142
    // takes effect at the same cycle in every run.
    const auto axis_id = static_cast<std::uint32_t>(axis->id);
    const auto home_id = static_cast<std::uint32_t>(owner->id);
    std::vector<std::uint32_t> candidates{home_id};
    for (const config::ChannelConfig& c : machine.channels) {
      if (std::find(c.exchange_axes.begin(), c.exchange_axes.end(), axis->name) !=
          c.exchange_axes.end()) {
        candidates.push_back(static_cast<std::uint32_t>(c.id));
      }
    }
    const bool exchangeable = axis->exchange != 0;  // its home channel may release it alone
    // G51.4 comes as an event from the channel that commands the axis (never exchanged).
    const bool may_follow = axis->sync_slave;
    const bool watches_events = exchangeable || may_follow;
    auto candidate_of = [&](std::uint32_t channel) -> int {
      for (std::size_t k = 0; k < candidates.size(); ++k) {
        if (candidates[k] == channel) {
          return static_cast<int>(k);
        }
      }
      return -1;
    };
    // Per candidate, its setpoints (lost: its writer left).
    std::vector<cycle::TrackedInput<AxisSetpoint>> from =
        cycle::tracked_inputs<AxisSetpoint>(0, candidates.size());
    // G114.1: a slave spindle follows its master (param 1420) once the master's channel says so;
    // in lockstep it runs cycle N with that channel's status N-1 (and its events) and the
    // master's feedback N-1 too. The coupling is this node's state: reset does not end it.
    const config::SpindleSyncGroup* sync_group = nullptr;
    for (const config::SpindleSyncGroup& g : machine.spindle_sync) {
      sync_group = g.slave == axis->id ? &g : sync_group;
    }
    const std::size_t sync_input = candidates.size();  // the master's channel's status
    const std::size_t master_input = candidates.size() + 1;
    cycle::LockstepGate gate(candidates.size() + (sync_group != nullptr ? 2 : 0));
    struct SpindleSyncRequest {
      bool on = false;
      coupling::SpindleCouplingCommand command;
    };
    cycle::PendingEvents<SpindleSyncRequest, 16> pending_sync;
    cycle::TrackedInput<AxisFeedback> master_feedback(master_input);
    cycle::TrackedInput<ChannelStatus> sync_channel_status(sync_input);
    // G51.4: a slave copies its master's increments once its channel says so (or from power-on,
    // param 5600.3). In lockstep it runs cycle N with its master's commanded position N-1,
    // from the master's feedback; the master is any axis of its kind that is no slave itself.
    std::vector<std::uint32_t> leaders;
    for (const config::AxisConfig& a : machine.axes) {
      if (may_follow && a.id != axis->id && a.type == axis->type && !a.sync_slave) {
        leaders.push_back(static_cast<std::uint32_t>(a.id));
      }
    }
    // Long enough for a master that runs ahead of its slave's channel (a minute at 1 ms).
    coupling::MasterHistory master_history(leaders, may_follow ? std::size_t{1} << 16 : 1);
    std::vector<std::pair<dds::WriterId, std::uint32_t>> leader_writers;
    leader_writers.reserve(leaders.size());
    struct AxisSyncRequest {
      bool on = false;
      std::uint32_t master = 0;
    };
    cycle::PendingEvents<AxisSyncRequest, 16> pending_axis_sync;
    coupling::AxisCoupling axis_coupling(machine.cycle_s());
    if (axis->sync_at_power_on) {
      axis_coupling.couple(static_cast<std::uint32_t>(axis->sync_master));
    }
    // The master the slave follows at cycle `c`: the coupling as the events sent before `c`
    // leave it.
    auto axis_master_at = [&](std::uint64_t c) {
      std::uint32_t m = axis_coupling.master();
      pending_axis_sync.peek_due(c, [&](const AxisSyncRequest& r) { m = r.on ? r.master : 0; });
      return m;
    };
    ownership::AxisOwnership ownership(home_id);
    // G140/G141/G142 requests as they arrive, applied from the cycle after they were sent.
    cycle::PendingEvents<ownership::OwnershipRequest, 256> pending;
    std::uint64_t pending_dropped = 0;
    std::uint32_t owner_now = home_id;  // the owner as the last decision left it
    bool owner_lost = false;            // the current owner's writer left
    process::Wakeup& wake = node.wakeup();
    dds::Reader<AxisSetpoint> setpoint_reader(
        node.participant(), dds::Keys::of({axis->name}),
        [&](const AxisSetpoint& sp, const dds::WriterId& writer) {
          const int k = sp.axis() == axis_id ? candidate_of(sp.channel()) : -1;
          if (k < 0) {
            return;
          }
          wake.update([&] {
            from[static_cast<std::size_t>(k)].on_sample(
                sp, sp.cycle(), watches_events ? sp.event_seq() : 0, writer, gate);
          });
        },
        [&](const dds::WriterId& writer, bool matched) {
          if (!matched) {
            wake.update([&] {
              for (std::size_t k = 0; k < from.size(); ++k) {
                if (from[k].on_unmatched(writer, gate)) {
                  owner_lost = owner_lost || candidates[k] == owner_now;
                }
              }
            });
          }
        });
    std::optional<dds::Reader<CoordinationEvent>> request_reader;
    std::optional<dds::Reader<ChannelStatus>> sync_status_reader;
    std::optional<dds::Reader<AxisFeedback>> master_reader;
    std::optional<dds::Reader<AxisFeedback>> leader_reader;
    if (may_follow) {
      std::vector<std::string> leader_names;
      for (const std::uint32_t id : leaders) {
        leader_names.push_back(machine.axes[id - 1].name);
      }
      leader_reader.emplace(
          node.participant(), dds::Keys::of(leader_names),
          [&](const AxisFeedback& fb, const dds::WriterId& writer) {
            if (master_history.may_lead(fb.axis())) {
              wake.update([&] {
                master_history.put(fb.axis(), fb.cycle(), fb.cmd(), fb.enabled());
                bool known = false;
                for (const auto& [w, id] : leader_writers) {
                  known = known || id == fb.axis();
                }
                if (!known && leader_writers.size() < leaders.size()) {
                  leader_writers.emplace_back(writer, fb.axis());
                }
              });
            }
          },
          [&](const dds::WriterId& writer, bool matched) {
            wake.update([&] {
              for (const auto& [w, id] : leader_writers) {
                if (!matched && writer == w) {
                  master_history.gone(id);
                }
              }
            });
          });
    }
    if (sync_group != nullptr) {
      const auto sync_channel = static_cast<std::uint32_t>(sync_group->channel);
      sync_status_reader.emplace(
          node.participant(),
          dds::Keys::of({machine.channels[static_cast<std::size_t>(sync_channel - 1)].name}),
          [&, sync_channel](const ChannelStatus& s, const dds::WriterId& writer) {
            if (s.channel() == sync_channel) {
              wake.update([&] {
                sync_channel_status.on_sample(s, s.cycle(), s.event_seq(), writer, gate);
              });
            }
          },
          [&](const dds::WriterId& writer, bool matched) {
            if (!matched) {
              wake.update([&] {
                sync_channel_status.on_unmatched(writer, gate);  // the coupling stays as it is
              });
            }
          });
      master_reader.emplace(
          node.participant(),
          dds::Keys::of({machine.axes[static_cast<std::size_t>(sync_group->master - 1)].name}),
          [&](const AxisFeedback& fb, const dds::WriterId& writer) {
            if (static_cast<int>(fb.axis()) == sync_group->master) {
              wake.update([&] { master_feedback.on_sample(fb, fb.cycle(), 0, writer, gate); });
            }
          },
          [&](const dds::WriterId& writer, bool matched) {
            if (!matched) {
              wake.update([&] { master_feedback.on_unmatched(writer, gate); });
            }
          });
    }
    if (watches_events || sync_group != nullptr) {
      request_reader.emplace(node.participant(), [&](const CoordinationEvent& e,
                                                     const dds::WriterId&) {
        const int k = candidate_of(e.channel());
        const bool from_sync_channel =
            sync_group != nullptr && static_cast<int>(e.channel()) == sync_group->channel;
        if (k < 0 && !from_sync_channel) {
          return;
        }
        wake.update([&] {
          if (k >= 0 && watches_events) {
            from[static_cast<std::size_t>(k)].on_event(e.seq(), gate);
          }
          if (may_follow && e.kind() == COORD_AXIS_SYNC && e.axis() == axis_id &&
              e.channel() == home_id) {
            (void)pending_axis_sync.push(
                AxisSyncRequest{e.sync_on(), e.sync_on() ? e.sync_master() : 0}, e.cycle());
          }
          if (from_sync_channel) {
            sync_channel_status.on_event(e.seq(), gate);
            if (e.kind() == COORD_SPINDLE_SYNC &&
                (e.sync_group() == sync_group->group || (!e.sync_on() && e.sync_group() == 0))) {
              (void)pending_sync.push(
                  SpindleSyncRequest{
                      e.sync_on(),
                      coupling::SpindleCouplingCommand{static_cast<int>(e.sync_p()),
                                                       static_cast<int>(e.sync_q()), e.sync_r()}},
                  e.cycle());
            }
          }
          if (k < 0 || !exchangeable || e.kind() != COORD_AXIS_REQUEST ||
              (e.axis() != axis_id && e.axis() != 0)) {
            return;
          }
          if (!pending.push(ownership::OwnershipRequest{to_core(e.axis_request()), e.channel(),
                                                        e.force(), e.cycle()},
                            e.cycle())) {
            ++pending_dropped;
          }
        });
      });
    }
    dds::Writer<AxisFeedback> feedback_writer(node.participant(), axis->name);

    axisnode::DriveLink link(can::open_can_bus(bus->uri), node_id, sync_producer, other_nodes,
                             wake);
    const bool spindle = axis->type == config::AxisType::spindle;
    canopen::NodeStartupConfig startup;
    startup.node = node_id;
    startup.bootup_attempts = 20;  // 20 x 500 ms
    if (spindle) {
      startup.pdos = canopen::spindle_pdos();
      startup.mode = axisnode::kModeCsv;
    } else if (axis->has_homing) {
      startup.pdos = canopen::homing_axis_pdos();
      startup.mode = axisnode::kModeHoming;
      startup.homing_method = static_cast<std::int8_t>(axis->homing_method);
      startup.home_offset =
          static_cast<std::int32_t>(std::llround(axis->home_offset * axis->counts_per_unit));
    }
    link.set_pdo_layout(spindle || axis->has_homing, spindle);
    startup.heartbeat_ms = static_cast<std::uint16_t>(axis->heartbeat_ms);
    startup.quick_stop_deceleration = static_cast<std::uint32_t>(
        std::llround(axis->quick_stop_deceleration * axis->counts_per_unit));
    if (axis->tpdo2_velocity) {
      startup.pdos.tpdo2.objects[startup.pdos.tpdo2.count++] = canopen::MappedObject{0x606C, 0, 32};
    }
    if (axis->tpdo2_following_error) {
      startup.pdos.tpdo2.objects[startup.pdos.tpdo2.count++] = canopen::MappedObject{0x60F4, 0, 32};
    }
    if (axis->tpdo2_torque) {
      startup.pdos.tpdo2.objects[startup.pdos.tpdo2.count++] = canopen::MappedObject{0x6077, 0, 16};
    }
    link.set_tpdo2(axis->tpdo2_velocity, axis->tpdo2_following_error, axis->tpdo2_torque);
    if (const auto error = link.bring_up(startup, 10s)) {
      spdlog::error("drive on {}: {}", bus->uri, *error);
      node.raise_alarm(axisnode::kAlarmBase + static_cast<int>(axisnode::AxisAlarm::drive_startup),
                       error->c_str(), 0, 0, axis->id);
      node.announce(PHASE_FAILED, 0, *error);
      return 1;
    }

    // Discovery: the setpoint writer of every channel that may command the node and the feedback
    // reader of every channel that reads it matched.
    const auto fed_channels = static_cast<int>(config::channels_fed_by(machine, axis->name));
    process::CycleLoop loop(node, machine.cycle_us);
    spdlog::info("node {} on {}{}", node_id, bus->uri, sync_producer ? " (SYNC producer)" : "");
    if (!loop.start(
            [&] {
              return setpoint_reader.matched_writers() >= static_cast<int>(candidates.size()) &&
                     (!sync_status_reader || sync_status_reader->matched_writers() >= 1) &&
                     (!master_reader || master_reader->matched_writers() >= 1) &&
                     (!leader_reader ||
                      leader_reader->matched_writers() >= static_cast<int>(leaders.size())) &&
                     feedback_writer.matched_readers() >= fed_channels &&
                     (!request_reader ||
                      request_reader->matched_writers() >= static_cast<int>(candidates.size()));
            },
            shell.clock)) {
      return 0;
    }
    const bool lockstep = loop.lockstep();
    if (sync_producer && !lockstep) {
      // Realtime: SYNC at a fixed offset inside every cycle, from a timer of its own.
      constexpr std::int64_t kNsPerUs = 1000;
      link.start_sync_timer(canopen::SyncSchedule(node.run_control().start_ns,
                                                  machine.cycle_us * kNsPerUs,
                                                  bus->sync_offset_us * kNsPerUs));
    }

    axisnode::AxisNodeSetup setup;
    setup.counts_per_unit = axis->counts_per_unit;
    setup.cycle_s = machine.cycle_s();
    setup.deadline_cycles = machine.deadline_cycles;
    setup.has_soft_limits = axis->has_soft_limits;
    setup.soft_min = axis->soft_limit_min;
    setup.soft_max = axis->soft_limit_max;
    setup.following_error_limit = axis->following_error_limit;
    // Heartbeat consumer time: 1.5 producer times (CiA 301 practice), in cycles.
    // At least one cycle: a heartbeat faster than the cycle is still watched.
    setup.heartbeat_cycles =
        startup.heartbeat_ms == 0
            ? 0
            : std::max(1, static_cast<int>(1.5 * startup.heartbeat_ms * 1000 / machine.cycle_us));
    setup.spindle = spindle;
    setup.homing = axis->has_homing;
    axisnode::AxisNodeController controller(setup);
    coupling::SpindleCoupling spindle_coupling(
        coupling::SpindleCouplingSetup{machine.cycle_s(), axis->acceleration, 0.05, 1.0});
    const char* master_name =
        sync_group != nullptr
            ? machine.axes[static_cast<std::size_t>(sync_group->master - 1)].name.c_str()
            : "";
    bool owner_loss_checked = false;
    std::uint64_t last_tpdo_count = 0;
    tracer.emit(0, "owner", "\"axis\":\"%s\",\"owner\":\"%s\"", axis->name.c_str(),
                owner->name.c_str());
    auto channel_name = [&](std::uint32_t id) -> const char* {
      return id >= 1 && id <= machine.channels.size() ? machine.channels[id - 1].name.c_str() : "";
    };
    std::uint32_t following = 0;  // the channel whose valid setpoints the node applied last
    auto trace_axis_coupling = [&](std::uint64_t cycle, const char* what, std::uint32_t master) {
      tracer.emit(cycle, what, "\"kind\":\"axis\",\"master\":\"%s\",\"slave\":\"%s\"",
                  machine.axes[master - 1].name.c_str(), axis->name.c_str());
    };
    if (axis_coupling.active()) {
      trace_axis_coupling(0, "couple", axis_coupling.master());  // a gantry from power-on
    }

    // A lockstep bus wait ends with the run, an E-stop or the owner gone. Built once: a
    // std::function made from this lambda inside the loop could allocate every cycle.
    const std::function<bool()> abandon_bus_wait = [&] {
      const RunCommand cmd = node.run_control().command;
      bool lost = false;
      wake.with_lock([&] { lost = owner_lost; });
      return cmd == RUN_STOP || cmd == RUN_ESTOP || lost || process::g_stop_signal != 0;
    };

    // 1. Wait until the cycle may run: every candidate owner's setpoint stamped N-1 is in,
    //    with the events it announces.
    for (std::uint64_t cycle = 0; loop.next(
             cycle,
             [&](std::uint64_t c) {
               if (c == 0 || !gate.may_run(c)) {
                 return c == 0;
               }
               const std::uint32_t m = may_follow ? axis_master_at(c) : 0;
               return m == 0 || master_history.at(m, c - 1).lookup !=
                                    coupling::MasterHistory::Lookup::not_yet;
             },
             [&] { return owner_lost; });
         ++cycle) {
      const bool degraded = loop.degraded();
      const bool estop = loop.emergency_stop();

      // 2. Inputs stamped N-1: first who owns the axis (the requests sent before this cycle),
      //    then that owner's setpoint.
      axisnode::AxisNodeInput in;
      bool lost_now = false;
      ownership::OwnershipChange change;
      {
        AxisSetpoint sp;
        bool have = false;
        wake.update([&] {
          auto setpoint_of = [&](std::uint32_t channel) -> const AxisSetpoint* {
            const int k = candidate_of(channel);
            if (k < 0 || cycle == 0) {
              return nullptr;
            }
            const cycle::TrackedInput<AxisSetpoint>& c = from[static_cast<std::size_t>(k)];
            if (const AxisSetpoint* s = c.for_cycle(cycle, true)) {
              return s;
            }
            // Realtime: the latest only while it is no older than the last cycle's.
            const AxisSetpoint* latest = c.latest();
            return !lockstep && latest != nullptr && latest->cycle() >= cycle - 1 ? latest
                                                                                  : nullptr;
          };
          if (exchangeable) {
            // Every request sent before this cycle, whatever order they arrived in (the core
            // puts them in decision order).
            pending.take_due(cycle, [&](const ownership::OwnershipRequest& r) {
              if (!ownership.request(r)) {
                ++pending_dropped;
              }
            });
            for (std::size_t k = 0; k < from.size(); ++k) {
              if (from[k].lost()) {
                ownership.channel_gone(candidates[k]);
              }
            }
            // At rest: the owner commands no motion and the axis stands in position (a forced
            // G141 or a G142 waits for the owner's move to end). An owner that is gone is not
            // at rest: its axis is stopped by the node's safety and nobody takes it over.
            const int owner_k = candidate_of(ownership.owner());
            const bool owner_gone = owner_k >= 0 && from[static_cast<std::size_t>(owner_k)].lost();
            const AxisSetpoint* current = setpoint_of(ownership.owner());
            const axisnode::AxisNodeOutput& last = controller.output();
            const bool at_rest = !owner_gone &&
                                 (current == nullptr || !current->valid() ||
                                  (current->vel() == 0.0 && current->acc() == 0.0)) &&
                                 std::abs(last.cmd - last.act) <= axis->in_position;
            change = ownership.decide(at_rest);
            owner_now = ownership.owner();
            const int k = candidate_of(owner_now);
            owner_lost = k >= 0 && from[static_cast<std::size_t>(k)].lost();
          }
          if (owner_now == 0) {
            have = true;  // released: nobody commands the axis, it holds where it is
          } else if (const AxisSetpoint* s = setpoint_of(owner_now)) {
            sp = *s;
            have = true;
          }
          lost_now = owner_lost;
        });
        in.have_setpoint = have;
        in.setpoint_pos = sp.pos();
        in.setpoint_vel = sp.vel();
        // A new owner's setpoint from before it knew is not followed (it holds, too).
        in.setpoint_valid = sp.valid() && !change.changed && owner_now != 0;
        in.setpoint_velocity = sp.mode() == SP_VELOCITY;
      }
      // G114.1: while coupled, the slave follows its master whatever its owner sends.
      if (sync_group != nullptr) {
        AxisFeedback master;
        bool have_master = false;
        wake.update([&] {
          pending_sync.take_due(cycle, [&](const SpindleSyncRequest& r) {
            if (r.on) {
              spindle_coupling.couple(r.command, controller.output().act, controller.output().vel);
              tracer.emit(cycle, "couple",
                          "\"kind\":\"spindle\",\"master\":\"%s\",\"slave\":\"%s\",\"p\":%d,"
                          "\"q\":%d,\"r\":%.3f",
                          master_name, axis->name.c_str(), r.command.p, r.command.q, r.command.r);
            } else if (spindle_coupling.active()) {
              spindle_coupling.decouple();
              tracer.emit(cycle, "decouple",
                          "\"kind\":\"spindle\",\"master\":\"%s\",\"slave\":\"%s\"", master_name,
                          axis->name.c_str());
            }
          });
          const AxisFeedback* m = master_feedback.for_cycle(cycle, lockstep);
          if (m != nullptr && !master_feedback.lost()) {
            master = *m;
            have_master = true;
          }
        });
        if (spindle_coupling.active()) {
          in.have_setpoint = true;
          in.setpoint_valid = have_master;  // without its master it holds where it is
          in.setpoint_velocity = false;
          if (have_master) {
            // The master's position of this cycle, from its feedback of the last one.
            const coupling::SlaveTarget t = spindle_coupling.step(
                master.act() + master.vel() * machine.cycle_s(), master.vel());
            in.setpoint_pos = t.pos;
            in.setpoint_vel = t.vel;
          }
        }
      }
      // G51.4: while coupled, the slave copies its master's increments.
      if (may_follow) {
        wake.update([&] {
          pending_axis_sync.take_due(cycle, [&](const AxisSyncRequest& r) {
            const std::uint32_t before = axis_coupling.master();
            const std::uint32_t after = r.on && master_history.may_lead(r.master) ? r.master : 0;
            if (after == before) {
              return;
            }
            if (before != 0) {
              axis_coupling.decouple();
              trace_axis_coupling(cycle, "decouple", before);
            }
            if (after != 0) {
              axis_coupling.couple(after);
              trace_axis_coupling(cycle, "couple", after);
            }
          });
        });
        if (axis_coupling.active()) {
          coupling::MasterHistory::Sample m;
          wake.update(
              [&] { m = master_history.estimate(axis_coupling.master(), cycle, lockstep); });
          in.have_setpoint = true;
          in.setpoint_velocity = false;
          in.setpoint_valid = false;  // without its master (or a drive in operation) it holds
          // Its master's increments while both are in operation; otherwise it holds, and
          // starts again from where both stand.
          if (m.lookup == coupling::MasterHistory::Lookup::found && m.operating &&
              controller.output().enabled) {
            const coupling::AxisTarget t = axis_coupling.step(m.cmd, controller.output().cmd);
            in.setpoint_pos = t.pos;
            in.setpoint_vel = t.vel;
            in.setpoint_valid = true;
          } else {
            axis_coupling.rebase();
          }
        }
      }
      if (change.changed) {
        if (change.owner == 0) {
          tracer.emit(cycle, "owner", "\"axis\":\"%s\",\"owner\":null,\"previous\":\"%s\"",
                      axis->name.c_str(), channel_name(change.previous));
        } else {
          tracer.emit(cycle, "owner",
                      "\"axis\":\"%s\",\"owner\":\"%s\",\"previous\":%s%s%s,\"forced\":%s",
                      axis->name.c_str(), channel_name(change.owner),
                      change.previous == 0 ? "null" : "\"", channel_name(change.previous),
                      change.previous == 0 ? "" : "\"", change.forced ? "true" : "false");
        }
      }
      const std::uint32_t follows = in.have_setpoint && in.setpoint_valid ? owner_now : 0;
      if (follows != following) {
        following = follows;
        if (follows == 0) {
          tracer.emit(cycle, "follow", "\"axis\":\"%s\",\"ch\":null", axis->name.c_str());
        } else {
          tracer.emit(cycle, "follow", "\"axis\":\"%s\",\"ch\":\"%s\"", axis->name.c_str(),
                      channel_name(follows));
        }
      }
      const axisnode::TpdoSample tpdo = link.tpdo();
      in.have_tpdo = tpdo.count > last_tpdo_count;
      last_tpdo_count = tpdo.count;
      in.statusword = tpdo.pdo.statusword;
      in.position_counts = tpdo.pdo.position_actual;
      in.mode_display = tpdo.pdo.mode_display;
      if (lost_now && !owner_loss_checked) {
        owner_loss_checked = true;
        if (node.stop_arrives_within(300ms)) {  // the owner left because the run ends
          break;
        }
      }
      in.owner_lost = lost_now;
      in.emergency_stop = estop;
      in.heartbeats = link.heartbeats();
      in.bus_off = link.bus_off();

      while (const auto request = node.take_operator_request(cycle)) {
        // The channel that commands the axis resets it (a lent axis: its borrower, whose own
        // reset also stops its setpoints); released, its home channel.
        if (request->action == process::OperatorActionKind::reset &&
            request->concerns(owner_now != 0 ? owner_now : home_id)) {
          controller.reset();
          tracer.emit(cycle, "operator", "\"axis\":\"%s\",\"action\":\"reset\"",
                      axis->name.c_str());
        }
      }
      const axisnode::AxisNodeOutput& out = controller.cycle(cycle, in);

      // 3. Feedback stamped N.
      AxisFeedback fb;
      fb.axis(axis_id);
      fb.owner(owner_now);
      fb.released_by(ownership.released_by());
      fb.coupled_to(spindle_coupling.active() ? static_cast<std::uint32_t>(sync_group->master)
                                              : axis_coupling.master());
      fb.coupling_locked(spindle_coupling.locked() || axis_coupling.active());
      fb.cycle(cycle);
      fb.cmd(out.cmd);
      fb.act(out.act);
      // The drive's own velocity and following error when TPDO2 carries them.
      fb.vel(axis->tpdo2_velocity ? tpdo.velocity_actual / axis->counts_per_unit : out.vel);
      fb.statusword(in.statusword);
      fb.drive_state(to_wire(out.drive_state));
      fb.enabled(out.enabled);
      fb.following_error(axis->tpdo2_following_error
                             ? tpdo.following_error_actual / axis->counts_per_unit
                             : out.cmd - out.act);
      fb.last_emcy(link.last_emcy());
      fb.load_known(axis->tpdo2_torque);
      fb.load(axis->tpdo2_torque ? tpdo.torque_actual / 10.0 : 0.0);  // per mille -> percent
      fb.mode_display(out.mode_display);
      fb.alarm(out.alarm != axisnode::AxisAlarm::none);
      feedback_writer.write(fb);

      if (out.mode_changed) {
        tracer.emit(cycle, "mode", "\"axis\":\"%s\",\"mode\":\"%s\"", axis->name.c_str(),
                    axisnode::mode_name(out.mode_display));
      }
      if (out.drive_state_changed) {
        tracer.emit(cycle, "drive", "\"axis\":\"%s\",\"state\":\"%s\"", axis->name.c_str(),
                    drive_state_name(out.drive_state));
      }
      if (out.new_alarm != axisnode::AxisAlarm::none) {
        const int number = axisnode::kAlarmBase + static_cast<int>(out.new_alarm);
        const char* text = axisnode::to_text(out.new_alarm);
        char with_emcy[160];
        if (out.new_alarm == axisnode::AxisAlarm::drive_fault && link.last_emcy() != 0) {
          std::snprintf(with_emcy, sizeof with_emcy, "drive fault: EMCY 0x%04X %s",
                        link.last_emcy(), canopen::emcy_text(link.last_emcy()));
          text = with_emcy;
        }
        tracer.emit(cycle, "alarm", "\"number\":%d,\"text\":\"%s\",\"axis\":\"%s\"", number, text,
                    axis->name.c_str());
        node.raise_alarm(static_cast<std::uint32_t>(number), text, cycle, 0, axis->id);
      }
      if (cycle % static_cast<std::uint64_t>(trace_pos_every) == 0) {
        tracer.emit(cycle, "pos", "\"axis\":\"%s\",\"cmd\":%.6f,\"act\":%.6f", axis->name.c_str(),
                    out.cmd, out.act);
      }

      // 4. The bus: RPDO and SYNC, and in lockstep the drive's answer to this SYNC.
      link.exchange(axisnode::DriveCommand{out.controlword, out.target_counts,
                                           out.target_velocity_counts, out.mode},
                    lockstep && !degraded, tpdo.count, abandon_bus_wait,
                    std::chrono::milliseconds(stall_ms));
    }

    link.stop_sync_timer();
    link.send_rpdo(
        axisnode::DriveCommand{cia402::encode_controlword(cia402::Command::disable_voltage),
                               controller.output().target_counts, 0, controller.output().mode});
    link.send_nmt(canopen::NmtCommand::enter_preoperational);
    tracer.flush();
    spdlog::info("stopped: {} EMCY, {} malformed frames, {} trace events dropped",
                 link.emcy_count(), link.malformed_count(), tracer.dropped());
    if (pending_dropped > 0) {
      spdlog::warn("{} axis requests dropped (more waiting than the node keeps)", pending_dropped);
    }
    node.announce_stopped();
    // The drives leave last: a channel still waiting for this cycle's feedback when the run
    // stops would otherwise see its axis go before it has seen the stop, and raise alarm 1202
    // for what is only the end of the run. Its feedback writer stays until the channels have
    // gone (2 s at most; the launcher waits 3 s for every DDS process).
    const auto linger_end = std::chrono::steady_clock::now() + 2s;
    while (process::g_stop_signal == 0 && setpoint_reader.matched_writers() > 0 &&
           std::chrono::steady_clock::now() < linger_end) {
      std::this_thread::sleep_for(10ms);
    }
  } catch (const std::exception& e) {
    spdlog::error("{}", e.what());
    return 1;
  }
  return 0;
}
