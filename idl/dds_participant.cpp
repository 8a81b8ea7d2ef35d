#include "idl/dds_participant.hpp"

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <stdexcept>

namespace fdds = eprosima::fastdds::dds;

namespace mcnc::dds {

namespace {

constexpr const char* kParticipantProfile = "mcnc_participant";

WriterId to_writer_id(const fdds::InstanceHandle_t& handle) {
  WriterId id{};
  std::memcpy(id.data(), handle.value, id.size());
  return id;
}

const char* writer_profile(QosKind qos, CyclicClock clock) {
  switch (qos) {
    case QosKind::cyclic:
      return clock == CyclicClock::lockstep ? "cyclic_writer_lockstep" : "cyclic_writer";
    case QosKind::state:
      return "state_writer";
    case QosKind::event:
      return "event_writer";
  }
  return "state_writer";
}

const char* reader_profile(QosKind qos, ReaderRole role) {
  switch (qos) {
    case QosKind::cyclic:
      return role == ReaderRole::observer ? "cyclic_observer" : "cyclic_reader";
    case QosKind::state:
      return "state_reader";
    case QosKind::event:
      return "event_reader";
  }
  return "state_reader";
}

// Profiles are loaded once per process, before the first participant.
void load_profiles_once() {
  static std::once_flag once;
  std::call_once(once, [] {
    auto* factory = fdds::DomainParticipantFactory::get_instance();
    if (factory->load_XML_profiles_file(qos_profiles_path()) != ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error("cannot load DDS QoS profiles from " + qos_profiles_path());
    }
  });
}

}  // namespace

std::string qos_profiles_path() {
  const char* env = std::getenv("MCNC_QOS_PROFILES");
  return env != nullptr && *env != '\0' ? env : MCNC_QOS_PROFILES_FILE;
}

std::chrono::nanoseconds participant_lease(const Participant& participant) {
  const auto& lease =
      participant.native()->get_qos().wire_protocol().builtin.discovery_config.leaseDuration;
  return std::chrono::seconds(lease.seconds) + std::chrono::nanoseconds(lease.nanosec);
}

struct Participant::Topics {
  std::mutex mutex;
  std::map<std::string, fdds::Topic*> by_name;
  // By their partitions, joined with '\n' ("" is the default partition).
  std::map<std::string, fdds::Publisher*> publishers;
  std::map<std::string, fdds::Subscriber*> subscribers;
};

namespace {

std::string partition_key(const Partitions& partitions) {
  std::string key;
  for (const std::string& name : partitions.names) {
    key += name;
    key += '\n';
  }
  return key;
}

fdds::PartitionQosPolicy partition_policy(const Partitions& partitions) {
  fdds::PartitionQosPolicy policy;
  for (const std::string& name : partitions.names) {
    policy.push_back(name.c_str());
  }
  return policy;
}

}  // namespace

Participant::Participant(int domain, const std::string& name, CyclicClock clock)
    : clock_(clock), topics_(std::make_unique<Topics>()) {
  load_profiles_once();
  auto* factory = fdds::DomainParticipantFactory::get_instance();
  // Copying PARTICIPANT_QOS_DEFAULT would bypass the XML profile, and on Fast DDS 2.9 so does
  // get_default_participant_qos() after loading a file: take the profile by name.
  fdds::DomainParticipantQos qos;
  if (factory->get_participant_qos_from_profile(kParticipantProfile, qos) !=
      ReturnCode_t::RETCODE_OK) {
    throw std::runtime_error(std::string("no participant profile ") + kParticipantProfile + " in " +
                             qos_profiles_path());
  }
  qos.name(name);
  participant_ = factory->create_participant(domain, qos);
  if (participant_ == nullptr) {
    throw std::runtime_error("cannot create DDS participant on domain " + std::to_string(domain));
  }
}

Participant::~Participant() {
  if (participant_ == nullptr) {
    return;
  }
  participant_->delete_contained_entities();
  fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
}

fdds::Topic* Participant::topic(const std::string& name, void* pubsub_type) {
  fdds::TypeSupport type(static_cast<fdds::TopicDataType*>(pubsub_type));
  std::lock_guard<std::mutex> lock(topics_->mutex);
  auto it = topics_->by_name.find(name);
  if (it != topics_->by_name.end()) {
    return it->second;
  }
  type.register_type(participant_);
  fdds::Topic* topic =
      participant_->create_topic(name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
  if (topic == nullptr) {
    throw std::runtime_error("cannot create DDS topic " + name);
  }
  topics_->by_name.emplace(name, topic);
  return topic;
}

template <class Entity, class Create>
Entity* Participant::in_partitions(std::map<std::string, Entity*>& cache,
                                   const Partitions& partitions, Create create) {
  std::lock_guard<std::mutex> lock(topics_->mutex);
  Entity*& entity = cache[partition_key(partitions)];
  if (entity == nullptr) {
    entity = create(partition_policy(partitions));
  }
  return entity;
}

fdds::DataWriter* Participant::create_writer(fdds::Topic* topic, QosKind qos,
                                             const Partitions& partitions) {
  fdds::Publisher* publisher =
      in_partitions(topics_->publishers, partitions, [this](const fdds::PartitionQosPolicy& p) {
        fdds::PublisherQos qos_of_publisher = fdds::PUBLISHER_QOS_DEFAULT;
        qos_of_publisher.partition(p);
        return participant_->create_publisher(qos_of_publisher);
      });
  if (publisher == nullptr) {
    throw std::runtime_error("cannot create DDS publisher for " + topic->get_name());
  }
  fdds::DataWriter* writer =
      publisher->create_datawriter_with_profile(topic, writer_profile(qos, clock_));
  if (writer == nullptr) {
    throw std::runtime_error("cannot create DDS writer for " + topic->get_name());
  }
  return writer;
}

void Participant::delete_writer(fdds::DataWriter* writer) noexcept {
  if (writer != nullptr) {
    const_cast<fdds::Publisher*>(writer->get_publisher())->delete_datawriter(writer);
  }
}

fdds::DataReader* Participant::create_reader(fdds::Topic* topic, QosKind qos, ReaderRole role,
                                             void* listener, const Partitions& partitions) {
  fdds::Subscriber* subscriber =
      in_partitions(topics_->subscribers, partitions, [this](const fdds::PartitionQosPolicy& p) {
        fdds::SubscriberQos qos_of_subscriber = fdds::SUBSCRIBER_QOS_DEFAULT;
        qos_of_subscriber.partition(p);
        return participant_->create_subscriber(qos_of_subscriber);
      });
  if (subscriber == nullptr) {
    throw std::runtime_error("cannot create DDS subscriber for " + topic->get_name());
  }
  fdds::DataReader* reader = subscriber->create_datareader_with_profile(
      topic, reader_profile(qos, role), static_cast<fdds::DataReaderListener*>(listener),
      fdds::StatusMask::data_available() << fdds::StatusMask::subscription_matched());
  if (reader == nullptr) {
    throw std::runtime_error("cannot create DDS reader for " + topic->get_name());
  }
  return reader;
}

void Participant::delete_reader(fdds::DataReader* reader) noexcept {
  if (reader != nullptr) {
    const_cast<fdds::Subscriber*>(reader->get_subscriber())->delete_datareader(reader);
  }
}

namespace detail {

WriterBase::WriterBase(Participant& participant, const char* topic, void* pubsub_type, QosKind qos,
                       const Partitions& partitions)
    : participant_(participant),
      writer_(participant.create_writer(participant.topic(topic, pubsub_type), qos, partitions)) {}

WriterBase::~WriterBase() {
  participant_.delete_writer(writer_);
}

bool WriterBase::write_raw(void* sample) noexcept {
  return writer_->write(sample);
}

int WriterBase::matched_readers() const noexcept {
  fdds::PublicationMatchedStatus status;
  writer_->get_publication_matched_status(status);
  return status.current_count;
}

struct ReaderBase::Listener : public fdds::DataReaderListener {
  std::function<void*()> make_sample;
  std::function<void(void*)> free_sample;
  SampleFn on_sample;
  MatchFn on_match;

  void on_data_available(fdds::DataReader* reader) override {
    void* sample = make_sample();
    fdds::SampleInfo info;
    while (reader->take_next_sample(sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        on_sample(sample, to_writer_id(info.publication_handle));
      }
    }
    free_sample(sample);
  }

  void on_subscription_matched(fdds::DataReader* /*reader*/,
                               const fdds::SubscriptionMatchedStatus& info) override {
    if (on_match && info.current_count_change != 0) {
      on_match(to_writer_id(info.last_publication_handle), info.current_count_change > 0);
    }
  }
};

ReaderBase::ReaderBase(Participant& participant, const char* topic, void* pubsub_type, QosKind qos,
                       ReaderRole role, const Partitions& partitions,
                       std::function<void*()> make_sample, std::function<void(void*)> free_sample,
                       SampleFn on_sample, MatchFn on_match)
    : participant_(participant), listener_(std::make_unique<Listener>()) {
  listener_->make_sample = std::move(make_sample);
  listener_->free_sample = std::move(free_sample);
  listener_->on_sample = std::move(on_sample);
  listener_->on_match = std::move(on_match);
  reader_ = participant.create_reader(participant.topic(topic, pubsub_type), qos, role,
                                      listener_.get(), partitions);
}

ReaderBase::~ReaderBase() {
  participant_.delete_reader(reader_);
}

int ReaderBase::matched_writers() const noexcept {
  fdds::SubscriptionMatchedStatus status;
  reader_->get_subscription_matched_status(status);
  return status.current_count;
}

}  // namespace detail
}  // namespace mcnc::dds
