#pragma once
// SDO abort codes (CiA 301, table "SDO abort codes") and their meaning in words, for alarms
// that name what a drive refused.
#include <cstdint>

namespace mcnc::canopen {

namespace sdo_abort {
inline constexpr std::uint32_t kToggleBit = 0x05030000;
inline constexpr std::uint32_t kTimeout = 0x05040000;
inline constexpr std::uint32_t kBadCommand = 0x05040001;
inline constexpr std::uint32_t kOutOfMemory = 0x05040005;
inline constexpr std::uint32_t kUnsupportedAccess = 0x06010000;
inline constexpr std::uint32_t kWriteOnly = 0x06010001;
inline constexpr std::uint32_t kReadOnly = 0x06010002;
inline constexpr std::uint32_t kNoObject = 0x06020000;
inline constexpr std::uint32_t kNotMappable = 0x06040041;
inline constexpr std::uint32_t kPdoTooLong = 0x06040042;
inline constexpr std::uint32_t kParameterIncompatible = 0x06040043;
inline constexpr std::uint32_t kDeviceIncompatible = 0x06040047;
inline constexpr std::uint32_t kHardware = 0x06060000;
inline constexpr std::uint32_t kLengthMismatch = 0x06070010;
inline constexpr std::uint32_t kLengthTooHigh = 0x06070012;
inline constexpr std::uint32_t kLengthTooLow = 0x06070013;
inline constexpr std::uint32_t kNoSubindex = 0x06090011;
inline constexpr std::uint32_t kInvalidValue = 0x06090030;
inline constexpr std::uint32_t kValueTooHigh = 0x06090031;
inline constexpr std::uint32_t kValueTooLow = 0x06090032;
inline constexpr std::uint32_t kGeneral = 0x08000000;
inline constexpr std::uint32_t kCannotStore = 0x08000020;
inline constexpr std::uint32_t kLocalControl = 0x08000021;
inline constexpr std::uint32_t kDeviceState = 0x08000022;
}  // namespace sdo_abort

// The standard's meaning of an abort code; "unknown abort code" for others.
const char* sdo_abort_text(std::uint32_t code) noexcept;

}  // namespace mcnc::canopen
