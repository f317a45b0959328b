// Progress of a long command on stderr: a bar redrawn in place on a terminal,
// else a plain line every few seconds, so that a log shows the work is alive.
#pragma once

#include <cstddef>
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

}  // namespace cdsim
