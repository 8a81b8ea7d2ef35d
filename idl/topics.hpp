#pragma once
// The topic catalogue: every wire type with its topic name and QoS profile (ARCHITECTURE.md §7).
#include "mcnc.h"
#include "mcncPubSubTypes.h"

namespace mcnc::dds {

enum class QosKind { cyclic, state, event };

// Who reads a cyclic topic. A `consumer` (a lockstep peer) gets every sample, reliably, and the
// writers' recent history when it matches. An `observer` (the HMI's axis view, the launcher's
// view of the run) gets the latest samples it keeps up with, best effort, and only those
// written after it matched: no writer repeats a sample for it or counts on its
// acknowledgements, so an observer that falls behind adds nothing to the machine's work. State
// and event topics are read reliably by both: their samples are few and none may be lost.
enum class ReaderRole { consumer, observer };

// Which clock a participant's cyclic writers serve. A realtime consumer must have a lost sample
// repaired within its deadline, so the writers heartbeat every 20 ms. A lockstep consumer only
// waits for the repair, while every heartbeat is work for every reader whether the machine
// moves or not, which a loaded host can ill afford: lockstep writers heartbeat every 100 ms
// (docs/decisions.md 27).
enum class CyclicClock { realtime, lockstep };

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
