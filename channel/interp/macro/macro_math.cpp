#include "channel/interp/macro/macro_math.hpp"

#include <array>
#include <cfloat>
#include <cmath>
#include <numbers>

namespace mcnc::interp::macro {

namespace {

constexpr std::array<FunctionInfo, 19> kFunctions{{
    {Function::kSin, "SIN", 1, 1},       {Function::kCos, "COS", 1, 1},
    {Function::kTan, "TAN", 1, 1},       {Function::kAsin, "ASIN", 1, 1},
    {Function::kAcos, "ACOS", 1, 1},     {Function::kAtan, "ATAN", 1, 2},
    {Function::kAtan2, "ATAN2", 2, 2},   {Function::kSqrt, "SQRT", 1, 1},
    {Function::kAbs, "ABS", 1, 1},       {Function::kRound, "ROUND", 1, 1},
    {Function::kRound2, "ROUND2", 2, 2}, {Function::kInt, "INT", 1, 1},
    {Function::kFix, "FIX", 1, 1},       {Function::kFup, "FUP", 1, 1},
    {Function::kLn, "LN", 1, 1},         {Function::kExp, "EXP", 1, 1},
    {Function::kPow, "POW", 2, 2},       {Function::kBin, "BIN", 1, 1},
    {Function::kBcd, "BCD", 1, 1},
}};

constexpr double kRadPerDeg = std::numbers::pi / 180.0;
constexpr double kDegPerRad = 180.0 / std::numbers::pi;
// Beyond 2^52 every double is an integer: nothing to round.
constexpr double kAllIntegers = 4503599627370496.0;

MathResult ok(double v) {
  return MathResult{v + 0.0, nullptr};  // + 0.0 turns -0 into 0, so results print as "0"
}
MathResult fail(const char* why) {
  return MathResult{0.0, why};
}

// The nearest integer when `x` is within the snap tolerance of it.
std::optional<double> near_integer(double x) {
  const double n = std::round(x);
  if (std::fabs(x - n) <= snap_tolerance(x)) {
    return n;
  }
  return std::nullopt;
}

// sin and cos of an angle in [0, 90): exact at 0 and 30/60 (where a programmer expects 0.5), and
// computed on the smaller of the two complementary angles for accuracy.
double sin_first_quadrant(double a) {
  if (a == 0.0) {
    return 0.0;
  }
  if (a == 30.0) {
    return 0.5;
  }
  return a <= 45.0 ? std::sin(a * kRadPerDeg) : std::cos((90.0 - a) * kRadPerDeg);
}
double cos_first_quadrant(double a) {
  if (a == 0.0) {
    return 1.0;
  }
  if (a == 60.0) {
    return 0.5;
  }
  return a < 45.0 ? std::cos(a * kRadPerDeg) : std::sin((90.0 - a) * kRadPerDeg);
}

// Reduces `deg` to a quadrant (0-3) and an angle in [0, 90).
bool reduce_degrees(double deg, int& quadrant, double& rest) {
  if (!std::isfinite(deg)) {
    return false;
  }
  double r = std::fmod(deg, 360.0);  // exact
  if (r < 0.0) {
    r += 360.0;
  }
  if (r >= 360.0) {  // r was a tiny negative number that rounded up
    r = 0.0;
  }
  quadrant = static_cast<int>(r / 90.0);
  rest = r - 90.0 * quadrant;
  return true;
}

double pow10(int k) {
  double p = 1.0;
  for (int i = 0; i < k; ++i) {
    p *= 10.0;
  }
  return p;
}

}  // namespace

const FunctionInfo* find_function(std::string_view upper_name) {
  for (const FunctionInfo& f : kFunctions) {
    if (f.name == upper_name) {
      return &f;
    }
  }
  return nullptr;
}

const FunctionInfo& function_info(Function f) {
  return kFunctions[static_cast<std::size_t>(f)];
}

double snap_tolerance(double scaled) {
  return 1e-9 + std::fabs(scaled) * 4.0 * DBL_EPSILON;
}

double round_half_away(double x) {
  if (!std::isfinite(x) || std::fabs(x) >= kAllIntegers) {
    return x;
  }
  const double a = std::fabs(x);
  double n = std::floor(a);
  if (a - n >= 0.5 - snap_tolerance(a)) {
    n += 1.0;
  }
  return std::copysign(n, x) + 0.0;
}

double fix(double x) {
  if (const auto n = near_integer(x)) {
    return *n + 0.0;
  }
  return std::trunc(x) + 0.0;
}

double fup(double x) {
  if (const auto n = near_integer(x)) {
    return *n + 0.0;
  }
  return std::copysign(std::ceil(std::fabs(x)), x) + 0.0;
}

MathResult round_decimals(double x, double k) {
  const auto digits = near_integer(k);
  if (!digits || *digits < 0.0 || *digits > 15.0) {
    return fail("ROUND2 takes 0 to 15 decimals");
  }
  const double scale = pow10(static_cast<int>(*digits));
  const double scaled = x * scale;
  if (std::fabs(scaled) >= kAllIntegers) {
    return ok(x);
  }
  return ok(round_half_away(scaled) / scale);
}

MathResult sin_deg(double deg) {
  int q = 0;
  double a = 0.0;
  if (!reduce_degrees(deg, q, a)) {
    return fail("SIN of a value out of range");
  }
  switch (q) {
    case 0:
      return ok(sin_first_quadrant(a));
    case 1:
      return ok(cos_first_quadrant(a));
    case 2:
      return ok(-sin_first_quadrant(a));
    default:
      return ok(-cos_first_quadrant(a));
  }
}

MathResult cos_deg(double deg) {
  int q = 0;
  double a = 0.0;
  if (!reduce_degrees(deg, q, a)) {
    return fail("COS of a value out of range");
  }
  switch (q) {
    case 0:
      return ok(cos_first_quadrant(a));
    case 1:
      return ok(-sin_first_quadrant(a));
    case 2:
      return ok(-cos_first_quadrant(a));
    default:
      return ok(sin_first_quadrant(a));
  }
}

MathResult tan_deg(double deg) {
  const MathResult s = sin_deg(deg);
  const MathResult c = cos_deg(deg);
  if (!s.ok()) {
    return fail("TAN of a value out of range");
  }
  if (c.value == 0.0) {
    return fail("TAN of 90 or 270 degrees");
  }
  return ok(s.value / c.value);
}

std::optional<std::int64_t> to_bit_integer(double x) {
  const double r = round_half_away(x);
  if (!std::isfinite(r) || std::fabs(r) > 9007199254740992.0) {
    return std::nullopt;
  }
  return static_cast<std::int64_t>(r);
}

double quantize_word_value(double value, int decimals, WordRounding rounding) {
  const double scale = pow10(decimals);
  const double scaled = value * scale;
  if (!std::isfinite(scaled) || std::fabs(scaled) >= kAllIntegers) {
    return value;
  }
  double n = 0.0;
  if (rounding == WordRounding::kRound) {
    n = round_half_away(scaled);
  } else if (const auto near = near_integer(scaled)) {
    n = *near;  // 1.001 is 1000.9999999999999 increments: one thousand and one, not 1000
  } else {
    n = std::trunc(scaled);
  }
  return n / scale + 0.0;
}

MathResult apply_function(Function f, const double* args, int argc) {
  const double x = args[0];
  switch (f) {
    case Function::kSin:
      return sin_deg(x);
    case Function::kCos:
      return cos_deg(x);
    case Function::kTan:
      return tan_deg(x);
    case Function::kAsin:
    case Function::kAcos: {
      // Dafeng writes the range as -1 < #j < 1 but the end points are valid angles (GSK D3-9:
      // ACOS[-1] = 180); a few ulps beyond them count as the end point.
      if (!(std::fabs(x) <= 1.0 + 4.0 * DBL_EPSILON)) {
        return fail(f == Function::kAsin ? "ASIN argument outside -1..1"
                                         : "ACOS argument outside -1..1");
      }
      const double c = std::fmax(-1.0, std::fmin(1.0, x));
      if (f == Function::kAsin) {
        if (c == 1.0 || c == -1.0 || c == 0.0 || c == 0.5 || c == -0.5) {
          return ok(c == 0.5 || c == -0.5 ? 60.0 * c : 90.0 * c);
        }
        return ok(std::asin(c) * kDegPerRad);
      }
      if (c == 1.0) {
        return ok(0.0);
      }
      if (c == -1.0) {
        return ok(180.0);
      }
      if (c == 0.0) {
        return ok(90.0);
      }
      if (c == 0.5 || c == -0.5) {
        return ok(c > 0 ? 60.0 : 120.0);
      }
      return ok(std::acos(c) * kDegPerRad);
    }
    case Function::kAtan:
    case Function::kAtan2: {
      if (argc == 1) {
        if (x == 1.0 || x == -1.0) {
          return ok(45.0 * x);
        }
        return ok(std::atan(x) * kDegPerRad);
      }
      // ATAN2[opposite, adjacent] (dafeng L6804): -180 < result <= 180.
      const double y = x;
      const double adj = args[1];
      if (y == 0.0 && adj == 0.0) {
        return fail("ATAN2 of 0 and 0 has no angle");
      }
      if (adj == 0.0) {
        return ok(y > 0 ? 90.0 : -90.0);
      }
      if (y == 0.0) {
        return ok(adj > 0 ? 0.0 : 180.0);
      }
      if (std::fabs(y) == std::fabs(adj)) {
        const double a = adj > 0 ? 45.0 : 135.0;
        return ok(y > 0 ? a : -a);
      }
      return ok(std::atan2(y, adj) * kDegPerRad);
    }
    case Function::kSqrt:
      if (x < 0.0) {
        return fail("SQRT of a negative value");
      }
      return ok(std::sqrt(x));
    case Function::kAbs:
      return ok(std::fabs(x));
    case Function::kRound:
      return round_decimals(x, 3.0);
    case Function::kRound2:
      return round_decimals(x, args[1]);
    case Function::kInt:
      return ok(round_half_away(x));
    case Function::kFix:
      return ok(fix(x));
    case Function::kFup:
      return ok(fup(x));
    case Function::kLn:
      if (!(x > 0.0)) {
        return fail("LN of a value that is not positive");
      }
      return ok(std::log(x));
    case Function::kExp:
      return ok(std::exp(x));
    case Function::kPow: {
      const double e = args[1];
      if (x < 0.0 && !near_integer(e)) {
        return fail("POW of a negative base to a fractional power");
      }
      if (x == 0.0 && e < 0.0) {
        return fail("POW of 0 to a negative power");
      }
      // A near-integer exponent counts as that integer so that a negative base keeps its sign.
      const auto ie = near_integer(e);
      return ok(std::pow(x, ie ? *ie : e));
    }
    case Function::kBin: {
      // BCD -> binary: every nibble a decimal digit, 8 digits at most (32 bits).
      const auto n = near_integer(x);
      if (!n || *n < 0.0 || *n > 4294967295.0) {
        return fail("BIN needs a BCD value from 0 to 99999999");
      }
      auto bits = static_cast<std::uint64_t>(*n);
      double result = 0.0;
      double weight = 1.0;
      while (bits != 0) {
        const auto digit = bits & 0xF;
        if (digit > 9) {
          return fail("BIN of a value that is not BCD");
        }
        result += static_cast<double>(digit) * weight;
        weight *= 10.0;
        bits >>= 4;
      }
      return ok(result);
    }
    case Function::kBcd: {
      const auto n = near_integer(x);
      if (!n || *n < 0.0 || *n > 99999999.0) {
        return fail("BCD needs an integer from 0 to 99999999");
      }
      auto value = static_cast<std::uint64_t>(*n);
      std::uint64_t result = 0;
      int shift = 0;
      while (value != 0) {
        result |= (value % 10) << shift;
        value /= 10;
        shift += 4;
      }
      return ok(static_cast<double>(result));
    }
  }
  return fail("unknown function");
}

}  // namespace mcnc::interp::macro
