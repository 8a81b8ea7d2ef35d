#pragma once
// The object dictionary of one simulated CiA 402 drive, as its SDO server sees it: the
// communication objects a master configures at start-up (device type, heartbeat time, the
// PDOs' communication and mapping parameters) and the drive-profile objects (controlword,
// statusword, modes of operation and display, position, velocity, following error, rated and
// actual torque, the target torque and max motor speed of CST). Mapping
// follows CiA 301: a PDO's mapping changes only while the PDO is invalid (COB-ID bit 31) and
// its count is 0; only mappable objects, at most 64 bits. A refusal can be injected for one
// object. Pure.
#include "canopen/object_access.hpp"
#include "canopen/pdo_layout.hpp"
#include "common/can/can_frame.hpp"

#include <array>
#include <cstdint>

namespace mcnc::drivesim {

// What the drive's objects show of its live state (the drive updates it every cycle).
struct DriveLiveValues {
  std::uint16_t statusword = 0;
  std::int32_t position = 0;             // counts (0x6064)
  std::int32_t velocity = 0;             // counts/s (0x606C)
  std::int32_t following_error = 0;      // counts (0x60F4)
  std::int16_t torque = 0;               // per mille of the rated torque (0x6077)
  std::uint32_t rated_torque = 0;        // mN m (0x6076)
  std::uint16_t touch_probe_status = 0;  // 0x60B9
  std::int32_t probe_positive = 0;       // counts (0x60BA)
  std::int32_t probe_negative = 0;       // counts (0x60BB)
};

// What an RPDO carried, by its mapping: only the objects it maps are set.
struct RpdoValues {
  std::uint16_t controlword = 0;
  std::int32_t target_position = 0;   // counts (0x607A)
  std::int32_t target_velocity = 0;   // counts/s (0x60FF)
  std::int8_t mode = 0;               // 0x6060
  std::uint16_t touch_probe = 0;      // 0x60B8
  std::uint16_t max_torque = 0;       // 0x6072, per mille of the rated torque
  std::int16_t target_torque = 0;     // 0x6071, per mille of the rated torque (CST)
  std::uint32_t max_motor_speed = 0;  // 0x6080, rpm (CST's speed limit)
  bool has_controlword = false;
  bool has_target_position = false;
  bool has_target_velocity = false;
  bool has_mode = false;
  bool has_touch_probe = false;
  bool has_max_torque = false;
  bool has_target_torque = false;
  bool has_max_motor_speed = false;
  // Takes what `other` carries, keeps the rest.
  void merge(const RpdoValues& other) noexcept;
};

class DriveObjects final : public canopen::ObjectAccess {
 public:
  static constexpr std::uint32_t kDeviceType = 0x00020192;  // CiA 402 servo drive

  struct Pdo {
    std::uint32_t cob_id = 0;
    std::uint8_t transmission_type = 1;
    std::array<std::uint32_t, 8> entries{};
    std::uint8_t count = 0;
    [[nodiscard]] bool valid() const noexcept { return (cob_id & 0x80000000U) == 0; }
  };

  explicit DriveObjects(std::uint8_t node) noexcept;

  // NMT reset communication: the communication objects (0x1000-0x1FFF) back to their defaults.
  void reset_communication() noexcept;
  // The TPDO `n` (0 or 1) packed by its mapping (canopen::pack) from the live values; false
  // while it is invalid.
  bool encode_tpdo(std::size_t n, can::CanFrame& out) const noexcept;
  // RPDO `n` (0 or 1) read by its mapping; false (not processed) while it is invalid or when the
  // frame's length is not the mapped length (CiA 301: a PDO length error).
  bool decode_rpdo(std::size_t n, const can::CanFrame& frame, RpdoValues& out) const noexcept;

  std::uint32_t read(std::uint16_t index, std::uint8_t sub,
                     canopen::SdoValue& out) noexcept override;
  std::uint32_t write(std::uint16_t index, std::uint8_t sub, const std::uint8_t* data,
                      std::size_t size) noexcept override;

  // Every SDO access to `index` is refused with `code` (fault injection; 0: none).
  void refuse(std::uint16_t index, std::uint32_t code) noexcept {
    refused_index_ = index;
    refused_code_ = code;
  }

  [[nodiscard]] std::int8_t mode() const noexcept { return mode_; }
  // 0x60B8, the touch probe function (by SDO or in an RPDO).
  [[nodiscard]] std::uint16_t touch_probe() const noexcept { return touch_probe_; }
  // 0x6072, the max torque (by SDO or in an RPDO), per mille of the rated torque.
  [[nodiscard]] std::uint16_t max_torque() const noexcept { return max_torque_; }
  // 0x6071, the target torque of CST (mode 10), per mille of the rated torque.
  [[nodiscard]] std::int16_t target_torque() const noexcept { return target_torque_; }
  // 0x6080, the max motor speed (rpm): CST's speed limit; 0: none but the drive's own.
  [[nodiscard]] std::uint32_t max_motor_speed() const noexcept { return max_motor_speed_; }
  [[nodiscard]] std::int32_t home_offset() const noexcept { return home_offset_; }
  [[nodiscard]] std::int8_t homing_method() const noexcept { return homing_method_; }
  [[nodiscard]] std::uint16_t heartbeat_ms() const noexcept { return heartbeat_ms_; }
  // 0x6085 quick stop deceleration, counts/s^2 (the drive's default until a master writes it).
  [[nodiscard]] std::uint32_t quick_stop_deceleration() const noexcept { return quick_stop_dec_; }
  [[nodiscard]] const Pdo& rpdo(std::size_t n) const noexcept { return rpdo_[n]; }
  [[nodiscard]] const Pdo& tpdo(std::size_t n) const noexcept { return tpdo_[n]; }
  DriveLiveValues live{};

 private:
  // The PDO's mapping objects as the layout both ends pack and unpack by.
  static canopen::PdoMapping mapping_of(const Pdo& pdo, bool receive, std::size_t n) noexcept;
  std::uint32_t read_pdo(const Pdo& pdo, bool mapping, std::uint8_t sub,
                         canopen::SdoValue& out) const noexcept;
  std::uint32_t write_pdo(Pdo& pdo, bool receive, bool mapping, std::uint8_t sub,
                          std::uint32_t value, std::size_t size) noexcept;

  std::array<Pdo, 2> rpdo_{};
  std::array<Pdo, 2> tpdo_{};
  std::int8_t mode_ = 0;
  std::int32_t home_offset_ = 0;    // counts (0x607C)
  std::int8_t homing_method_ = 37;  // 0x6098: 35/37, the current position is home
  std::uint16_t heartbeat_ms_ = 0;
  std::uint32_t quick_stop_dec_ = 0;
  std::uint16_t controlword_ = 0;
  std::uint16_t touch_probe_ = 0;
  std::uint16_t max_torque_ = 0;
  std::int16_t target_torque_ = 0;
  std::uint32_t max_motor_speed_ = 0;
  std::int32_t target_position_ = 0;
  std::int32_t target_velocity_ = 0;
  std::uint16_t refused_index_ = 0;
  std::uint32_t refused_code_ = 0;
  std::uint8_t node_ = 0;
};

}  // namespace mcnc::drivesim
