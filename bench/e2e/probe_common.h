// Shared by the e2e probe's parts (bench_probe.cpp, probe_cpu.h, probe_screen.h): clock, messages.
#pragma once

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace bench_probe
{
using Clock = std::chrono::steady_clock;

inline double seconds(Clock::duration d)
{
  return std::chrono::duration<double>(d).count();
}

[[noreturn]] inline void fail(const std::string& what)
{
  std::fprintf(stderr, "bench_probe: %s\n", what.c_str());
  std::exit(2);
}

inline void note(const std::string& what)
{
  std::fprintf(stderr, "[bench_probe] %s\n", what.c_str());
}
}  // namespace bench_probe
