// The cache of RTL verilated for widths that no built-in configuration has.
//
//   <cache>/<model key>/       one width configuration, verilated and compiled;
//                              built in <cache>/tmp-*, renamed into place when
//                              complete, so a folder under this name is finished
//     cd_widths.svh            rtl_header(widths); for the adaptive unit
//                              (rtl/adaptive_unit.sv), its leaf unit's
//     inputs.txt               the widths and everything else the key covers
//     verilated/               Verilator's C++ (Vcd_scan_unit_custom*, whichever the top:
//                              the adaptive unit has the scan unit's ports)
//     obj/                     its objects, compiled as cdsim_rtl's plus -fPIC
//     log/                     verilator.log and one log per compile
//     bench-<bench key>.so     bench_entry.cpp and obj/, for one cdsim build
//   <cache>/tmp-*              a build in progress, failed or interrupted: never used
//
// The model key is FNV-1a 64 of the header, every rtl/*.sv, Verilator's binary,
// version and arguments, and the compiler and its flags. The bench key adds
// cdsim's build ID and the bench's sources and flags: the shared object takes
// the SystemC kernel, the Verilator runtime and the model code from cdsim
// (which exports its symbols), so it must match this very build. A rebuild of
// cdsim thus recompiles the bench alone (one file), not the model.
#include "rtl_cache.hpp"

#include "cache_files.hpp"

#include <dlfcn.h>
#include <elf.h>
#include <fcntl.h>
#include <link.h>
#include <sched.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>
#include <systemc.h>
#include <verilated.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "build_info.hpp"
#include "derived_widths.hpp"
#include "rtl_build.hpp"

extern char** environ;

namespace cdsim::rtl {

namespace fs = std::filesystem;

namespace {

// Bumped whenever the layout or the build steps below change.
constexpr const char* kCacheVersion = "rtl-cache-1";
constexpr const char* kPrefix = "Vcd_scan_unit_custom";

std::string hex(uint64_t value) { return fmt::format("{:016x}", value); }

template <size_t N>
std::vector<std::string> strings(const char* const (&items)[N]) {
  std::vector<std::string> out;
  // An empty CMake list leaves "", "-D" or "-I" behind.
  for (const char* item : items)
    if (*item && std::strcmp(item, "-D") != 0 && std::strcmp(item, "-I") != 0) out.push_back(item);
  return out;
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : " ") + w;
  return out;
}

std::vector<fs::path> files_in(const fs::path& dir, const std::string& extension) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file() && entry.path().extension() == extension) out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

// The GNU build ID of the running cdsim, or a hash of its file without one.
std::string own_build_id() {
  std::string id;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) {
        auto& out = *static_cast<std::string*>(data);
        for (int i = 0; i < info->dlpi_phnum && out.empty(); ++i) {
          const ElfW(Phdr)& segment = info->dlpi_phdr[i];
          if (segment.p_type != PT_NOTE) continue;
          const char* at = reinterpret_cast<const char*>(info->dlpi_addr + segment.p_vaddr);
          const char* end = at + segment.p_memsz;
          while (at + sizeof(ElfW(Nhdr)) <= end) {
            const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(at);
            const char* name = at + sizeof(ElfW(Nhdr));
            const char* desc = name + ((note->n_namesz + 3) & ~3u);
            if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 &&
                std::memcmp(name, "GNU", 4) == 0) {
              for (size_t b = 0; b < note->n_descsz; ++b)
                out += fmt::format("{:02x}", static_cast<unsigned char>(desc[b]));
              break;
            }
            at = desc + ((note->n_descsz + 3) & ~3u);
          }
        }
        return 1;  // the first object is the executable: stop there
      },
      &id);
  if (id.empty()) id = "exe-" + hex(fnv1a(read_text_file("/proc/self/exe")));
  return id;
}

size_t parallel_jobs() {
  cpu_set_t cpus;
  if (sched_getaffinity(0, sizeof cpus, &cpus) == 0) return std::max(1, CPU_COUNT(&cpus));
  return std::max(1u, std::thread::hardware_concurrency());
}

// One command of a build, its output going to its own log.
struct Step {
  std::vector<std::string> argv;
  fs::path log;
  std::string what;  // "Verilator", "compiling X.cpp"
};

pid_t spawn(const Step& step) {
  write_file_atomic(step.log, "$ " + joined(step.argv) + "\n");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, step.log.c_str(), O_WRONLY | O_APPEND, 0);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> argv;
  for (const std::string& a : step.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int error = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0)
    throw std::runtime_error(fmt::format("cannot run {}: {}", step.argv[0], std::strerror(error)));
  return pid;
}

std::string failure_of(const Step& step, int status) {
  std::string out = fmt::format(
      "{} failed ({}); log: {}", step.what,
      WIFEXITED(status) ? fmt::format("exit {}", WEXITSTATUS(status))
                        : fmt::format("signal {}", WTERMSIG(status)),
      step.log.string());
  std::ifstream log(step.log);
  std::string line;
  std::getline(log, line);  // the command
  for (int shown = 0; shown < 15 && std::getline(log, line); ++shown) out += "\n  " + line;
  return out;
}

// Runs the steps, up to `jobs` at a time; after a failure starts no more, waits
// for those running and throws the first failure.
void run_steps(const std::vector<Step>& steps, size_t jobs) {
  std::map<pid_t, size_t> running;
  std::string failure;
  size_t next = 0;
  while (!running.empty() || (failure.empty() && next < steps.size())) {
    while (failure.empty() && next < steps.size() && running.size() < jobs) {
      running[spawn(steps[next])] = next;
      ++next;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("waitpid: {}", std::strerror(errno)));
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const Step& step = steps[it->second];
    running.erase(it);
    if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0) && failure.empty())
      failure = failure_of(step, status);
  }
  if (!failure.empty()) throw std::runtime_error(failure);
}

// Build times of the last builds in this cache, for the estimate printed first.
struct Timings {
  double model = 30, bench = 10;  // until measured here (2 busy cores: about that)
};

Timings read_timings(const fs::path& root) {
  Timings t;
  std::ifstream in(root / "build_seconds");
  std::string what;
  double seconds = 0;
  while (in >> what >> seconds) (what == "model" ? t.model : t.bench) = seconds;
  return t;
}

void write_timings(const fs::path& root, const Timings& t) {
  try {
    write_file_atomic(root / "build_seconds", fmt::format("model {:.1f}\nbench {:.1f}\n", t.model, t.bench));
  } catch (const std::exception&) {
    // only an estimate
  }
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Leftovers of interrupted or failed builds, kept a day for their logs.
void remove_stale(const fs::path& dir, const std::string& prefix) {
  const auto day_ago = fs::file_time_type::clock::now() - std::chrono::hours(24);
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    if (entry.last_write_time(ec) < day_ago) fs::remove_all(entry.path(), ec);
  }
}

// Verilator's coverage options for a coverage build, and the cover points.
std::vector<std::string> coverage_args(CoverageBuild coverage) {
  switch (coverage) {
    case CoverageBuild::None: return {};
    case CoverageBuild::Lines: return {"--coverage-line", "--coverage-user", build::kCoverSource};
    case CoverageBuild::All: return {"--coverage", build::kCoverSource};
  }
  return {};
}

// The top and its sources: the scan unit, or the adaptive design's unit.
const char* top_of(bool adaptive) { return adaptive ? build::kAdaptiveTop : build::kRtlTop; }
std::vector<std::string> sources_of(bool adaptive) {
  return adaptive ? strings(build::kAdaptiveSources) : strings(build::kRtlSources);
}

// Verilator as verilate() in sim/CMakeLists.txt runs it for the built-in configurations.
std::vector<std::string> verilator_command(const fs::path& verilated, const fs::path& header_dir,
                                           CoverageBuild coverage, bool adaptive) {
  std::vector<std::string> argv = {build::kVerilatorBin, "--compiler", build::kVerilatorCompiler,
                                   "--prefix", kPrefix, "--Mdir", verilated.string(),
                                   "--make", "cmake", "--top", top_of(adaptive), "--trace-fst", "--sc",
                                   "-y", header_dir.string(), "-y", kRtlDir};
  for (const std::string& a : strings(build::kVerilatorArgs)) argv.push_back(a);
  for (const std::string& s : sources_of(adaptive)) argv.push_back(s);
  for (const std::string& a : coverage_args(coverage)) argv.push_back(a);
  return argv;
}

// The model's compile flags; a coverage build defines VM_COVERAGE as verilate() would.
std::vector<std::string> model_flags(CoverageBuild coverage) {
  std::vector<std::string> flags = strings(build::kModelFlags);
  if (coverage != CoverageBuild::None)
    for (std::string& f : flags)
      if (f == "-DVM_COVERAGE=0") f = "-DVM_COVERAGE=1";
  return flags;
}

// What the model key covers besides the header and the RTL.
std::string model_recipe(CoverageBuild coverage, bool adaptive) {
  std::string recipe = fmt::format(
      "verilator: {} {} --prefix {} --top {} --trace-fst --sc {} {}\ncompiler: {} ({})\nflags: {}\n",
      build::kVerilatorBin, build::kVerilatorVersion, kPrefix, top_of(adaptive),
      joined(strings(build::kVerilatorArgs)), joined(sources_of(adaptive)),
      build::kCompiler, build::kCompilerVersion, joined(model_flags(coverage)));
  if (coverage != CoverageBuild::None)
    recipe += fmt::format("coverage: {} {}\n", joined(coverage_args(coverage)),
                          hex(fnv1a(read_text_file(build::kCoverSource))));
  return recipe;
}

void build_model(const fs::path& root, const fs::path& model_dir, const std::string& header,
                 const std::string& inputs, CoverageBuild coverage, bool adaptive) {
  const fs::path tmp = root / fmt::format("tmp-{}-{}", model_dir.filename().string(), getpid());
  fs::remove_all(tmp);
  fs::create_directories(tmp / "log");
  fs::create_directories(tmp / "obj");
  write_file_atomic(tmp / "cd_widths.svh", header);
  write_file_atomic(tmp / "inputs.txt", inputs);
  const auto start = std::chrono::steady_clock::now();
  run_steps({{verilator_command(tmp / "verilated", tmp, coverage, adaptive), tmp / "log/verilator.log",
              "Verilator"}},
            1);
  std::vector<Step> compiles;
  for (const fs::path& source : files_in(tmp / "verilated", ".cpp")) {
    const std::string name = source.stem().string();
    std::vector<std::string> argv = {build::kCompiler};
    for (const std::string& f : model_flags(coverage)) argv.push_back(f);
    argv.insert(argv.end(), {"-I" + (tmp / "verilated").string(), "-c", source.string(), "-o",
                             (tmp / "obj" / (name + ".o")).string()});
    compiles.push_back(
        {argv, tmp / "log" / (name + ".log"), "compiling " + source.filename().string()});
  }
  const size_t jobs = parallel_jobs();
  std::cout << fmt::format("  verilated in {:.1f} s; compiling its {} files, {} at a time\n",
                           seconds_since(start), compiles.size(), jobs);
  std::cout.flush();
  run_steps(compiles, jobs);
  std::error_code ec;
  fs::rename(tmp, model_dir, ec);
  if (ec) {
    if (!fs::exists(model_dir))
      throw std::runtime_error(fmt::format("cannot rename {} to {}: {}", tmp.string(),
                                           model_dir.string(), ec.message()));
    fs::remove_all(tmp);  // another cdsim finished the same build first
  }
}

std::vector<std::string> bench_flags() {
  std::vector<std::string> flags = strings(build::kBenchFlags);
  flags.push_back("-I" + std::string(build::kBenchSources));
  return flags;
}

void build_bench(const fs::path& model_dir, const fs::path& library) {
  const fs::path tmp = model_dir / fmt::format("tmp-bench-{}", getpid());
  fs::remove_all(tmp);
  fs::create_directories(tmp);
  const fs::path object = tmp / "bench_entry.o";
  std::vector<std::string> compile = {build::kCompiler};
  for (const std::string& f : bench_flags()) compile.push_back(f);
  const fs::path source = fs::path(build::kBenchSources) / "bench_entry.cpp";
  compile.insert(compile.end(), {"-I" + (model_dir / "verilated").string(), "-c", source.string(),
                                 "-o", object.string()});
  std::cout << "  compiling the bench for this cdsim build\n";
  std::cout.flush();
  run_steps({{compile, tmp / "bench.log", "compiling the bench (bench_entry.cpp)"}}, 1);
  // No -z defs: the SystemC kernel, the Verilator runtime and the model code
  // are undefined here on purpose and come from cdsim when it loads the object.
  std::vector<std::string> link = {build::kCompiler, "-shared"};
  for (const std::string& f : strings(build::kLinkFlags)) link.push_back(f);
  link.insert(link.end(), {"-o", (tmp / "bench.so").string(), object.string()});
  for (const fs::path& o : files_in(model_dir / "obj", ".o")) link.push_back(o.string());
  run_steps({{link, tmp / "link.log", "linking the bench"}}, 1);
  fs::rename(tmp / "bench.so", library);  // atomic; a concurrent build's copy is the same
  fs::remove_all(tmp);
  // Benches of older cdsim builds, unused for a week.
  const auto week_ago = fs::file_time_type::clock::now() - std::chrono::hours(24 * 7);
  std::error_code ec;
  for (const fs::path& old : files_in(model_dir, ".so"))
    if (old != library && fs::last_write_time(old, ec) < week_ago) fs::remove(old, ec);
}

RunBench open_bench(const fs::path& library) {
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);  // never closed
  if (!handle)
    throw std::runtime_error(fmt::format(
        "cannot load {}: {} (cdsim provides the SystemC kernel, Verilator runtime and model code "
        "to it, so it must be linked with ENABLE_EXPORTS)",
        library.string(), dlerror()));
  const auto run = reinterpret_cast<RunBench>(dlsym(handle, "cdsim_rtl_run_bench"));
  const auto runtime = reinterpret_cast<void (*)(void**, void**)>(dlsym(handle, "cdsim_rtl_runtime"));
  if (!run || !runtime)
    throw std::runtime_error(fmt::format("{}: not a cdsim bench (no entry point)", library.string()));
  void* simcontext = nullptr;
  void* verilated_context = nullptr;
  runtime(&simcontext, &verilated_context);
  if (simcontext != sc_core::sc_get_curr_simcontext() ||
      verilated_context != Verilated::threadContextp())
    throw std::runtime_error(fmt::format(
        "{} has a SystemC kernel or Verilator runtime of its own; delete its folder and rerun",
        library.string()));
  return run;
}

}  // namespace

std::string default_rtl_cache_dir() { return cache_root("rtl").string(); }

void run_tool(const std::vector<std::string>& argv, const std::string& log, const std::string& what) {
  run_steps({{argv, log, what}}, 1);
}

RunBench load_custom_rtl(const Widths& widths, const std::string& cache_dir, CoverageBuild coverage,
                         bool adaptive) {
  const std::string header = adaptive ? rtl_header(adaptive_leaf_widths(widths), "custom, adaptive leaf unit")
                                      : rtl_header(widths, "custom");
  const fs::path root = fs::absolute(cache_dir.empty() ? default_rtl_cache_dir() : cache_dir);
  fs::create_directories(root);

  std::string inputs = fmt::format("widths: {}\n{}", describe(widths), model_recipe(coverage, adaptive));
  uint64_t model_key = fnv1a(kCacheVersion);
  model_key = fnv1a(header, model_key);
  for (const fs::path& sv : files_in(kRtlDir, ".sv")) {
    const std::string text = read_text_file(sv);
    model_key = fnv1a(text, fnv1a(sv.filename().string(), model_key));
    inputs += fmt::format("rtl: {} {}\n", sv.filename().string(), hex(fnv1a(text)));
  }
  model_key = fnv1a(inputs, model_key);
  const fs::path model_dir = root / hex(model_key);

  uint64_t bench_key = fnv1a(own_build_id(), model_key);
  bench_key = fnv1a(joined(bench_flags()) + "\n" + joined(strings(build::kLinkFlags)), bench_key);
  for (const auto& entry : fs::directory_iterator(build::kBenchSources))
    if (entry.is_regular_file() && entry.path().filename() != "stamp")
      bench_key = fnv1a(read_text_file(entry.path()), fnv1a(entry.path().filename().string(), bench_key));
  const fs::path library = model_dir / fmt::format("bench-{}.so", hex(bench_key));

  Timings timings = read_timings(root);
  const auto start = std::chrono::steady_clock::now();
  if (!fs::exists(model_dir)) {
    remove_stale(root, "tmp-");
    std::cout << fmt::format(
        "regress: building the RTL{}{} for widths {} in {} (first use; about {:.0f} s)\n",
        adaptive ? " of the adaptive unit" : "",
        coverage == CoverageBuild::All     ? " with coverage"
        : coverage == CoverageBuild::Lines ? " with line coverage"
                                           : "",
        describe(widths), model_dir.string(), timings.model + timings.bench);
    std::cout.flush();
    build_model(root, model_dir, header, inputs, coverage, adaptive);
    timings.model = seconds_since(start);
    const auto bench_start = std::chrono::steady_clock::now();
    build_bench(model_dir, library);
    timings.bench = seconds_since(bench_start);
    write_timings(root, timings);
    std::cout << fmt::format("regress: built in {:.0f} s\n", seconds_since(start));
  } else if (!fs::exists(library)) {
    remove_stale(model_dir, "tmp-bench-");
    std::cout << fmt::format(
        "regress: reusing the RTL verilated for these widths in {}; a new cdsim build needs its "
        "own bench (about {:.0f} s)\n",
        model_dir.string(), timings.bench);
    std::cout.flush();
    build_bench(model_dir, library);
    timings.bench = seconds_since(start);
    write_timings(root, timings);
  } else {
    std::cout << fmt::format("regress: reusing the RTL built for these widths in {}\n",
                             model_dir.string());
  }
  std::cout.flush();
  return open_bench(library);
}

}  // namespace cdsim::rtl
