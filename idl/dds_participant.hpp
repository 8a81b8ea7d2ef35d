#pragma once
// The typed publish/subscribe layer over Fast DDS. One Participant per process; Writer<T> and
// Reader<T> take their topic name and QoS profile from the topic catalogue (topics.hpp), and for a
// routed topic the partition they write in or read.
// Reader callbacks run on a Fast DDS thread: hand the data to your own thread, do not block.
#include "idl/topics.hpp"

#include <array>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>

namespace eprosima::fastdds::dds {
class DomainParticipant;
class Publisher;
class Subscriber;
class Topic;
class DataWriter;
class DataReader;
}  // namespace eprosima::fastdds::dds

namespace mcnc::dds {

// Identifies one remote writer (its DDS instance handle), to tell whose samples are whose.
using WriterId = std::array<std::uint8_t, 16>;

// The QoS profiles file: MCNC_QOS_PROFILES if set, else the one in the source tree.
std::string qos_profiles_path();

class Participant {
 public:
  // Throws std::runtime_error when the participant cannot be created (start-up error).
  Participant(int domain, const std::string& name, CyclicClock clock = CyclicClock::realtime);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  // The topic of that name, created (and its type registered) on first use. Takes ownership of
  // `pubsub_type` (a new'd Fast DDS TopicDataType).
  eprosima::fastdds::dds::Topic* topic(const std::string& name, void* pubsub_type);
  // An empty `partitions` is the default partition (the unrouted topics).
  eprosima::fastdds::dds::DataWriter* create_writer(eprosima::fastdds::dds::Topic* topic,
                                                    QosKind qos, const Partitions& partitions);
  void delete_writer(eprosima::fastdds::dds::DataWriter* writer) noexcept;
  eprosima::fastdds::dds::DataReader* create_reader(eprosima::fastdds::dds::Topic* topic,
                                                    QosKind qos, ReaderRole role, void* listener,
                                                    const Partitions& partitions);
  void delete_reader(eprosima::fastdds::dds::DataReader* reader) noexcept;

  [[nodiscard]] eprosima::fastdds::dds::DomainParticipant* native() const noexcept {
    return participant_;
  }

 private:
  // The publisher or subscriber of those partitions, made by `create` on first use.
  template <class Entity, class Create>
  Entity* in_partitions(std::map<std::string, Entity*>& cache, const Partitions& partitions,
                        Create create);

  CyclicClock clock_;
  eprosima::fastdds::dds::DomainParticipant* participant_ = nullptr;
  struct Topics;  // also the publishers and subscribers, one per set of partitions
  std::unique_ptr<Topics> topics_;
};

// How long peers wait before they declare this participant gone (from the QoS profile).
std::chrono::nanoseconds participant_lease(const Participant& participant);

namespace detail {
// Type-erased writer/reader so that the Fast DDS headers stay in one translation unit.
class WriterBase {
 public:
  WriterBase(Participant& participant, const char* topic, void* pubsub_type, QosKind qos,
             const Partitions& partitions);
  ~WriterBase();
  WriterBase(const WriterBase&) = delete;
  WriterBase& operator=(const WriterBase&) = delete;
  bool write_raw(void* sample) noexcept;
  [[nodiscard]] int matched_readers() const noexcept;

 private:
  Participant& participant_;
  eprosima::fastdds::dds::DataWriter* writer_ = nullptr;
};

class ReaderBase {
 public:
  using SampleFn = std::function<void(const void* sample, const WriterId& writer)>;
  using MatchFn = std::function<void(const WriterId& writer, bool matched)>;
  ReaderBase(Participant& participant, const char* topic, void* pubsub_type, QosKind qos,
             ReaderRole role, const Partitions& partitions, std::function<void*()> make_sample,
             std::function<void(void*)> free_sample, SampleFn on_sample, MatchFn on_match);
  ~ReaderBase();
  ReaderBase(const ReaderBase&) = delete;
  ReaderBase& operator=(const ReaderBase&) = delete;
  [[nodiscard]] int matched_writers() const noexcept;

  struct Listener;

 private:
  Participant& participant_;
  std::unique_ptr<Listener> listener_;
  eprosima::fastdds::dds::DataReader* reader_ = nullptr;
};
}  // namespace detail

template <class T>
class Writer {
 public:
  explicit Writer(Participant& participant) requires(!TopicTraits<T>::routed)
      : base_(participant, TopicTraits<T>::name, new typename TopicTraits<T>::PubSubType(),
              TopicTraits<T>::qos, Partitions{}) {}
  // A routed topic's writer writes in the partition of its key (an axis's or channel's name).
  Writer(Participant& participant, const std::string& key) requires TopicTraits<T>::routed
      : base_(participant, TopicTraits<T>::name, new typename TopicTraits<T>::PubSubType(),
              TopicTraits<T>::qos, Partitions::of({key})) {}
  bool write(const T& sample) noexcept { return base_.write_raw(const_cast<T*>(&sample)); }
  [[nodiscard]] int matched_readers() const noexcept { return base_.matched_readers(); }

 private:
  detail::WriterBase base_;
};

template <class T>
class Reader {
 public:
  using SampleFn = std::function<void(const T&, const WriterId&)>;
  using MatchFn = detail::ReaderBase::MatchFn;
  Reader(Participant& participant, SampleFn on_sample, MatchFn on_match = {},
         ReaderRole role = ReaderRole::consumer) requires(!TopicTraits<T>::routed)
      : Reader(participant, Partitions{}, std::move(on_sample), std::move(on_match), role, 0) {}
  // A routed topic's reader hears the writers of the partitions it names, and only them.
  Reader(Participant& participant, Partitions partitions, SampleFn on_sample, MatchFn on_match = {},
         ReaderRole role = ReaderRole::consumer) requires TopicTraits<T>::routed
      : Reader(participant, std::move(partitions), std::move(on_sample), std::move(on_match), role,
               0) {}
  [[nodiscard]] int matched_writers() const noexcept { return base_.matched_writers(); }

 private:
  Reader(Participant& participant, const Partitions& partitions, SampleFn on_sample,
         MatchFn on_match, ReaderRole role, int /*either*/)
      : base_(
            participant, TopicTraits<T>::name, new typename TopicTraits<T>::PubSubType(),
            TopicTraits<T>::qos, role, partitions, [] { return static_cast<void*>(new T()); },
            [](void* p) { delete static_cast<T*>(p); },
            [fn = std::move(on_sample)](const void* s, const WriterId& w) {
              fn(*static_cast<const T*>(s), w);
            },
            std::move(on_match)) {}

  detail::ReaderBase base_;
};

}  // namespace mcnc::dds
