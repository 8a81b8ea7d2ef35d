#pragma once
// The sender's side of operator commands: which processes answer a command (each process that
// serves it, OperatorScope), and what their answers add up to. A command is taken once every
// one of them took it, refused as soon as one refuses; a sender that hears nothing in time
// says so, and never that the command was taken.
#include "common/operator/operator_admission.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace mcnc::config {
struct MachineConfig;
}

namespace mcnc::process {

// The processes (channel and axis names) that answer a command for `channel` (0: the whole
// machine) with the wire's `action`.
std::vector<std::string> answering_processes(const config::MachineConfig& machine,
                                             std::uint32_t channel, int action);

class AnswerTally {
 public:
  enum class Outcome { pending, taken, refused };

  explicit AnswerTally(std::vector<std::string> expected);
  // One process's answer; answers of processes not expected, and repeats, change nothing.
  void add(const std::string& process, OperatorRefusal refusal, const std::string& reason);
  [[nodiscard]] Outcome outcome() const noexcept;
  // Refused: who refused first, and why ("CH1: inbox_full: ..."); pending: who has not answered.
  [[nodiscard]] const std::string& refused_by() const noexcept { return refused_by_; }
  [[nodiscard]] OperatorRefusal refusal() const noexcept { return refusal_; }
  [[nodiscard]] std::string refusal_text() const;
  [[nodiscard]] std::string unanswered_text() const;

 private:
  std::vector<std::string> waiting_;  // expected, not yet answered
  bool any_expected_ = false;
  std::string refused_by_;
  OperatorRefusal refusal_ = OperatorRefusal::none;
  std::string reason_;
};

}  // namespace mcnc::process
