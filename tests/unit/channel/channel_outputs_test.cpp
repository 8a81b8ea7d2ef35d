// ChannelOutputs (channel/wire), the adapter that puts what the controller decided on the wire
// and in the trace, over a real DDS participant: a reader of the test hears CH1's setpoints and
// status as its axis nodes and the launcher would (DDS domain of its own, network transport),
// and the trace file is read back. What it must do (channel_outputs.hpp): each cycle, every
// axis's setpoint of that cycle to that axis's node and the channel's status; each block start
// in the trace with its file and its line as written.
#include "channel/wire/channel_outputs.hpp"
#include "channel/control/channel_controller.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/motion/motion_planner.hpp"
#include "channel/setup/controller_setup.hpp"
#include "channel/setup/interpreter_setup.hpp"
#include "channel/setup/motion_setup.hpp"
#include "common/config/cyclic_routes.hpp"
#include "common/config/machine_config.hpp"
#include "common/trace/trace_writer.hpp"
#include "support/eventually.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <random>

namespace mcnc::channel {
namespace {

using namespace std::chrono_literals;
using test::eventually;

constexpr int kDomain = 221;

TEST(ChannelOutputs, EachCyclesSetpointsAndStatusGoOutAndEachBlockStartIsTraced) {
  const config::MachineConfig machine =
      config::load_machine_file(std::string(MCNC_SOURCE_DIR) + "/launch/machines/small_lathe.yaml");
  const config::ChannelConfig& ch = machine.channels[0];
  ControllerLayout layout = controller_layout_for(machine, ch);
  interp::InterpreterSource source(interpreter_config_for(machine, ch));
  ASSERT_FALSE(source.load("G01 X10 Z-5 F3000 (first move)\nG00 Z0\nM30\n", "T.nc"));
  motion::MotionPlanner planner(motion_config_for(machine, ch), interp::AxisVector{});
  ChannelController controller(layout.setup, source, planner);

  std::random_device rd;
  const std::string trace_path =
      (std::filesystem::temp_directory_path() / ("mcnc_outputs_" + std::to_string(rd()) + ".jsonl"))
          .string();
  process::ProcessNode node(kDomain, "CH1", dds::CyclicClock::lockstep, dds::Middleware::cyclonedds,
                            dds::LocalTransport::network);
  std::optional<trace::TraceWriter> tracer(std::in_place, trace_path, "CH1");
  SharedWriteLog writes;
  ChannelOutputs outputs(node, *tracer, ch, config::channel_names(machine), layout.axes,
                         layout.spindles, "T.nc", writes);

  // The axis nodes' and the launcher's side.
  dds::Participant wire(kDomain, "listener", dds::CyclicClock::lockstep,
                        dds::Middleware::cyclonedds, dds::LocalTransport::network);
  std::mutex mutex;
  std::map<std::pair<std::uint32_t, std::uint64_t>, double> heard;  // (axis, cycle) -> pos
  std::map<std::uint64_t, ::mcnc::ChannelStatus> statuses;
  dds::Reader<::mcnc::AxisSetpoint> setpoints(
      wire, dds::Keys::of(config::node_keys(layout.axes)),
      [&](const ::mcnc::AxisSetpoint& s, const dds::WriterId&) {
        std::lock_guard<std::mutex> lock(mutex);
        heard[{s.axis(), s.cycle()}] = s.pos();
      });
  dds::Reader<::mcnc::ChannelStatus> status(
      wire, dds::Keys::of({"CH1"}), [&](const ::mcnc::ChannelStatus& s, const dds::WriterId&) {
        std::lock_guard<std::mutex> lock(mutex);
        statuses[s.cycle()] = s;
      });
  ASSERT_TRUE(eventually(
      [&] { return outputs.setpoints_discovered() && status.matched_writers() > 0; }, 20s, 5ms));

  // The controller's cycles, on axes that follow; what it decided, by cycle.
  std::vector<AxisFeedbackView> views(layout.axes.size() + layout.spindles.size());
  for (auto& v : views) {
    v.enabled = v.present = true;
    v.owner = 1;
  }
  std::map<std::pair<std::uint32_t, std::uint64_t>, double> decided;
  controller.request_start();
  std::uint64_t cycle = 0;
  std::uint64_t end_cycle = 0;
  for (; cycle < 20000 && end_cycle == 0; ++cycle) {
    const CycleOutput& out = controller.cycle(cycle, views);
    outputs.publish(cycle, controller, out, views, 3, true);
    for (std::size_t a = 0; a < layout.axes.size(); ++a) {
      if (out.setpoints[a].valid) {
        decided[{static_cast<std::uint32_t>(layout.axes[a]->id), cycle}] = out.setpoints[a].pos;
        views[a].cmd = views[a].act = out.setpoints[a].pos;
      }
    }
    end_cycle = out.program_end ? cycle : 0;
  }
  ASSERT_NE(end_cycle, 0U) << "the program did not end";

  ASSERT_TRUE(eventually(
      [&] {
        std::lock_guard<std::mutex> lock(mutex);
        return statuses.count(end_cycle) == 1 && heard.size() >= decided.size();
      },
      20s, 5ms));
  std::lock_guard<std::mutex> lock(mutex);
  ASSERT_FALSE(decided.empty());
  for (const auto& [key, pos] : decided) {
    const auto it = heard.find(key);
    ASSERT_NE(it, heard.end()) << "axis " << key.first << " cycle " << key.second;
    EXPECT_DOUBLE_EQ(it->second, pos) << "axis " << key.first << " cycle " << key.second;
  }
  EXPECT_TRUE(statuses.at(end_cycle).program_end());
  EXPECT_EQ(statuses.at(end_cycle).end_code(), 30);
  EXPECT_EQ(statuses.at(end_cycle).block_total(), 3U);

  tracer.reset();  // flushed and closed
  std::ifstream in(trace_path);
  std::vector<nlohmann::json> blocks;
  for (std::string line; std::getline(in, line);) {
    const nlohmann::json e = nlohmann::json::parse(line, nullptr, false);
    if (!e.is_discarded() && e.value("ev", "") == "block") {
      blocks.push_back(e);
    }
  }
  std::filesystem::remove(trace_path);
  ASSERT_EQ(blocks.size(), 3U);
  EXPECT_EQ(blocks[0]["prog"], "T.nc");
  EXPECT_EQ(blocks[0]["line"], 1);
  EXPECT_EQ(blocks[0]["text"], "G01 X10 Z-5 F3000 (first move)");
  EXPECT_EQ(blocks[1]["text"], "G00 Z0");
  EXPECT_EQ(blocks[2]["line"], 3);
}

}  // namespace
}  // namespace mcnc::channel
