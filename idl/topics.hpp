#pragma once
// The topic catalogue: every wire type with its topic name and QoS profile (ARCHITECTURE.md §7).
#include "mcnc.h"
#include "mcncPubSubTypes.h"

#include <string>
#include <utility>
#include <vector>

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

// Where the samples of a routed topic travel (ARCHITECTURE.md §7: a cyclic sample goes only to
// the readers that use it). Each key (an axis, a channel) has a DDS partition of its name: a
// writer writes in its key's, a reader reads the partitions of the keys it uses, and an observer
// (the HMI, `mcnc status`, the launcher) reads them all. Partitions, not per-key topics: the
// topic names and keys stay `mcnc/<Name>` and the matching is done once, at discovery, by both
// DDS implementations alike, so a sample is never sent to a process that would drop it.
struct Partitions {
  std::vector<std::string> names;
  static Partitions of(std::vector<std::string> keys) { return Partitions{std::move(keys)}; }
  static Partitions all() { return Partitions{{"*"}}; }
};

template <class T>
struct TopicTraits;

// `routed`: its writers and readers name their partitions (the constructors without them do not
// compile for it, so that no reader of a routed topic silently hears nothing).
#define MCNC_TOPIC(Type, Kind, Routed)                 \
  template <>                                          \
  struct TopicTraits<::mcnc::Type> {                   \
    using PubSubType = ::mcnc::Type##PubSubType;       \
    static constexpr const char* name = "mcnc/" #Type; \
    static constexpr QosKind qos = QosKind::Kind;      \
    static constexpr bool routed = Routed;             \
  };

MCNC_TOPIC(AxisSetpoint, cyclic, true)
MCNC_TOPIC(AxisFeedback, cyclic, true)
MCNC_TOPIC(ChannelStatus, cyclic, true)
MCNC_TOPIC(Alarm, event, false)
MCNC_TOPIC(RunControl, state, false)
MCNC_TOPIC(ProcessState, state, false)
MCNC_TOPIC(OperatorCommand, event, false)
MCNC_TOPIC(CoordinationEvent, event, false)
MCNC_TOPIC(PlcStatus, cyclic, false)  // one writer, read by every channel: nothing to route
MCNC_TOPIC(AuxAck, event, false)

#undef MCNC_TOPIC

}  // namespace mcnc::dds
