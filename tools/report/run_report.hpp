#pragma once
// The run report of `mcnc run --report DIR` (docs/report.md): from a run's event trace
// (docs/trace.md), a timeline of every channel (its blocks, waits, holds and alarms, its G04.1
// sync points, the axes it took or gave up) and a toolpath per channel in the ZX plane, as SVG,
// and an HTML page with both, the cycle times and the alarms. Pure: trace events in, text out.
#include "common/config/machine_config.hpp"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace mcnc::report {

using Trace = std::vector<nlohmann::json>;

// One lane per channel, time to the right (machine time: cycles x cycle_us). Elements carry
// classes for what they show: `block` (data-line), `wait`, `hold`, `alarm`, `sync` (data-p) and
// `owner` (data-axis), each in a group with data-channel.
std::string timeline_svg(const config::MachineConfig& machine, const Trace& trace);

// The path of the channel's X and Z axes (the axis nodes' `pos` samples; X as a radius), Z to
// the right and X up: one `toolpath` path, and a `sync` circle (data-p) where the channel stood
// at each of its sync points. Empty when the channel has no X and Z or no samples.
std::string toolpath_svg(const config::MachineConfig& machine, const Trace& trace,
                         const std::string& channel);

// The page: the machine, each channel's result and cycle time, the alarms, the timeline and the
// toolpaths (inline).
std::string report_html(const config::MachineConfig& machine, const Trace& trace);

}  // namespace mcnc::report
