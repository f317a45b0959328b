// SIGINT and SIGTERM for the long commands (run, sweep, render, size, bench,
// regress, area, choose, area-model; the tools of cache builds are stopped by
// support/child_process.hpp). The handler only records the signal; the loops that take time
// poll interrupted() (a relaxed atomic load, cheap enough once per triangle)
// and stop by throwing Interrupted, so every file is either written whole or
// not at all. main() turns it into a message and exit status 128 + signal
// (130 for SIGINT). A second signal is not caught: it kills at once.
#pragma once

#include <stdexcept>

namespace cdsim {

class Interrupted : public std::runtime_error {
 public:
  explicit Interrupted(int signal);
  int signal_number() const { return signal_; }
  int exit_status() const { return 128 + signal_; }

 private:
  int signal_;
};

// Installs the handler for SIGINT and SIGTERM (once, from main), except for
// a signal the parent process set to be ignored.
void install_interrupt_handlers();
// The signal received, or 0.
int interrupt_signal();
inline bool interrupted() { return interrupt_signal() != 0; }
// Throws Interrupted if a signal has arrived.
void throw_if_interrupted();

}  // namespace cdsim
