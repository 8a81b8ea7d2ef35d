#include "common/operator/operator_answers.hpp"

#include "common/config/machine_config.hpp"

#include <algorithm>

namespace mcnc::process {

std::vector<std::string> answering_processes(const config::MachineConfig& machine,
                                             std::uint32_t channel, int action) {
  std::vector<std::string> names;
  for (const config::ChannelConfig& ch : machine.channels) {
    if (OperatorScope::of_channel(static_cast<std::uint32_t>(ch.id)).covers(channel, action)) {
      names.push_back(ch.name);
    }
  }
  if (OperatorScope::of_axis_node().covers(channel, action)) {  // the same for every node
    for (const config::AxisConfig& axis : machine.axes) {
      names.push_back(axis.name);
    }
  }
  return names;
}

AnswerTally::AnswerTally(std::vector<std::string> expected)
    : waiting_(std::move(expected)), any_expected_(!waiting_.empty()) {}

void AnswerTally::add(const std::string& process, OperatorRefusal refusal,
                      const std::string& reason) {
  const auto it = std::find(waiting_.begin(), waiting_.end(), process);
  if (it == waiting_.end()) {
    return;
  }
  waiting_.erase(it);
  if (refusal != OperatorRefusal::none && refusal_ == OperatorRefusal::none) {
    refusal_ = refusal;
    refused_by_ = process;
    reason_ = reason;
  }
}

AnswerTally::Outcome AnswerTally::outcome() const noexcept {
  if (refusal_ != OperatorRefusal::none) {
    return Outcome::refused;
  }
  return waiting_.empty() && any_expected_ ? Outcome::taken : Outcome::pending;
}

std::string AnswerTally::refusal_text() const {
  return "refused by " + refused_by_ + " (" + code_of(refusal_) + "): " + reason_;
}

std::string AnswerTally::unanswered_text() const {
  if (!any_expected_) {
    return "no process serves this command";
  }
  std::string names;
  for (const std::string& name : waiting_) {
    names += (names.empty() ? "" : ", ") + name;
  }
  return "no answer from " + names;
}

}  // namespace mcnc::process
