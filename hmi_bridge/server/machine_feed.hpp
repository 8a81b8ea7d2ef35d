#pragma once
// mcnc-hmi's side of DDS: what the status topics and the alarm topic say, kept for the
// browsers as the HMI's messages, and the operator commands it sends. Thread-safe: DDS
// callbacks fill it, the server's threads read it.
#include "common/config/machine_config.hpp"
#include "common/process/command_answers.hpp"
#include "hmi_bridge/core/alarm_log.hpp"
#include "hmi_bridge/core/client_message.hpp"
#include "hmi_bridge/core/meeting_tracker.hpp"
#include "idl/dds_participant.hpp"
#include "idl/topics.hpp"
#include "tools/status/status_lines.hpp"

#include <chrono>
#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace mcnc::hmi {

// Why a command was not taken: for people, and for programs the refusal's code and the process
// that refused (both empty when the HMI itself refused).
struct CommandRefusal {
  std::string reason;
  std::string code;
  std::string process;
};

// How long the HMI waits for the machine's answers to a command before it tells the operator
// that none came. The processes answer as a command arrives, not when it takes effect.
inline constexpr std::chrono::milliseconds kAnswerLimit{2000};

class MachineFeed {
 public:
  // `programs`: the main program file of a channel, by channel name (its text is shown until
  // the channel names another file); `program_dir`: where the others are; `security`: the
  // HMI's identity on a secured machine.
  MachineFeed(const config::MachineConfig& machine, int domain,
              std::map<std::string, std::string> programs, std::string program_dir,
              std::optional<security::IdentityFiles> security = std::nullopt);

  // The state message of now; notes the programs channels have moved to.
  std::string state();
  // Alarms and programs that changed since the last call, as messages for every browser.
  std::vector<std::string> take_news();
  // What a browser that starts viewing gets first: the alarm history and every program known.
  std::vector<std::string> welcome();
  // Sends the command as a DDS operator command and waits (kAnswerLimit at most) for every
  // process that serves it to take it: true once they all did. False with the refusal when a
  // process refused it, none answered in time, it cannot go out, or it asks for a program or
  // MDI blocks while the channel does not stand in reset or idle (the channel would refuse it
  // too). Blocks the calling thread only.
  bool send(const CommandMessage& command, CommandRefusal& refusal);
  // Whether every channel and axis has been heard (for start-up logs).
  [[nodiscard]] bool all_heard();

 private:
  struct Program {
    std::string name;
    std::vector<std::string> lines;
  };
  void on_alarm(const ::mcnc::Alarm& a);
  void on_operator(const ::mcnc::OperatorCommand& c);
  void on_coordination(const ::mcnc::CoordinationEvent& e);
  // The text of `name` for `channel`: its main program, a file of the program store, or its
  // last MDI blocks.
  Program load(const std::string& channel, const std::string& name);

  const config::MachineConfig& machine_;
  std::map<std::string, std::string> main_programs_;
  std::string program_dir_;
  std::mutex mutex_;
  status::StatusSnapshot snapshot_;
  AlarmLog alarms_;
  MeetingTracker meetings_;
  std::map<std::string, Program> programs_;  // by channel name
  std::map<std::string, std::string> mdi_;   // the last MDI blocks sent to a channel, by name
  std::vector<std::string> news_;
  std::uint64_t seq_ = 0;
  dds::Participant participant_;
  dds::Writer<::mcnc::OperatorCommand> commands_;
  process::CommandAnswers answers_;
  dds::Reader<::mcnc::ChannelStatus> channels_;
  dds::Reader<::mcnc::AxisFeedback> axes_;
  dds::Reader<::mcnc::Alarm> alarm_reader_;
  dds::Reader<::mcnc::OperatorCommand> command_reader_;
  dds::Reader<::mcnc::CoordinationEvent> coordination_reader_;
  dds::Reader<::mcnc::RunControl> run_reader_;
};

}  // namespace mcnc::hmi
