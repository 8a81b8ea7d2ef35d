#include "channel/setup/interpreter_setup.hpp"

#include "channel/interp/dialect.hpp"

namespace mcnc::channel {

static_assert(config::kMaxProgramAxes == interp::kMaxChannelAxes,
              "the machine file allows as many program axes as a channel has slots");

interp::InterpreterConfig interpreter_config_for(const config::MachineConfig& machine,
                                                 const config::ChannelConfig& channel) {
  interp::InterpreterConfig c;
  // The machine file checked the name; the channel's axes below replace the mill's defaults.
  interp::select_dialect(c,
                         interp::dialect_named(channel.dialect).value_or(interp::Dialect::dafeng));
  c.channel = channel.id;
  c.spindles = static_cast<int>(channel.spindles.size());
  c.power_on_feed_mode =
      channel.feed_per_rev ? interp::FeedMode::per_rev : interp::FeedMode::per_min;
  c.channel_count = static_cast<int>(machine.channels.size());
  c.plc = machine.plc.present;
  for (const config::PlcSignal& s : machine.plc.signals) {
    if (!s.output && s.port > 0) {
      c.input_ports.push_back(s.port);
    }
    if (!s.output && s.skip > 0) {
      c.skip_signals[static_cast<std::size_t>(s.skip - 1)] = true;
    }
  }
  c.program_dir = machine.program_dir;
  c.polar_linear = channel.polar_linear;
  c.polar_rotary = channel.polar_rotary;
  c.polar_tolerance = channel.polar_tolerance;
  c.cylindrical_parallel = channel.cylindrical_parallel;
  c.normal_axis = channel.normal_axis;
  c.normal_feed = channel.normal_feed;
  c.inclined_axis = channel.inclined_axis;
  c.inclined_orthogonal = channel.inclined_orthogonal;
  c.inclined_degrees = channel.inclined_degrees;
  c.skip_input = channel.skip_input;
  c.torque_skip_percent = channel.torque_skip_limit;
  c.torque_skip_deviation = channel.torque_skip_deviation;
  const auto overload = [](const config::ChannelConfig::Overload& o) {
    return interp::OverloadParams{o.retract, o.retry, o.alarm, o.variable};
  };
  c.cycles.drill_overload = overload(channel.drill_overload);
  c.cycles.tap_overload = overload(channel.tap_overload);
  c.axes.clear();
  for (const std::string& name : channel.program_axes()) {
    const config::AxisConfig* a = machine.find_axis(name);
    interp::AxisConfig axis;
    axis.name = a->address;
    axis.diameter = a->diameter;
    axis.rotary = a->address == 'A' || a->address == 'B' || a->address == 'C';
    axis.exchange = a->exchange;
    axis.id = a->id;
    axis.may_follow = a->sync_slave;
    axis.probe_input = a->probe_input;
    axis.torque_skip = a->torque_skip;
    axis.skip_load = a->skip_load;
    axis.torque_mode_speed = a->torque_mode_speed;
    axis.torque_mode = a->torque_mode;
    axis.oscillation = a->oscillation;
    for (std::size_t s = 0; s < channel.spindles.size() && !a->spindle.empty(); ++s) {
      axis.spindle = channel.spindles[s] == a->spindle ? static_cast<int>(s) + 1 : axis.spindle;
    }
    c.axes.push_back(axis);
  }
  return c;
}

}  // namespace mcnc::channel
