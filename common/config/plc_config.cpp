#include "common/config/plc_config.hpp"

namespace mcnc::config {

const PlcMCode* PlcConfig::find_m_code(int code, int channel) const noexcept {
  for (const PlcMCode& m : m_codes) {
    if (m.code != code) {
      continue;
    }
    if (m.channels.empty()) {
      return &m;
    }
    for (int c : m.channels) {
      if (c == channel) {
        return &m;
      }
    }
  }
  return nullptr;
}

const PlcSignal* PlcConfig::find_signal(const std::string& name) const noexcept {
  for (const PlcSignal& s : signals) {
    if (s.name == name) {
      return &s;
    }
  }
  return nullptr;
}

}  // namespace mcnc::config
