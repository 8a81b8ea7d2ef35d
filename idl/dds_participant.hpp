#pragma once
// The typed publish/subscribe layer, over Fast DDS or Cyclone DDS (docs/decisions.md 32): one
// Participant per process, of the middleware it is told; Writer<T> and Reader<T> take their
// topic name and QoS profile from the topic catalogue (topics.hpp), and for a routed topic the
// partition they write in or read. Both middlewares speak the same wire (RTPS, the same IDL,
// XCDR1), so processes on either meet.
// Reader callbacks run on a middleware thread: hand the data to your own thread, do not block.
#include "common/security/identity_files.hpp"
#include "idl/topics.hpp"

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace mcnc::dds {

// Identifies one remote writer (its DDS instance handle), to tell whose samples are whose.
using WriterId = std::array<std::uint8_t, 16>;

// The QoS profiles file: MCNC_QOS_PROFILES if set, else the one in the source tree.
std::string qos_profiles_path();

enum class Middleware { fastdds, cyclonedds };
// "fastdds" or "cyclonedds"; nullopt for anything else.
std::optional<Middleware> parse_middleware(std::string_view name) noexcept;
const char* middleware_name(Middleware middleware) noexcept;
// The middleware a process runs on: MCNC_MIDDLEWARE (set by mcnc-launch from the machine
// file's `middleware:`), else the default. Throws std::runtime_error naming a bad value.
Middleware middleware_from_env();
enum class LocalTransport { shared_memory, network };

// The default when nothing chooses: the one the figures show to be better (docs/decisions.md
// 36).
inline constexpr Middleware kDefaultMiddleware = Middleware::cyclonedds;

// A Cyclone DDS process moves its cyclic samples through iceoryx shared memory, brokered by the
// host's RouDi (iox-roudi). Without one, creating a participant would block for ever: the
// Participant checks first and throws. True while a RouDi answers on its socket.
inline constexpr const char* kRoudiSocket = "/tmp/roudi";
bool roudi_answers() noexcept;

namespace detail {
// A wire type as each middleware knows it: `fastdds` is a new'd Fast DDS TopicDataType, owned by
// whoever it is handed to; `cyclonedds` is idlc's descriptor of the same IDL type.
struct TypeSupport {
  void* fastdds = nullptr;
  const struct dds_topic_descriptor* cyclonedds = nullptr;
};

using SampleFn = std::function<void(const void* sample, const WriterId& writer)>;
using MatchFn = std::function<void(const WriterId& writer, bool matched)>;
struct ReaderCallbacks {
  std::function<void*()> make_sample;  // a new T
  std::function<void(void*)> free_sample;
  SampleFn on_sample;
  MatchFn on_match;
};

class WriterImpl {
 public:
  virtual ~WriterImpl() = default;
  virtual bool write(const void* sample) noexcept = 0;
  [[nodiscard]] virtual int matched_readers() const noexcept = 0;
};

// Once destroyed, its callbacks are never called again.
class ReaderImpl {
 public:
  virtual ~ReaderImpl() = default;
  [[nodiscard]] virtual int matched_writers() const noexcept = 0;
};

class ParticipantImpl {
 public:
  virtual ~ParticipantImpl() = default;
  // An empty `partitions` is the default partition (the unrouted topics).
  virtual std::unique_ptr<WriterImpl> writer(const char* topic, TypeSupport type, QosKind qos,
                                             const Partitions& partitions) = 0;
  virtual std::unique_ptr<ReaderImpl> reader(const char* topic, TypeSupport type, QosKind qos,
                                             ReaderRole role, const Partitions& partitions,
                                             ReaderCallbacks callbacks) = 0;
  [[nodiscard]] virtual std::chrono::nanoseconds lease() const = 0;
  // Makes sure every reliable reader of this participant's cyclic writers learns of their
  // latest sample, for a lockstep process that waits (Participant::announce_latest_cyclic).
  virtual void announce_latest_cyclic() noexcept = 0;
};

// The key of a set of partitions, by which an implementation keeps one publisher or subscriber
// per set: the names joined with '\n' ("" is the default partition).
std::string partition_key(const Partitions& partitions);

// `security`: DDS Security's builtin plugins (PKI-DH, permissions, AES-GCM-GMAC) with these
// files; null: an unsecured participant.
std::unique_ptr<ParticipantImpl> make_fastdds_participant(int domain, const std::string& name,
                                                          CyclicClock clock,
                                                          const security::IdentityFiles* security);
std::unique_ptr<ParticipantImpl> make_cyclonedds_participant(
    int domain, const std::string& name, CyclicClock clock, bool shared_memory,
    const security::IdentityFiles* security);
}  // namespace detail

class Participant {
 public:
  // Throws std::runtime_error when the participant cannot be created (start-up error), among
  // them a Cyclone DDS participant with shared memory and no RouDi to answer. `local` says
  // how its samples meet the processes of its host on Cyclone DDS: a process on the machine's
  // cyclic path uses shared memory; an onlooker (the launcher, `mcnc status`) uses the network,
  // needs no RouDi, and is not among the processes RouDi ends when it stops. The first
  // participant of a domain in a process decides for every other. With `security` it joins a
  // secured machine with that identity (docs/operations.md, "Security"): it meets only
  // participants the machine's CA vouches for, and writes only what its grant allows.
  Participant(int domain, const std::string& name, CyclicClock clock = CyclicClock::realtime,
              std::optional<Middleware> middleware = std::nullopt,
              LocalTransport local = LocalTransport::shared_memory,
              std::optional<security::IdentityFiles> security = std::nullopt);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  [[nodiscard]] Middleware middleware() const noexcept { return middleware_; }
  // For a lockstep process that has waited a while for its inputs: every reliable reader of
  // its cyclic writers learns of their latest sample, so one that lost it asks for it again.
  // A lockstep writer writes nothing new until its inputs come, so without this a reader that
  // lost the last sample and missed the writer's heartbeats would wait for ever (decision 98).
  // Call it from the thread that writes the cyclic samples, not under the wake-up lock.
  void announce_latest_cyclic() noexcept { impl_->announce_latest_cyclic(); }
  detail::ParticipantImpl& impl() noexcept { return *impl_; }
  [[nodiscard]] const detail::ParticipantImpl& impl() const noexcept { return *impl_; }

 private:
  Middleware middleware_;
  std::unique_ptr<detail::ParticipantImpl> impl_;
};

// How long peers wait before they declare this participant gone (from the QoS profile).
std::chrono::nanoseconds participant_lease(const Participant& participant);

namespace detail {
class WriterBase {
 public:
  WriterBase(Participant& participant, const std::string& topic, TypeSupport type, QosKind qos)
      : impl_(participant.impl().writer(topic.c_str(), type, qos, Partitions{})) {}
  bool write_raw(const void* sample) noexcept { return impl_->write(sample); }
  [[nodiscard]] int matched_readers() const noexcept { return impl_->matched_readers(); }

 private:
  std::unique_ptr<WriterImpl> impl_;
};

// One reader of the topics `topics` (one topic, or a routed topic's keys), all calling the same
// callbacks.
class ReaderBase {
 public:
  ReaderBase(Participant& participant, const std::vector<std::string>& topics,
             TypeSupport (*type)(), QosKind qos, ReaderRole role,
             const ReaderCallbacks& callbacks) {
    for (const std::string& topic : topics) {
      impls_.push_back(
          participant.impl().reader(topic.c_str(), type(), qos, role, Partitions{}, callbacks));
    }
  }
  // Over all its topics.
  [[nodiscard]] int matched_writers() const noexcept {
    int n = 0;
    for (const auto& impl : impls_) {
      n += impl->matched_writers();
    }
    return n;
  }

 private:
  std::vector<std::unique_ptr<ReaderImpl>> impls_;
};

template <class T>
TypeSupport type_support() {
  return TypeSupport{new typename TopicTraits<T>::PubSubType(), TopicTraits<T>::cyclonedds()};
}

inline std::vector<std::string> keyed_topics(const char* topic, const Keys& keys) {
  std::vector<std::string> topics;
  topics.reserve(keys.names.size());
  for (const std::string& key : keys.names) {
    topics.push_back(keyed_topic(topic, key));
  }
  return topics;
}
}  // namespace detail

template <class T>
class Writer {
 public:
  explicit Writer(Participant& participant) requires(!TopicTraits<T>::routed)
      : base_(participant, TopicTraits<T>::name, detail::type_support<T>(), TopicTraits<T>::qos) {}
  // A routed topic's writer writes on the topic of its key (an axis node's or channel's name).
  Writer(Participant& participant, const std::string& key) requires TopicTraits<T>::routed
      : base_(participant, keyed_topic(TopicTraits<T>::name, key), detail::type_support<T>(),
              TopicTraits<T>::qos) {}
  bool write(const T& sample) noexcept { return base_.write_raw(&sample); }
  [[nodiscard]] int matched_readers() const noexcept { return base_.matched_readers(); }

 private:
  detail::WriterBase base_;
};

template <class T>
class Reader {
 public:
  using SampleFn = std::function<void(const T&, const WriterId&)>;
  using MatchFn = detail::MatchFn;
  Reader(Participant& participant, SampleFn on_sample, MatchFn on_match = {},
         ReaderRole role = ReaderRole::consumer) requires(!TopicTraits<T>::routed)
      : Reader(participant, {TopicTraits<T>::name}, std::move(on_sample), std::move(on_match), role,
               0) {}
  // A routed topic's reader hears the writers of the keys it names, and only them.
  Reader(Participant& participant, const Keys& keys, SampleFn on_sample, MatchFn on_match = {},
         ReaderRole role = ReaderRole::consumer) requires TopicTraits<T>::routed
      : Reader(participant, detail::keyed_topics(TopicTraits<T>::name, keys), std::move(on_sample),
               std::move(on_match), role, 0) {}
  [[nodiscard]] int matched_writers() const noexcept { return base_.matched_writers(); }

 private:
  Reader(Participant& participant, const std::vector<std::string>& topics, SampleFn on_sample,
         MatchFn on_match, ReaderRole role, int /*either*/)
      : base_(
            participant, topics, &detail::type_support<T>, TopicTraits<T>::qos, role,
            detail::ReaderCallbacks{[] { return static_cast<void*>(new T()); },
                                    [](void* p) { delete static_cast<T*>(p); },
                                    [fn = std::move(on_sample)](const void* s, const WriterId& w) {
                                      fn(*static_cast<const T*>(s), w);
                                    },
                                    std::move(on_match)}) {}

  detail::ReaderBase base_;
};

}  // namespace mcnc::dds
