// Shared helpers of the libFuzzer targets: turn the fuzz input into numbers that like to be
// nasty (NaN, +-Inf, huge, tiny, denormal, zero, negative), and an invariant check that aborts
// with a readable message (libFuzzer then saves the input as crash-<sha1>).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include <fuzzer/FuzzedDataProvider.h>

#include "rviz_projector/core/vec2.h"
#include "rviz_projector/core/vec3.h"

namespace rviz_projector_fuzz
{
/// Inputs within +-kSane are "sane finite": for them the core promises finite outputs. Beyond it
/// (up to DBL_MAX) sums and differences may overflow to Inf; there only "no crash, no UB" holds.
constexpr double kSane = 1e100;

[[noreturn]] inline void fail(const char* file, int line, const char* what)
{
  std::fprintf(stderr, "%s:%d: invariant violated: %s\n", file, line, what);
  std::abort();
}
#define RP_FUZZ_CHECK(condition) \
  ((condition) ? (void)0 : ::rviz_projector_fuzz::fail(__FILE__, __LINE__, #condition))

/**
 * Known bugs of src/ that a fuzz target found, reported and pinned by a DISABLED_ regression test
 * in test/core/core_regression_test.cpp: inputs that trigger one are skipped so that the bounded
 * fuzz runs of scripts/test stay meaningful for everything else. RP_FUZZ_STRICT=1 in the
 * environment turns the skips off (to check a fix). Delete the skip together with the fix.
 */
inline bool strict()
{
  static const bool value = std::getenv("RP_FUZZ_STRICT") != nullptr;
  return value;
}
#define RP_FUZZ_SKIP_KNOWN_BUG(condition) \
  do                                     \
  {                                      \
    if (!::rviz_projector_fuzz::strict() && (condition)) return;  \
  } while (false)

class Input
{
public:
  Input(const std::uint8_t* data, std::size_t size) : fdp_(data, size) {}

  bool empty() { return fdp_.remaining_bytes() == 0; }
  bool boolean() { return fdp_.ConsumeBool(); }
  template <typename T>
  T integer(T lo, T hi) { return fdp_.ConsumeIntegralInRange<T>(lo, hi); }
  template <typename T>
  T integer() { return fdp_.ConsumeIntegral<T>(); }
  std::string text(std::size_t max) { return fdp_.ConsumeRandomLengthString(max); }

  /// A double that is one of the special values a quarter of the time, a plain value in
  /// [-range, range] most of the rest, and any bit pattern occasionally.
  double number(double range = 10.0)
  {
    const std::uint8_t kind = fdp_.ConsumeIntegral<std::uint8_t>();
    if (kind < 40)
    {
      static const double special[] = {std::numeric_limits<double>::quiet_NaN(),
                                       std::numeric_limits<double>::infinity(),
                                       -std::numeric_limits<double>::infinity(),
                                       0.0,
                                       -0.0,
                                       1e9,
                                       -1e9,
                                       1e-9,
                                       1e300,
                                       -1e300,
                                       std::numeric_limits<double>::max(),
                                       std::numeric_limits<double>::lowest(),
                                       std::numeric_limits<double>::min(),
                                       std::numeric_limits<double>::denorm_min(),
                                       1.0,
                                       -1.0,
                                       0.5,
                                       1e-300};
      return special[kind % (sizeof(special) / sizeof(special[0]))];
    }
    if (kind < 56)
    {
      double d;
      const std::uint64_t bits = fdp_.ConsumeIntegral<std::uint64_t>();
      static_assert(sizeof d == sizeof bits, "64-bit double");
      __builtin_memcpy(&d, &bits, sizeof d);
      return d;
    }
    return fdp_.ConsumeFloatingPointInRange<double>(-range, range);
  }
  /// A number that is non-negative most of the time (sizes, distances).
  double size(double range = 1.0)
  {
    const double v = number(range);
    return boolean() || std::isnan(v) ? v : std::fabs(v);
  }

  rviz_projector::Vec2 vec2(double range = 10.0) { return {number(range), number(range)}; }
  rviz_projector::Vec3 vec3(double range = 10.0) { return {number(range), number(range), number(range)}; }

  FuzzedDataProvider& provider() { return fdp_; }

private:
  FuzzedDataProvider fdp_;
};

inline bool sane(double v) { return std::isfinite(v) && std::fabs(v) <= kSane; }
inline bool sane(const rviz_projector::Vec2& v) { return sane(v.x) && sane(v.y); }
inline bool sane(const rviz_projector::Vec3& v) { return sane(v.x) && sane(v.y) && sane(v.z); }
}  // namespace rviz_projector_fuzz
