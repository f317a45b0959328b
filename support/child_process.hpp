// The tools that cdsim runs while it builds a cache entry (yosys, verilator,
// the compiler), each in a process group of its own with a small supervisor
// at its head, so that none of them outlives the cdsim that started it:
//  - SIGINT or SIGTERM to cdsim: the code waiting for the tool sees the flag
//    (interrupt.hpp), stops the whole group (the tool and whatever it started:
//    cc1plus, as, yosys-abc) and throws Interrupted;
//  - cdsim killed outright (SIGKILL, a crash): the supervisor holds the read
//    end of a pipe whose only write end is cdsim's, sees it close, and kills
//    the group.
// waitpid(-1) is never used, so several threads (cdsim area on all cores) can
// each run their own tools.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace cdsim {

class ChildProcess {
 public:
  // Starts argv (argv[0] looked up on PATH, else throws naming it) with stdin
  // from /dev/null and stdout and stderr appended to `output`.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& output);
  // Stops the group if it still runs.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  // Without blocking: true once the tool has ended, with its wait status
  // (exit status, or the signal that killed it) in `status`.
  bool finished(int& status);
  // SIGTERM to the group, SIGKILL to what is left after half a second; reaps it.
  void stop();

 private:
  pid_t supervisor_ = -1;  // also the process group's id
  int lifeline_ = -1;      // the write end of the pipe the supervisor watches
};

// Runs one tool to its end and returns its wait status. On SIGINT or SIGTERM
// stops it within a tenth of a second and throws Interrupted.
int run_child(const std::vector<std::string>& argv, const std::filesystem::path& output);

// Several tools, up to `jobs` at a time, each with its output file. Returns
// each one's wait status, in the commands' order; with stop_at_failure no
// command starts after one has failed (their status stays empty). `waiting`,
// if given, is called about every 100 ms with the seconds since the start and
// the count of those that have ended. On SIGINT or SIGTERM stops every running
// one and throws Interrupted.
struct ChildCommand {
  std::vector<std::string> argv;
  std::filesystem::path output;
};
std::vector<std::optional<int>> run_children(const std::vector<ChildCommand>& commands, size_t jobs,
                                             bool stop_at_failure,
                                             const std::function<void(double, size_t)>& waiting = {});

// The wait status as words: "exit 2", "signal 9".
std::string describe_status(int status);

}  // namespace cdsim
