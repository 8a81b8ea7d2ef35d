// A channel's interpreter parameters from the machine file: the spindles it has.
#include "channel/setup/interpreter_setup.hpp"
#include "common/config/machine_config.hpp"

#include <gtest/gtest.h>

namespace mcnc::channel {
namespace {

config::MachineConfig machine() {
  return config::parse_machine_yaml(R"(
machine: {name: m, cycle_us: 4000}
buses: [{name: b, uri: "socketcan:can0", sync_producer: X1}]
channels:
  - {name: LATHE, axes: [X1, Z1], spindles: [S1]}
  - {name: LOADER, axes: [X2]}
axes:
  - {name: X1, address: X, diameter: true, bus: b, node_id: 1}
  - {name: Z1, address: Z, bus: b, node_id: 2}
  - {name: S1, type: spindle, bus: b, node_id: 3}
  - {name: X2, address: X, bus: b, node_id: 4}
)");
}

TEST(InterpreterSetup, SpindlesAreCounted) {
  const config::MachineConfig m = machine();
  EXPECT_EQ(interpreter_config_for(m, m.channels[0]).spindles, 1);
  EXPECT_EQ(interpreter_config_for(m, m.channels[1]).spindles, 0);  // known: none
}

}  // namespace
}  // namespace mcnc::channel
