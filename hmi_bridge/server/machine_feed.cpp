#include "hmi_bridge/server/machine_feed.hpp"

#include "channel/interp/command.hpp"
#include "common/config/cyclic_routes.hpp"
#include "common/process/process_node.hpp"
#include "common/text/file_name.hpp"
#include "common/text/text_lines.hpp"
#include "hmi_bridge/core/hmi_messages.hpp"
#include "tools/status/wire/status_wire.hpp"

#include <chrono>
#include <filesystem>

namespace mcnc::hmi {

MachineFeed::MachineFeed(const config::MachineConfig& machine, int domain,
                         std::map<std::string, std::string> programs, std::string program_dir,
                         std::optional<security::IdentityFiles> security)
    : machine_(machine),
      main_programs_(std::move(programs)),
      program_dir_(std::move(program_dir)),
      participant_(domain, "hmi", dds::CyclicClock::realtime,
                   process::resolve_middleware(machine, "HMI"), dds::LocalTransport::shared_memory,
                   std::move(security)),
      commands_(participant_),
      answers_(participant_, machine),
      // Reliable: a run's end is in its last few samples (docs/decisions.md 26).
      channels_(participant_, dds::Keys::of(config::channel_names(machine)),
                [this](const ::mcnc::ChannelStatus& s, const dds::WriterId&) {
                  std::lock_guard<std::mutex> lock(mutex_);
                  snapshot_.channels[s.channel()] = status::view_of(s);
                }),
      // An observer: the axes' feedback changes every cycle, and an HMI behind the machine
      // must not add to its work.
      axes_(
          participant_, dds::Keys::of(config::node_keys(machine)),
          [this](const ::mcnc::AxisFeedback& f, const dds::WriterId&) {
            std::lock_guard<std::mutex> lock(mutex_);
            snapshot_.axes[f.axis()] = status::view_of(f);
          },
          {}, dds::ReaderRole::observer),
      alarm_reader_(participant_,
                    [this](const ::mcnc::Alarm& a, const dds::WriterId&) { on_alarm(a); }),
      command_reader_(participant_, [this](const ::mcnc::OperatorCommand& c,
                                           const dds::WriterId&) { on_operator(c); }),
      coordination_reader_(participant_, [this](const ::mcnc::CoordinationEvent& e,
                                                const dds::WriterId&) { on_coordination(e); }),
      run_reader_(participant_, [this](const ::mcnc::RunControl& r, const dds::WriterId&) {
        std::lock_guard<std::mutex> lock(mutex_);
        switch (r.command()) {
          case RUN_START:
            snapshot_.run.phase = status::RunPhase::running;
            break;
          case RUN_STOP:
            snapshot_.run.phase = status::RunPhase::stopped;
            break;
          case RUN_ESTOP:
            snapshot_.run.phase = status::RunPhase::estop;
            break;
          default:
            snapshot_.run.phase = status::RunPhase::starting;
            break;
        }
        snapshot_.run.reason = r.reason();
      }) {
  for (const auto& [channel, path] : main_programs_) {
    programs_[channel] =
        Program{std::filesystem::path(path).filename().string(), text::read_lines(path)};
  }
}

void MachineFeed::on_alarm(const ::mcnc::Alarm& a) {
  AlarmEntry e;
  e.src = a.src();
  e.seq = a.seq();
  e.number = a.number();
  e.text = a.text();
  e.channel = a.channel();
  e.axis = a.axis();
  e.line = a.line();
  e.program = a.program();
  e.column = a.column();
  e.cycle = a.cycle();
  std::lock_guard<std::mutex> lock(mutex_);
  if (alarms_.add(e)) {
    news_.push_back(alarm_message(machine_, alarms_.entries().back()));
  }
}

void MachineFeed::on_operator(const ::mcnc::OperatorCommand& c) {
  if (c.action() == OP_MDI && c.channel() >= 1 && c.channel() <= machine_.channels.size()) {
    // Any HMI's MDI blocks (this one's too): the text the channel's "MDI" program shows.
    const std::string& channel = machine_.channels[c.channel() - 1].name;
    std::lock_guard<std::mutex> lock(mutex_);
    mdi_[channel] = c.text();
    if (const auto it = programs_.find(channel);
        it != programs_.end() && it->second.name == interp::kMdiName) {
      programs_.erase(it);  // shown again, with the new blocks, when they run
    }
    return;
  }
  // Any HMI's acknowledgement (this one's too, as it comes back) marks the alarm everywhere.
  if (c.action() != OP_ALARM_ACK) {
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (const AlarmEntry* e = alarms_.acknowledge(c.text(), static_cast<std::uint64_t>(c.value()))) {
    news_.push_back(alarm_message(machine_, *e));
  }
}

void MachineFeed::on_coordination(const ::mcnc::CoordinationEvent& e) {
  if (e.kind() != COORD_SYNC_ARRIVE) {
    return;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (const auto m =
          meetings_.arrive(e.channel(), e.p(), e.generation(), e.channels(), e.cycle())) {
    news_.push_back(meeting_message(machine_, *m));
  }
}

MachineFeed::Program MachineFeed::load(const std::string& channel, const std::string& name) {
  if (name == interp::kMdiName) {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = mdi_.find(channel);
    return Program{name,
                   it == mdi_.end() ? std::vector<std::string>{} : text::split_lines(it->second)};
  }
  const auto main = main_programs_.find(channel);
  if (main != main_programs_.end() && std::filesystem::path(main->second).filename() == name) {
    return Program{name, text::read_lines(main->second)};
  }
  // The name comes from the wire: a plain file of the program store, of a program's size.
  constexpr std::uintmax_t kLargestProgram = 16U << 20U;
  if (!program_dir_.empty() && text::is_plain_file_name(name)) {
    const std::filesystem::path path = std::filesystem::path(program_dir_) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(path, ec) &&
        std::filesystem::file_size(path, ec) <= kLargestProgram && !ec) {
      return Program{name, text::read_lines(path.string())};
    }
  }
  return Program{name, {}};
}

std::string MachineFeed::state() {
  status::StatusSnapshot snapshot;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    snapshot = snapshot_;
  }
  // A channel that moved to another file (a subprogram, a selected program): its text, read
  // here, outside the lock and the DDS threads.
  for (const auto& [id, view] : snapshot.channels) {
    if (id < 1 || id > machine_.channels.size() || view.program.empty()) {
      continue;
    }
    const std::string& channel = machine_.channels[id - 1].name;
    bool changed = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const auto it = programs_.find(channel);
      changed = it == programs_.end() || it->second.name != view.program;
    }
    if (changed) {
      Program p = load(channel, view.program);
      std::lock_guard<std::mutex> lock(mutex_);
      news_.push_back(program_message(channel, p.name, p.lines));
      programs_[channel] = std::move(p);
    }
  }
  return state_message(machine_, snapshot);
}

std::vector<std::string> MachineFeed::take_news() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> news;
  news.swap(news_);
  return news;
}

std::vector<std::string> MachineFeed::welcome() {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::string> messages{alarms_message(machine_, alarms_)};
  for (const auto& [channel, program] : programs_) {
    messages.push_back(program_message(channel, program.name, program.lines));
  }
  return messages;
}

bool MachineFeed::send(const CommandMessage& command, CommandRefusal& refusal) {
  ::mcnc::OperatorCommand c;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (command.action == process::OperatorActionKind::select_program ||
        command.action == process::OperatorActionKind::mdi) {
      const auto it = snapshot_.channels.find(command.channel);
      const bool stands =
          it != snapshot_.channels.end() && (it->second.state == status::ChannelState::reset ||
                                             it->second.state == status::ChannelState::idle);
      if (!stands) {
        refusal.reason = std::string(process::to_string(command.action)) +
                         ": the channel must stand in reset or idle";
        return false;
      }
    }
    c.seq(++seq_);
  }
  c.generation(0);  // the run going on
  c.cycle(0);       // at the channel's next cycle
  c.channel(command.channel);
  c.action(static_cast<::mcnc::OperatorAction>(static_cast<int>(command.action)));
  c.origin("hmi");
  c.value(command.value);
  c.text(command.text);
  c.sender(answers_.sender());
  answers_.expect(c.seq(), c.channel(), static_cast<int>(c.action()));
  if (!commands_.write(c)) {
    answers_.forget(c.seq());
    refusal.reason = "the command could not be sent (DDS write failed)";
    return false;
  }
  const process::CommandAnswers::Standing answer = answers_.wait(c.seq(), kAnswerLimit);
  answers_.forget(c.seq());
  switch (answer.outcome) {
    case process::AnswerTally::Outcome::taken:
      return true;
    case process::AnswerTally::Outcome::refused:
      refusal.reason = answer.why;
      refusal.code = process::code_of(answer.refusal);
      refusal.process = answer.refused_by;
      return false;
    case process::AnswerTally::Outcome::pending:
      refusal.reason = answer.why + " within " + std::to_string(kAnswerLimit.count()) +
                       " ms: the command may or may not take effect";
      refusal.code = "unanswered";
      return false;
  }
  return false;
}

bool MachineFeed::all_heard() {
  std::lock_guard<std::mutex> lock(mutex_);
  return status::missing(machine_, snapshot_).empty();
}

}  // namespace mcnc::hmi
