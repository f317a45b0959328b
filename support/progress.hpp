// Progress of a long command on stderr: a bar redrawn in place on a terminal,
// else a plain line every few seconds, so that a log shows the work is alive.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace cdsim {

class Progress {
 public:
  // `prefix` starts the plain lines ("sweep"), `noun` counts ("configurations").
  Progress(size_t total, std::string prefix, std::string noun);
  void update(size_t done, double seconds, bool final = false);

 private:
  size_t total_;
  std::string prefix_, noun_;
  bool tty_;
  double next_line_;
};

enum class ProgressShown { Always, AfterASecond };

// Runs job(0) .. job(count - 1), `threads` at a time (0: all cores), with a
// Progress bar: always, or once the batch has run for a second (so that a
// batch of cached results stays quiet). Stops taking jobs at the first
// exception or on SIGINT/SIGTERM, then rethrows it (or throws Interrupted).
void run_parallel(size_t count, unsigned threads, const std::string& prefix, const std::string& noun,
                  const std::function<void(size_t)>& job,
                  ProgressShown shown = ProgressShown::AfterASecond);

}  // namespace cdsim
