#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "interrupt.hpp"

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

void run_parallel(size_t count, unsigned threads, const std::string& prefix, const std::string& noun,
                  const std::function<void(size_t)>& job, ProgressShown when) {
  if (count == 0) return;
  const unsigned wanted = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  const unsigned workers_count = std::min<unsigned>(wanted, static_cast<unsigned>(std::min<size_t>(count, 1024)));
  std::atomic<size_t> next{0}, done{0};
  std::atomic<unsigned> running{workers_count};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::vector<std::thread> workers;
  for (unsigned t = 0; t < workers_count; ++t)
    workers.emplace_back([&] {
      for (size_t i; (i = next++) < count;) {
        try {
          job(i);
        } catch (...) {
          std::lock_guard<std::mutex> guard(failure_mutex);
          if (!failure) failure = std::current_exception();
          next = count;
        }
        ++done;
      }
      --running;
    });
  Progress progress(count, prefix, noun);
  bool shown = false;
  for (int tick = 0; running > 0; ++tick) {
    if (interrupted()) next = count;
    // Only a batch that really works shows progress; a cached one is instant.
    if (when == ProgressShown::Always ? tick % 2 == 0 : tick >= 10 && tick % 10 == 0) {
      progress.update(done, elapsed());
      shown = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  for (auto& w : workers) w.join();
  throw_if_interrupted();
  if (failure) std::rethrow_exception(failure);
  if (shown || when == ProgressShown::Always) progress.update(done, elapsed(), true);
}

}  // namespace cdsim
