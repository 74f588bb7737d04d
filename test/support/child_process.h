// Test helper: runs a program (no shell) and talks to it: its stdout line by line with timeouts,
// its stderr into a file, its exit status. For the calibrate_projector / mount_tf_publisher tests.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace rviz_projector_test
{
class ChildProcess
{
public:
  /// Starts `argv[0]` with the arguments; `ok()` tells whether it started.
  explicit ChildProcess(const std::vector<std::string>& argv);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  bool ok() const { return pid_ > 0; }
  /// The next line of stdout (without '\n'); false on EOF or when `timeout_s` passes first.
  bool readLine(std::string& line, double timeout_s);
  /// Reads stdout to its end (at most `timeout_s`), waits for the exit; the status (-1: killed
  /// or timed out, then the process is killed).
  int wait(double timeout_s);
  /// Everything read from stdout so far, and stderr once wait() returned.
  const std::string& output() const { return output_; }
  const std::string& errors() const { return errors_; }

private:
  pid_t pid_ = -1;
  int stdout_fd_ = -1;
  std::string stderr_path_;
  std::string buffer_;  ///< read but not yet returned by readLine
  std::string output_;
  std::string errors_;
  bool eof_ = false;

  bool fill(double timeout_s);
};

struct RunResult
{
  int status = -1;
  std::string out;
  std::string err;
};

/// Runs a program to its end (at most `timeout_s`).
RunResult run(const std::vector<std::string>& argv, double timeout_s = 30.0);

/// A fresh empty directory under /tmp (removed by the caller if it wants).
std::string makeTempDir();
bool fileExists(const std::string& path);
std::string readFile(const std::string& path);
void writeFile(const std::string& path, const std::string& text);
}  // namespace rviz_projector_test
