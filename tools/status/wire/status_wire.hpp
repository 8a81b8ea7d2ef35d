#pragma once
// The status topics' samples as the status views (adapter: `mcnc status` and mcnc-hmi fill a
// StatusSnapshot with these).
#include "idl/topics.hpp"
#include "tools/status/status_lines.hpp"

namespace mcnc::status {

ChannelView view_of(const ::mcnc::ChannelStatus& s);
AxisView view_of(const ::mcnc::AxisFeedback& f);

}  // namespace mcnc::status
