// The e2e probe's CPU and memory figures from /proc: process and thread ticks, RSS, system ticks.
#pragma once

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <dirent.h>
#include <unistd.h>

#include "probe_common.h"

namespace bench_probe
{
// ---- CPU from /proc --------------------------------------------------------------------------
/// utime + stime of a process (all its threads), in clock ticks; -1 when it is gone.
inline long long cpuTicks(pid_t pid)
{
  std::ifstream in("/proc/" + (pid == 0 ? std::string("self") : std::to_string(pid)) + "/stat");
  std::string line;
  if (!std::getline(in, line))
  {
    return -1;
  }
  // The command name (field 2) is in parentheses and may hold spaces: count fields after ')'.
  const auto close = line.rfind(')');
  if (close == std::string::npos)
  {
    return -1;
  }
  std::istringstream fields(line.substr(close + 2));
  std::string field;
  long long utime = 0, stime = 0;
  for (int index = 3; fields >> field; ++index)
  {
    if (index == 14) utime = std::stoll(field);
    if (index == 15)
    {
      stime = std::stoll(field);
      break;
    }
  }
  return utime + stime;
}

/// Resident set size of a process in MB (VmRSS of /proc/<pid>/status), NaN when it is gone.
inline double rssMegabytes(pid_t pid)
{
  std::ifstream in("/proc/" + (pid == 0 ? std::string("self") : std::to_string(pid)) + "/status");
  std::string line;
  while (std::getline(in, line))
  {
    if (line.rfind("VmRSS:", 0) == 0)
    {
      return std::stod(line.substr(6)) / 1024.0;  // kB
    }
  }
  return NAN;
}

/// utime + stime of every thread of a process, by thread group: "main" (the thread that runs Qt and
/// rviz's update loop), "llvmpipe" (Mesa's rasterizer threads), "other" (ROS, tf, Qt helpers).
inline std::map<std::string, long long> threadTicks(pid_t pid)
{
  std::map<std::string, long long> groups;
  const std::string task = "/proc/" + std::to_string(pid) + "/task/";
  DIR* dir = opendir(task.c_str());
  if (!dir)
  {
    return groups;
  }
  while (dirent* entry = readdir(dir))
  {
    if (entry->d_name[0] < '0' || entry->d_name[0] > '9')
    {
      continue;
    }
    std::ifstream in(task + entry->d_name + "/stat");
    std::string line;
    if (!std::getline(in, line))
    {
      continue;
    }
    const auto open = line.find('('), close = line.rfind(')');
    if (open == std::string::npos || close == std::string::npos)
    {
      continue;
    }
    const std::string comm = line.substr(open + 1, close - open - 1);
    std::istringstream fields(line.substr(close + 2));
    std::string field;
    long long ticks = 0;
    for (int index = 3; fields >> field; ++index)
    {
      if (index == 14) ticks += std::stoll(field);
      if (index == 15)
      {
        ticks += std::stoll(field);
        break;
      }
    }
    const std::string group = std::to_string(pid) == entry->d_name ? "main"
                              : comm.rfind("llvmpipe", 0) == 0  ? "llvmpipe"
                                                                : "other";
    groups[group] += ticks;
  }
  closedir(dir);
  return groups;
}

/// Time all cores ran something (user, system, interrupts), and time the hypervisor gave them to
/// someone else (steal: a virtual machine's CPUs are not always its own), in clock ticks.
struct SystemTicks
{
  long long busy = 0;
  long long steal = 0;
};

inline SystemTicks systemTicks()
{
  std::ifstream in("/proc/stat");
  std::string cpu;
  long long user = 0, nice = 0, system = 0, idle = 0, iowait = 0, irq = 0, softirq = 0, steal = 0;
  in >> cpu >> user >> nice >> system >> idle >> iowait >> irq >> softirq >> steal;
  return SystemTicks{user + nice + system + irq + softirq, steal};
}

class CpuMeter
{
public:
  CpuMeter(std::vector<std::pair<std::string, pid_t>> pids, std::string split_threads)
    : pids_(std::move(pids)), split_(std::move(split_threads))
  {
    pids_.emplace_back("probe", 0);
  }

  void start()
  {
    start_time_ = Clock::now();
    system_start_ = systemTicks();
    start_.clear();
    thread_start_.clear();
    for (const auto& p : pids_)
    {
      start_.push_back(cpuTicks(p.second));
      if (p.first == split_)
      {
        thread_start_ = threadTicks(p.second);
      }
    }
  }

  /// Cores used by each process since start().
  std::vector<std::pair<std::string, double>> stop() const
  {
    const double wall = seconds(Clock::now() - start_time_);
    const double hz = static_cast<double>(sysconf(_SC_CLK_TCK));
    std::vector<std::pair<std::string, double>> out;
    for (std::size_t i = 0; i < pids_.size(); ++i)
    {
      const long long now = cpuTicks(pids_[i].second);
      out.emplace_back(pids_[i].first, now < 0 || start_[i] < 0 ? NAN : (now - start_[i]) / hz / wall);
    }
    for (const auto& p : pids_)
    {
      if (p.first != split_)
      {
        continue;
      }
      for (const auto& group : threadTicks(p.second))
      {
        const auto before = thread_start_.find(group.first);
        const long long start = before == thread_start_.end() ? 0 : before->second;
        out.emplace_back("thread:" + p.first + "." + group.first, std::max(0LL, group.second - start) / hz / wall);
      }
    }
    const SystemTicks system = systemTicks();
    out.emplace_back("system", (system.busy - system_start_.busy) / hz / wall);
    out.emplace_back("steal", (system.steal - system_start_.steal) / hz / wall);
    return out;
  }

  bool alive(const std::string& name) const
  {
    for (const auto& p : pids_)
    {
      if (p.first == name) return cpuTicks(p.second) >= 0;
    }
    return false;
  }

  const std::vector<std::pair<std::string, pid_t>>& pids() const { return pids_; }

private:
  std::vector<std::pair<std::string, pid_t>> pids_;
  std::string split_;
  std::vector<long long> start_;
  std::map<std::string, long long> thread_start_;
  SystemTicks system_start_;
  Clock::time_point start_time_;
};
}  // namespace bench_probe
