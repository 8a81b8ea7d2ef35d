#pragma once
// The macro B value: a double or null ("vacant", the value of #0 and of every variable that was
// never assigned). The null rules of spec dafeng §4.1 (L6437-6476) and gsk B.4 item 8:
//   - assignment keeps null: `#1=#0` leaves #1 null (a plain reference yields the MacroValue as
//     stored; brackets around it do not change that: `Y[#0]` is still null);
//   - arithmetic, functions and every operator count null as 0: `#0+1` = 1, `#0*3` = 0;
//   - EQ/NE treat null as a value of its own: null EQ null, null NE 0;
//   - GT/GE/LT/LE treat null as 0 (VacantOrdering::kAsZero, the Dafeng rule and the default);
//     the GSK seed's literal table (`0 GE #0` false) is VacantOrdering::kLiteralGskTable;
//   - an address word whose value is null disappears from its block (as_word_value).
#include <array>
#include <optional>
#include <string_view>

namespace mcnc::interp::macro {

class MacroValue {
 public:
  constexpr MacroValue() = default;  // null
  static constexpr MacroValue null() { return MacroValue(); }
  static constexpr MacroValue of(double v) { return MacroValue(v); }

  constexpr bool is_null() const { return null_; }
  // The value as arithmetic sees it: null counts as 0.
  constexpr double number() const { return null_ ? 0.0 : value_; }

  // Identity, not the EQ operator: two nulls are equal, null differs from 0.
  friend constexpr bool operator==(MacroValue a, MacroValue b) {
    return a.null_ == b.null_ && (a.null_ || a.value_ == b.value_);
  }

 private:
  constexpr explicit MacroValue(double v) : value_(v), null_(false) {}
  double value_ = 0.0;
  bool null_ = true;
};

// The value an address word takes, or nothing when the word disappears (dafeng L6437-6445:
// `G00 X100 Y[#0]` is `G00 X100`; with #1 = 0 `Y#1` is Y0).
constexpr std::optional<double> as_word_value(MacroValue v) {
  if (v.is_null()) {
    return std::nullopt;
  }
  return v.number();
}

enum class CompareOp { kEq, kNe, kGt, kGe, kLt, kLe };

enum class VacantOrdering {
  // Dafeng L6459-6460: for >, >=, <, <= null and 0 are the same value. Default.
  kAsZero,
  // GSK seed S3 table (gsk B.4 item 8c): GE and LE hold when EQ holds (null as a value of its
  // own) or the strict comparison holds with null as 0, so `0 GE #0` is false, `#0 GE #0` true.
  kLiteralGskTable,
};

constexpr bool compare(CompareOp op, MacroValue a, MacroValue b,
                       VacantOrdering ordering = VacantOrdering::kAsZero) {
  const double x = a.number();
  const double y = b.number();
  switch (op) {
    case CompareOp::kEq:
      return a == b;
    case CompareOp::kNe:
      return !(a == b);
    case CompareOp::kGt:
      return x > y;
    case CompareOp::kLt:
      return x < y;
    case CompareOp::kGe:
      return ordering == VacantOrdering::kAsZero ? x >= y : (a == b || x > y);
    case CompareOp::kLe:
      return ordering == VacantOrdering::kAsZero ? x <= y : (a == b || x < y);
  }
  return false;
}

// An alarm of the macro layer: number (macro_alarms.hpp), 1-based column in the line (0 when no
// column applies) and a text. The text lives in the object so that raising an alarm during
// evaluation does not allocate.
struct MacroAlarm {
  // Only the first character is cleared: results carry a MacroAlarm on every evaluation and
  // variable read, and clearing the whole buffer each time would dominate their cost.
  MacroAlarm() { text_buffer[0] = '\0'; }

  int number = 0;  // 0: no alarm
  int column = 0;
  std::array<char, 120> text_buffer;  // NOLINT(cppcoreguidelines-pro-type-member-init)

  explicit operator bool() const { return number != 0; }
  std::string_view text() const { return std::string_view(text_buffer.data()); }
};

#if defined(__GNUC__)
#define MCNC_MACRO_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define MCNC_MACRO_PRINTF(f, a)
#endif

// printf-style; the text is cut at the buffer size.
MacroAlarm make_alarm(int number, int column, const char* format, ...) MCNC_MACRO_PRINTF(3, 4);
#undef MCNC_MACRO_PRINTF

}  // namespace mcnc::interp::macro
