#include "channel/interp/macro/macro_value.hpp"

#include <cstdarg>
#include <cstdio>

namespace mcnc::interp::macro {

MacroAlarm make_alarm(int number, int column, const char* format, ...) {
  MacroAlarm a;
  a.number = number;
  a.column = column;
  va_list args;
  va_start(args, format);
  std::vsnprintf(a.text_buffer.data(), a.text_buffer.size(), format, args);
  va_end(args);
  return a;
}

}  // namespace mcnc::interp::macro
