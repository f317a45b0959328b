#include "child_process.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cerrno>
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <thread>

#include "interrupt.hpp"

extern char** environ;

namespace cdsim {

namespace fs = std::filesystem;

namespace {

// argv[0] as execvp would find it; resolved before fork, since the search
// allocates and a forked child of a threaded process must not.
std::string executable_of(const std::string& name) {
  if (name.find('/') != std::string::npos) return name;
  const char* path = std::getenv("PATH");
  std::string dirs = path && *path ? path : "/usr/local/bin:/usr/bin:/bin";
  size_t start = 0;
  while (start <= dirs.size()) {
    const size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
    const std::string candidate = dir + "/" + name;
    struct stat st;
    if (::stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate;
    start = end + 1;
  }
  throw std::runtime_error(fmt::format("cannot run {}: not found on PATH", name));
}

// A descriptor moved above the standard ones, close-on-exec: the child
// rearranges 0..3 and must not overwrite one it still needs.
int high_fd(int fd, const char* what) {
  if (fd < 0) throw std::runtime_error(fmt::format("cannot start a tool: {}: {}", what, std::strerror(errno)));
  const int moved = ::fcntl(fd, F_DUPFD_CLOEXEC, 10);
  const int error = errno;
  ::close(fd);
  if (moved < 0) throw std::runtime_error(fmt::format("cannot start a tool: {}: {}", what, std::strerror(error)));
  return moved;
}

// The supervisor: the forked child, leader of the new group. Only
// async-signal-safe calls from here on (cdsim may have other threads).
[[noreturn]] void supervise(const char* path, char* const* argv, int input, int output, int lifeline) {
  ::setpgid(0, 0);
  struct sigaction ignore;
  std::memset(&ignore, 0, sizeof ignore);
  ignore.sa_handler = SIG_IGN;
  // The group's SIGTERM is for the tool; the supervisor stays to reap it.
  ::sigaction(SIGINT, &ignore, nullptr);
  ::sigaction(SIGTERM, &ignore, nullptr);
  ::dup2(input, 0);
  ::dup2(output, 1);
  ::dup2(output, 2);
  ::dup2(lifeline, 3);
  // Other threads' pipes must close with cdsim, not stay open here.
  ::close_range(4, ~0u, 0);
  sigset_t child_signal, none;
  sigemptyset(&child_signal);
  sigaddset(&child_signal, SIGCHLD);
  sigemptyset(&none);
  ::sigprocmask(SIG_BLOCK, &child_signal, nullptr);
  const int child_events = ::signalfd(-1, &child_signal, SFD_CLOEXEC);
  const pid_t tool = ::fork();
  if (tool == 0) {
    struct sigaction standard;
    std::memset(&standard, 0, sizeof standard);
    standard.sa_handler = SIG_DFL;
    ::sigaction(SIGINT, &standard, nullptr);
    ::sigaction(SIGTERM, &standard, nullptr);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    ::close_range(3, ~0u, 0);
    ::execve(path, argv, environ);
    _exit(127);
  }
  if (tool < 0 || child_events < 0) _exit(126);
  for (;;) {
    pollfd watched[2] = {{3, POLLIN, 0}, {child_events, POLLIN, 0}};
    if (::poll(watched, 2, -1) < 0) continue;
    if (watched[0].revents) ::kill(0, SIGKILL);  // cdsim is gone (nothing is ever written)
    if (watched[1].revents) {
      signalfd_siginfo info;
      (void)!::read(child_events, &info, sizeof info);
      int status = 0;
      if (::waitpid(tool, &status, WNOHANG) == tool) {
        if (WIFEXITED(status)) _exit(WEXITSTATUS(status));
        // The same death for cdsim to see.
        struct sigaction standard;
        std::memset(&standard, 0, sizeof standard);
        standard.sa_handler = SIG_DFL;
        ::sigaction(WTERMSIG(status), &standard, nullptr);
        ::sigprocmask(SIG_SETMASK, &none, nullptr);
        ::kill(::getpid(), WTERMSIG(status));
        _exit(128 + WTERMSIG(status));
      }
    }
  }
}

}  // namespace

ChildProcess::ChildProcess(const std::vector<std::string>& arguments, const fs::path& output) {
  if (arguments.empty()) throw std::invalid_argument("ChildProcess: no command");
  const std::string path = executable_of(arguments[0]);
  std::vector<char*> argv;
  for (const std::string& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const int input = high_fd(::open("/dev/null", O_RDONLY | O_CLOEXEC), "/dev/null");
  int log = -1;
  try {
    log = high_fd(::open(output.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0600),
                  output.c_str());
  } catch (...) {
    ::close(input);
    throw;
  }
  int ends[2];
  if (::pipe2(ends, O_CLOEXEC) != 0) {
    ::close(input);
    ::close(log);
    throw std::runtime_error(fmt::format("cannot start {}: pipe: {}", arguments[0], std::strerror(errno)));
  }
  int lifeline_read = -1;
  try {
    lifeline_read = high_fd(ends[0], "pipe");
    lifeline_ = high_fd(ends[1], "pipe");
  } catch (...) {
    ::close(input);
    ::close(log);
    if (lifeline_read >= 0) ::close(lifeline_read);
    throw;
  }
  const pid_t pid = ::fork();
  if (pid == 0) supervise(path.c_str(), argv.data(), input, log, lifeline_read);
  const int error = errno;
  ::close(input);
  ::close(log);
  ::close(lifeline_read);
  if (pid < 0) {
    ::close(lifeline_);
    throw std::runtime_error(fmt::format("cannot start {}: fork: {}", arguments[0], std::strerror(error)));
  }
  // Also here, so that a stop() right away cannot miss the group.
  ::setpgid(pid, pid);
  supervisor_ = pid;
}

ChildProcess::~ChildProcess() {
  if (supervisor_ > 0) stop();
  if (lifeline_ >= 0) ::close(lifeline_);
}

bool ChildProcess::finished(int& status) {
  if (supervisor_ <= 0) return true;
  const pid_t done = ::waitpid(supervisor_, &status, WNOHANG);
  if (done == 0 || (done < 0 && errno == EINTR)) return false;
  if (done < 0) status = 0x7f00;  // lost (cannot happen: no one else waits for it)
  supervisor_ = -1;
  return true;
}

void ChildProcess::stop() {
  if (supervisor_ <= 0) return;
  const pid_t group = supervisor_;
  ::kill(-group, SIGTERM);
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(500);
  while (!finished(status) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  // What ignored SIGTERM, and the supervisor if it still waits for it.
  ::kill(-group, SIGKILL);
  if (supervisor_ > 0) {
    while (::waitpid(supervisor_, &status, 0) < 0 && errno == EINTR) {
    }
    supervisor_ = -1;
  }
}

int run_child(const std::vector<std::string>& argv, const fs::path& output) {
  ChildProcess child(argv, output);
  int status = 0;
  while (!child.finished(status)) {
    if (interrupted()) {
      child.stop();
      throw_if_interrupted();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return status;
}

std::vector<std::optional<int>> run_children(const std::vector<ChildCommand>& commands, size_t jobs,
                                             bool stop_at_failure,
                                             const std::function<void(double, size_t)>& waiting) {
  std::vector<std::optional<int>> status(commands.size());
  std::vector<std::pair<std::unique_ptr<ChildProcess>, size_t>> running;
  const auto start = std::chrono::steady_clock::now();
  bool failed = false;
  size_t next = 0, ended = 0;
  while (!running.empty() || (!(failed && stop_at_failure) && next < commands.size())) {
    while (!(failed && stop_at_failure) && next < commands.size() && running.size() < std::max<size_t>(jobs, 1)) {
      running.emplace_back(std::make_unique<ChildProcess>(commands[next].argv, commands[next].output), next);
      ++next;
    }
    throw_if_interrupted();  // the destructors stop what runs
    bool any = false;
    for (auto it = running.begin(); it != running.end();) {
      int s = 0;
      if (!it->first->finished(s)) {
        ++it;
        continue;
      }
      any = true;
      status[it->second] = s;
      failed = failed || !(WIFEXITED(s) && WEXITSTATUS(s) == 0);
      ++ended;
      it = running.erase(it);
    }
    if (!any) {
      if (waiting) waiting(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), ended);
      std::this_thread::sleep_for(std::chrono::milliseconds(running.size() > 1 ? 100 : 20));
    }
  }
  return status;
}

std::string describe_status(int status) {
  if (WIFEXITED(status)) return fmt::format("exit {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return fmt::format("signal {}", WTERMSIG(status));
  return fmt::format("status {}", status);
}

}  // namespace cdsim
