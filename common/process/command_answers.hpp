#pragma once
// The answers to one sender's operator commands (OperatorAnswer), as the processes that serve
// them give them: the sender registers each command before it writes it, then asks how it
// went. Thread-safe: a DDS thread adds the answers. Every command this sender writes carries
// `sender()`, so that answers to another sender of the same origin are told apart.
#include "common/operator/operator_answers.hpp"
#include "idl/dds_participant.hpp"
#include "idl/topics.hpp"

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>

namespace mcnc::config {
struct MachineConfig;
}

namespace mcnc::process {

class CommandAnswers {
 public:
  CommandAnswers(dds::Participant& participant, const config::MachineConfig& machine);

  [[nodiscard]] std::uint64_t sender() const noexcept { return sender_; }
  // Before command `seq` (for `channel`, with the wire's `action`) is written: the processes it
  // waits for (answering_processes).
  void expect(std::uint64_t seq, std::uint32_t channel, int action);
  // How command `seq` stands: taken, refused (by whom, and why: the tally's refusal_text) or
  // pending (why: who has not answered).
  struct Standing {
    AnswerTally::Outcome outcome = AnswerTally::Outcome::pending;
    std::string why;
    OperatorRefusal refusal = OperatorRefusal::none;
    std::string refused_by;
  };
  // How command `seq` stands once decided, waiting up to `limit` for that (pending after it).
  Standing wait(std::uint64_t seq, std::chrono::milliseconds limit);
  // Forgets command `seq` (decided, or given up).
  void forget(std::uint64_t seq);

 private:
  void on_answer(const ::mcnc::OperatorAnswer& answer);
  Standing standing_locked(std::uint64_t seq);

  const config::MachineConfig& machine_;
  const std::uint64_t sender_;
  std::mutex mutex_;
  std::condition_variable answered_;
  std::map<std::uint64_t, AnswerTally> tallies_;  // by seq
  dds::Reader<::mcnc::OperatorAnswer> reader_;
};

}  // namespace mcnc::process
