#pragma once
// The topic catalogue: every wire type with its topic name and QoS profile (ARCHITECTURE.md §7).
#include "mcnc.h"
#include "mcncPubSubTypes.h"

namespace mcnc::dds {

enum class QosKind { cyclic, state, event };

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
