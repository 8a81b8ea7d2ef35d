#include "common/process/command_answers.hpp"

#include <random>

namespace mcnc::process {

namespace {

std::uint64_t random_sender() {
  std::random_device device;
  std::uint64_t id = 0;
  while (id == 0) {  // 0 says "no answer awaited"
    id = (static_cast<std::uint64_t>(device()) << 32U) | device();
  }
  return id;
}

}  // namespace

CommandAnswers::CommandAnswers(dds::Participant& participant, const config::MachineConfig& machine)
    : machine_(machine),
      sender_(random_sender()),
      reader_(participant,
              [this](const ::mcnc::OperatorAnswer& a, const dds::WriterId&) { on_answer(a); }) {}

void CommandAnswers::expect(std::uint64_t seq, std::uint32_t channel, int action) {
  AnswerTally tally(answering_processes(machine_, channel, action));
  std::lock_guard<std::mutex> lock(mutex_);
  tallies_.insert_or_assign(seq, std::move(tally));
}

void CommandAnswers::on_answer(const ::mcnc::OperatorAnswer& answer) {
  if (answer.sender() != sender_) {
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = tallies_.find(answer.seq());
    if (it == tallies_.end()) {
      return;
    }
    // A refusal this build does not know still refuses.
    const OperatorRefusal refusal = process::refusal_numbered(static_cast<int>(answer.refusal()))
                                        .value_or(OperatorRefusal::unknown_action);
    it->second.add(answer.process(), refusal, answer.reason());
  }
  answered_.notify_all();
}

CommandAnswers::Standing CommandAnswers::standing_locked(std::uint64_t seq) {
  Standing standing;
  const auto it = tallies_.find(seq);
  if (it == tallies_.end()) {
    standing.why = "command " + std::to_string(seq) + " was not sent";
    return standing;
  }
  const AnswerTally& tally = it->second;
  standing.outcome = tally.outcome();
  if (standing.outcome == AnswerTally::Outcome::refused) {
    standing.why = tally.refusal_text();
    standing.refusal = tally.refusal();
    standing.refused_by = tally.refused_by();
  } else if (standing.outcome == AnswerTally::Outcome::pending) {
    standing.why = tally.unanswered_text();
  }
  return standing;
}

CommandAnswers::Standing CommandAnswers::wait(std::uint64_t seq, std::chrono::milliseconds limit) {
  std::unique_lock<std::mutex> lock(mutex_);
  Standing standing;
  answered_.wait_for(lock, limit, [&] {
    standing = standing_locked(seq);
    return standing.outcome != AnswerTally::Outcome::pending;
  });
  return standing;
}

void CommandAnswers::forget(std::uint64_t seq) {
  std::lock_guard<std::mutex> lock(mutex_);
  tallies_.erase(seq);
}

}  // namespace mcnc::process
