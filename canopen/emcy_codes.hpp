#pragma once
// EMCY error codes (CiA 301 §7.2.7.1 and the drive profile CiA 402) in words, for the alarm
// an axis node raises when its drive reports one.
#include <cstdint>

namespace mcnc::canopen {

// The meaning of the code: the exact one where the standards name it, else its class
// ("current, device output side", "monitoring, communication", ...).
const char* emcy_text(std::uint16_t error_code) noexcept;

}  // namespace mcnc::canopen
