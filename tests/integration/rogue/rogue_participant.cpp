// A participant of an attacker's (issue 25), built on the project's own IDL: it joins a DDS
// domain, over the network, unsecured or with the DDS Security files it is given, and until
// SIGINT or SIGTERM publishes every 20 ms what commanded a machine in issue 25: operator
// commands (feed hold, override 0, reset, MDI, cycle start), an E-stop, CH1's program end,
// CH2's arrival at G04.1 P1, a setpoint and a feedback of X1. A process of its own: Cyclone
// DDS 0.10 keeps one access control per domain and process, so two identities in one process
// would share a grant.
// With --announce-to it also announces itself to the ports of a secured machine's processes.
// Prints "writers N" once its writers are made (those its own access control allows) and
// "rounds N" at its end.
// With --flood it only fills the machine's operator inboxes as in issue 25: `--count` feed holds
// stamped with each cycle of --flood, once, then it waits; at its end it prints how the machine
// answered them ("answers taken N too_far_ahead N ..."), counted over every answering process.
#include "common/operator/operator_admission.hpp"
#include "common/security/identity_files.hpp"
#include "idl/dds_participant.hpp"
#include "idl/discovery_port.hpp"

#include <CLI/CLI.hpp>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

using namespace mcnc;

namespace {

volatile std::sig_atomic_t g_stop = 0;
void on_stop(int /*signal*/) {
  g_stop = 1;
}

class Rogue {
 public:
  Rogue(int domain, std::optional<security::IdentityFiles> identity)
      : participant_(domain, "rogue", dds::CyclicClock::lockstep, dds::Middleware::cyclonedds,
                     dds::LocalTransport::network, std::move(identity)) {
    make(commands_);
    make(run_control_);
    make(status_, "CH1");
    make(events_);
    make(setpoints_, "X1");
    make(feedback_, "X1");
    answer_reader_.emplace(participant_, [this](const OperatorAnswer& a, const dds::WriterId&) {
      if (a.sender() == kFloodSender) {
        const auto refusal = process::refusal_numbered(static_cast<int>(a.refusal()));
        std::lock_guard<std::mutex> lock(mutex_);
        ++answers_[refusal ? process::code_of(*refusal) : "unknown"];
      }
    });
  }
  [[nodiscard]] int writers() const { return writers_; }

  // Feed holds for the whole machine stamped `cycle`, as an HMI would send them.
  void flood(std::uint64_t cycle, int count) {
    for (int i = 0; i < count; ++i) {
      OperatorCommand c;
      c.seq(++flood_seq_);
      c.cycle(cycle);
      c.action(OP_FEED_HOLD);
      c.origin("hmi");
      c.sender(kFloodSender);
      write(commands_, c);
    }
  }
  // The machine's answers to the flood so far, by refusal code ("taken" when taken).
  std::map<std::string, int> flood_answers() {
    std::lock_guard<std::mutex> lock(mutex_);
    return answers_;
  }

  void publish_round(std::uint64_t seq) {
    for (OperatorAction action :
         {OP_FEED_HOLD, OP_FEED_OVERRIDE, OP_RESET, OP_MDI, OP_CYCLE_START}) {
      OperatorCommand c;
      c.seq(seq * 8 + static_cast<std::uint64_t>(action));
      c.action(action);
      c.origin("hmi");
      c.value(0.0);
      c.text(action == OP_MDI ? "G01 X100 Z100 F5000" : "");
      write(commands_, c);
    }
    RunControl rc;
    rc.generation(seq);
    rc.command(RUN_ESTOP);
    rc.reason("rogue");
    write(run_control_, rc);
    ::mcnc::ChannelStatus status;
    status.channel(1);
    status.cycle(seq);
    status.state(::mcnc::CH_IDLE);
    status.program_end(true);
    status.end_code(30);
    status.end_cycle(seq);
    write(status_, status);
    CoordinationEvent arrival;
    arrival.channel(2);
    arrival.seq(seq);
    arrival.kind(COORD_SYNC_ARRIVE);
    arrival.p(1);
    arrival.generation(1);
    arrival.channels(0b11);
    write(events_, arrival);
    AxisSetpoint setpoint;
    setpoint.axis(1);
    setpoint.channel(1);
    setpoint.cycle(seq);
    setpoint.pos(50.0);
    setpoint.valid(true);
    write(setpoints_, setpoint);
    AxisFeedback feedback;
    feedback.axis(1);
    feedback.owner(2);  // X1 handed to CH2
    feedback.cycle(seq);
    feedback.act(50.0);
    write(feedback_, feedback);
  }

 private:
  template <class T, class... Key>
  void make(std::optional<dds::Writer<T>>& writer, const Key&... key) {
    try {
      writer.emplace(participant_, key...);
      ++writers_;
    } catch (const std::runtime_error&) {
      // refused by its own access control plugin
    }
  }
  template <class T, class Sample>
  static void write(std::optional<dds::Writer<T>>& writer, const Sample& sample) {
    if (writer) {
      writer->write(sample);
    }
  }

  dds::Participant participant_;
  std::optional<dds::Writer<OperatorCommand>> commands_;
  std::optional<dds::Writer<RunControl>> run_control_;
  std::optional<dds::Writer<::mcnc::ChannelStatus>> status_;
  std::optional<dds::Writer<CoordinationEvent>> events_;
  std::optional<dds::Writer<AxisSetpoint>> setpoints_;
  std::optional<dds::Writer<AxisFeedback>> feedback_;
  int writers_ = 0;
  static constexpr std::uint64_t kFloodSender = 0x726f677565;
  std::uint64_t flood_seq_ = 0;
  std::mutex mutex_;
  std::map<std::string, int> answers_;
  std::optional<dds::Reader<OperatorAnswer>> answer_reader_;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"a rogue DDS participant (issue 25's tests)"};
  int domain = 0;
  std::string certs;
  std::string identity;
  std::string permissions_ca;
  std::string governance;
  std::string permissions;
  app.add_option("--domain", domain)->required();
  app.add_option("--certs", certs, "a directory `mcnc certs` made");
  app.add_option("--identity", identity, "with --certs: whose files it presents");
  app.add_option("--permissions-ca", permissions_ca, "instead of the directory's");
  app.add_option("--governance", governance, "instead of the directory's");
  app.add_option("--permissions", permissions, "instead of the directory's");
  std::vector<std::uint64_t> flood;
  int count = 40;
  app.add_option("--flood", flood, "only send --count operator commands stamped with each cycle");
  app.add_option("--count", count);
  int announce_to = 0;
  app.add_option("--announce-to", announce_to,
                 "also announce itself to participant indices 0 to N-1 on this host (a secured "
                 "machine discovers by unicast, and its ports follow from the domain)");
  CLI11_PARSE(app, argc, argv);
  if (announce_to > 0) {
    std::string peers;
    for (int index = 0; index < announce_to; ++index) {
      peers += "<Peer address=\"127.0.0.1:" +
               std::to_string(dds::unicast_discovery_port(domain, index)) + "\"/>";
    }
    // Read after the participant's own configuration (idl/cyclonedds_participant.cpp).
    setenv("CYCLONEDDS_URI",
           ("<CycloneDDS><Domain id=\"any\"><Discovery><Peers>" + peers +
            "</Peers></Discovery></Domain></CycloneDDS>")
               .c_str(),
           1);
  }
  std::optional<security::IdentityFiles> files;
  if (!certs.empty()) {
    files = security::identity_files(certs, identity);
    for (auto [given, field] : {std::pair{&permissions_ca, &files->permissions_ca},
                                std::pair{&governance, &files->governance},
                                std::pair{&permissions, &files->permissions}}) {
      if (!given->empty()) {
        *field = *given;
      }
    }
  }
  std::signal(SIGINT, on_stop);
  std::signal(SIGTERM, on_stop);
  try {
    Rogue rogue(domain, files);
    std::printf("writers %d\n", rogue.writers());
    std::fflush(stdout);
    std::uint64_t rounds = 0;
    for (const std::uint64_t cycle : flood) {
      rogue.flood(cycle, count);
    }
    int answered = 0;
    while (g_stop == 0) {
      if (flood.empty()) {
        rogue.publish_round(1000 + rounds);
        ++rounds;
      } else {
        // Each time more answers came: all of them so far.
        const std::map<std::string, int> answers = rogue.flood_answers();
        int total = 0;
        for (const auto& [code, n] : answers) {
          total += n;
        }
        if (total != answered) {
          answered = total;
          std::printf("answers");
          for (const auto& [code, n] : answers) {
            std::printf(" %s %d", code.c_str(), n);
          }
          std::printf("\n");
          std::fflush(stdout);
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    std::printf("rounds %llu\n", static_cast<unsigned long long>(rounds));
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "rogue: %s\n", error.what());
    return 1;
  }
}
