// The Cyclone DDS implementation of the typed publish/subscribe layer (dds_participant.hpp), over
// its C API. One IDL, two generated forms: the program's samples are Fast DDS's C++ types, and
// Cyclone DDS's idlc types carry them. A sample crosses between the two as the wire's own bytes
// (XCDR1, little-endian, what both put on the wire): Fast DDS's serializer writes them and
// Cyclone DDS's stream reader makes its C sample of them, and back. So nothing is written per
// type, and the two middlewares cannot disagree on a field.
//
// Cyclic topics travel between the processes of one host through iceoryx shared memory (a C
// sample of a fixed-size type written straight into a loaned chunk); state and event topics go
// over RTPS (writer_qos).
#include "idl/dds_participant.hpp"
#include "idl/discovery_port.hpp"

#include <dds/dds.h>
#include <dds/ddsc/dds_loan_api.h>
#include <dds/ddsi/ddsi_cdrstream.h>
#include <fastdds/rtps/common/SerializedPayload.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>
#include <fastdds/dds/topic/TopicDataType.hpp>

#include <algorithm>
#include <cstring>
#include <map>
#include <mutex>
#include <set>
#include <stdexcept>
#include <vector>

namespace fdds = eprosima::fastdds::dds;
using eprosima::fastrtps::rtps::SerializedPayload_t;

namespace mcnc::dds {

bool roudi_answers() noexcept {
  // iceoryx 2.0's RouDi listens on a Unix datagram socket of this name; connect() succeeds only
  // while a process has it bound (a stale file left by a killed RouDi refuses).
  const int fd = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd < 0) {
    return false;
  }
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::strncpy(address.sun_path, kRoudiSocket, sizeof(address.sun_path) - 1);
  const bool answers =
      ::connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) == 0;
  ::close(fd);
  return answers;
}

namespace {

constexpr std::uint32_t kXcdr1 = 1;
// A cyclic reader's history and iceoryx queue (reader_qos): iceoryx 2.0's largest queue.
constexpr std::int32_t kSharedMemoryQueue = 256;
// The encapsulation header of little-endian plain CDR, which Fast DDS's deserializer expects.
constexpr std::array<unsigned char, 4> kCdrLe{0x00, 0x01, 0x00, 0x00};
constexpr std::size_t kHeader = kCdrLe.size();

WriterId to_writer_id(dds_instance_handle_t handle) {
  WriterId id{};
  std::memcpy(id.data(), &handle, sizeof(handle));
  return id;
}

std::string error_text(dds_return_t rc) {
  return dds_strretcode(rc);
}

// The QoS of each stream, the same as the Fast DDS profiles (qos_profiles.xml) say.
struct QosOf {
  dds_qos_t* qos = dds_create_qos();
  QosOf() = default;
  ~QosOf() { dds_delete_qos(qos); }
  QosOf(const QosOf&) = delete;
  QosOf& operator=(const QosOf&) = delete;
};

void keep(dds_qos_t* qos, bool reliable, bool transient_local, std::int32_t depth,
          std::int32_t max_samples, std::int32_t max_instances) {
  dds_qset_reliability(qos, reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT,
                       DDS_MSECS(100));
  dds_qset_durability(qos,
                      transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  dds_qset_history(qos, DDS_HISTORY_KEEP_LAST, depth);
  // What a late joiner gets of a transient-local writer's history (and iceoryx's history).
  dds_qset_durability_service(qos, 0, DDS_HISTORY_KEEP_LAST, depth, DDS_LENGTH_UNLIMITED,
                              DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  dds_qset_resource_limits(qos, max_samples, max_instances, depth);
}

// State and events go over RTPS, whose repair makes them reliable where an iceoryx queue would
// drop its oldest: Cyclone DDS 0.10 puts no KEEP_ALL reader or writer on shared memory, and a
// reader that is on it is reached only through it (so a writer off it must not be the only
// way). KEEP_ALL on both sides keeps them off; the history they keep for a late joiner is
// bounded by the resource limits (a state topic's few samples, an event writer's own).
void keep_all(dds_qos_t* qos, std::int32_t max_samples, std::int32_t max_instances) {
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_MSECS(100));
  dds_qset_durability(qos, DDS_DURABILITY_TRANSIENT_LOCAL);
  dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
  dds_qset_durability_service(qos, 0, DDS_HISTORY_KEEP_ALL, 0, max_samples, max_instances,
                              max_samples);
  dds_qset_resource_limits(qos, max_samples, max_instances, max_samples);
}

void writer_qos(dds_qos_t* qos, QosKind kind) {
  switch (kind) {
    case QosKind::cyclic:
      keep(qos, true, true, 8, 2048, 256);
      return;
    case QosKind::state:
      keep_all(qos, 1024, 256);
      return;
    case QosKind::event:
      keep_all(qos, 1024, 4);
      return;
  }
}

void reader_qos(dds_qos_t* qos, QosKind kind, ReaderRole role) {
  switch (kind) {
    case QosKind::cyclic:
      // Over shared memory a reader's iceoryx queue is as deep as its history, and it drops
      // its oldest when full. Cyclone DDS 0.10 queues every writer's chunk of the topic for
      // every reader of it (it ignores partitions; the project's topics are per key, decision
      // 35): in lockstep they come in bursts, and a queue of 8 once dropped samples.
      if (role == ReaderRole::observer) {
        keep(qos, false, false, kSharedMemoryQueue, 4096, 256);
      } else {
        keep(qos, true, true, kSharedMemoryQueue, 16384, 256);
      }
      return;
    case QosKind::state:
      keep_all(qos, 16384, 256);
      return;
    case QosKind::event:
      keep_all(qos, 16384, 64);
      return;
  }
}

// Domain configuration: the lease and announcements of the Fast DDS profile, and shared memory
// under a service name of the domain's own, so that two machines on two domains of one host
// share a RouDi and never each other's samples. Multicast only for discovery, as Fast DDS does:
// a sample sent to a multicast group reaches every participant of the domain on every host,
// each of which wakes to drop what it does not read; sent to each matched reader it wakes only
// those (decision 54). A writer's heartbeats stay 100 ms apart while a reader lacks a sample:
// Cyclone DDS doubles the interval, up to 8 s, after five heartbeats without a write, and a
// lockstep writer writes nothing until that reader's answer comes (decision 91).
// A secured participant announces itself to its peers alone, by unicast (at 127.0.0.1 on one
// host, at their hosts' addresses across hosts), and listens on the discovery port of its
// participant index (decisions 137, 151): without multicast, participants that share no topic
// never meet, nor authenticate each other.
// CYCLONEDDS_URI, when set, is read after it.
std::string domain_config(int domain, bool shared_memory, const security::DiscoveryPeers* peers) {
  std::string config =
      "<CycloneDDS><Domain id=\"any\">"
      "<General><AllowMulticast>" +
      std::string(peers != nullptr ? "false" : "spdp") +
      "</AllowMulticast></General>"
      "<Discovery><LeaseDuration>3s</LeaseDuration><SPDPInterval>1s</SPDPInterval>";
  if (peers != nullptr) {
    config += "<ParticipantIndex>" +
              (peers->participant_index < 0 ? std::string("none")
                                            : std::to_string(peers->participant_index)) +
              "</ParticipantIndex><Peers>";
    for (std::size_t k = 0; k < peers->peers.size(); ++k) {
      const std::string host =
          k < peers->peer_addresses.size() ? peers->peer_addresses[k] : std::string("127.0.0.1");
      config += "<Peer address=\"" + host + ":" +
                std::to_string(unicast_discovery_port(domain, peers->peers[k])) + "\"/>";
    }
    config += "</Peers>";
  }
  config +=
      "</Discovery>"
      "<Internal><HeartbeatInterval max=\"100 ms\">100 ms</HeartbeatInterval></Internal>"
      "<SharedMemory><Enable>" +
      std::string(shared_memory ? "true" : "false") + "</Enable><Prefix>mcnc_d" +
      std::to_string(domain) +
      "</Prefix><LogLevel>warn</LogLevel></SharedMemory>"
      "</Domain></CycloneDDS>";
  const char* uri = std::getenv("CYCLONEDDS_URI");
  if (uri != nullptr && *uri != '\0') {
    config += ",";
    config += uri;
  }
  return config;
}

// A domain is configured before its first participant (which decides whether the process uses
// shared memory) and deleted after its last: the domain made with a configuration lives until it
// is deleted, and with it the listener thread that waits in iceoryx's shared memory. Left to the
// process's exit, that thread could still wait there when iceoryx's own exit unmapped the
// memory: a channel ended by a segmentation fault in sem_wait after its run (seen twice in a day
// of runs).
class DomainUse {
 public:
  static void enter(int domain, bool shared_memory, const security::DiscoveryPeers* peers) {
    std::lock_guard<std::mutex> lock(mutex());
    Entry& entry = entries()[domain];
    if (entry.participants++ > 0) {
      return;
    }
    const dds_entity_t created = dds_create_domain(
        static_cast<dds_domainid_t>(domain), domain_config(domain, shared_memory, peers).c_str());
    if (created < 0 && created != DDS_RETCODE_PRECONDITION_NOT_MET) {
      entries().erase(domain);
      throw std::runtime_error("cannot configure Cyclone DDS domain " + std::to_string(domain) +
                               ": " + error_text(created));
    }
    entry.handle = created > 0 ? created : 0;  // 0: made elsewhere, not ours to delete
  }

  static void leave(int domain) noexcept {
    std::lock_guard<std::mutex> lock(mutex());
    const auto it = entries().find(domain);
    if (it == entries().end() || --it->second.participants > 0) {
      return;
    }
    if (it->second.handle > 0) {
      dds_delete(it->second.handle);  // stops its threads, the shared-memory listener's among them
    }
    entries().erase(it);
  }

 private:
  struct Entry {
    int participants = 0;
    dds_entity_t handle = 0;
  };
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  static std::map<int, Entry>& entries() {
    static std::map<int, Entry> e;
    return e;
  }
};

// DDS Security's builtin plugins, as Cyclone DDS names its properties. Debian ships the
// plugins beside libddsc in a directory of their own, which Cyclone DDS does not search: the
// build found them (idl/CMakeLists.txt).
void secure(dds_qos_t* qos, const security::IdentityFiles& files) {
  const std::string plugins = MCNC_CYCLONEDDS_SECURITY_DIR;
  const auto set = [qos](const char* name, const std::string& value) {
    dds_qset_prop(qos, name, value.c_str());
  };
  set("dds.sec.auth.library.path", plugins + "/libdds_security_auth.so");
  set("dds.sec.auth.library.init", "init_authentication");
  set("dds.sec.auth.library.finalize", "finalize_authentication");
  set("dds.sec.access.library.path", plugins + "/libdds_security_ac.so");
  set("dds.sec.access.library.init", "init_access_control");
  set("dds.sec.access.library.finalize", "finalize_access_control");
  set("dds.sec.crypto.library.path", plugins + "/libdds_security_crypto.so");
  set("dds.sec.crypto.library.init", "init_crypto");
  set("dds.sec.crypto.library.finalize", "finalize_crypto");
  set("dds.sec.auth.identity_ca", "file:" + files.ca_certificate);
  set("dds.sec.auth.identity_certificate", "file:" + files.certificate);
  set("dds.sec.auth.private_key", "file:" + files.private_key);
  set("dds.sec.access.permissions_ca", "file:" + files.permissions_ca);
  set("dds.sec.access.governance", "file:" + files.governance);
  set("dds.sec.access.permissions", "file:" + files.permissions);
}

class CycloneWriter;

class CycloneParticipant final : public detail::ParticipantImpl {
 public:
  CycloneParticipant(int domain, const std::string& name, bool shared_memory,
                     const security::IdentityFiles* security)
      : domain_(domain) {
    if (shared_memory && !roudi_answers()) {
      throw std::runtime_error(std::string("no iceoryx RouDi answers at ") + kRoudiSocket +
                               ": a Cyclone DDS process needs one running on its host (iox-roudi;"
                               " mcnc-launch starts it)");
    }
    DomainUse::enter(domain, shared_memory,
                     security != nullptr && security->discovery ? &*security->discovery : nullptr);
    QosOf qos;
    dds_qset_entity_name(qos.qos, name.c_str());
    if (security != nullptr) {
      secure(qos.qos, *security);
    }
    participant_ = dds_create_participant(static_cast<dds_domainid_t>(domain), qos.qos, nullptr);
    if (participant_ < 0) {
      DomainUse::leave(domain);
      throw std::runtime_error(
          "cannot create Cyclone DDS participant on domain " + std::to_string(domain) + ": " +
          error_text(participant_) +
          (security != nullptr ? " (secured as " + security->identity + ")" : std::string()));
    }
  }
  ~CycloneParticipant() override {
    dds_delete(participant_);
    DomainUse::leave(domain_);
  }
  CycloneParticipant(const CycloneParticipant&) = delete;
  CycloneParticipant& operator=(const CycloneParticipant&) = delete;

  std::unique_ptr<detail::WriterImpl> writer(const char* topic, detail::TypeSupport type,
                                             QosKind qos, const Partitions& partitions) override;
  std::unique_ptr<detail::ReaderImpl> reader(const char* topic, detail::TypeSupport type,
                                             QosKind qos, ReaderRole role,
                                             const Partitions& partitions,
                                             detail::ReaderCallbacks callbacks) override;
  [[nodiscard]] std::chrono::nanoseconds lease() const override { return std::chrono::seconds(3); }
  void announce_latest_cyclic() noexcept override;

  // The cyclic writers, for announce_latest_cyclic(): a writer enlists when made and leaves when
  // deleted.
  void enlist(CycloneWriter* writer) {
    std::lock_guard<std::mutex> lock(mutex_);
    cyclic_writers_.push_back(writer);
  }
  void delist(CycloneWriter* writer) noexcept {
    std::lock_guard<std::mutex> lock(mutex_);
    cyclic_writers_.erase(std::remove(cyclic_writers_.begin(), cyclic_writers_.end(), writer),
                          cyclic_writers_.end());
  }

  dds_entity_t topic(const char* name, const dds_topic_descriptor_t* descriptor) {
    std::lock_guard<std::mutex> lock(mutex_);
    auto it = topics_.find(name);
    if (it != topics_.end()) {
      return it->second;
    }
    const dds_entity_t topic = dds_create_topic(participant_, descriptor, name, nullptr, nullptr);
    if (topic < 0) {
      throw std::runtime_error(std::string("cannot create Cyclone DDS topic ") + name + ": " +
                               error_text(topic));
    }
    topics_.emplace(name, topic);
    return topic;
  }

  // The publisher (or subscriber) of those partitions, made on first use.
  dds_entity_t in_partitions(bool publisher, const Partitions& partitions) {
    const std::string key = detail::partition_key(partitions);
    std::lock_guard<std::mutex> lock(mutex_);
    dds_entity_t& entity = (publisher ? publishers_ : subscribers_)[key];
    if (entity == 0) {
      QosOf qos;
      if (!partitions.names.empty()) {
        std::vector<const char*> names;
        for (const std::string& name : partitions.names) {
          names.push_back(name.c_str());
        }
        dds_qset_partition(qos.qos, static_cast<std::uint32_t>(names.size()), names.data());
      }
      entity = publisher ? dds_create_publisher(participant_, qos.qos, nullptr)
                         : dds_create_subscriber(participant_, qos.qos, nullptr);
      if (entity < 0) {
        const dds_entity_t failed = entity;
        entity = 0;
        throw std::runtime_error(std::string("cannot create Cyclone DDS ") +
                                 (publisher ? "publisher: " : "subscriber: ") + error_text(failed));
      }
    }
    return entity;
  }

 private:
  int domain_;
  dds_entity_t participant_ = 0;
  std::mutex mutex_;
  std::map<std::string, dds_entity_t> topics_;
  std::map<std::string, dds_entity_t> publishers_;
  std::map<std::string, dds_entity_t> subscribers_;
  std::vector<CycloneWriter*> cyclic_writers_;
};

class CycloneWriter final : public detail::WriterImpl {
 public:
  CycloneWriter(CycloneParticipant& participant, const char* topic, detail::TypeSupport type,
                QosKind kind, const Partitions& partitions)
      : fast_(static_cast<fdds::TopicDataType*>(type.fastdds)),
        descriptor_(type.cyclonedds),
        sample_((descriptor_->m_size + sizeof(std::max_align_t) - 1) / sizeof(std::max_align_t)) {
    QosOf qos;
    writer_qos(qos.qos, kind);
    writer_ = dds_create_writer(participant.in_partitions(true, partitions),
                                participant.topic(topic, descriptor_), qos.qos, nullptr);
    if (writer_ < 0) {
      throw std::runtime_error(std::string("cannot create Cyclone DDS writer for ") + topic + ": " +
                               error_text(writer_));
    }
    loans_ = dds_is_loan_available(writer_);
    payload_.reserve(std::max<std::uint32_t>(fast_->m_typeSize, 64));
    if (kind == QosKind::cyclic) {
      participant_ = &participant;
      participant.enlist(this);
    }
  }
  ~CycloneWriter() override {
    if (participant_ != nullptr) {
      participant_->delist(this);
    }
    dds_delete(writer_);
  }
  CycloneWriter(const CycloneWriter&) = delete;
  CycloneWriter& operator=(const CycloneWriter&) = delete;

  bool write(const void* sample) noexcept override {
    std::lock_guard<std::mutex> lock(mutex_);
    void* data = const_cast<void*>(sample);
    payload_.length = 0;
    if (!fast_->serialize(data, &payload_)) {
      // Only a type of unbounded size outgrows the reserve (never a cyclic one).
      payload_.reserve(fast_->getSerializedSizeProvider(data)());
      payload_.length = 0;
      if (!fast_->serialize(data, &payload_)) {
        return false;
      }
    }
    if (payload_.length < kHeader || payload_.data[1] != kCdrLe[1]) {
      payload_.length = 0;
      return false;  // not the little-endian plain CDR both sides speak
    }
    return send_payload();
  }

  // Writes the latest sample again, as a sample of its own: its data and the heartbeat that
  // goes with it reach every matched reader. Cyclone DDS 0.10 sends a writer's periodic
  // heartbeat to one reader alone when one reliable reader lacks samples, and it may pick a
  // best-effort one (an observer) instead of that reader: the reader that lost the last
  // sample never hears of it (decision 98).
  void repeat_latest() noexcept {
    std::lock_guard<std::mutex> lock(mutex_);
    if (payload_.length >= kHeader) {
      (void)send_payload();
    }
  }

  [[nodiscard]] int matched_readers() const noexcept override {
    dds_publication_matched_status_t status{};
    dds_get_publication_matched_status(writer_, &status);
    return static_cast<int>(status.current_count);
  }

 private:
  // Writes the sample serialized in payload_ (under mutex_).
  bool send_payload() noexcept {
    void* c_sample = sample_.data();
    if (loans_ && dds_loan_sample(writer_, &c_sample) != DDS_RETCODE_OK) {
      return false;
    }
    std::memset(c_sample, 0, descriptor_->m_size);
    dds_istream_t in;
    dds_istream_init(&in, payload_.length - kHeader, payload_.data + kHeader, kXcdr1);
    dds_stream_read(&in, static_cast<char*>(c_sample), descriptor_->m_ops);
    const dds_return_t rc = dds_write(writer_, c_sample);  // takes back a loaned sample
    if (!loans_) {
      dds_sample_free(c_sample, descriptor_, DDS_FREE_CONTENTS);
    }
    return rc == DDS_RETCODE_OK;
  }

  CycloneParticipant* participant_ = nullptr;  // a cyclic writer's, where it is enlisted
  std::unique_ptr<fdds::TopicDataType> fast_;
  const dds_topic_descriptor_t* descriptor_;
  dds_entity_t writer_ = 0;
  bool loans_ = false;
  std::mutex mutex_;  // a writer may be shared by threads; one sample at a time
  SerializedPayload_t payload_;
  std::vector<std::max_align_t> sample_;  // the C sample, when no loan is available
};

void CycloneParticipant::announce_latest_cyclic() noexcept {
  std::lock_guard<std::mutex> lock(mutex_);
  for (CycloneWriter* writer : cyclic_writers_) {
    writer->repeat_latest();
  }
}

class CycloneReader final : public detail::ReaderImpl {
 public:
  CycloneReader(CycloneParticipant& participant, const char* topic, detail::TypeSupport type,
                QosKind kind, ReaderRole role, const Partitions& partitions,
                detail::ReaderCallbacks callbacks)
      : fast_(static_cast<fdds::TopicDataType*>(type.fastdds)),
        descriptor_(type.cyclonedds),
        callbacks_(std::move(callbacks)),
        sample_(callbacks_.make_sample()) {
    dds_ostream_init(&out_, 256, kXcdr1);
    payload_.reserve(std::max<std::uint32_t>(fast_->m_typeSize, 256));
    QosOf qos;
    reader_qos(qos.qos, kind, role);
    dds_listener_t* listener = dds_create_listener(this);
    dds_lset_data_available(listener, &CycloneReader::on_data_available);
    dds_lset_subscription_matched(listener, &CycloneReader::on_subscription_matched);
    reader_ = dds_create_reader(participant.in_partitions(false, partitions),
                                participant.topic(topic, descriptor_), qos.qos, listener);
    dds_delete_listener(listener);
    if (reader_ < 0) {
      callbacks_.free_sample(sample_);
      dds_ostream_fini(&out_);
      throw std::runtime_error(std::string("cannot create Cyclone DDS reader for ") + topic + ": " +
                               error_text(reader_));
    }
  }
  // dds_delete waits for a listener that is running.
  ~CycloneReader() override {
    dds_delete(reader_);
    callbacks_.free_sample(sample_);
    dds_ostream_fini(&out_);
  }
  CycloneReader(const CycloneReader&) = delete;
  CycloneReader& operator=(const CycloneReader&) = delete;

  [[nodiscard]] int matched_writers() const noexcept override {
    dds_subscription_matched_status_t status{};
    dds_get_subscription_matched_status(reader_, &status);
    return static_cast<int>(status.current_count);
  }

 private:
  static void on_data_available(dds_entity_t reader, void* arg) {
    static_cast<CycloneReader*>(arg)->take_all(reader);
  }

  static void on_subscription_matched(dds_entity_t reader,
                                      const dds_subscription_matched_status_t status, void* arg) {
    auto* self = static_cast<CycloneReader*>(arg);
    if (status.current_count_change == 0) {
      return;
    }
    self->refresh_matched(reader);
    if (self->callbacks_.on_match) {
      self->callbacks_.on_match(to_writer_id(status.last_publication_handle),
                                status.current_count_change > 0);
    }
  }

  // The writers matched now, from the reader itself: a status can stand for several changes.
  // Here, at a match, and not at each sample of a writer it does not know.
  void refresh_matched(dds_entity_t reader) {
    std::array<dds_instance_handle_t, 256> handles{};
    const dds_return_t n = dds_get_matched_publications(reader, handles.data(), handles.size());
    std::lock_guard<std::mutex> lock(mutex_);
    matched_.clear();
    for (dds_return_t i = 0; i < std::min<dds_return_t>(n, handles.size()); ++i) {
      matched_.insert(handles[static_cast<std::size_t>(i)]);
    }
  }

  // Cyclone DDS 0.10 hands a reader every shared-memory sample of its topic, whatever the
  // writer's partition: only the samples of a matched writer are this reader's (a guard: the
  // project's routed topics are per key, decision 35).
  bool from_matched(dds_instance_handle_t writer) {
    std::lock_guard<std::mutex> lock(mutex_);
    return matched_.count(writer) != 0;
  }

  void take_all(dds_entity_t reader) {
    std::lock_guard<std::mutex> lock(take_mutex_);  // shared memory and RTPS have a thread each
    for (;;) {
      void* samples[1] = {nullptr};
      dds_sample_info_t info{};
      const dds_return_t n = dds_take(reader, samples, &info, 1, 1);
      if (n <= 0) {
        return;
      }
      if (info.valid_data && from_matched(info.publication_handle)) {
        deliver(samples[0], info.publication_handle);
      }
      dds_return_loan(reader, samples, n);
    }
  }

  void deliver(const void* c_sample, dds_instance_handle_t writer) {
    out_.m_index = 0;
    dds_stream_write(&out_, static_cast<const char*>(c_sample), descriptor_->m_ops);
    const std::uint32_t length = static_cast<std::uint32_t>(kHeader) + out_.m_index;
    if (payload_.max_size < length) {
      payload_.reserve(length);
    }
    std::memcpy(payload_.data, kCdrLe.data(), kHeader);
    std::memcpy(payload_.data + kHeader, out_.m_buffer, out_.m_index);
    payload_.length = length;
    payload_.pos = 0;
    if (fast_->deserialize(&payload_, sample_)) {
      callbacks_.on_sample(sample_, to_writer_id(writer));
    }
  }

  std::unique_ptr<fdds::TopicDataType> fast_;
  const dds_topic_descriptor_t* descriptor_;
  detail::ReaderCallbacks callbacks_;
  void* sample_;  // the T handed to on_sample, reused (one listener thread at a time)
  dds_ostream_t out_{};
  SerializedPayload_t payload_;
  dds_entity_t reader_ = 0;
  std::mutex take_mutex_;
  std::mutex mutex_;  // matched_
  std::set<dds_instance_handle_t> matched_;
};

std::unique_ptr<detail::WriterImpl> CycloneParticipant::writer(const char* topic,
                                                               detail::TypeSupport type,
                                                               QosKind qos,
                                                               const Partitions& partitions) {
  return std::make_unique<CycloneWriter>(*this, topic, type, qos, partitions);
}

std::unique_ptr<detail::ReaderImpl> CycloneParticipant::reader(const char* topic,
                                                               detail::TypeSupport type,
                                                               QosKind qos, ReaderRole role,
                                                               const Partitions& partitions,
                                                               detail::ReaderCallbacks callbacks) {
  return std::make_unique<CycloneReader>(*this, topic, type, qos, role, partitions,
                                         std::move(callbacks));
}

}  // namespace

namespace detail {
std::unique_ptr<ParticipantImpl> make_cyclonedds_participant(
    int domain, const std::string& name, CyclicClock /*clock*/, bool shared_memory,
    const security::IdentityFiles* security) {
  return std::make_unique<CycloneParticipant>(domain, name, shared_memory, security);
}
}  // namespace detail

}  // namespace mcnc::dds
