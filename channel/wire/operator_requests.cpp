#include "channel/wire/operator_requests.hpp"

#include <utility>

namespace mcnc::channel {

namespace {

// What the operator asked for, as the trace's `text` (escaped).
struct EscapedText {
  char text[2 * process::OperatorRequest::kTextSize + 8] = {};
};

EscapedText escaped(const char* text) noexcept {
  EscapedText e;
  trace::json_escape(text, e.text, sizeof e.text);
  return e;
}

}  // namespace

OperatorRequests::OperatorRequests(process::ProcessNode& node, trace::TraceWriter& tracer,
                                   const config::ChannelConfig& channel, ProgramLoader& loader,
                                   ChannelController& controller, interp::CommandSource& source,
                                   ChannelOutputs& outputs) noexcept
    : node_(node),
      tracer_(tracer),
      channel_(channel),
      loader_(loader),
      controller_(controller),
      source_(source),
      outputs_(outputs) {}

void OperatorRequests::apply(std::uint64_t cycle) {
  const char* self = channel_.name.c_str();
  while (const auto request = node_.take_operator_request(cycle)) {
    if (!request->concerns(static_cast<std::uint32_t>(channel_.id))) {
      continue;
    }
    using Kind = process::OperatorActionKind;
    switch (request->action) {
      case Kind::reset:
        controller_.request_reset();
        break;
      case Kind::cycle_start:
        controller_.request_start();
        break;
      case Kind::feed_hold:
        controller_.request_feed_hold();
        break;
      case Kind::feed_override:
        controller_.set_feed_override(request->value);
        break;
      case Kind::rapid_override:
        controller_.set_rapid_override(request->value);
        break;
      case Kind::spindle_override:
        controller_.set_spindle_override(request->value);
        break;
      case Kind::single_block:
        controller_.set_single_block(request->value != 0.0);
        break;
      case Kind::select_program:
      case Kind::mdi:
        select(cycle, *request);
        continue;
      case Kind::alarm_ack:  // for the HMIs: which alarms an operator has seen
      case Kind::none:
        continue;
    }
    if (request->action == Kind::reset || request->action == Kind::cycle_start ||
        request->action == Kind::feed_hold) {
      tracer_.emit(cycle, "operator", "\"ch\":\"%s\",\"action\":\"%s\"", self,
                   process::to_string(request->action));
    } else {
      tracer_.emit(cycle, "operator", "\"ch\":\"%s\",\"action\":\"%s\",\"value\":%.3f", self,
                   process::to_string(request->action), request->value);
    }
  }
}

void OperatorRequests::select(std::uint64_t cycle, const process::OperatorRequest& request) {
  const bool mdi = request.action == process::OperatorActionKind::mdi;
  const char* refused = !controller_.may_change_program()
                            ? "programs are selected and MDI blocks run only in reset or idle"
                        : loaded_ || !loader_.submit(mdi, request.text.data())
                            ? "another program or MDI block is still being checked"
                            : nullptr;
  mdi_epoch_ = mdi && refused == nullptr ? controller_.run_epoch() : mdi_epoch_;
  tracer_.emit(cycle, "operator", "\"ch\":\"%s\",\"action\":\"%s\",\"text\":\"%s\"%s%s%s",
               channel_.name.c_str(), process::to_string(request.action),
               escaped(request.text.data()).text, refused ? ",\"refused\":\"" : "",
               refused ? refused : "", refused ? "\"" : "");
}

void OperatorRequests::take_loaded(std::uint64_t cycle) {
  if (!loaded_) {
    loaded_ = loader_.take();
  }
  if (loaded_ && loaded_->mdi && controller_.run_epoch() != mdi_epoch_) {
    // A reset or another run came while the blocks were checked: they no longer run.
    tracer_.emit(cycle, "operator",
                 "\"ch\":\"%s\",\"action\":\"mdi\",\"text\":\"%s\",\"refused\":\"a reset or "
                 "another run came first\"",
                 channel_.name.c_str(), escaped(loaded_->program.text.c_str()).text);
    loaded_.reset();
  }
  if (loaded_ && controller_.may_change_program()) {
    if (loaded_->program.alarm) {
      controller_.report_alarm(*loaded_->program.alarm);  // the program selected stays
    } else if (loaded_->mdi) {
      source_.prepare_mdi(std::move(loaded_->program));
      controller_.request_mdi();
    } else {
      tracer_.emit(cycle, "program", "\"ch\":\"%s\",\"prog\":\"%s\",\"blocks\":%zu",
                   channel_.name.c_str(), escaped(loaded_->program.name.c_str()).text,
                   loaded_->program.block_count);
      outputs_.set_program(loaded_->program.name);
      source_.adopt(std::move(loaded_->program));
    }
    loaded_.reset();
  }
  controller_.set_program_pending(loaded_.has_value() || loader_.busy());
}

}  // namespace mcnc::channel
