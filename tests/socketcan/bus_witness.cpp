// The bus as a CANopen engineer reads it: checks a `candump -L` record of a machine run against
// what the machine file says must be on each bus. Standard tools are the witness; the
// expectations come from the machine file, never from the master's code (only CiA 301's
// COB-IDs and codes are shared with it):
//   - SYNC (0x080) every cycle of the run on each bus;
//   - per node, every SYNC interval of the cyclic phase carries its RPDO1 (0x200+node) and
//     TPDO1 (0x180+node), a spindle's RPDO2 (0x300+node) and, where the machine file maps
//     one, its TPDO2 (0x280+node): one SYNC per bus and cycle, 2 frames per axis, 3 per
//     spindle, one more per mapped TPDO2;
//   - heartbeats (0x700+node): a boot-up at power-on and after each NMT reset, then
//     "operational" every heartbeat_ms of SYNC time once the node is started;
//   - SDO at start-up (0x600+node requests, 0x580+node answers): each request answered before
//     the next, no abort, all before the node's NMT start;
//   - no frame with a COB-ID outside that set.
//   bus_witness MACHINE.yaml CANDUMP.log TRACE.jsonl
// Prints a line per check ("ok" or "FAIL"), exits 0 when all hold, 1 otherwise, 2 on bad input.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "canopen/frames.hpp"
#include "canopen/sdo_client.hpp"
#include "canopen/sdo_frames.hpp"
#include "common/config/machine_config.hpp"

namespace {

using mcnc::canopen::kHeartbeatBase;
using mcnc::canopen::kNmtId;
using mcnc::canopen::kRpdo1Base;
using mcnc::canopen::kRpdo2Base;
using mcnc::canopen::kSdoRequestBase;
using mcnc::canopen::kSdoResponseBase;
using mcnc::canopen::kSyncId;
using mcnc::canopen::kTpdo1Base;
using mcnc::canopen::kTpdo2Base;
using mcnc::canopen::NmtCommand;
using mcnc::canopen::NmtState;

struct Frame {
  std::string bus;  // interface, e.g. vcan0
  std::uint32_t id = 0;
  std::vector<std::uint8_t> data;
};

bool is_hex(const std::string& text) {
  return !text.empty() && text.find_first_not_of("0123456789abcdefABCDEF") == std::string::npos;
}

// "(1764770000.123456) vcan0 181#2700E8030000"; false when the line is not such a frame.
bool parse_candump_line(const std::string& line, Frame& out) {
  std::istringstream in(line);
  std::string stamp;
  std::string body;
  std::string rest;
  if (!(in >> stamp >> out.bus >> body) || (in >> rest) || stamp.front() != '(') {
    return false;
  }
  const auto hash = body.find('#');
  if (hash > 8 || !is_hex(body.substr(0, hash))) {  // no "#" is npos, above 8 too
    return false;
  }
  out.id = static_cast<std::uint32_t>(std::stoul(body.substr(0, hash), nullptr, 16));
  out.data.clear();
  const std::string hex = body.substr(hash + 1);
  if (!hex.empty() && hex[0] == 'R') {
    return true;  // remote frame, no data
  }
  if (hex.size() % 2 != 0 || hex.size() > 16 || (!hex.empty() && !is_hex(hex))) {
    return false;
  }
  for (std::size_t i = 0; i < hex.size(); i += 2) {
    out.data.push_back(static_cast<std::uint8_t>(std::stoul(hex.substr(i, 2), nullptr, 16)));
  }
  return true;
}

int failures = 0;

void check(bool ok, const std::string& what) {
  std::printf("%s%s\n", ok ? "ok   " : "FAIL ", what.c_str());
  if (!ok) {
    ++failures;
  }
}

std::string hex(std::uint32_t v) {
  char text[16];
  std::snprintf(text, sizeof text, "0x%03X", v);
  return text;
}

// The interface of a socketcan: URI ("socketcan:vcan0" -> "vcan0"); empty for other transports.
std::string interface_of(const std::string& uri) {
  const std::string scheme = "socketcan:";
  return uri.rfind(scheme, 0) == 0 ? uri.substr(scheme.size()) : std::string();
}

struct NodeExpectation {
  std::string axis;
  int node = 0;
  std::vector<std::uint32_t> cyclic;  // the PDO COB-IDs on the bus every cycle
  int heartbeat_ms = 0;
};

bool is_tpdo(std::uint32_t id) {
  const std::uint32_t base = id & 0x780;  // the function code, bits 10-7 of the COB-ID
  return base == kTpdo1Base || base == kTpdo2Base;
}

// An NMT command to `node` (or to all, node 0).
bool is_nmt(const Frame& f, NmtCommand command, std::uint32_t node) {
  return f.id == kNmtId && f.data.size() == 2 && f.data[0] == static_cast<std::uint8_t>(command) &&
         (f.data[1] == node || f.data[1] == 0);
}

// The index of the first NMT start of `node`; frames.size() when there is none.
std::size_t nmt_start(const std::vector<Frame>& frames, std::uint32_t node) {
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (is_nmt(frames[i], NmtCommand::start, node)) {
      return i;
    }
  }
  return frames.size();
}

// The index of the NMT command that ends the run `node` started at frame `start` (stop,
// pre-operational or a reset); frames.size() when its run is not ended on the record.
std::size_t nmt_end(const std::vector<Frame>& frames, std::size_t start, std::uint32_t node) {
  for (std::size_t i = start + 1; i < frames.size(); ++i) {
    if (is_nmt(frames[i], NmtCommand::stop, node) ||
        is_nmt(frames[i], NmtCommand::enter_preoperational, node) ||
        is_nmt(frames[i], NmtCommand::reset_node, node) ||
        is_nmt(frames[i], NmtCommand::reset_communication, node)) {
      return i;
    }
  }
  return frames.size();
}

// The end of a node's cyclic phase: its master's last setpoint (RPDO1) before the NMT command
// that ends its run. The master sends that last setpoint as it stops, out of the SYNC rhythm, and
// the drive sends no PDO after the NMT command (CiA 301); the SYNC producer, another node's
// master, may go on for a cycle or two. So only the intervals closed before it are complete.
std::size_t cyclic_end(const std::vector<Frame>& frames, std::size_t ended, std::uint32_t node) {
  for (std::size_t i = ended; i-- > 0;) {
    if (frames[i].id == kRpdo1Base + node) {
      return i;
    }
  }
  return ended;
}

// The position in `syncs` (frame indices of SYNCs) of the first SYNC after frame `index`.
std::size_t first_sync_after(const std::vector<std::size_t>& syncs, std::size_t index) {
  return static_cast<std::size_t>(std::upper_bound(syncs.begin(), syncs.end(), index) -
                                  syncs.begin());
}

void check_bus(const mcnc::config::MachineConfig& machine, const mcnc::config::BusConfig& bus,
               const std::vector<Frame>& all, std::uint64_t cycles) {
  const std::string itf = interface_of(bus.uri);
  std::vector<Frame> frames;
  for (const auto& f : all) {
    if (f.bus == itf) {
      frames.push_back(f);
    }
  }
  std::vector<NodeExpectation> nodes;
  for (const auto& axis : machine.axes) {
    if (axis.bus != bus.name) {
      continue;
    }
    NodeExpectation e{axis.name, axis.node_id, {}, axis.heartbeat_ms};
    const auto n = static_cast<std::uint32_t>(axis.node_id);
    e.cyclic = {kRpdo1Base + n, kTpdo1Base + n};
    if (axis.type == mcnc::config::AxisType::spindle) {
      e.cyclic.push_back(kRpdo2Base + n);  // target velocity
    }
    if (mcnc::config::tpdo2_bytes(axis) > 0) {
      e.cyclic.push_back(kTpdo2Base + n);
    }
    nodes.push_back(e);
  }
  const std::string on = bus.name + " (" + itf + ")";

  // COB-IDs the machine file accounts for.
  std::set<std::uint32_t> known = {kNmtId, kSyncId};
  for (const auto& e : nodes) {
    const auto n = static_cast<std::uint32_t>(e.node);
    known.insert(e.cyclic.begin(), e.cyclic.end());
    known.insert({kSdoRequestBase + n, kSdoResponseBase + n, kHeartbeatBase + n});
  }
  std::map<std::uint32_t, int> strangers;
  for (const auto& f : frames) {
    if (known.count(f.id) == 0) {
      ++strangers[f.id];
    }
  }
  std::string stranger_text;
  for (const auto& [id, count] : strangers) {
    stranger_text += " " + hex(id) + " x" + std::to_string(count);
  }
  check(!frames.empty() && strangers.empty(),
        on + ": " + std::to_string(frames.size()) +
            " frames, none outside what the machine file accounts for" +
            (stranger_text.empty() ? "" : ":" + stranger_text));

  // SYNC: every cycle; the frame's position is the interval boundary.
  std::vector<std::size_t> syncs;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (frames[i].id == kSyncId) {
      syncs.push_back(i);
    }
  }
  check(syncs.size() >= cycles, on + ": a SYNC on " + hex(kSyncId) + " every cycle (" +
                                    std::to_string(syncs.size()) + " SYNC, " +
                                    std::to_string(cycles) + " cycles)");

  // Frames per cycle, as the machine file counts them: SYNC plus each node's cyclic PDOs,
  // over the SYNC intervals in which every node of the bus is started (the last SYNC's
  // interval is cut short by the stop and is not counted).
  std::vector<std::size_t> started;  // per node, the frame of its NMT start
  std::vector<std::size_t> ended;    // per node, the NMT command that ends its run
  std::vector<std::size_t> cyclic_ends;
  std::size_t all_started = 0;
  std::size_t first_end = frames.size();
  std::set<std::uint32_t> cyclic = {kSyncId};
  for (const auto& e : nodes) {
    const auto n = static_cast<std::uint32_t>(e.node);
    started.push_back(nmt_start(frames, n));
    ended.push_back(nmt_end(frames, started.back(), n));
    cyclic_ends.push_back(cyclic_end(frames, ended.back(), n));
    all_started = std::max(all_started, started.back());
    first_end = std::min(first_end, cyclic_ends.back());
    cyclic.insert(e.cyclic.begin(), e.cyclic.end());
  }
  const std::size_t from = first_sync_after(syncs, all_started);
  // The last SYNC that closes an interval before the first node's cyclic phase ends.
  const std::size_t to = first_sync_after(syncs, first_end) - 1;
  long long counted = 0;
  const long long intervals =
      to != static_cast<std::size_t>(-1) && to > from ? static_cast<long long>(to - from) : 0;
  if (intervals > 0) {
    for (std::size_t i = syncs[from]; i < syncs[to]; ++i) {
      counted += static_cast<long long>(cyclic.count(frames[i].id));
    }
  }
  const auto per_cycle = static_cast<long long>(cyclic.size());
  // Only a drive's TPDOs may be missing, in the first interval after its start.
  const auto tpdos = static_cast<long long>(std::count_if(cyclic.begin(), cyclic.end(), is_tpdo));
  check(
      intervals > 0 && counted <= per_cycle * intervals && counted >= per_cycle * intervals - tpdos,
      on + ": " + std::to_string(per_cycle) + " frames a cycle as the machine file says (" +
          std::to_string(counted) + " in " + std::to_string(intervals) + " cycles)");

  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const auto& e = nodes[j];
    const auto n = static_cast<std::uint32_t>(e.node);
    const std::string who = on + " node " + std::to_string(e.node) + " (" + e.axis + ")";
    // NMT start of the node: the end of its start-up, the start of its cyclic phase.
    const std::size_t start = started[j];
    check(start < frames.size(), who + ": NMT start (000#01" + hex(n).substr(3) + ")");

    // SDO: request, answer, request, answer ... all before the NMT start, none refused.
    int requests = 0;
    int answers = 0;
    int aborts = 0;
    bool alternating = true;
    bool before_start = true;
    bool reads_device_type_first = false;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const auto& f = frames[i];
      if (f.id == kSdoRequestBase + n) {
        if (requests == 0) {
          reads_device_type_first = f.data.size() == 8 && f.data[0] == 0x40 && f.data[1] == 0x00 &&
                                    f.data[2] == 0x10 && f.data[3] == 0x00;
        }
        alternating &= requests == answers;
        ++requests;
        before_start &= i < start;
      } else if (f.id == kSdoResponseBase + n) {
        alternating &= answers + 1 == requests;
        ++answers;
        aborts += !f.data.empty() && f.data[0] == mcnc::canopen::sdo::kAbort;
        before_start &= i < start;
      }
    }
    check(requests >= 3 && reads_device_type_first,
          who + ": SDO requests on " + hex(kSdoRequestBase + n) +
              " at start-up, device type 0x1000 first (" + std::to_string(requests) + ")");
    check(answers == requests && alternating && aborts == 0,
          who + ": each answered on " + hex(kSdoResponseBase + n) + " before the next, no abort (" +
              std::to_string(answers) + " answers, " + std::to_string(aborts) + " aborts)");
    check(before_start, who + ": all SDO traffic before the NMT start");

    // The cyclic phase: from the first SYNC after the NMT start to the last SYNC before its
    // end (cyclic_end). Every interval between two SYNCs carries each cyclic PDO once; the
    // interval after the last of them is not complete and is not counted.
    const std::size_t first = first_sync_after(syncs, start);
    const std::size_t last = first_sync_after(syncs, cyclic_ends[j]);  // one past
    for (const std::uint32_t id : e.cyclic) {
      const bool transmitted = is_tpdo(id);
      int intervals = 0;
      int once = 0;
      int missing = 0;
      int doubled = 0;
      for (std::size_t k = first; k + 1 < last; ++k) {
        int count = 0;
        for (std::size_t i = syncs[k] + 1; i < syncs[k + 1]; ++i) {
          count += frames[i].id == id;
        }
        ++intervals;
        once += count == 1;
        // The master's RPDO of the interval's cycle goes out before the next SYNC; a drive's
        // TPDO answers the SYNC that opens the interval, so only a TPDO may be missing, in the
        // first interval after the start (the last SYNC's interval is not counted at all).
        missing += count == 0 && (k != first || !transmitted);
        doubled += count > 1;
      }
      check(intervals > 0 && missing == 0 && doubled == 0,
            who + ": " + hex(id) + " once in every SYNC interval (" + std::to_string(once) +
                " of " + std::to_string(intervals) + ", " + std::to_string(missing) + " without, " +
                std::to_string(doubled) + " with more)");
    }

    // Heartbeats: a boot-up (state 0) at power-on and after each NMT reset, then one every
    // heartbeat_ms of SYNC time while the node runs: from the NMT start to the NMT command
    // that ends its run (after that it reports the state it was put in, CiA 301).
    int bootups = 0;
    int beats = 0;        // "operational" (0x05) while it runs
    int other_after = 0;  // any other state while it runs
    int resets = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
      const auto& f = frames[i];
      if (f.id == kHeartbeatBase + n && f.data.size() == 1) {
        if (f.data[0] == static_cast<std::uint8_t>(NmtState::bootup)) {
          ++bootups;
        } else if (i > start && i < ended[j]) {
          (f.data[0] == static_cast<std::uint8_t>(NmtState::operational) ? beats : other_after) +=
              1;
        }
      }
      resets +=
          is_nmt(f, NmtCommand::reset_node, n) || is_nmt(f, NmtCommand::reset_communication, n);
    }
    const std::uint64_t cyclic_syncs = syncs.size() - first;
    const long long expected = e.heartbeat_ms > 0
                                   ? static_cast<long long>(cyclic_syncs) * machine.cycle_us /
                                         (static_cast<long long>(e.heartbeat_ms) * 1000)
                                   : 0;
    check(resets >= 1 && bootups == resets + 1, who + ": a boot-up on " + hex(kHeartbeatBase + n) +
                                                    " at power-on and after each of the " +
                                                    std::to_string(resets) + " NMT resets (" +
                                                    std::to_string(bootups) + ")");
    check(other_after == 0 && beats >= expected - 2 && beats <= expected + 3,
          who + ": operational (0x05) every " + std::to_string(e.heartbeat_ms) +
              " ms of SYNC time after the start (" + std::to_string(beats) + ", expected about " +
              std::to_string(expected) + "; " + std::to_string(other_after) + " in another state)");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: bus_witness MACHINE.yaml CANDUMP.log TRACE.jsonl\n");
    return 2;
  }
  try {
    const auto machine = mcnc::config::load_machine_file(argv[1]);
    std::vector<Frame> frames;
    std::ifstream dump(argv[2]);
    if (!dump) {
      std::fprintf(stderr, "bus_witness: cannot read %s\n", argv[2]);
      return 2;
    }
    int number = 0;
    for (std::string line; std::getline(dump, line);) {
      ++number;
      Frame f;
      if (line.empty()) {
        continue;
      }
      if (!parse_candump_line(line, f)) {
        std::fprintf(stderr, "bus_witness: %s:%d: not a candump -L frame: %s\n", argv[2], number,
                     line.c_str());
        return 2;
      }
      frames.push_back(std::move(f));
    }
    std::uint64_t cycles = 0;
    std::ifstream trace(argv[3]);
    if (!trace) {
      std::fprintf(stderr, "bus_witness: cannot read %s\n", argv[3]);
      return 2;
    }
    for (std::string line; std::getline(trace, line);) {
      const auto event = nlohmann::json::parse(line, nullptr, false);
      if (event.is_object() && event.contains("cycles") && event.contains("ok")) {
        cycles = event["cycles"].get<std::uint64_t>();
      }
    }
    check(cycles > 0, "the trace has the run's summary (" + std::to_string(cycles) + " cycles)");
    for (const auto& bus : machine.buses) {
      if (interface_of(bus.uri).empty()) {
        std::fprintf(stderr, "bus_witness: bus %s is not on socketcan (%s)\n", bus.name.c_str(),
                     bus.uri.c_str());
        return 2;
      }
      check_bus(machine, bus, frames, cycles);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bus_witness: %s\n", e.what());
    return 2;
  }
  return failures == 0 ? 0 : 1;
}
