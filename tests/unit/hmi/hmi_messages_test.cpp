#include "hmi_bridge/core/hmi_messages.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

namespace mcnc::hmi {
namespace {

config::MachineConfig twin() {
  config::MachineConfig m;
  m.name = "twin";
  m.cycle_us = 2000;
  for (int i = 1; i <= 2; ++i) {
    config::ChannelConfig ch;
    ch.name = "CH" + std::to_string(i);
    ch.id = i;
    ch.axes = {"X" + std::to_string(i)};
    m.channels.push_back(ch);
  }
  m.channels[1].exchange_axes = {"A1"};
  for (const char* name : {"X1", "X2", "A1"}) {
    config::AxisConfig a;
    a.name = name;
    a.id = static_cast<int>(m.axes.size()) + 1;
    a.address = name[0];
    a.type = name[0] == 'A' ? config::AxisType::rotary : config::AxisType::linear;
    a.diameter = name[0] == 'X';
    a.channel = name[1] == '2' ? "CH2" : "CH1";
    m.axes.push_back(a);
  }
  return m;
}

TEST(HmiMessages, TheMachineMessageGivesTheLayout) {
  const auto j = nlohmann::json::parse(machine_message(twin()));
  EXPECT_EQ(j["type"], "machine");
  EXPECT_EQ(j["cycle_us"], 2000);
  EXPECT_EQ(j["channels"][1]["exchange_axes"], nlohmann::json::array({"A1"}));
  EXPECT_EQ(j["axes"][2]["address"], "A");
  EXPECT_EQ(j["axes"][2]["type"], "rotary");
  EXPECT_EQ(j["axes"][0]["diameter"], true);
}

TEST(HmiMessages, TheStateSaysWhatEachChannelWaitsForAndWhoOwnsEachAxis) {
  status::StatusSnapshot s;
  status::ChannelView ch2;
  ch2.state = channel::ChannelState::waiting;
  ch2.cycle = 500;
  ch2.sync_p = 1;
  ch2.sync_channels = 0b11;
  ch2.sync_waiting_for = 0b01;
  ch2.program = "ch2.nc";
  ch2.line = 4;
  ch2.feed_override = 50.0;
  s.channels[2] = ch2;
  status::AxisView a1;
  a1.owner = 2;
  a1.act = 30.5;
  a1.drive_state = 4;
  s.axes[3] = a1;
  const auto j = nlohmann::json::parse(state_message(twin(), s));
  EXPECT_EQ(j["cycle"], 500);
  EXPECT_DOUBLE_EQ(j["time_s"].get<double>(), 1.0);
  EXPECT_TRUE(j["channels"][0]["state"].is_null());  // CH1 not heard
  const auto& c = j["channels"][1];
  EXPECT_EQ(c["state"], "waiting");
  EXPECT_EQ(c["wait"]["kind"], "mark");
  EXPECT_EQ(c["wait"]["p"], 1);
  EXPECT_EQ(c["wait"]["participants"], nlohmann::json::array({"CH1", "CH2"}));
  EXPECT_EQ(c["wait"]["waiting_for"], nlohmann::json::array({"CH1"}));
  EXPECT_EQ(c["program"], "ch2.nc");
  EXPECT_EQ(c["line"], 4);
  EXPECT_DOUBLE_EQ(c["feed_override"].get<double>(), 50.0);
  EXPECT_TRUE(c["call"].is_null());
  EXPECT_EQ(j["axes"][2]["owner"], "CH2");
  EXPECT_EQ(j["axes"][2]["drive"], "operation_enabled");
  EXPECT_TRUE(j["axes"][0]["drive"].is_null());  // X1 not heard
}

TEST(HmiMessages, AG144WaitNamesItsTarget) {
  status::StatusSnapshot s;
  status::ChannelView ch1;
  ch1.state = channel::ChannelState::waiting;
  ch1.call_waiting_for = 2;
  s.channels[1] = ch1;
  const auto j = nlohmann::json::parse(state_message(twin(), s));
  EXPECT_EQ(j["channels"][0]["wait"], (nlohmann::json{{"kind", "call"}, {"target", "CH2"}}));
}

TEST(HmiMessages, AFinWaitNamesItsCodeEvenWhileThePathRunsAndAnExchangeItsAxis) {
  status::StatusSnapshot s;
  status::ChannelView ch1;
  ch1.state = channel::ChannelState::running;  // an M code's FIN: the path may still move
  ch1.waiting_m = 10;
  s.channels[1] = ch1;
  status::ChannelView ch2;
  ch2.state = channel::ChannelState::waiting;
  ch2.waiting_exchange = 141;
  ch2.waiting_axis = 3;
  s.channels[2] = ch2;
  auto j = nlohmann::json::parse(state_message(twin(), s));
  EXPECT_EQ(j["channels"][0]["wait"], (nlohmann::json{{"kind", "fin"}, {"code", "M10"}}));
  EXPECT_EQ(j["channels"][1]["wait"],
            (nlohmann::json{{"kind", "exchange"}, {"g", 141}, {"axis", "A1"}}));
  s.channels[1].waiting_m = -1;
  s.channels[1].waiting_t = 101;
  s.channels[2].waiting_exchange = 142;
  s.channels[2].waiting_axis = 0;  // G142: every axis the channel lent or took
  j = nlohmann::json::parse(state_message(twin(), s));
  EXPECT_EQ(j["channels"][0]["wait"]["code"], "T0101");
  EXPECT_TRUE(j["channels"][1]["wait"]["axis"].is_null());
  s.channels[1].waiting_t = -1;
  j = nlohmann::json::parse(state_message(twin(), s));
  EXPECT_TRUE(j["channels"][0]["wait"].is_null());  // running, waiting for nothing
}

TEST(HmiMessages, TheRunPhaseAndAnEStopsCause) {
  status::StatusSnapshot s;
  auto j = nlohmann::json::parse(state_message(twin(), s));
  EXPECT_EQ(j["run"]["phase"], "starting");
  s.run.phase = status::RunPhase::estop;
  s.run.reason = "CH1 lost axis Z1";
  j = nlohmann::json::parse(state_message(twin(), s));
  EXPECT_EQ(j["run"], (nlohmann::json{{"phase", "estop"}, {"reason", "CH1 lost axis Z1"}}));
}

TEST(HmiMessages, TheModalCodesAreListedAsTheControlWritesThem) {
  status::StatusSnapshot s;
  status::ChannelView ch1;
  ch1.modal_g = {0, 180, 0, 990, 960, 210, 410, 541};  // group 03 (G90/G91) has no code
  ch1.modal_feed = 0.25;
  s.channels[1] = ch1;
  const auto j = nlohmann::json::parse(state_message(twin(), s));
  EXPECT_EQ(j["channels"][0]["modal"],
            nlohmann::json::array({"G00", "G18", "G99", "G96", "G21", "G41", "G54.1"}));
  EXPECT_DOUBLE_EQ(j["channels"][0]["feed"].get<double>(), 0.25);
}

TEST(HmiMessages, AlarmsAndProgramTextsThatAreNotUtf8StillMakeJson) {
  AlarmLog log;
  AlarmEntry e;
  e.src = "CH1";
  e.seq = 1;
  e.number = 1101;
  e.text = "bad \xff byte";
  e.channel = 1;
  ASSERT_TRUE(log.add(e));
  const auto j = nlohmann::json::parse(alarms_message(twin(), log));
  EXPECT_EQ(j["list"][0]["channel"], "CH1");
  EXPECT_EQ(j["list"][0]["number"], 1101);
  const auto p = nlohmann::json::parse(program_message("CH1", "p.nc", {"G00 X1", "(\xfe)"}));
  EXPECT_EQ(p["lines"].size(), 2U);
}

TEST(HmiMessages, ATakenCommandsReplyIsAsBeforeARefusedOneNamesItsCodeAndProcess) {
  EXPECT_EQ(reply_message(4, true, ""), R"({"id":4,"ok":true,"reason":"","type":"reply"})");
  EXPECT_EQ(reply_message(5, false, "commands need the operator token"),
            R"({"id":5,"ok":false,"reason":"commands need the operator token","type":"reply"})");
  const auto refused = nlohmann::json::parse(
      reply_message(6, false, "refused by CH1 (inbox_full): why", "inbox_full", "CH1"));
  EXPECT_EQ(refused["ok"], false);
  EXPECT_EQ(refused["refusal"], "inbox_full");
  EXPECT_EQ(refused["process"], "CH1");
  const auto unanswered =
      nlohmann::json::parse(reply_message(7, false, "no answer from CH1", "unanswered"));
  EXPECT_EQ(unanswered["refusal"], "unanswered");
  EXPECT_FALSE(unanswered.contains("process"));
}

TEST(AlarmLog, AnAlarmIsKeptOnceAndAcknowledgedOnce) {
  AlarmLog log;
  AlarmEntry e;
  e.src = "X1";
  e.seq = 4;
  EXPECT_TRUE(log.add(e));
  EXPECT_FALSE(log.add(e));  // delivered again to a late reader
  e.src = "X2";
  EXPECT_TRUE(log.add(e));  // same seq, another process
  const AlarmEntry* acked = log.acknowledge("X1", 4);
  ASSERT_NE(acked, nullptr);
  EXPECT_TRUE(acked->acknowledged);
  EXPECT_EQ(log.acknowledge("X1", 4), nullptr);
  EXPECT_EQ(log.acknowledge("X1", 5), nullptr);
  EXPECT_FALSE(log.entries()[1].acknowledged);
}

TEST(AlarmLog, TheOldestGoFirst) {
  AlarmLog log;
  for (std::uint64_t i = 1; i <= AlarmLog::kKept + 3; ++i) {
    AlarmEntry e;
    e.src = "CH1";
    e.seq = i;
    log.add(e);
  }
  EXPECT_EQ(log.entries().size(), AlarmLog::kKept);
  EXPECT_EQ(log.entries().front().seq, 4U);
}

}  // namespace
// An alarm in a called program names its file and column beside the line (issue 25).
TEST(HmiMessages, AnAlarmNamesTheFileAndColumnOfItsLine) {
  AlarmEntry e;
  e.src = "CH3";
  e.seq = 2;
  e.number = 3105;
  e.text = "bad address";
  e.channel = 3;
  e.line = 3;
  e.program = "progs/O2000.nc";
  e.column = 10;
  const auto j = nlohmann::json::parse(alarm_message(twin(), e));
  EXPECT_EQ(j["line"], 3);
  EXPECT_EQ(j["program"], "progs/O2000.nc");
  EXPECT_EQ(j["column"], 10);
}

}  // namespace mcnc::hmi
