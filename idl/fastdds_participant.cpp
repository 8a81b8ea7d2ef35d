// The Fast DDS implementation of the typed publish/subscribe layer (dds_participant.hpp).
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

namespace {

fdds::PartitionQosPolicy partition_policy(const Partitions& partitions) {
  fdds::PartitionQosPolicy policy;
  for (const std::string& name : partitions.names) {
    policy.push_back(name.c_str());
  }
  return policy;
}

}  // namespace

namespace {

class FastWriter;
class FastReader;

// DDS Security's builtin plugins, as Fast DDS names its properties. Fast DDS 2.9 takes a file
// as a "file://" URI only (Cyclone DDS takes "file:" and a path).
void secure(fdds::DomainParticipantQos& qos, const security::IdentityFiles& files) {
  auto& properties = qos.properties().properties();
  const auto set = [&properties](const char* name, const std::string& value) {
    properties.emplace_back(name, value);
  };
  const auto uri = [](const std::string& path) { return "file://" + path; };
  set("dds.sec.auth.plugin", "builtin.PKI-DH");
  set("dds.sec.auth.builtin.PKI-DH.identity_ca", uri(files.ca_certificate));
  set("dds.sec.auth.builtin.PKI-DH.identity_certificate", uri(files.certificate));
  set("dds.sec.auth.builtin.PKI-DH.private_key", uri(files.private_key));
  set("dds.sec.access.plugin", "builtin.Access-Permissions");
  set("dds.sec.access.builtin.Access-Permissions.permissions_ca", uri(files.permissions_ca));
  set("dds.sec.access.builtin.Access-Permissions.governance", uri(files.governance));
  set("dds.sec.access.builtin.Access-Permissions.permissions", uri(files.permissions));
  set("dds.sec.crypto.plugin", "builtin.AES-GCM-GMAC");
}

class FastParticipant final : public detail::ParticipantImpl {
 public:
  FastParticipant(int domain, const std::string& name, CyclicClock clock,
                  const security::IdentityFiles* security)
      : clock_(clock) {
    load_profiles_once();
    auto* factory = fdds::DomainParticipantFactory::get_instance();
    // Copying PARTICIPANT_QOS_DEFAULT would bypass the XML profile, and on Fast DDS 2.9 so does
    // get_default_participant_qos() after loading a file: take the profile by name.
    fdds::DomainParticipantQos qos;
    if (factory->get_participant_qos_from_profile(kParticipantProfile, qos) !=
        ReturnCode_t::RETCODE_OK) {
      throw std::runtime_error(std::string("no participant profile ") + kParticipantProfile +
                               " in " + qos_profiles_path());
    }
    qos.name(name);
    if (security != nullptr) {
      secure(qos, *security);
    }
    participant_ = factory->create_participant(domain, qos);
    if (participant_ == nullptr) {
      throw std::runtime_error(
          "cannot create DDS participant on domain " + std::to_string(domain) +
          (security != nullptr ? " (secured as " + security->identity + ")" : std::string()));
    }
  }

  ~FastParticipant() override {
    participant_->delete_contained_entities();
    fdds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
  }
  FastParticipant(const FastParticipant&) = delete;
  FastParticipant& operator=(const FastParticipant&) = delete;

  std::unique_ptr<detail::WriterImpl> writer(const char* topic, detail::TypeSupport type,
                                             QosKind qos, const Partitions& partitions) override;
  std::unique_ptr<detail::ReaderImpl> reader(const char* topic, detail::TypeSupport type,
                                             QosKind qos, ReaderRole role,
                                             const Partitions& partitions,
                                             detail::ReaderCallbacks callbacks) override;

  [[nodiscard]] std::chrono::nanoseconds lease() const override {
    const auto& lease =
        participant_->get_qos().wire_protocol().builtin.discovery_config.leaseDuration;
    return std::chrono::seconds(lease.seconds) + std::chrono::nanoseconds(lease.nanosec);
  }
  // Nothing to do: a Fast DDS writer's periodic heartbeat goes to every matched reader while
  // one lacks samples, and that reader then asks for what it lost (decision 98).
  void announce_latest_cyclic() noexcept override {}

  // The topic of that name, created (and its type registered) on first use. Takes ownership of
  // `pubsub_type` (a new'd Fast DDS TopicDataType).
  fdds::Topic* topic(const std::string& name, void* pubsub_type) {
    fdds::TypeSupport type(static_cast<fdds::TopicDataType*>(pubsub_type));
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = topics_.find(name);
    if (it != topics_.end()) {
      return it->second;
    }
    type.register_type(participant_);
    fdds::Topic* topic =
        participant_->create_topic(name, type.get_type_name(), fdds::TOPIC_QOS_DEFAULT);
    if (topic == nullptr) {
      throw std::runtime_error("cannot create DDS topic " + name);
    }
    topics_.emplace(name, topic);
    return topic;
  }

  fdds::DataWriter* create_writer(fdds::Topic* topic, QosKind qos, const Partitions& partitions) {
    fdds::Publisher* publisher =
        in_partitions(publishers_, partitions, [this](const fdds::PartitionQosPolicy& p) {
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

  fdds::DataReader* create_reader(fdds::Topic* topic, QosKind qos, ReaderRole role,
                                  fdds::DataReaderListener* listener,
                                  const Partitions& partitions) {
    fdds::Subscriber* subscriber =
        in_partitions(subscribers_, partitions, [this](const fdds::PartitionQosPolicy& p) {
          fdds::SubscriberQos qos_of_subscriber = fdds::SUBSCRIBER_QOS_DEFAULT;
          qos_of_subscriber.partition(p);
          return participant_->create_subscriber(qos_of_subscriber);
        });
    if (subscriber == nullptr) {
      throw std::runtime_error("cannot create DDS subscriber for " + topic->get_name());
    }
    fdds::DataReader* reader = subscriber->create_datareader_with_profile(
        topic, reader_profile(qos, role), listener,
        fdds::StatusMask::data_available() << fdds::StatusMask::subscription_matched());
    if (reader == nullptr) {
      throw std::runtime_error("cannot create DDS reader for " + topic->get_name());
    }
    return reader;
  }

 private:
  // The publisher or subscriber of those partitions, made by `create` on first use.
  template <class Entity, class Create>
  Entity* in_partitions(std::map<std::string, Entity*>& cache, const Partitions& partitions,
                        Create create) {
    std::lock_guard<std::mutex> lock(mutex_);
    Entity*& entity = cache[detail::partition_key(partitions)];
    if (entity == nullptr) {
      entity = create(partition_policy(partitions));
    }
    return entity;
  }

  CyclicClock clock_;
  fdds::DomainParticipant* participant_ = nullptr;
  std::mutex mutex_;
  std::map<std::string, fdds::Topic*> topics_;
  // By their partitions, joined with '\n' ("" is the default partition).
  std::map<std::string, fdds::Publisher*> publishers_;
  std::map<std::string, fdds::Subscriber*> subscribers_;
};

class FastWriter final : public detail::WriterImpl {
 public:
  FastWriter(FastParticipant& participant, const char* topic, detail::TypeSupport type, QosKind qos,
             const Partitions& partitions)
      : writer_(
            participant.create_writer(participant.topic(topic, type.fastdds), qos, partitions)) {}
  ~FastWriter() override {
    const_cast<fdds::Publisher*>(writer_->get_publisher())->delete_datawriter(writer_);
  }
  FastWriter(const FastWriter&) = delete;
  FastWriter& operator=(const FastWriter&) = delete;

  bool write(const void* sample) noexcept override {
    return writer_->write(const_cast<void*>(sample));
  }
  [[nodiscard]] int matched_readers() const noexcept override {
    fdds::PublicationMatchedStatus status;
    writer_->get_publication_matched_status(status);
    return status.current_count;
  }

 private:
  fdds::DataWriter* writer_;
};

struct FastListener : public fdds::DataReaderListener {
  detail::ReaderCallbacks callbacks;

  void on_data_available(fdds::DataReader* reader) override {
    void* sample = callbacks.make_sample();
    fdds::SampleInfo info;
    while (reader->take_next_sample(sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        callbacks.on_sample(sample, to_writer_id(info.publication_handle));
      }
    }
    callbacks.free_sample(sample);
  }

  void on_subscription_matched(fdds::DataReader* /*reader*/,
                               const fdds::SubscriptionMatchedStatus& info) override {
    if (callbacks.on_match && info.current_count_change != 0) {
      callbacks.on_match(to_writer_id(info.last_publication_handle), info.current_count_change > 0);
    }
  }
};

class FastReader final : public detail::ReaderImpl {
 public:
  FastReader(FastParticipant& participant, const char* topic, detail::TypeSupport type, QosKind qos,
             ReaderRole role, const Partitions& partitions, detail::ReaderCallbacks callbacks)
      : listener_(std::make_unique<FastListener>()) {
    listener_->callbacks = std::move(callbacks);
    reader_ = participant.create_reader(participant.topic(topic, type.fastdds), qos, role,
                                        listener_.get(), partitions);
  }
  // The reader goes first: its listener may be running until then.
  ~FastReader() override {
    const_cast<fdds::Subscriber*>(reader_->get_subscriber())->delete_datareader(reader_);
  }
  FastReader(const FastReader&) = delete;
  FastReader& operator=(const FastReader&) = delete;

  [[nodiscard]] int matched_writers() const noexcept override {
    fdds::SubscriptionMatchedStatus status;
    reader_->get_subscription_matched_status(status);
    return status.current_count;
  }

 private:
  std::unique_ptr<FastListener> listener_;
  fdds::DataReader* reader_ = nullptr;
};

std::unique_ptr<detail::WriterImpl> FastParticipant::writer(const char* topic,
                                                            detail::TypeSupport type, QosKind qos,
                                                            const Partitions& partitions) {
  return std::make_unique<FastWriter>(*this, topic, type, qos, partitions);
}

std::unique_ptr<detail::ReaderImpl> FastParticipant::reader(const char* topic,
                                                            detail::TypeSupport type, QosKind qos,
                                                            ReaderRole role,
                                                            const Partitions& partitions,
                                                            detail::ReaderCallbacks callbacks) {
  return std::make_unique<FastReader>(*this, topic, type, qos, role, partitions,
                                      std::move(callbacks));
}

}  // namespace

namespace detail {
std::unique_ptr<ParticipantImpl> make_fastdds_participant(int domain, const std::string& name,
                                                          CyclicClock clock,
                                                          const security::IdentityFiles* security) {
  return std::make_unique<FastParticipant>(domain, name, clock, security);
}
}  // namespace detail

}  // namespace mcnc::dds
