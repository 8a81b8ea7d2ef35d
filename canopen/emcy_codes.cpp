#include "canopen/emcy_codes.hpp"

namespace mcnc::canopen {

namespace {

struct Named {
  std::uint16_t code;
  const char* text;
};

// Codes named exactly (CiA 301 and CiA 402).
constexpr Named kExact[] = {
    {0x0000, "error reset or no error"},
    {0x1000, "generic error"},
    {0x2310, "continuous over-current"},
    {0x2320, "short circuit or earth leakage"},
    {0x3210, "DC link over-voltage"},
    {0x3220, "DC link under-voltage"},
    {0x4210, "excess temperature of the device"},
    {0x4310, "excess temperature of the drive"},
    {0x5530, "data storage error"},
    {0x6010, "software reset (watchdog)"},
    {0x7121, "motor blocked"},
    {0x7305, "incremental sensor 1 fault"},
    {0x8110, "CAN overrun: objects lost"},
    {0x8120, "CAN in error passive mode"},
    {0x8130, "life guard or heartbeat error"},
    {0x8140, "recovered from bus off"},
    {0x8150, "CAN-ID collision"},
    {0x8210, "PDO not processed: length error"},
    {0x8220, "PDO length exceeded"},
    {0x8611, "following error"},
    {0x8612, "reference limit"},
    {0xFF00, "device specific"},
};

// Classes by the high byte, then by the high nibble.
constexpr Named kByByte[] = {
    {0x21, "current, device input side"},
    {0x22, "current inside the device"},
    {0x23, "current, device output side"},
    {0x31, "mains voltage"},
    {0x32, "voltage inside the device"},
    {0x33, "output voltage"},
    {0x41, "ambient temperature"},
    {0x42, "device temperature"},
    {0x61, "internal software"},
    {0x62, "user software"},
    {0x63, "data set"},
    {0x81, "monitoring, communication"},
    {0x82, "monitoring, protocol error"},
    {0x86, "monitoring, position control"},
};
constexpr Named kByNibble[] = {
    {0x1, "generic error"},        {0x2, "current"},         {0x3, "voltage"},
    {0x4, "temperature"},          {0x5, "device hardware"}, {0x6, "device software"},
    {0x7, "additional modules"},   {0x8, "monitoring"},      {0x9, "external error"},
    {0xF, "additional functions"},
};

}  // namespace

const char* emcy_text(std::uint16_t error_code) noexcept {
  for (const Named& n : kExact) {
    if (n.code == error_code) {
      return n.text;
    }
  }
  if ((error_code & 0xFF00) == 0xFF00) {
    return "device specific";
  }
  for (const Named& n : kByByte) {
    if (n.code == (error_code >> 8)) {
      return n.text;
    }
  }
  for (const Named& n : kByNibble) {
    if (n.code == (error_code >> 12)) {
      return n.text;
    }
  }
  return "unknown error code";
}

}  // namespace mcnc::canopen
