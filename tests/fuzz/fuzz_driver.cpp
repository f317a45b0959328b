// Runs a libFuzzer target's LLVMFuzzerTestOneInput once on each file named on
// the command line: the target's seeds, in every build, also those without
// libFuzzer (tests/fuzz/CMakeLists.txt). Exits non-zero if a file cannot be
// read; a failing property aborts, as under libFuzzer.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "%s: cannot read\n", argv[i]);
      return 1;
    }
    const std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(data.data()), data.size());
  }
  std::printf("%d inputs ran\n", argc - 1);
  return argc > 1 ? 0 : 1;
}
