// libFuzzer target: the command line (app/cli.cpp, cli_checks.cpp). The
// input is an argv, one argument per line. Parsing must refuse bad input
// with a CLI11 error, never crash, and what it accepts must lie in each
// option's documented range; then the settings are checked as the commands
// check them (no command runs: nothing is read or written).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "sweep_file.hpp"

// The RTL is not linked into the fuzzer; parsing never runs it.
namespace cdsim::rtl {
int verify_widths(const VerifyRequest&) { return 2; }
}  // namespace cdsim::rtl

namespace {

void check(bool property) {
  if (!property) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> words = {"cdsim"};
  for (size_t start = 0; start <= text.size() && words.size() < 64;) {
    const size_t end = std::min(text.find('\n', start), text.size());
    words.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  if (!text.empty() && text.back() == '\n') words.pop_back();
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());

  const std::unique_ptr<cdsim::Cli> cli = cdsim::make_cli();
  try {
    cli->app.parse(int(argv.size()), argv.data());
  } catch (const CLI::Error&) {
    return 0;
  }
  check(std::isfinite(cli->bench_seconds) && cli->bench_seconds > 0 && cli->bench_seconds <= 3600);
  check(cli->regress.backpressure >= 0 && cli->regress.backpressure <= 0.95);
  check(cli->regress.random <= 10'000'000 && cli->regress.only >= -1);
  check(cli->sweep.jobs >= 0 && cli->sweep.jobs <= 1024);
  check(cli->render.checker_texels >= 1 && cli->render.checker_texels <= 4096);
  check(std::isfinite(cli->size.max_error) && cli->size.max_error > 0);
  check(cli->size.verify_backpressure >= 0 && cli->size.verify_backpressure <= 0.95);
  try {
    for (const cdsim::CommonOptions* common :
         {&cli->run, &cli->bench, &cli->widths, &cli->render.common, &cli->size.common}) {
      cdsim::widths_from(*common);
      cdsim::designs_from(common->designs);
    }
    for (const std::string& setting : cli->sweep.common.settings) cdsim::parse_axis(setting);
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
