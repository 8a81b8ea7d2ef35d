#pragma once
// Numbers in the alarm texts of the cycles, corner insertion and nose compensation.
#include <string>

namespace mcnc::interp::path {

// A length in mm with 3 decimals: "-10.000".
std::string mm_text(double v);

}  // namespace mcnc::interp::path
