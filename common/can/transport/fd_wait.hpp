#pragma once
// Waiting for a socket to become readable, shared by the CAN transports.
#include "common/can/can_bus.hpp"

#include <chrono>

namespace mcnc::can {

// ok: readable; timeout: the time ran out or a signal interrupted the wait (so the caller can
// look at its stop flag); error: the descriptor failed. A negative timeout polls.
BusResult wait_readable(int fd, std::chrono::nanoseconds timeout) noexcept;

}  // namespace mcnc::can
