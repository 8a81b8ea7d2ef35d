#pragma once
// How a program addresses a channel axis: its absolute letter, its incremental twin (lathe
// system A: X-U, Z-W, Y-V, C-H) and whether X is programmed as a diameter.
namespace mcnc::interp {

// One axis of the channel as the program addresses it.
struct AxisAddress {
  char absolute = 'X';     // X, Z, Y, C ...
  char incremental = 'U';  // U, W, V, H ...
  bool diameter = false;
};

// The lathe's address pair for an axis letter: X-U, Z-W, Y-V, C-H; other letters have no
// incremental twin ('\0').
inline AxisAddress lathe_axis_address(char absolute, bool diameter) noexcept {
  char incremental = '\0';
  switch (absolute) {
    case 'X':
      incremental = 'U';
      break;
    case 'Z':
      incremental = 'W';
      break;
    case 'Y':
      incremental = 'V';
      break;
    case 'C':
      incremental = 'H';
      break;
    default:
      break;
  }
  return AxisAddress{absolute, incremental, diameter};
}

}  // namespace mcnc::interp
