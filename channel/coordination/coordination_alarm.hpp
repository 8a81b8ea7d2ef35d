#pragma once
// What a coordination state machine reports when a block cannot go on: the alarm number (listed
// with causes and remedies in docs/alarms.md), its text and the axis concerned. Fixed-size, as
// every machine here steps inside the channel's cycle.
#include <array>
#include <cstdarg>
#include <cstdio>

namespace mcnc::coordination {

inline constexpr int kAlarmCallBusy = 1220;          // G144: the target runs something else
inline constexpr int kAlarmCallFailed = 1221;        // G144: the called program stopped
inline constexpr int kAlarmCallRefused = 1222;       // G144: the target refused the call
inline constexpr int kAlarmCallCycle = 1223;         // G144: the target is this call's caller
inline constexpr int kAlarmCallTimeout = 1224;       // G144: the target did not become free
inline constexpr int kAlarmNotOwner = 1230;          // G140: the axis is not this channel's
inline constexpr int kAlarmAxisAway = 1231;          // a block moves an axis another channel has
inline constexpr int kAlarmRequestRefused = 1232;    // the axis node refused G140-G142 or is full
inline constexpr int kAlarmAuxRefused = 1240;        // the PLC refused an M or T code
inline constexpr int kAlarmAuxTimeout = 1241;        // no FIN from the PLC in time
inline constexpr int kAlarmSlaveSpindle = 1250;      // a spindle start of a G114.1 slave
inline constexpr int kAlarmSyncGroup = 1251;         // G114.1 K of a group this channel lacks
inline constexpr int kAlarmPolygon = 1252;           // G51.2 the channel or its axes do not allow
inline constexpr int kAlarmCam = 1253;               // G51.8 on a channel without a cam
inline constexpr int kAlarmEgb = 1254;               // G81.4 refused, or its gear lost
inline constexpr int kAlarmAxisSync = 1260;          // G51.4 / G50.4 the axes do not allow
inline constexpr int kAlarmAxisFollows = 1261;       // a block moves an axis that follows (G51.4)
inline constexpr int kAlarmSpindleNotAtRest = 1262;  // M18: the spindle did not come to rest
inline constexpr int kAlarmTorqueMode = 1263;  // a block moves an axis in torque mode (G10 L14 P10)

struct CoordinationAlarm {
  int number = 0;
  std::array<char, 192> text{};
  int axis = 0;  // channel axis index + 1 when an axis is concerned

  // The alarm `number` with a printf-formatted text (truncated to fit).
  __attribute__((format(printf, 3, 4))) void set(int alarm_number, const char* format,
                                                 ...) noexcept {
    number = alarm_number;
    axis = 0;
    va_list args;
    va_start(args, format);
    std::vsnprintf(text.data(), text.size(), format, args);
    va_end(args);
  }
};

}  // namespace mcnc::coordination
