// mcnc-hmi on a running machine: who may command it, what it does with garbage, and (with
// Debian's Chromium driven by playwright-core) an operator running the twin-turret part
// transfer from the page.
#include "harness.hpp"
#include "ws_client.hpp"

#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <random>
#include <regex>
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
  op.send(R"({"type":"auth","token":")" + hmi.token + "\"}");
  ASSERT_TRUE(shows_role(op, "operator"));
  ASSERT_TRUE(eventually([&] { return ch1_state(op) == "idle"; }, 60s));
  op.send(command(1, "cycle_start", "CH1"));
  const nlohmann::json ok = op.wait_for(reply_to(1), 5s);
  ASSERT_FALSE(ok.is_null());
  EXPECT_EQ(ok["ok"], true) << ok;
  EXPECT_EQ(launch.wait(120s), 0) << slurp(machine.file("launch.out"));
  const auto trace = read_trace(machine.file("trace.jsonl"));
  const auto ops = events(trace, "operator", "CH1");
  ASSERT_EQ(ops.size(), 1U);
  EXPECT_EQ(ops[0]["action"], "cycle_start");
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
