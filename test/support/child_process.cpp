#include "child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace rviz_projector_test
{
namespace
{
double secondsSince(const std::chrono::steady_clock::time_point& start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& argv)
{
  char dir_template[] = "/tmp/child_process_XXXXXX";
  const char* dir = mkdtemp(dir_template);
  stderr_path_ = std::string(dir != nullptr ? dir : "/tmp") + "/stderr";
  int pipe_fds[2];
  if (pipe(pipe_fds) != 0)
  {
    return;
  }
  const pid_t pid = fork();
  if (pid < 0)
  {
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    return;
  }
  if (pid == 0)
  {
    dup2(pipe_fds[1], STDOUT_FILENO);
    const int err = open(stderr_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (err >= 0)
    {
      dup2(err, STDERR_FILENO);
    }
    const int null = open("/dev/null", O_RDONLY);
    if (null >= 0)
    {
      dup2(null, STDIN_FILENO);
    }
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    std::vector<char*> args;
    for (const std::string& arg : argv)
    {
      args.push_back(const_cast<char*>(arg.c_str()));
    }
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  close(pipe_fds[1]);
  stdout_fd_ = pipe_fds[0];
  pid_ = pid;
}

ChildProcess::~ChildProcess()
{
  if (pid_ > 0)
  {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
  }
  if (stdout_fd_ >= 0)
  {
    close(stdout_fd_);
  }
}

bool ChildProcess::fill(double timeout_s)
{
  if (eof_ || stdout_fd_ < 0)
  {
    return false;
  }
  pollfd fd{stdout_fd_, POLLIN, 0};
  const int ready = poll(&fd, 1, static_cast<int>(timeout_s * 1000.0));
  if (ready <= 0)
  {
    return false;
  }
  char chunk[4096];
  const ssize_t n = read(stdout_fd_, chunk, sizeof(chunk));
  if (n <= 0)
  {
    eof_ = true;
    return false;
  }
  buffer_.append(chunk, static_cast<std::size_t>(n));
  output_.append(chunk, static_cast<std::size_t>(n));
  return true;
}

bool ChildProcess::readLine(std::string& line, double timeout_s)
{
  const auto start = std::chrono::steady_clock::now();
  while (true)
  {
    const std::size_t newline = buffer_.find('\n');
    if (newline != std::string::npos)
    {
      line = buffer_.substr(0, newline);
      buffer_.erase(0, newline + 1);
      return true;
    }
    const double left = timeout_s - secondsSince(start);
    if (left <= 0.0 || !fill(left))
    {
      if (eof_ && !buffer_.empty())
      {
        line = buffer_;
        buffer_.clear();
        return true;
      }
      return false;
    }
  }
}

int ChildProcess::wait(double timeout_s)
{
  if (pid_ <= 0)
  {
    return -1;
  }
  const auto start = std::chrono::steady_clock::now();
  while (!eof_ && secondsSince(start) < timeout_s)
  {
    fill(timeout_s - secondsSince(start));
  }
  int status = 0;
  pid_t done = 0;
  while ((done = waitpid(pid_, &status, WNOHANG)) == 0 && secondsSince(start) < timeout_s)
  {
    pollfd none{-1, 0, 0};
    poll(&none, 0, 10);  // the process closed stdout: its exit follows at once
  }
  if (done != pid_)
  {
    kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    pid_ = -1;
    errors_ = readFile(stderr_path_);
    return -1;
  }
  pid_ = -1;
  errors_ = readFile(stderr_path_);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

RunResult run(const std::vector<std::string>& argv, double timeout_s)
{
  ChildProcess child(argv);
  RunResult result;
  result.status = child.wait(timeout_s);
  result.out = child.output();
  result.err = child.errors();
  return result;
}

std::string makeTempDir()
{
  char dir_template[] = "/tmp/calibrate_projector_test_XXXXXX";
  const char* dir = mkdtemp(dir_template);
  return dir != nullptr ? dir : "/tmp";
}

bool fileExists(const std::string& path)
{
  struct stat info;
  return stat(path.c_str(), &info) == 0;
}

std::string readFile(const std::string& path)
{
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

void writeFile(const std::string& path, const std::string& text)
{
  std::ofstream(path) << text;
}
}  // namespace rviz_projector_test
