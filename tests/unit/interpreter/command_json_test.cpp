// The JSON form of a command prints every number as std::to_chars's shortest round trip of the
// value rounded to 1e-9: its fast path for short decimals must write the very same text.
#include "channel/interp/output/command_json.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace mcnc::interp::output {
namespace {

std::string dwell_json(double seconds) {
  Command c;
  c.op = Op::dwell;
  c.n = 1;
  c.line = 2;
  c.seconds = seconds;
  std::string out;
  append_json(out, c, {}, "main.nc");
  return out;
}

std::string expected_json(double seconds) {
  double r = std::round(seconds * 1e9) / 1e9;
  if (r == 0.0 || !std::isfinite(r)) {
    r = 0.0;
  }
  char buf[40];
  const auto res = std::to_chars(buf, buf + sizeof buf, r);
  return "{\"n\":1,\"line\":2,\"op\":\"dwell\",\"seconds\":" + std::string(buf, res.ptr) + "}\n";
}

TEST(CommandJson, NumbersAreTheShortestRoundTripOfTheValueRoundedToANanometre) {
  std::vector<double> values{0.0,
                             -0.0,
                             1.0,
                             -1.0,
                             10.0,
                             99999.0,
                             -99999.0,
                             99999.9999999999,
                             -7.0000000001,
                             100000.0,
                             -100000.0,
                             123456.0,
                             1200000.0,
                             0.5,
                             0.001,
                             0.0001,
                             0.00012,
                             1e-9,
                             -1e-9,
                             4e-10,
                             6e-10,
                             0.1 + 0.2,
                             1e11,
                             123456789012.5,
                             999999999999.0,
                             1e12,
                             1e13,
                             1e15,
                             1e20,
                             -2.5e-5,
                             1.5e-7,
                             NAN,
                             INFINITY,
                             -INFINITY,
                             1e300,
                             5e-324};
  std::mt19937_64 random(23);
  for (int decimals = 0; decimals <= 10; ++decimals) {
    for (int scale = -10; scale <= 13; ++scale) {
      std::uniform_int_distribution<long long> mantissa(-999999, 999999);
      for (int i = 0; i < 300; ++i) {
        values.push_back(static_cast<double>(mantissa(random)) * std::pow(10.0, scale) /
                         std::pow(10.0, decimals));
      }
    }
  }
  std::uniform_real_distribution<double> anywhere(-1e4, 1e4);
  for (int i = 0; i < 20000; ++i) {
    values.push_back(anywhere(random));
  }
  for (const double v : values) {
    EXPECT_EQ(dwell_json(v), expected_json(v)) << "value " << v;
  }
}

}  // namespace
}  // namespace mcnc::interp::output
