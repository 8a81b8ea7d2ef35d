#pragma once
// The numeric functions of macro B (spec dafeng §4.2, gsk A.7.4): angles in degrees, the
// dialect's rounding rules, BIN/BCD. Pure functions over doubles; none throws or allocates.
// Null arguments are the evaluator's business (they arrive here as 0).
#include <cstdint>
#include <optional>
#include <string_view>

namespace mcnc::interp::macro {

// Result of a function that can fail: `error` is a static text naming the domain violated.
struct MathResult {
  double value = 0.0;
  const char* error = nullptr;
  bool ok() const { return error == nullptr; }
};

enum class Function : std::uint8_t {
  kSin,
  kCos,
  kTan,
  kAsin,
  kAcos,
  kAtan,
  kAtan2,
  kSqrt,
  kAbs,
  kRound,
  kRound2,
  kInt,
  kFix,
  kFup,
  kLn,
  kExp,
  kPow,
  kBin,
  kBcd,
};

struct FunctionInfo {
  Function function;
  std::string_view name;
  int min_args;
  int max_args;
};

// Every function of the dialect, by upper-case name (ATAN takes one or two arguments).
const FunctionInfo* find_function(std::string_view upper_name);
const FunctionInfo& function_info(Function f);

// Applies `f` to `args` (argc within the function's arity; checked by the parser).
MathResult apply_function(Function f, const double* args, int argc);

// Largest magnitude a macro value may take (FANUC/GSK: beyond 10^47 is P/S 111).
inline constexpr double kMaxMagnitude = 1e47;

// Values this close to a rounding boundary count as on it: decimal inputs such as 2.0005 or
// [0.3-0.1]*10 are not exact in binary, and a programmer expects the decimal result. The
// tolerance is 1e-9 of the last kept digit plus a few ulps of the scaled value.
double snap_tolerance(double scaled);

// INT (dafeng L6884-6886): round half away from zero. INT[1.5] = 2, INT[-1.5] = -2.
double round_half_away(double x);
// FIX (L6878-6882): toward zero. FIX[1.2] = 1, FIX[-1.2] = -1.
double fix(double x);
// FUP (L6878-6882): away from zero. FUP[1.2] = 2, FUP[-1.2] = -2.
double fup(double x);
// ROUND2[x, k]: half away from zero at k decimals; ROUND[x] is ROUND2[x, 3] (decision D16).
MathResult round_decimals(double x, double k);

MathResult sin_deg(double deg);
MathResult cos_deg(double deg);
MathResult tan_deg(double deg);

// Operand of the bitwise operators | & ^ ~: rounded half away from zero to an integer of at
// most 53 bits (so that it converts back to a double exactly); nullopt beyond that.
std::optional<std::int64_t> to_bit_integer(double x);

// A value substituted into an address word, reduced to `decimals` decimals (the address's
// least increment): truncated toward zero as dafeng L6671-6676 says (12.3455 -> 12.345), or
// rounded half away from zero as the GSK/FANUC text says (12.3456 -> 12.346).
enum class WordRounding { kTruncate, kRound };
double quantize_word_value(double value, int decimals, WordRounding rounding);

}  // namespace mcnc::interp::macro
