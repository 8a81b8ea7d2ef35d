// Cost of one cycle of the pure cores (no DDS, no CAN): what each process spends computing.
#include "axisnode/control/axis_node_controller.hpp"
#include "axisnode/drivesim/drive_bus_simulator.hpp"
#include "canopen/cia402/drive_pdos.hpp"
#include "canopen/frames.hpp"
#include "channel/control/channel_controller.hpp"
#include "channel/interp/interpreter_source.hpp"
#include "channel/motion/motion_planner.hpp"
#include "common/cycle/lockstep_gate.hpp"

#include <benchmark/benchmark.h>

#include <array>
#include <string>

using namespace mcnc;

namespace {

interp::InterpreterConfig xz_channel() {
  interp::InterpreterConfig c;
  c.axes = {interp::AxisConfig{'X', true}, interp::AxisConfig{'Z', false}};
  return c;
}

std::string long_program(int blocks) {
  std::string text = "%\nO0001\n";
  for (int i = 0; i < blocks; ++i) {
    text += "G01 X" + std::to_string(20 + i % 40) + ". Z-" + std::to_string(i % 50) + ". F3000\n";
  }
  return text + "M30\n%\n";
}

void BM_ChannelControllerCycle(benchmark::State& state) {
  interp::InterpreterSource interpreter(xz_channel());
  interpreter.load(long_program(100000), "bench.nc");
  motion::MotionConfig motion;
  motion.axis_count = 2;
  for (std::size_t i = 0; i < 2; ++i) {
    motion.axes[i] = motion::AxisDynamics{100.0, 1000.0, 50000.0};
    motion.rapid_rate[i] = 100.0;
  }
  motion::MotionPlanner planner(motion, interp::AxisVector{});
  channel::ChannelSetup setup{2, {1e9, 1e9}, 0.001};  // in position at once: the cost is the path
  channel::ChannelController controller(setup, interpreter, planner);
  std::array<channel::AxisFeedbackView, 2> feedback{};
  for (auto& f : feedback) {
    f = channel::AxisFeedbackView{0.0, 0.0, true, false, true};
  }
  controller.request_start();
  std::uint64_t cycle = 0;
  for (auto _ : state) {
    const auto& out = controller.cycle(cycle++, feedback);
    benchmark::DoNotOptimize(out.setpoints[0].pos);
  }
}
BENCHMARK(BM_ChannelControllerCycle);

void BM_AxisNodeControllerWithDrive(benchmark::State& state) {
  axisnode::AxisNodeController node(axisnode::AxisNodeSetup{10000.0, 0.001, 5});
  drivesim::SimulatedDrive drive(drivesim::DriveParams{}, 0.001);
  drive.power_on();
  drive.on_nmt(canopen::NmtCommand::start);
  canopen::TxPdoCsp tpdo{};
  std::uint64_t cycle = 0;
  for (auto _ : state) {
    axisnode::AxisNodeInput in;
    in.have_setpoint = true;
    in.setpoint_valid = true;
    in.setpoint_pos = static_cast<double>(cycle % 1000) * 0.01;
    in.have_tpdo = true;
    in.statusword = tpdo.statusword;
    in.position_counts = tpdo.position_actual;
    const auto& out = node.cycle(cycle++, in);
    drive.on_rpdo(canopen::RxPdoCsp{out.controlword, out.target_counts});
    tpdo = drive.on_sync();
    benchmark::DoNotOptimize(tpdo);
  }
}
BENCHMARK(BM_AxisNodeControllerWithDrive);

void BM_LockstepGateTenInputs(benchmark::State& state) {
  cycle::LockstepGate gate(10);
  std::uint64_t cycle = 1;
  for (auto _ : state) {
    for (std::size_t i = 0; i < 10; ++i) {
      gate.on_sample(i, cycle - 1, 0);
    }
    benchmark::DoNotOptimize(gate.may_run(cycle++));
  }
}
BENCHMARK(BM_LockstepGateTenInputs);

void BM_RpdoEncodeDecode(benchmark::State& state) {
  std::int32_t target = 0;
  for (auto _ : state) {
    const auto frame = canopen::encode_rpdo_csp(3, canopen::RxPdoCsp{0x0F, target++});
    benchmark::DoNotOptimize(canopen::decode_rpdo_csp(frame));
  }
}
BENCHMARK(BM_RpdoEncodeDecode);

void BM_InterpreterLoad1000Blocks(benchmark::State& state) {
  const std::string text = long_program(1000);
  for (auto _ : state) {
    interp::Interpreter interpreter(xz_channel());
    benchmark::DoNotOptimize(interpreter.start(text, "bench.nc"));
  }
  state.SetItemsProcessed(state.iterations() * 1000);
}
BENCHMARK(BM_InterpreterLoad1000Blocks);

}  // namespace

BENCHMARK_MAIN();
