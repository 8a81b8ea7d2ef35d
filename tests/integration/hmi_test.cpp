// mcnc-hmi on a running machine: who may command it, what it does with garbage, that idle and
// half-open connections and oversized frames do not keep the operator out, and (with Debian's
// Chromium driven by playwright-core) an operator running the twin-turret part transfer from
// the page.
#include "harness.hpp"
#include "ws_client.hpp"

#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <sstream>
#include <thread>

using namespace std::chrono_literals;
using namespace mcnc::test;

namespace {

// `mcnc run` of `programs` (CH=FILE) waiting for CYCLE START, paced, with the HMI on any
// free port.
std::vector<std::string> hmi_run(const TestMachine& machine,
                                 const std::vector<std::string>& programs,
                                 const std::vector<std::string>& more = {}) {
  std::vector<std::string> argv{bin("mcnc"), "run", machine.path()};
  argv.insert(argv.end(), more.begin(), more.end());
  for (const std::string& p : programs) {
    argv.insert(argv.end(), {"--program", p});
  }
  argv.insert(argv.end(), {"--manual-start", "--pace", "--hmi", "127.0.0.1:0", "--trace",
                           machine.file("trace.jsonl")});
  return argv;
}

// The HMI's port and operator token, as mcnc run prints them once the HMI listens.
struct HmiAddress {
  int port = 0;
  std::string token;
};

HmiAddress wait_for_hmi(const std::string& out_file) {
  HmiAddress a;
  eventually(
      [&] {
        const std::string out = slurp(out_file);
        std::smatch m;
        if (std::regex_search(out, m, std::regex(R"(HMI at http://127\.0\.0\.1:([0-9]+)/)"))) {
          a.port = std::stoi(m[1]);
        }
        if (std::regex_search(out, m, std::regex(R"(operator token: ([0-9a-f]{32}))"))) {
          a.token = m[1];
        }
        return a.port != 0 && !a.token.empty();
      },
      60s);
  return a;
}

std::string command(int id, const std::string& action, const std::string& channel) {
  return R"({"type":"command","id":)" + std::to_string(id) + R"(,"action":")" + action +
         R"(","channel":")" + channel + R"("})";
}

auto reply_to(int id) {
  return [id](const nlohmann::json& j) {
    return j.is_object() && j.value("type", "") == "reply" && j.value("id", -1) == id;
  };
}

// Waits until the server tells `client` its role is `role`.
bool shows_role(WsClient& client, const std::string& role) {
  return !client
              .wait_for(
                  [&](const nlohmann::json& j) {
                    return j.is_object() && j.value("type", "") == "role" &&
                           j.value("role", "") == role;
                  },
                  5s)
              .is_null();
}

// Sends a cycle start for CH1 as command `id`; expects it refused for `reason`.
void expect_refused(WsClient& client, int id, const std::string& reason) {
  client.send(command(id, "cycle_start", "CH1"));
  const nlohmann::json reply = client.wait_for(reply_to(id), 5s);
  ASSERT_FALSE(reply.is_null());
  EXPECT_EQ(reply["ok"], false);
  EXPECT_EQ(reply["reason"], reason);
}

auto type_is(const std::string& type) {
  return [type](const nlohmann::json& j) { return j.is_object() && j.value("type", "") == type; };
}

// The last state CH1 was seen in by `client`.
std::string ch1_state(WsClient& client) {
  const auto states = client.of_type("state");
  if (states.empty() || states.back()["channels"][0]["state"].is_null()) {
    return "";
  }
  return states.back()["channels"][0]["state"];
}

constexpr const char* kViewerToken = "viewer-token-for-the-tests";

// `op`, connected, shows the operator token and starts CH1's program (waiting for its cycle
// start): the start is answered ok.
void operator_starts_ch1(WsClient& op, const HmiAddress& hmi) {
  op.send(R"({"type":"auth","token":")" + hmi.token + "\"}");
  ASSERT_TRUE(shows_role(op, "operator"));
  ASSERT_TRUE(eventually([&] { return ch1_state(op) == "idle"; }, 60s));
  op.send(command(1, "cycle_start", "CH1"));
  const nlohmann::json ok = op.wait_for(reply_to(1), 5s);
  ASSERT_FALSE(ok.is_null());
  EXPECT_EQ(ok["ok"], true) << ok;
}

// The run of xz_move.nc ended well, started once by the operator.
void ch1_ran_to_its_end_once_started(Background& launch, const TestMachine& machine) {
  EXPECT_EQ(launch.wait(120s), 0) << slurp(machine.file("launch.out"));
  const auto trace = read_trace(machine.file("trace.jsonl"));
  const auto ops = events(trace, "operator", "CH1");
  ASSERT_EQ(ops.size(), 1U);
  EXPECT_EQ(ops[0]["action"], "cycle_start");
  ASSERT_FALSE(trace.empty());
  EXPECT_EQ(trace.back()["channels"]["CH1"]["end"], 30);
}

// A raw TCP connection to the HMI from `source`, an address of the loopback net (the server sees
// each such address as a peer of its own); -1 when it cannot connect.
int raw_connect(int port, const std::string& source) {
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in from{};
  from.sin_family = AF_INET;
  ::inet_pton(AF_INET, source.c_str(), &from.sin_addr);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(static_cast<std::uint16_t>(port));
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::bind(fd, reinterpret_cast<sockaddr*>(&from), sizeof from) != 0 ||
      ::connect(fd, reinterpret_cast<sockaddr*>(&to), sizeof to) != 0) {
    ::close(fd);
    return -1;
  }
  const timeval two_seconds{2, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &two_seconds, sizeof two_seconds);
  ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &two_seconds, sizeof two_seconds);
  return fd;
}

// Asks for the WebSocket on `fd` and reads the answer's head: true when it is switched.
bool raw_upgrade(int fd) {
  const std::string request =
      "GET /ws HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n\r\n";
  if (::send(fd, request.data(), request.size(), MSG_NOSIGNAL) !=
      static_cast<ssize_t>(request.size())) {
    return false;
  }
  std::string answer;
  char c = 0;
  while (answer.find("\r\n\r\n") == std::string::npos && ::recv(fd, &c, 1, 0) == 1) {
    answer += c;
  }
  return answer.starts_with("HTTP/1.1 101");
}

// Whether the server ends `fd` (end of stream, or reset) within `within`; what it sends before is
// read and dropped.
bool ended_by_server(int fd, std::chrono::milliseconds within) {
  const auto until = std::chrono::steady_clock::now() + within;
  std::array<char, 65536> buffer{};
  while (std::chrono::steady_clock::now() < until) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) == 1) {
      const ssize_t n = ::recv(fd, buffer.data(), buffer.size(), MSG_DONTWAIT);
      if (n == 0 || (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK)) {
        return true;
      }
    }
  }
  return false;
}

// The largest resident set `pid` has had, in bytes (VmHWM of /proc/PID/status).
std::uint64_t peak_resident_bytes(pid_t pid) {
  const std::string status = slurp("/proc/" + std::to_string(pid) + "/status");
  std::smatch m;
  if (!std::regex_search(status, m, std::regex(R"(VmHWM:\s+([0-9]+) kB)"))) {
    return 0;
  }
  return std::stoull(m[1]) * 1024;
}

// The pid of the mcnc-hmi that runs `machine`, or -1.
pid_t hmi_pid(const TestMachine& machine) {
  for (const pid_t pid : pids_with_arg(machine.path())) {
    if (slurp("/proc/" + std::to_string(pid) + "/comm").starts_with("mcnc-hmi")) {
      return pid;
    }
  }
  return -1;
}

// Closes the descriptors it holds when it goes.
struct RawSockets {
  std::vector<int> fds;
  ~RawSockets() {
    for (const int fd : fds) {
      if (fd >= 0) {
        ::close(fd);
      }
    }
  }
};

}  // namespace

TEST(Hmi, CommandsWithoutTheOperatorTokenOrFromAForeignPageChangeNothing) {
  TestMachine machine("small_lathe.yaml", 86);
  std::ofstream(machine.path(), std::ios::app)
      << "\nhmi:\n  viewer_token: " << kViewerToken << "\n";
  Background launch(hmi_run(machine, {"CH1=" + source("launch/programs/xz_move.nc")}), -1,
                    machine.file("launch"));
  const HmiAddress hmi = wait_for_hmi(machine.file("launch.out"));
  ASSERT_NE(hmi.port, 0) << slurp(machine.file("launch.out")) << slurp(machine.file("launch.err"));

  // A page of another site cannot open the socket.
  WsClient foreign("127.0.0.1", hmi.port, "http://evil.example:" + std::to_string(hmi.port));
  EXPECT_FALSE(foreign.connected());

  // Without a token (a viewer token is configured): nothing seen, commands refused.
  WsClient anonymous("127.0.0.1", hmi.port, "http://127.0.0.1:" + std::to_string(hmi.port));
  ASSERT_TRUE(anonymous.connected()) << anonymous.error();
  ASSERT_FALSE(anonymous.wait_for(type_is("role"), 5s).is_null());
  EXPECT_EQ(anonymous.of_type("role").back()["role"], "none");
  expect_refused(anonymous, 1, "commands need the operator token");

  // A viewer sees the machine and cannot command it.
  WsClient viewer("127.0.0.1", hmi.port, "");
  ASSERT_TRUE(viewer.connected()) << viewer.error();
  viewer.send(std::string(R"({"type":"auth","token":")") + kViewerToken + "\"}");
  ASSERT_TRUE(shows_role(viewer, "viewer"));
  ASSERT_TRUE(eventually([&] { return ch1_state(viewer) == "idle"; }, 60s));
  expect_refused(viewer, 2, "a viewer cannot command: show the operator token");
  // A wrong token gives nothing, and the socket is closed: every guess costs a connection.
  WsClient guesser("127.0.0.1", hmi.port, "");
  ASSERT_TRUE(guesser.connected()) << guesser.error();
  guesser.send(R"({"type":"auth","token":"guess"})");
  const nlohmann::json unknown = guesser.wait_for(type_is("error"), 5s);
  ASSERT_FALSE(unknown.is_null());
  EXPECT_EQ(unknown["reason"], "unknown token");
  EXPECT_EQ(guesser.of_type("role").back()["role"], "none");
  guesser.send(command(3, "cycle_start", "CH1"));
  EXPECT_TRUE(guesser.wait_for(reply_to(3), 2s).is_null());

  // Nothing changed: the channel still waits for its cycle start, a second later.
  std::this_thread::sleep_for(1s);
  EXPECT_EQ(ch1_state(viewer), "idle");
  EXPECT_TRUE(anonymous.of_type("state").empty());  // it saw nothing either

  launch.kill(SIGINT);
  launch.wait(60s);
  const auto trace = read_trace(machine.file("trace.jsonl"));
  EXPECT_TRUE(events(trace, "operator").empty());
  EXPECT_TRUE(events(trace, "block", "CH1").empty());
}

TEST(Hmi, TenThousandMalformedMessagesLeaveItServingAndTheOperatorStartsTheProgram) {
  TestMachine machine("small_lathe.yaml", 87);
  Background launch(hmi_run(machine, {"CH1=" + source("launch/programs/xz_move.nc")}), -1,
                    machine.file("launch"));
  const HmiAddress hmi = wait_for_hmi(machine.file("launch.out"));
  ASSERT_NE(hmi.port, 0) << slurp(machine.file("launch.out"));

  WsClient noisy("127.0.0.1", hmi.port, "");
  ASSERT_TRUE(noisy.connected()) << noisy.error();
  std::mt19937 rng(8);
  for (int i = 0; i < 10000; ++i) {
    std::string garbage(1 + rng() % 300, ' ');
    for (char& c : garbage) {
      c = static_cast<char>(rng() % 256);
    }
    switch (i % 4) {
      case 0:
        break;  // random bytes
      case 1:
        garbage = R"({"type":"command","id":)" + std::to_string(i) +
                  R"(,"action":"feed_override",)"
                  R"("channel":"CH1","value":1e999})";
        break;
      case 2:
        garbage = R"({"type":"command","id":"x","action":[1,{"a":null}]})";
        break;
      default:
        garbage = std::string(5000, '{');
        break;
    }
    ASSERT_TRUE(noisy.send(garbage)) << i;
  }
  // Every one answered with an error (or a refusal), none taken for a command.
  ASSERT_TRUE(eventually(
      [&] { return noisy.of_type("error").size() + noisy.of_type("reply").size() >= 10000; }, 60s))
      << noisy.received().size();
  for (const auto& r : noisy.of_type("reply")) {
    EXPECT_EQ(r["ok"], false);
  }

  // Still serving: the operator connects and starts the program; it runs to its end.
  WsClient op("127.0.0.1", hmi.port, "http://localhost:" + std::to_string(hmi.port));
  ASSERT_TRUE(op.connected()) << op.error();
  ASSERT_NO_FATAL_FAILURE(operator_starts_ch1(op, hmi));
  ASSERT_NO_FATAL_FAILURE(ch1_ran_to_its_end_once_started(launch, machine));
}

// The machine's answers to a rogue's flood, as its last "answers" line says: by refusal code.
std::map<std::string, int> rogue_answers(const std::string& out) {
  std::map<std::string, int> answers;
  const auto at = out.rfind("answers");
  if (at == std::string::npos) {
    return answers;
  }
  std::istringstream line(out.substr(at + 7, out.find('\n', at) - at - 7));
  std::string code;
  int n = 0;
  while (line >> code >> n) {
    answers[code] = n;
  }
  return answers;
}

// Issue 25: a participant floods the machine with feed holds stamped for cycle 2^64-1, for a
// cycle long past and for one far ahead but within the hour a process keeps commands for. The
// machine refuses each with its reason, which reaches the flooder; the ones it keeps fill only
// the slots left to commands for later. The operator's RESET and CYCLE START through the HMI are
// then answered ok because every process took them, and obeyed: the program runs to its end
// and no feed hold ever takes effect.
TEST(Hmi, AFloodOfStampedCommandsIsRefusedWithReasonsAndTheOperatorIsStillTakenAndObeyed) {
  TestMachine machine("small_lathe.yaml", 183);
  Background launch(hmi_run(machine, {"CH1=" + source("launch/programs/xz_move.nc")}), -1,
                    machine.file("launch"));
  const HmiAddress hmi = wait_for_hmi(machine.file("launch.out"));
  ASSERT_NE(hmi.port, 0) << slurp(machine.file("launch.out")) << slurp(machine.file("launch.err"));
  WsClient op("127.0.0.1", hmi.port, "");
  ASSERT_TRUE(op.connected()) << op.error();
  op.send(R"({"type":"auth","token":")" + hmi.token + "\"}");
  ASSERT_TRUE(shows_role(op, "operator"));
  // Past cycle 2500: a stamp of 1 is more than a second (1000 cycles) old.
  ASSERT_TRUE(eventually(
      [&] {
        const auto states = op.of_type("state");
        return ch1_state(op) == "idle" && states.back()["cycle"].get<std::uint64_t>() > 2500;
      },
      60s));

  const std::string rogue_log = machine.file("rogue");
  Background rogue({bin("mcnc_rogue"), "--domain", std::to_string(machine.domain()), "--flood",
                    "18446744073709551615", "--flood", "1", "--flood", "2000000", "--count", "40"},
                   -1, rogue_log);
  // CH1 answers all 120 (an axis node serves only resets).
  ASSERT_TRUE(eventually(
      [&] {
        int total = 0;
        for (const auto& [code, n] : rogue_answers(slurp(rogue_log + ".out"))) {
          total += n;
        }
        return total >= 120;
      },
      30s))
      << slurp(rogue_log + ".out") << slurp(rogue_log + ".err");
  const std::map<std::string, int> answers = rogue_answers(slurp(rogue_log + ".out"));
  EXPECT_EQ(answers, (std::map<std::string, int>{
                         {"too_far_ahead", 40}, {"stale", 40}, {"taken", 24}, {"inbox_full", 16}}));

  // The operator's commands, answered by CH1 (and a reset by the axis nodes too).
  for (const auto& [id, action] : {std::pair{1, "reset"}, std::pair{2, "cycle_start"}}) {
    op.send(command(id, action, "CH1"));
    const nlohmann::json reply = op.wait_for(reply_to(id), 10s);
    ASSERT_FALSE(reply.is_null()) << action;
    EXPECT_EQ(reply, nlohmann::json::parse(R"({"type":"reply","id":)" + std::to_string(id) +
                                           R"(,"ok":true,"reason":""})"))
        << action;
  }
  EXPECT_EQ(launch.wait(120s), 0) << slurp(machine.file("launch.out"));
  rogue.kill(SIGTERM);
  rogue.wait(20s);
  const auto trace = read_trace(machine.file("trace.jsonl"));
  const auto ops = events(trace, "operator", "CH1");
  ASSERT_EQ(ops.size(), 2U);
  EXPECT_EQ(ops[0]["action"], "reset");
  EXPECT_EQ(ops[1]["action"], "cycle_start");
  ASSERT_FALSE(trace.empty());
  EXPECT_EQ(trace.back()["channels"]["CH1"]["end"], 30);
}

TEST(Hmi, AnOperatorRunsThePartTransferFromTheBrowser) {
  TestMachine machine("twin_turret.yaml", 88);
  Background launch(hmi_run(machine, {"CH1=" + source("launch/programs/part_transfer_ch1.nc"),
                                      "CH2=" + source("launch/programs/part_transfer_ch2.nc")}),
                    -1, machine.file("launch"));
  const HmiAddress hmi = wait_for_hmi(machine.file("launch.out"));
  ASSERT_NE(hmi.port, 0) << slurp(machine.file("launch.out"));
  const std::string shots = std::string(MCNC_BINARY_DIR) + "/hmi-screenshots";
  const RunResult browser =
      run({"/usr/bin/env", "node", source("tests/e2e/hmi_browser.mjs"),
           "http://127.0.0.1:" + std::to_string(hmi.port) + "/#token=" + hmi.token, shots},
          -1, 360s);
  if (browser.exit_code != 0) {
    launch.kill(SIGINT);  // the machine would wait for its operator
  }
  const int launch_exit = launch.wait(120s);
  // The browser's steps (each with its wall and machine time) and its error come last, where
  // the end of a long log still shows them.
  const std::string launch_out = slurp(machine.file("launch.out"));
  EXPECT_EQ(launch_exit, 0) << launch_out.substr(launch_out.size() -
                                                 std::min<std::size_t>(launch_out.size(), 2000));

  // What the page did reached the machine: the cycle starts and the feed hold from the HMI.
  const auto trace = read_trace(machine.file("trace.jsonl"));
  const auto actions = [&](const std::string& ch) {
    std::vector<std::string> list;
    for (const auto& e : events(trace, "operator", ch)) {
      list.push_back(e["action"]);
    }
    return list;
  };
  // CH1 is proved out at 10 % feed override, back to 100 % after the hold.
  EXPECT_EQ(actions("CH1"), (std::vector<std::string>{"feed_override", "cycle_start", "feed_hold",
                                                      "cycle_start", "feed_override"}));
  std::vector<double> overrides;
  for (const auto& e : events(trace, "operator", "CH1")) {
    if (e["action"] == "feed_override") {
      overrides.push_back(e["value"]);
    }
  }
  EXPECT_EQ(overrides, (std::vector<double>{10.0, 100.0}));
  EXPECT_EQ(actions("CH2"), (std::vector<std::string>{"cycle_start"}));
  EXPECT_FALSE(trace.empty());
  if (!trace.empty()) {
    EXPECT_EQ(trace.back()["channels"]["CH1"]["end"], 30);
    EXPECT_EQ(trace.back()["channels"]["CH2"]["end"], 30);
  }
  std::cout << browser.out;
  EXPECT_EQ(browser.exit_code, 0) << browser.err;
}

TEST(Hmi, AnOperatorRunsMdiBlocksThenSelectsAnotherProgramAndRunsIt) {
  TestMachine machine("small_lathe.yaml", 89);
  const std::string store = machine.file("store");
  std::filesystem::create_directories(store);
  std::ofstream(store + "/other.nc") << "O2000 (selected from the HMI)\nG00 X30 Z20\n"
                                        "G01 Z-20 F600\nM30\n";
  Background launch(
      hmi_run(machine, {"CH1=" + source("launch/programs/xz_move.nc")}, {"--progdir", store}), -1,
      machine.file("launch"));
  const HmiAddress hmi = wait_for_hmi(machine.file("launch.out"));
  ASSERT_NE(hmi.port, 0) << slurp(machine.file("launch.out"));
  WsClient op("127.0.0.1", hmi.port, "");
  ASSERT_TRUE(op.connected()) << op.error();
  op.send(R"({"type":"auth","token":")" + hmi.token + "\"}");
  ASSERT_TRUE(shows_role(op, "operator"));
  ASSERT_TRUE(eventually([&] { return ch1_state(op) == "idle"; }, 60s));
  const auto with_text = [](int id, const std::string& action, const std::string& text) {
    return R"({"type":"command","id":)" + std::to_string(id) + R"(,"action":")" + action +
           R"(","channel":"CH1","text":")" + text + "\"}";
  };
  const auto program_named = [](const std::string& name) {
    return [name](const nlohmann::json& j) {
      return j.is_object() && j.value("type", "") == "program" && j.value("name", "") == name;
    };
  };

  // MDI: the block runs at once; the page shows it as the channel's "MDI" program.
  op.send(with_text(1, "mdi", "G00 X20 Z5"));
  nlohmann::json reply = op.wait_for(reply_to(1), 5s);
  ASSERT_FALSE(reply.is_null());
  EXPECT_EQ(reply["ok"], true) << reply;
  const nlohmann::json mdi = op.wait_for(program_named("MDI"), 60s);
  ASSERT_FALSE(mdi.is_null());
  EXPECT_EQ(mdi["lines"], nlohmann::json::array({"G00 X20 Z5"}));
  ASSERT_TRUE(eventually([&] { return ch1_state(op) == "idle"; }, 60s));

  // Select a file of the program store; it replaces xz_move.nc, which never runs.
  op.send(with_text(2, "select_program", "other.nc"));
  reply = op.wait_for(reply_to(2), 5s);
  ASSERT_FALSE(reply.is_null());
  EXPECT_EQ(reply["ok"], true) << reply;
  const nlohmann::json other = op.wait_for(program_named("other.nc"), 60s);
  ASSERT_FALSE(other.is_null());
  EXPECT_EQ(other["lines"].size(), 4U);
  op.send(command(3, "cycle_start", "CH1"));
  ASSERT_TRUE(eventually([&] { return ch1_state(op) == "running"; }, 60s));
  // While it runs, neither MDI nor another program: refused by the HMI, as by the channel.
  op.send(with_text(4, "mdi", "G00 X0"));
  reply = op.wait_for(reply_to(4), 5s);
  ASSERT_FALSE(reply.is_null());
  EXPECT_EQ(reply["ok"], false);
  EXPECT_EQ(reply["reason"], "mdi: the channel must stand in reset or idle");
  EXPECT_EQ(launch.wait(120s), 0) << slurp(machine.file("launch.out"));

  const auto trace = read_trace(machine.file("trace.jsonl"));
  std::vector<std::string> order;  // what CH1 did, in order
  for (const auto& e : trace) {
    if (e.value("src", "") != "CH1") {
      continue;
    }
    const std::string ev = e["ev"];
    if (ev == "operator") {
      order.push_back("operator " + e["action"].get<std::string>() +
                      (e.contains("text") ? " " + e["text"].get<std::string>() : ""));
    } else if (ev == "block") {
      order.push_back("block " + e["prog"].get<std::string>() + ":" +
                      std::to_string(e["line"].get<int>()) + " " + e["text"].get<std::string>());
    } else if (ev == "mdi_end" || ev == "end") {
      order.push_back(ev + " " + std::to_string(e["code"].get<int>()));
    } else if (ev == "program") {
      order.push_back("program " + e["prog"].get<std::string>() + " " +
                      std::to_string(e["blocks"].get<int>()));
    }
  }
  EXPECT_EQ(order, (std::vector<std::string>{
                       "operator mdi G00 X20 Z5",
                       "block MDI:1 G00 X20 Z5",
                       "mdi_end 0",
                       "operator select_program other.nc",
                       "program other.nc 3",
                       "operator cycle_start",
                       "block other.nc:2 G00 X30 Z20",
                       "block other.nc:3 G01 Z-20 F600",
                       "block other.nc:4 M30",
                       "end 30",
                   }));
  // The MDI block went where it said (X in diameter: the slide at radius 10).
  bool mdi_end_seen = false;
  for (const auto& e : trace) {
    if (e.value("src", "") == "CH1" && e["ev"] == "pos" && !mdi_end_seen) {
      if (e["axis"] == "X1") {
        EXPECT_NEAR(e["cmd"].get<double>(), 10.0, 1e-6);
      } else {
        EXPECT_NEAR(e["cmd"].get<double>(), 5.0, 1e-6);
      }
    }
    mdi_end_seen = mdi_end_seen || e["ev"] == "mdi_end";
  }
  EXPECT_TRUE(mdi_end_seen);
  ASSERT_FALSE(trace.empty());
  EXPECT_EQ(trace.back()["channels"]["CH1"]["end"], 30);
}

TEST(Hmi, FiftyIdleAndHalfOpenConnectionsDoNotKeepTheOperatorOut) {
  TestMachine machine("small_lathe.yaml", 187);
  Background launch(hmi_run(machine, {"CH1=" + source("launch/programs/xz_move.nc")}), -1,
                    machine.file("launch"));
  const HmiAddress hmi = wait_for_hmi(machine.file("launch.out"));
  ASSERT_NE(hmi.port, 0) << slurp(machine.file("launch.out"));

  // 12 sockets that never show a token, each from an address of its own: viewers (no viewer
  // token is configured), on every seat that viewers may take.
  RawSockets viewers;
  for (int i = 1; i <= 12; ++i) {
    viewers.fds.push_back(raw_connect(hmi.port, "127.0.1." + std::to_string(i)));
    ASSERT_TRUE(raw_upgrade(viewers.fds.back())) << i;
  }
  // 13 more from the operator's own address, and 25 that connect and say nothing.
  RawSockets idle;
  for (int i = 1; i <= 13; ++i) {
    idle.fds.push_back(raw_connect(hmi.port, "127.0.0.1"));
    raw_upgrade(idle.fds.back());
  }
  RawSockets half_open;
  for (int i = 1; i <= 25; ++i) {
    half_open.fds.push_back(raw_connect(hmi.port, "127.0.2." + std::to_string(i)));
    ASSERT_GE(half_open.fds.back(), 0) << i;
  }

  // The operator gets in while they are held, and is obeyed.
  WsClient op("127.0.0.1", hmi.port, "");
  ASSERT_TRUE(op.connected()) << op.error();
  ASSERT_NO_FATAL_FAILURE(operator_starts_ch1(op, hmi));

  // The server ended the half-open connections and the sockets beyond the viewers' seats.
  for (std::size_t i = 0; i < half_open.fds.size(); ++i) {
    EXPECT_TRUE(ended_by_server(half_open.fds[i], 10s)) << "half-open " << i;
  }
  for (std::size_t i = 0; i < idle.fds.size(); ++i) {
    EXPECT_TRUE(ended_by_server(idle.fds[i], 10s)) << "idle socket " << i;
  }

  ASSERT_NO_FATAL_FAILURE(ch1_ran_to_its_end_once_started(launch, machine));
}

TEST(Hmi, AGigabyteFrameAnnouncedWithoutATokenIsRefusedBeforeItIsRead) {
  TestMachine machine("small_lathe.yaml", 196);
  std::ofstream(machine.path(), std::ios::app)
      << "\nhmi:\n  viewer_token: " << kViewerToken << "\n";
  Background launch(hmi_run(machine, {"CH1=" + source("launch/programs/xz_move.nc")}), -1,
                    machine.file("launch"));
  const HmiAddress hmi = wait_for_hmi(machine.file("launch.out"));
  ASSERT_NE(hmi.port, 0) << slurp(machine.file("launch.out"));
  const pid_t server = hmi_pid(machine);
  ASSERT_GT(server, 0);
  std::cout << "mcnc-hmi's peak resident set before: " << peak_resident_bytes(server) / 1024
            << " kB\n";

  RawSockets raw;
  raw.fds.push_back(raw_connect(hmi.port, "127.0.0.1"));
  ASSERT_TRUE(raw_upgrade(raw.fds[0]));
  // A masked text frame announcing 1 GiB, then its payload for as long as the server takes it.
  std::string header = "\x81\xff";
  for (int shift = 56; shift >= 0; shift -= 8) {
    header += static_cast<char>(((1ULL << 30) >> shift) & 0xFF);
  }
  header += "\x01\x02\x03\x04";
  ASSERT_EQ(::send(raw.fds[0], header.data(), header.size(), MSG_NOSIGNAL),
            static_cast<ssize_t>(header.size()));
  const std::string mebibyte(1 << 20, 'x');
  std::uint64_t sent = 0;
  constexpr std::uint64_t kOffered = 160ULL << 20;
  while (sent < kOffered) {
    const ssize_t n = ::send(raw.fds[0], mebibyte.data(), mebibyte.size(), MSG_NOSIGNAL);
    if (n <= 0) {
      break;  // the server closed it (or stopped reading for 2 s)
    }
    sent += static_cast<std::uint64_t>(n);
  }
  EXPECT_LT(sent, kOffered) << "the server read on";
  EXPECT_TRUE(ended_by_server(raw.fds[0], 5s));
  const std::uint64_t peak = peak_resident_bytes(server);
  EXPECT_GT(peak, 0U);
  EXPECT_LT(peak, 100ULL << 20) << "mcnc-hmi's peak resident set " << peak / 1024 << " kB";

  // Still serving: the operator gets in.
  WsClient op("127.0.0.1", hmi.port, "");
  ASSERT_TRUE(op.connected()) << op.error();
  op.send(R"({"type":"auth","token":")" + hmi.token + "\"}");
  EXPECT_TRUE(shows_role(op, "operator"));
  launch.kill(SIGINT);
  launch.wait(60s);
}
