#include "hmi_bridge/core/client_message.hpp"

#include "common/text/file_name.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <variant>

namespace mcnc::hmi {
namespace {

using process::OperatorActionKind;

config::MachineConfig two_channels() {
  config::MachineConfig m;
  m.name = "lathe";
  config::ChannelConfig ch1;
  ch1.name = "CH1";
  ch1.id = 1;
  config::ChannelConfig ch2;
  ch2.name = "CH2";
  ch2.id = 2;
  m.channels = {ch1, ch2};
  return m;
}

std::string reason_of(const ClientMessage& m) {
  const auto* e = std::get_if<MessageError>(&m);
  return e == nullptr ? std::string("(no error)") : e->reason;
}

TEST(ClientMessage, ACommandNamesItsChannelByName) {
  const ClientMessage m = read_client_message(
      R"({"type":"command","id":7,"action":"cycle_start","channel":"CH2"})", two_channels());
  const auto* c = std::get_if<CommandMessage>(&m);
  ASSERT_NE(c, nullptr) << reason_of(m);
  EXPECT_EQ(c->id, 7);
  EXPECT_EQ(c->action, OperatorActionKind::cycle_start);
  EXPECT_EQ(c->channel, 2U);
}

TEST(ClientMessage, WithoutAChannelACommandIsForTheWholeMachine) {
  const ClientMessage m =
      read_client_message(R"({"type":"command","id":1,"action":"reset"})", two_channels());
  const auto* c = std::get_if<CommandMessage>(&m);
  ASSERT_NE(c, nullptr) << reason_of(m);
  EXPECT_EQ(c->channel, 0U);
}

TEST(ClientMessage, OverridesAreReadInTheirRangeAndRefusedOutsideIt) {
  const auto read = [](const std::string& action, const std::string& value) {
    return read_client_message(R"({"type":"command","id":3,"action":")" + action +
                                   R"(","channel":"CH1","value":)" + value + "}",
                               two_channels());
  };
  const ClientMessage ok = read("feed_override", "150");
  ASSERT_TRUE(std::holds_alternative<CommandMessage>(ok)) << reason_of(ok);
  EXPECT_DOUBLE_EQ(std::get<CommandMessage>(ok).value, 150.0);
  EXPECT_EQ(reason_of(read("feed_override", "201")), "feed_override: value out of 0-200");
  EXPECT_EQ(reason_of(read("rapid_override", "101")), "rapid_override: value out of 0-100");
  EXPECT_EQ(reason_of(read("spindle_override", "49")), "spindle_override: value out of 50-120");
  EXPECT_EQ(reason_of(read("feed_override", "\"50\"")), "feed_override needs a number \"value\"");
  EXPECT_EQ(reason_of(read("single_block", "2")), "single_block: value out of 0-1");
  // A refused command keeps its id for the reply.
  EXPECT_EQ(std::get<MessageError>(read("feed_override", "-1")).id, 3);
}

TEST(ClientMessage, ChannelActionsNeedAChannelAndTextsAreChecked) {
  const config::MachineConfig m = two_channels();
  EXPECT_EQ(reason_of(read_client_message(
                R"({"type":"command","id":1,"action":"mdi","text":"G00 X10"})", m)),
            "mdi needs a \"channel\"");
  EXPECT_EQ(reason_of(read_client_message(
                R"({"type":"command","id":1,"action":"mdi","channel":"CH1"})", m)),
            "mdi needs a \"text\"");
  EXPECT_EQ(reason_of(read_client_message(
                R"({"type":"command","id":1,"action":"select_program","channel":"CH1",)"
                R"("text":"../etc/passwd"})",
                m)),
            "a program is named by its file name in the program store");
  EXPECT_NE(reason_of(read_client_message(
                R"({"type":"command","id":1,"action":"mdi","channel":"CH1","text":"G00\nX1"})", m)),
            "(no error)");
  EXPECT_NE(reason_of(read_client_message(R"({"type":"command","id":1,"action":"mdi",)"
                                          R"("channel":"CH1","text":")" +
                                              std::string(200, 'X') + "\"}",
                                          m)),
            "(no error)");
  const ClientMessage mdi = read_client_message(
      R"({"type":"command","id":1,"action":"mdi","channel":"CH1","text":"G00 X10"})", m);
  ASSERT_TRUE(std::holds_alternative<CommandMessage>(mdi)) << reason_of(mdi);
  EXPECT_EQ(std::get<CommandMessage>(mdi).text, "G00 X10");
}

TEST(ClientMessage, UnknownChannelsActionsAndTypesAreErrors) {
  const config::MachineConfig m = two_channels();
  EXPECT_EQ(reason_of(read_client_message(
                R"({"type":"command","id":1,"action":"reset","channel":"CH9"})", m)),
            "no channel \"CH9\" on this machine");
  EXPECT_EQ(reason_of(read_client_message(R"({"type":"command","id":1,"action":"explode"})", m)),
            "unknown action \"explode\"");
  EXPECT_EQ(reason_of(read_client_message(R"({"type":"command","action":"reset"})", m)),
            "a command needs an integer \"id\"");
  EXPECT_EQ(reason_of(read_client_message(R"({"type":"hello"})", m)),
            "unknown message type \"hello\"");
  EXPECT_EQ(reason_of(read_client_message(R"([1,2])", m)), "not a JSON object");
  EXPECT_EQ(reason_of(read_client_message("{\"type\":", m)), "not a JSON object");
  EXPECT_EQ(reason_of(read_client_message(std::string(kMaxMessageBytes + 1, ' '), m)),
            "message longer than 4096 bytes");
}

TEST(ClientMessage, OnlyPlainFileNamesNameAProgram) {
  EXPECT_TRUE(text::is_plain_file_name("O1100.nc"));
  EXPECT_TRUE(text::is_plain_file_name("part transfer.nc"));
  for (const char* name : {"", ".", "..", "../O1100.nc", "/etc/passwd", "a/b.nc", "a\\b.nc"}) {
    EXPECT_FALSE(text::is_plain_file_name(name)) << name;
  }
}

TEST(ClientMessage, AnAuthCarriesItsToken) {
  const ClientMessage m = read_client_message(R"({"type":"auth","token":"abc"})", two_channels());
  ASSERT_TRUE(std::holds_alternative<AuthMessage>(m));
  EXPECT_EQ(std::get<AuthMessage>(m).token, "abc");
}

TEST(ClientMessage, RandomBytesAreErrorsNeverCommands) {
  // Fixed seed: the same 20 000 messages every run, mutations of a valid command.
  std::mt19937 rng(20261202);
  const std::string valid = R"({"type":"command","id":5,"action":"feed_override","value":120})";
  const config::MachineConfig m = two_channels();
  int commands = 0;
  for (int i = 0; i < 20000; ++i) {
    std::string text = valid;
    const int edits = 1 + static_cast<int>(rng() % 4);
    for (int e = 0; e < edits; ++e) {
      text[rng() % text.size()] = static_cast<char>(rng() % 256);
    }
    const ClientMessage msg = read_client_message(text, m);
    if (const auto* c = std::get_if<CommandMessage>(&msg)) {
      // A mutation that is still a command must still be a valid one.
      ++commands;
      EXPECT_NE(c->action, OperatorActionKind::none);
      if (c->action == OperatorActionKind::feed_override) {
        EXPECT_GE(c->value, 0.0);
        EXPECT_LE(c->value, 200.0);
      }
    }
  }
  EXPECT_LT(commands, 20000);
}

}  // namespace
}  // namespace mcnc::hmi
