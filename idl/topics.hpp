#pragma once
// The topic catalogue: every wire type with its topic name and QoS profile (ARCHITECTURE.md §7).
#include "mcnc.h"
#include "mcncPubSubTypes.h"

namespace mcnc::dds {

enum class QosKind { cyclic, state, event };

// Who reads a cyclic topic. A `consumer` (a lockstep peer) gets every sample, reliably. An
// `observer` (an HMI, a status view) gets the latest samples it keeps up with, best effort: no
// writer heartbeats it or repeats a sample for it, so an observer that falls behind cannot slow
// the machine. State and event topics are read reliably by both: their samples are few and
// none may be lost.
enum class ReaderRole { consumer, observer };

template <class T>
struct TopicTraits;

#define MCNC_TOPIC(Type, Kind)                         \
  template <>                                          \
  struct TopicTraits<::mcnc::Type> {                   \
    using PubSubType = ::mcnc::Type##PubSubType;       \
    static constexpr const char* name = "mcnc/" #Type; \
    static constexpr QosKind qos = QosKind::Kind;      \
  };

MCNC_TOPIC(AxisSetpoint, cyclic)
MCNC_TOPIC(AxisFeedback, cyclic)
MCNC_TOPIC(ChannelStatus, cyclic)
MCNC_TOPIC(Alarm, event)
MCNC_TOPIC(RunControl, state)
MCNC_TOPIC(ProcessState, state)
MCNC_TOPIC(OperatorCommand, event)
MCNC_TOPIC(CoordinationEvent, event)
MCNC_TOPIC(PlcStatus, cyclic)
MCNC_TOPIC(AuxAck, event)

#undef MCNC_TOPIC

}  // namespace mcnc::dds
