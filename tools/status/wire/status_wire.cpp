#include "tools/status/wire/status_wire.hpp"

#include <algorithm>
#include <cstring>

namespace mcnc::status {

ChannelView view_of(const ::mcnc::ChannelStatus& s) {
  ChannelView v;
  v.state = static_cast<channel::ChannelState>(static_cast<int>(s.state()));
  v.block = s.block();
  v.block_total = s.block_total();
  v.line = s.line();
  v.alarms = s.alarms();
  v.program_end = s.program_end();
  v.sync_p = s.sync_p();
  v.sync_waiting_for = s.sync_waiting_for();
  v.call_caller = s.call_caller();
  v.cycle = s.cycle();
  v.end_code = s.end_code();
  v.sync_channels = s.sync_channels();
  v.call_waiting_for = s.call_waiting_for();
  v.feed_override = s.feed_override();
  v.rapid_override = s.rapid_override();
  v.spindle_override = s.spindle_override();
  v.single_block = s.single_block();
  v.spindle_rpm = s.spindle_rpm();
  // NUL-terminated by the sender; a sample without the NUL is read up to its size.
  const auto& name = s.program();
  v.program.assign(name.data(), std::find(name.begin(), name.end(), '\0'));
  v.waiting_m = s.waiting_m();
  v.waiting_t = s.waiting_t();
  v.waiting_exchange = s.waiting_exchange();
  v.waiting_axis = s.waiting_axis();
  v.modal_g = s.modal_g();
  v.modal_feed = s.modal_feed();
  return v;
}

AxisView view_of(const ::mcnc::AxisFeedback& f) {
  AxisView v;
  v.cmd = f.cmd();
  v.act = f.act();
  v.vel = f.vel();
  v.following_error = f.following_error();
  v.enabled = f.enabled();
  v.alarm = f.alarm();
  v.owner = f.owner();
  v.released_by = f.released_by();
  v.coupled_to = f.coupled_to();
  v.coupling_locked = f.coupling_locked();
  v.load_known = f.load_known();
  v.load = f.load();
  v.mode_display = f.mode_display();
  v.cycle = f.cycle();
  v.drive_state = static_cast<std::uint8_t>(f.drive_state());
  return v;
}

}  // namespace mcnc::status
