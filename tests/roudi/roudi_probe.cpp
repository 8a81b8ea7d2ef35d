// mcnc_roudi_probe: what the host's RouDi holds, from its own introspection, as one JSON line:
// the processes registered with it, their publisher and subscriber ports (service, instance and
// event) and, per shared-memory segment and mempool, the chunks in use. The tests read it to see
// that RouDi has cleaned up after a process killed with SIGKILL (its chunks back in the pools, its
// registration gone). Exits 2 when no RouDi answers (the runtime would otherwise wait for one for
// ever), 1 when RouDi sent no introspection within
// --timeout seconds.
#include "idl/dds_participant.hpp"

#include <iceoryx_hoofs/log/logmanager.hpp>
#include <iceoryx_posh/popo/subscriber.hpp>
#include <iceoryx_posh/roudi/introspection_types.hpp>
#include <iceoryx_posh/runtime/posh_runtime.hpp>

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <thread>

namespace {

// Names are plain identifiers here (process names, segment groups); quotes and backslashes are
// escaped all the same.
std::string quoted(const char* text) {
  std::string out = "\"";
  for (const char* c = text; *c != '\0'; ++c) {
    if (*c == '"' || *c == '\\') {
      out += '\\';
    }
    out += *c;
  }
  return out + "\"";
}

}  // namespace

int main(int argc, char** argv) {
  int timeout_s = 10;
  if (argc == 3 && std::strcmp(argv[1], "--timeout") == 0) {
    timeout_s = std::atoi(argv[2]);
  } else if (argc != 1) {
    std::fprintf(stderr, "usage: mcnc_roudi_probe [--timeout SECONDS]\n");
    return 2;
  }
  if (!mcnc::dds::roudi_answers()) {
    std::fprintf(stderr, "mcnc_roudi_probe: no iceoryx RouDi answers\n");
    return 2;
  }
  iox::log::LogManager::GetLogManager().SetDefaultLogLevel(iox::log::LogLevel::kWarn);
  const std::string name = "mcnc_roudi_probe_" + std::to_string(::getpid());
  iox::runtime::PoshRuntime::initRuntime(iox::RuntimeName_t(iox::cxx::TruncateToCapacity, name));

  iox::popo::SubscriberOptions options;
  options.queueCapacity = 1U;
  // No history: what RouDi published before the probe asked may be a second old.
  options.historyRequest = 0U;
  iox::popo::Subscriber<iox::roudi::MemPoolIntrospectionInfoContainer> mempools(
      iox::roudi::IntrospectionMempoolService, options);
  iox::popo::Subscriber<iox::roudi::ProcessIntrospectionFieldTopic> processes(
      iox::roudi::IntrospectionProcessService, options);
  iox::popo::Subscriber<iox::roudi::PortIntrospectionFieldTopic> ports(
      iox::roudi::IntrospectionPortService, options);

  std::optional<std::string> pools_json;
  std::optional<std::string> processes_json;
  std::optional<std::string> ports_json;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
  while ((!pools_json || !processes_json || !ports_json) &&
         std::chrono::steady_clock::now() < deadline) {
    mempools.take().and_then([&](auto& sample) {
      std::string json = "[";
      for (const auto& segment : *sample) {
        json += std::string(json.size() > 1 ? "," : "") +
                "{\"id\":" + std::to_string(segment.m_id) +
                ",\"writer\":" + quoted(segment.m_writerGroupName.c_str()) + ",\"pools\":[";
        bool first = true;
        for (const auto& pool : segment.m_mempoolInfo) {
          json += std::string(first ? "" : ",") + "{\"chunk\":" + std::to_string(pool.m_chunkSize) +
                  ",\"used\":" + std::to_string(pool.m_usedChunks) +
                  ",\"total\":" + std::to_string(pool.m_numChunks) + "}";
          first = false;
        }
        json += "]}";
      }
      pools_json = json + "]";
    });
    processes.take().and_then([&](auto& sample) {
      std::string json = "[";
      for (const auto& process : sample->m_processList) {
        // The probe itself is not what a test asks about.
        if (std::string(process.m_name.c_str()) == name) {
          continue;
        }
        json += std::string(json.size() > 1 ? "," : "") +
                "{\"name\":" + quoted(process.m_name.c_str()) +
                ",\"pid\":" + std::to_string(process.m_pid) + "}";
      }
      processes_json = json + "]";
    });
    ports.take().and_then([&](auto& sample) {
      std::string json = "[";
      const auto add = [&](const iox::roudi::PortData& port, const char* kind) {
        if (std::string(port.m_name.c_str()) == name) {
          return;
        }
        json += std::string(json.size() > 1 ? "," : "") +
                "{\"process\":" + quoted(port.m_name.c_str()) + ",\"kind\":\"" + kind +
                "\",\"service\":" + quoted(port.m_caproServiceID.c_str()) +
                ",\"instance\":" + quoted(port.m_caproInstanceID.c_str()) +
                ",\"event\":" + quoted(port.m_caproEventMethodID.c_str()) + "}";
      };
      for (const auto& port : sample->m_publisherList) {
        add(port, "publisher");
      }
      for (const auto& port : sample->m_subscriberList) {
        add(port, "subscriber");
      }
      ports_json = json + "]";
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!pools_json || !processes_json || !ports_json) {
    std::fprintf(stderr, "mcnc_roudi_probe: RouDi sent no introspection within %d s\n", timeout_s);
    return 1;
  }
  std::printf("{\"processes\":%s,\"ports\":%s,\"segments\":%s}\n", processes_json->c_str(),
              ports_json->c_str(), pools_json->c_str());
  return 0;
}
