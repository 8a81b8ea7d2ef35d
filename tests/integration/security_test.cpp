// Nobody outside the machine commands it (issue 25): a machine secured by `mcnc certs` ignores a
// participant of the attacker's, which joins its DDS domain without a certificate, with another
// machine's, and with the machine's own viewer certificate under permissions it forged; the same
// participant commands an unsecured machine. A machine whose certificates are bad starts nothing.
#include "common/security/identity_files.hpp"
#include "common/security/machine_permissions.hpp"
#include "common/security/pki/pki.hpp"
#include "harness.hpp"
#include "launch/ephemeral_ports.hpp"
#include "launch/port_reservation.hpp"

#include <gtest/gtest.h>

#include <sys/mount.h>
#include <sys/ptrace.h>
#include <sys/wait.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <set>

using namespace mcnc;
using namespace mcnc::test;
using namespace std::chrono_literals;
namespace fs = std::filesystem;

namespace {

using Trace = std::vector<nlohmann::json>;

// Domains no other test uses.
constexpr int kSecuredDomain = 207;
constexpr int kUnsecuredDomain = 208;
constexpr int kBadCertificatesDomain = 209;
constexpr int kHungTeardownDomain = 213;
constexpr int kOneHostDomain = 222;
constexpr int kAcrossHostsDomain = 225;
// Its small lathe's fixed ports, 60660-60669, lie in Linux's default ephemeral range.
constexpr int kEphemeralPortsDomain = 213;

// CH1 reaches its wait mark long before CH2: a fake arrival of CH2 would release it early.
constexpr const char* kCh1 = "G00 X20 Z5\nG01 Z-10 F600\nG04.1 P1 Q12\nG01 X30 F600\nM30\n";
constexpr const char* kCh2 = "G00 X20 Z5\nG01 Z-40 F300\nG04.1 P1 Q12\nG01 X30 F300\nM30\n";

std::string write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// `mcnc certs` for `machine_file` into `dir`.
void make_certs(const std::string& machine_file, const std::string& dir) {
  const RunResult r = run({bin("mcnc"), "certs", machine_file, dir}, -1, 120s);
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
}

// The machine file of `machine` naming `dir` (relative to it) as its security_dir.
void name_security_dir(const TestMachine& machine, const std::string& dir) {
  const std::string text = slurp(machine.path());
  write_text(machine.path(), std::regex_replace(text, std::regex("machine:\n"),
                                                "machine:\n  security_dir: " + dir + "\n"));
}

struct Outcome {
  int exit_code = -1;
  std::string output;
  Trace trace;
};

// The two channels' programs run on `machine`; `during` runs while the machine runs.
Outcome run_programs(const TestMachine& machine, const std::string& name) {
  const std::string trace_file = machine.file(name + ".jsonl");
  const RunResult r =
      run({bin("mcnc"), "run", machine.path(), "--program",
           "CH1=" + write_text(machine.file("ch1.nc"), kCh1), "--program",
           "CH2=" + write_text(machine.file("ch2.nc"), kCh2), "--trace", trace_file},
          -1, 240s);
  return Outcome{r.exit_code, r.out + r.err, read_trace(trace_file)};
}

// A participant of an attacker's (tests/integration/rogue): it joins `domain` over the network
// with `args` (none: no DDS Security) and publishes what would command the machine until it is
// destroyed.
class Rogue {
 public:
  Rogue(const TestMachine& machine, const std::string& name, std::vector<std::string> args)
      : log_(machine.file("rogue-" + name)) {
    // It also announces itself to the ports a secured machine's processes discover on: an
    // attacker on the host knows the DDSI port mapping (decision 137).
    std::vector<std::string> argv{bin("mcnc_rogue"), "--domain", std::to_string(machine.domain()),
                                  "--announce-to", "20"};
    argv.insert(argv.end(), args.begin(), args.end());
    process_ = std::make_unique<Background>(argv, -1, log_);
    // Its writers are made before the machine starts.
    eventually([&] { return slurp(log_ + ".out").find("writers") != std::string::npos; }, 20s);
  }
  // How many kinds of sample its own access control let it write.
  [[nodiscard]] int writers() const { return number_after("writers "); }
  // Stops it; how many rounds of samples it wrote.
  int stop() {
    process_->kill(SIGTERM);
    EXPECT_EQ(process_->wait(20s), 0) << slurp(log_ + ".err");
    return number_after("rounds ");
  }

 private:
  [[nodiscard]] int number_after(const std::string& label) const {
    const std::string out = slurp(log_ + ".out");
    const auto at = out.find(label);
    return at == std::string::npos ? -1 : std::stoi(out.substr(at + label.size()));
  }
  std::string log_;
  std::unique_ptr<Background> process_;
};

// Permissions of the attacker's own: everything granted to the machine's viewer, signed by a CA
// the attacker made (the machine's CA key stays with its integrator). The rogue's arguments.
std::vector<std::string> forged_viewer(const std::string& certs, const std::string& dir) {
  fs::create_directories(dir);
  const auto now = std::chrono::system_clock::now();
  const security::KeyAndCertificate ca = security::make_ca("CA.attacker", now - 1h, now + 24h);
  const security::Identity everything{"viewer", security::Role::launcher, {"*"}};
  return {"--certs",
          certs,
          "--identity",
          security::kViewerIdentity,
          "--permissions-ca",
          write_text(dir + "/attacker_ca.pem", ca.certificate_pem),
          "--permissions",
          write_text(dir + "/permissions.p7s",
                     security::sign_document(
                         ca, security::permissions_xml(
                                 "twin_turret", {everything},
                                 {security::xml_date(now - 1h), security::xml_date(now + 24h)}))),
          "--governance",
          write_text(
              dir + "/governance.p7s",
              security::sign_document(ca, security::governance_xml(security::Protection::sign)))};
}

// One thread of another process held still, as a thread that spins for good would hold what
// waits for it: ptrace-stopped (the rest of its process runs on), until the process ends.
class HeldThread {
 public:
  explicit HeldThread(pid_t tid) : tid_(tid) {
    held_ = ::ptrace(PTRACE_SEIZE, tid_, nullptr, nullptr) == 0 &&
            ::ptrace(PTRACE_INTERRUPT, tid_, nullptr, nullptr) == 0;
  }
  ~HeldThread() { (void)::ptrace(PTRACE_DETACH, tid_, nullptr, nullptr); }
  HeldThread(const HeldThread&) = delete;
  HeldThread& operator=(const HeldThread&) = delete;
  [[nodiscard]] bool held() const { return held_; }
  // Its process cannot be reaped before its tracer has reaped the thread's own end.
  void reap() const {
    int status = 0;
    (void)::waitpid(tid_, &status, __WALL | WNOHANG);
  }

 private:
  pid_t tid_;
  bool held_ = false;
};

// The thread of process `pid` whose name is `name`, or -1.
pid_t thread_named(pid_t pid, const std::string& name) {
  std::error_code ec;
  for (const auto& task : fs::directory_iterator("/proc/" + std::to_string(pid) + "/task", ec)) {
    std::string comm = slurp(task.path().string() + "/comm");
    if (!comm.empty() && comm.back() == '\n') {
      comm.pop_back();
    }
    if (comm == name) {
      return static_cast<pid_t>(std::stol(task.path().filename().string()));
    }
  }
  return -1;
}

std::set<std::string> shm_listing() {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator("/dev/shm")) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

}  // namespace

TEST(Security, ASecuredMachineIgnoresParticipantsWithoutItsCertificatesOrBeyondTheirPermissions) {
  TestMachine machine("twin_turret.yaml", kSecuredDomain);
  make_certs(machine.path(), machine.file("certs"));
  TestMachine other("small_lathe.yaml", kSecuredDomain);
  make_certs(other.path(), other.file("certs"));
  name_security_dir(machine, "certs");

  const Outcome alone = run_programs(machine, "alone");
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  EXPECT_EQ(alone.output.find("UNSECURED"), std::string::npos) << alone.output;
  ASSERT_FALSE(events(alone.trace, "sync_release", "CH1").empty());

  // The viewer's own access control refuses it every writer.
  {
    Rogue viewer(machine, "viewer", {"--certs", machine.file("certs"), "--identity", "viewer"});
    EXPECT_EQ(viewer.writers(), 0);
    viewer.stop();
  }

  std::vector<std::unique_ptr<Rogue>> rogues;
  rogues.push_back(std::make_unique<Rogue>(machine, "uncertified", std::vector<std::string>{}));
  EXPECT_EQ(rogues.back()->writers(), 6);
  // Another machine's launcher, channel and axis node write among them every kind of sample.
  for (const std::string identity : {"launch", "CH1", "X1"}) {
    rogues.push_back(std::make_unique<Rogue>(
        machine, "other-" + identity,
        std::vector<std::string>{"--certs", other.file("certs"), "--identity", identity}));
  }
  EXPECT_EQ(rogues[1]->writers(), 2);  // operator commands and run control
  EXPECT_EQ(rogues[2]->writers(), 3);  // CH1's status, coordination, X1's setpoints
  EXPECT_EQ(rogues[3]->writers(), 1);  // X1's feedback
  rogues.push_back(std::make_unique<Rogue>(
      machine, "forged", forged_viewer(machine.file("certs"), machine.file("forged"))));
  EXPECT_EQ(rogues.back()->writers(), 6);
  const Outcome attacked = run_programs(machine, "attacked");
  for (const auto& rogue : rogues) {
    EXPECT_GT(rogue->stop(), 10);
  }
  ASSERT_EQ(attacked.exit_code, 0) << attacked.output;
  // Not a sample of theirs reached the machine: the trace is the undisturbed run's, cycle for
  // cycle (the barrier released as late, no hold, no reset, no E-stop, no early end).
  EXPECT_EQ(trace_until_end(attacked.trace), trace_until_end(alone.trace));
}

TEST(Security, AnUnsecuredMachineSaysSoOnceAndObeysAnyParticipant) {
  TestMachine machine("twin_turret.yaml", kUnsecuredDomain);
  const Outcome alone = run_programs(machine, "alone");
  ASSERT_EQ(alone.exit_code, 0) << alone.output;
  const std::regex warning("warning: machine twin_turret runs UNSECURED on DDS domain 208");
  EXPECT_EQ(std::distance(std::sregex_iterator(alone.output.begin(), alone.output.end(), warning),
                          std::sregex_iterator()),
            1)
      << alone.output;

  Rogue rogue(machine, "uncertified", {});
  const Outcome attacked = run_programs(machine, "attacked");
  EXPECT_GT(rogue.stop(), 10);
  // Obeyed: the rogue's E-stop (or its reset, its feed hold) ended the run before its programs.
  EXPECT_NE(attacked.exit_code, 0) << attacked.output;
  EXPECT_NE(trace_until_end(attacked.trace), trace_until_end(alone.trace));
}

TEST(Security, BadCertificatesStopTheStartNamingTheFileAndNothingStarts) {
  TestMachine machine("twin_turret.yaml", kBadCertificatesDomain);
  const std::string certs = machine.file("certs");
  make_certs(machine.path(), certs);
  name_security_dir(machine, "certs");
  const security::IdentityFiles ch1 = security::identity_files(certs, "CH1");
  const security::KeyAndCertificate ca{slurp(security::ca_key_file(certs)),
                                       slurp(ch1.ca_certificate)};
  const std::string good_certificate = slurp(ch1.certificate);
  const std::string good_key = slurp(ch1.private_key);
  const auto now = std::chrono::system_clock::now();

  const auto expect_refused = [&](const std::string& named_file, const std::string& reason,
                                  const std::string& what) {
    const std::string trace_file = machine.file("trace-" + what + ".jsonl");
    const RunResult r =
        run({bin("mcnc"), "run", machine.path(), "--program",
             "CH1=" + write_text(machine.file("ch1.nc"), kCh1), "--trace", trace_file},
            -1, 60s);
    EXPECT_EQ(r.exit_code, 2) << what << ": " << r.out << r.err;
    EXPECT_NE(r.err.find(named_file + ": "), std::string::npos) << what << ": " << r.err;
    EXPECT_NE(r.err.find(reason), std::string::npos) << what << ": " << r.err;
    EXPECT_NE(r.err.find("nothing started"), std::string::npos) << what << ": " << r.err;
    EXPECT_FALSE(fs::exists(trace_file)) << what;
    EXPECT_FALSE(fs::exists(trace_file + ".parts")) << what;
  };

  const security::KeyAndCertificate expired = security::make_identity(
      ca, security::common_name("twin_turret", "CH1"), now - 48h, now - 24h);
  write_text(ch1.certificate, expired.certificate_pem);
  write_text(ch1.private_key, expired.key_pem);
  expect_refused(ch1.certificate, "expired", "expired");

  const security::KeyAndCertificate stranger =
      security::make_ca("CA.stranger", now - 1h, now + 24h);
  const security::KeyAndCertificate foreign = security::make_identity(
      stranger, security::common_name("twin_turret", "CH1"), now - 1h, now + 24h);
  write_text(ch1.certificate, foreign.certificate_pem);
  write_text(ch1.private_key, foreign.key_pem);
  expect_refused(ch1.certificate, ch1.ca_certificate, "wrong CA");

  write_text(ch1.certificate, good_certificate);
  fs::remove(ch1.private_key);
  expect_refused(ch1.private_key, "cannot read", "missing key");

  write_text(ch1.private_key, "-----BEGIN PRIVATE KEY-----\ngarbage\n-----END PRIVATE KEY-----\n");
  expect_refused(ch1.private_key, "not an unencrypted PEM private key", "unreadable key");

  write_text(ch1.private_key, good_key);
  // Nor does a secured machine that mixes the implementations (their handshakes fail), or one
  // on a domain above Cyclone DDS's access control's 230.
  const std::string file = slurp(machine.path());
  write_text(machine.path(), std::regex_replace(file, std::regex("  - name: CH1\n"),
                                                "  - name: CH1\n    middleware: fastdds\n"));
  RunResult refused = run(
      {bin("mcnc"), "run", machine.path(), "--program", "CH1=" + machine.file("ch1.nc")}, -1, 60s);
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_NE(refused.err.find("runs every process on one DDS implementation, but launch runs on "
                             "cyclonedds and CH1 on fastdds"),
            std::string::npos)
      << refused.err;
  write_text(machine.path(), file);
  refused = run({bin("mcnc"), "run", machine.path(), "--program", "CH1=" + machine.file("ch1.nc")},
                231, 60s);
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_NE(refused.err.find("domains 0-230"), std::string::npos) << refused.err;

  // With its files back the machine runs, secured.
  const RunResult good = run({bin("mcnc"), "run", machine.path(), "--program",
                              "CH1=" + write_text(machine.file("short.nc"), "G00 X20 Z5\nM30\n")},
                             -1, 240s);
  EXPECT_EQ(good.exit_code, 0) << good.out << good.err;
}

// Cyclone DDS 0.10's security handshake thread ("fsm") can spin for good (a race on a
// handshake's time-out), and the deletion of a secured participant then waits for it: `mcnc
// run` hung after a failed start until killed, SIGTERM doing nothing. Here the launcher's fsm
// thread is held still once the run is under way: the run ends as it should, `mcnc run` says
// what happened and leaves with the run's exit code within its bound, with its RouDi, every
// child and every file of the run in /dev/shm gone.
TEST(Security, ALauncherWhoseDdsSecurityTeardownHangsStillEndsInBoundedTime) {
  isolate_iceoryx_host();  // its RouDi and /dev/shm are the test's: what is left is the run's
  TestMachine machine("small_lathe.yaml", kHungTeardownDomain);
  make_certs(machine.path(), machine.file("certs"));
  name_security_dir(machine, "certs");
  const std::set<std::string> shm_before = shm_listing();
  Background launcher({bin("mcnc"), "run", machine.path(), "--pace", "--program",
                       "CH1=" + source("launch/programs/xz_move.nc")},
                      -1, machine.file("launch"));
  const auto output = [&] {
    return slurp(machine.file("launch.out")) + slurp(machine.file("launch.err"));
  };
  ASSERT_TRUE(eventually(
      [&] { return slurp(machine.file("launch.out")).find("running") != std::string::npos; }, 120s))
      << output();
  const pid_t fsm = thread_named(launcher.pid(), "fsm");
  ASSERT_GT(fsm, 0) << "no Cyclone DDS security thread in the launcher";
  const HeldThread held(fsm);
  ASSERT_TRUE(held.held()) << std::strerror(errno);
  const auto held_at = std::chrono::steady_clock::now();
  int code = -1000;
  while (code == -1000 && std::chrono::steady_clock::now() < held_at + 60s) {
    held.reap();
    code = launcher.wait(1s);
  }
  const auto took =
      std::chrono::duration_cast<std::chrono::seconds>(std::chrono::steady_clock::now() - held_at);
  std::cout << "mcnc run left " << took.count() << " s after its fsm thread was held\n";
  ASSERT_NE(code, -1000) << "mcnc run still there 60 s after its run\n" << output();
  EXPECT_EQ(code, 0) << output();
  EXPECT_NE(output().find("ok after 4829 cycles"), std::string::npos) << output();
  EXPECT_NE(output().find("DDS teardown did not end within 10 s"), std::string::npos) << output();
  EXPECT_TRUE(pids_with_arg(machine.path()).empty()) << "a child of the run is left";
  EXPECT_TRUE(pids_with_arg("mcnc-roudi-" + std::to_string(launcher.pid())).empty())
      << "its RouDi is left";
  EXPECT_EQ(shm_listing(), shm_before) << output();
}

// A secured machine's processes listen on fixed ports (decision 137); from domain 102 up those
// lie in Linux's ephemeral port range, where another program's outgoing socket may take one.
// The launcher reserves them (net.ipv4.ip_local_reserved_ports) before anything starts, and
// refuses the start, naming the domain and the setting, when it cannot.
TEST(Security, ASecuredMachineReservesItsFixedPortsInTheEphemeralRangeOrDoesNotStart) {
  isolate_iceoryx_host();  // a mount namespace: /proc/sys is made read-only in it alone
  TestMachine machine("small_lathe.yaml", kEphemeralPortsDomain);
  make_certs(machine.path(), machine.file("certs"));
  name_security_dir(machine, "certs");
  const std::string setting = "/proc/sys/net/ipv4/ip_local_reserved_ports";
  const auto range = launch::parse_port_range(slurp("/proc/sys/net/ipv4/ip_local_port_range"));
  ASSERT_TRUE(range);
  const auto ports =
      launch::fixed_ports(config::load_machine_file(machine.path()), kEphemeralPortsDomain);
  ASSERT_TRUE(ports);
  ASSERT_TRUE(ports->first >= range->first && ports->last <= range->last)
      << "the host's ephemeral range " << launch::port_list({*range}) << " misses the ports "
      << launch::port_list({*ports});
  // Not reserved yet: the test takes back what an earlier run reserved.
  const auto reserved = launch::parse_port_list(slurp(setting));
  ASSERT_TRUE(reserved);
  std::vector<launch::PortRange> others;
  for (const launch::PortRange& r : *reserved) {
    for (const launch::PortRange& kept : launch::exposed_ports(r, {0, 65535}, {*ports})) {
      others.push_back(kept);
    }
  }
  std::ofstream(setting) << launch::port_list(others) << "\n";
  const auto run_short = [&](const std::string& name) {
    return run({bin("mcnc"), "run", machine.path(), "--program",
                "CH1=" + write_text(machine.file("short.nc"), "G00 X20 Z5\nM30\n"), "--trace",
                machine.file(name + ".jsonl")},
               -1, 240s);
  };

  // The settings read-only, as for a launcher that is not root.
  ASSERT_EQ(::mount("/proc/sys", "/proc/sys", nullptr, MS_BIND, nullptr), 0)
      << std::strerror(errno);
  ASSERT_EQ(::mount(nullptr, "/proc/sys", nullptr, MS_BIND | MS_REMOUNT | MS_RDONLY, nullptr), 0)
      << std::strerror(errno);
  const RunResult refused = run_short("refused");
  ASSERT_EQ(::umount("/proc/sys"), 0) << std::strerror(errno);
  EXPECT_EQ(refused.exit_code, 2) << refused.out << refused.err;
  EXPECT_NE(refused.err.find("error: machine.domain 213 (or MCNC_DOMAIN): the secured machine's "
                             "processes listen on the fixed ports 60660-60669"),
            std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("sysctl -w net.ipv4.ip_local_reserved_ports="), std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("nothing started"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(machine.file("refused.jsonl")));

  const RunResult good = run_short("good");
  EXPECT_EQ(good.exit_code, 0) << good.out << good.err;
  const auto now_reserved = launch::parse_port_list(slurp(setting));
  ASSERT_TRUE(now_reserved);
  EXPECT_TRUE(launch::exposed_ports(*ports, *range, *now_reserved).empty())
      << launch::port_list(*now_reserved);
}

// A secured machine across hosts discovers by unicast at its hosts' addresses, each process
// only the processes it talks to (decision 151), as on one host: it runs, its trace the one-host
// machine's, on a network that carries no multicast between the hosts (before, its processes
// announced themselves only by multicast there, and no process of one host met another's).
TEST(Security, ASecuredMachineAcrossHostsDiscoversItsPeersByUnicastWithoutMulticast) {
  const std::map<std::string, std::string> programs{{"CH1", "launch/programs/twin_turret_ch1.nc"},
                                                    {"CH2", "launch/programs/twin_turret_ch2.nc"}};
  const auto one_host = run_programs("cell_3ncu.yaml", kOneHostDomain, programs);
  const HostsRun across = run_across_hosts("cell_3ncu.yaml", kAcrossHostsDomain,
                                           {{"ncu1", "CH1, X1, Z1, A1, S1, can0, CH3, X3, can2"},
                                            {"ncu2", "CH2, X2, Z2, S2, Z3, can1, plc, hmi"}},
                                           programs, HostsRunOptions{true, true});
  expect_same_trace(one_host, across.trace);
}
