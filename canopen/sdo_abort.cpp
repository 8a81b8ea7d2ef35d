#include "canopen/sdo_abort.hpp"

namespace mcnc::canopen {

const char* sdo_abort_text(std::uint32_t code) noexcept {
  switch (code) {
    case sdo_abort::kToggleBit:
      return "toggle bit not alternated";
    case sdo_abort::kTimeout:
      return "SDO protocol timed out";
    case sdo_abort::kBadCommand:
      return "client/server command specifier not valid or unknown";
    case 0x05040002:
      return "invalid block size";
    case 0x05040003:
      return "invalid sequence number";
    case 0x05040004:
      return "CRC error";
    case sdo_abort::kOutOfMemory:
      return "out of memory";
    case sdo_abort::kUnsupportedAccess:
      return "unsupported access to an object";
    case sdo_abort::kWriteOnly:
      return "attempt to read a write only object";
    case sdo_abort::kReadOnly:
      return "attempt to write a read only object";
    case sdo_abort::kNoObject:
      return "object does not exist in the object dictionary";
    case sdo_abort::kNotMappable:
      return "object cannot be mapped to the PDO";
    case sdo_abort::kPdoTooLong:
      return "the objects to be mapped would exceed the PDO length";
    case sdo_abort::kParameterIncompatible:
      return "general parameter incompatibility";
    case sdo_abort::kDeviceIncompatible:
      return "general internal incompatibility in the device";
    case sdo_abort::kHardware:
      return "access failed due to a hardware error";
    case sdo_abort::kLengthMismatch:
      return "data type does not match: length of service parameter does not match";
    case sdo_abort::kLengthTooHigh:
      return "data type does not match: length of service parameter too high";
    case sdo_abort::kLengthTooLow:
      return "data type does not match: length of service parameter too low";
    case sdo_abort::kNoSubindex:
      return "sub-index does not exist";
    case sdo_abort::kInvalidValue:
      return "invalid value for parameter";
    case sdo_abort::kValueTooHigh:
      return "value of parameter written too high";
    case sdo_abort::kValueTooLow:
      return "value of parameter written too low";
    case 0x06090036:
      return "maximum value is less than minimum value";
    case 0x060A0023:
      return "resource not available: SDO connection";
    case sdo_abort::kGeneral:
      return "general error";
    case sdo_abort::kCannotStore:
      return "data cannot be transferred or stored to the application";
    case sdo_abort::kLocalControl:
      return "data cannot be transferred or stored because of local control";
    case sdo_abort::kDeviceState:
      return "data cannot be transferred or stored because of the present device state";
    case 0x08000023:
      return "object dictionary dynamic generation fails or no object dictionary is present";
    case 0x08000024:
      return "no data available";
    default:
      return "unknown abort code";
  }
}

}  // namespace mcnc::canopen
