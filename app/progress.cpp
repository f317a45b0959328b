#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace cdsim {

namespace {
constexpr double kPlainProgressSeconds = 5.0;
}

Progress::Progress(size_t total, std::string prefix, std::string noun)
    : total_(total),
      prefix_(std::move(prefix)),
      noun_(std::move(noun)),
      tty_(isatty(fileno(stderr))),
      next_line_(kPlainProgressSeconds) {}

void Progress::update(size_t done, double seconds, bool final) {
  const std::string left =
      done > 0 && done < total_
          ? fmt::format(", about {:.0f} s to go", seconds / double(done) * double(total_ - done))
          : "";
  if (tty_) {
    const int width = 40;
    const int filled = total_ ? int(width * done / total_) : width;
    fmt::print(stderr, "\r[{:<{}}] {}/{} {}, {:.0f} s{}\x1b[K", std::string(size_t(filled), '='),
               width, done, total_, noun_, seconds, left);
    if (final) fmt::print(stderr, "\n");
  } else if (final || seconds >= next_line_) {
    fmt::print(stderr, "{}: {}/{} {} ({:.1f} %), {:.0f} s{}\n", prefix_, done, total_, noun_,
               total_ ? 100.0 * double(done) / double(total_) : 100.0, seconds, left);
    next_line_ = seconds + kPlainProgressSeconds;
  }
}

}  // namespace cdsim
