#pragma once
// What the cycle tests share: seeded random amounts for the property tests and a check of one
// move of a path.
#include "channel/interp/path/plane_path.hpp"

#include <gtest/gtest.h>

#include <random>

namespace mcnc::interp::cycles::test {

// Reproducible uniform numbers: the same seed gives the same cases on every run.
class Uniform {
 public:
  explicit Uniform(unsigned seed) : rng_(seed) {}
  double operator()(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng_);
  }
  bool chance(double p) { return (*this)(0.0, 1.0) < p; }
  int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

 private:
  std::mt19937 rng_;
};

inline void expect_move(const path::PlaneMove& m, path::MoveKind kind, double a, double b,
                        double tolerance = 1e-9) {
  EXPECT_EQ(m.kind, kind);
  EXPECT_NEAR(m.to.a, a, tolerance);
  EXPECT_NEAR(m.to.b, b, tolerance);
}

}  // namespace mcnc::interp::cycles::test
