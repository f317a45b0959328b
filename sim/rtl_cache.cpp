// The cache of the RTL that `cdsim regress` runs: every unit, at any widths,
// verilated on first use (cdsim itself holds no verilated unit).
//
//   <cache>/                   a folder of this user's, mode 0700, checked
//                              (owner, mode) before each use: cdsim loads code
//                              from it (cache_files.hpp, check_cache_folder)
//   <cache>/<model key>/       one unit at one width configuration, verilated and compiled;
//                              built in <cache>/tmp-<model key>-*, renamed into
//                              place when complete, so a folder under this name
//                              is finished
//     cd_widths.svh            rtl_header(widths); for the adaptive unit
//                              (rtl/adaptive_unit.sv), its leaf unit's
//     inputs.txt               the widths and everything else the key covers
//     verilated/               Verilator's C++ (Vcd_scan_unit_custom*, whichever the top:
//                              the adaptive unit has the scan unit's ports)
//     obj/                     its objects, compiled as cdsim_rtl's plus -fPIC
//     log/                     verilator.log and one log per compile
//     manifest                 size and hash of every file above, written last
//     bench-<bench key>.so     bench_entry.cpp and obj/, for one cdsim build
//     bench-<bench key>.so.manifest  its size and hash
//   <cache>/<model key>.lock   flock(2) while a cdsim builds or loads the entry:
//                              a second one waits instead of building it twice
//   <cache>/failed-<model key>/  the logs of the last failed build of the entry
//
// An entry is checked against its manifests before use (a bench-*.so that a
// full disk truncated would otherwise crash the dlopen with SIGBUS); a
// mismatch is said, naming the file, and the entry rebuilt. A failed or
// interrupted build leaves no tmp- folder: its logs go to failed-<model key>/,
// and SIGINT or SIGTERM stops Verilator and the compilers as process groups
// (support/child_process.hpp).
//
// The model key is FNV-1a 64 of the header, every rtl/*.sv, Verilator's binary,
// version and arguments (the unit's -G parameters among them), and the
// compiler and its flags. The bench key adds
// cdsim's build ID and the bench's sources and flags: the shared object takes
// the SystemC kernel, the Verilator runtime and the model code from cdsim
// (which exports its symbols), so it must match this very build. A rebuild of
// cdsim thus recompiles the bench alone (one file), not the model.
#include "rtl_cache.hpp"

#include "cache_files.hpp"
#include "child_process.hpp"
#include "interrupt.hpp"

#include <dlfcn.h>
#include <elf.h>
#include <fcntl.h>
#include <link.h>
#include <sched.h>
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
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "build_info.hpp"
#include "derived_widths.hpp"
#include "rtl_build.hpp"

namespace cdsim::rtl {

namespace fs = std::filesystem;

namespace {

// Bumped whenever the layout or the build steps below change.
constexpr const char* kCacheVersion = "rtl-cache-3";
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

std::string failure_of(const Step& step, int status, const fs::path& log) {
  std::string out = fmt::format("{} failed ({}); log: {}", step.what, describe_status(status), log.string());
  std::ifstream in(log);
  std::string line;
  std::getline(in, line);  // the command
  for (int shown = 0; shown < 15 && std::getline(in, line); ++shown) out += "\n  " + line;
  return out;
}

// A step that failed; the message is made once its log has its final place.
struct StepFailed {
  Step step;
  int status;
};

// Runs the steps, up to `jobs` at a time; after a failure starts no more, waits
// for those running and throws the first failure (in the steps' order) as
// StepFailed. SIGINT or SIGTERM stops every running step's process group and
// throws Interrupted.
void run_steps(const std::vector<Step>& steps, size_t jobs) {
  std::vector<ChildCommand> commands;
  for (const Step& step : steps) {
    write_file_atomic(step.log, "$ " + joined(step.argv) + "\n");
    commands.push_back({step.argv, step.log});
  }
  const std::vector<std::optional<int>> status = run_children(commands, jobs, /*stop_at_failure=*/true);
  for (size_t i = 0; i < steps.size(); ++i)
    if (status[i] && !(WIFEXITED(*status[i]) && WEXITSTATUS(*status[i]) == 0)) throw StepFailed{steps[i], *status[i]};
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

// Work folders that a killed cdsim (SIGKILL: nothing ran to remove them)
// left: those of this entry at once (its lock is held, so no one builds it),
// those of other entries after a day.
void remove_leftovers(const fs::path& root, const fs::path& model_dir) {
  const auto day_ago = fs::file_time_type::clock::now() - std::chrono::hours(24);
  const std::string own = "tmp-" + model_dir.filename().string() + "-";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(root, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind("tmp-", 0) != 0) continue;
    if (name.rfind(own, 0) == 0 || entry.last_write_time(ec) < day_ago) fs::remove_all(entry.path(), ec);
  }
  if (fs::is_directory(model_dir, ec))
    for (const auto& entry : fs::directory_iterator(model_dir, ec))
      if (entry.path().filename().string().rfind("tmp-bench-", 0) == 0) fs::remove_all(entry.path(), ec);
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

// Verilator with the arguments sim/CMakeLists.txt gives verilate() (CDSIM_VERILATOR_ARGS).
// Verilator's -G overrides of the top's parameters.
std::vector<std::string> parameter_args(const std::vector<UnitParameter>& parameters) {
  std::vector<std::string> args;
  // The Has* parameters are `bit`s: a 32-bit constant would be a width warning.
  for (const UnitParameter& p : parameters)
    args.push_back(std::string(p.name).rfind("Has", 0) == 0 ? fmt::format("-G{}=1'b{}", p.name, p.value)
                                                            : fmt::format("-G{}={}", p.name, p.value));
  return args;
}

std::vector<std::string> verilator_command(const fs::path& verilated, const fs::path& header_dir,
                                           CoverageBuild coverage, bool adaptive,
                                           const std::vector<UnitParameter>& parameters) {
  std::vector<std::string> argv = {build::kVerilatorBin, "--compiler", build::kVerilatorCompiler,
                                   "--prefix", kPrefix, "--Mdir", verilated.string(),
                                   "--make", "cmake", "--top", top_of(adaptive), "--trace-fst", "--cc",
                                   "-y", header_dir.string(), "-y", kRtlDir};
  for (const std::string& a : strings(build::kVerilatorArgs)) argv.push_back(a);
  for (const std::string& s : sources_of(adaptive)) argv.push_back(s);
  for (const std::string& a : coverage_args(coverage)) argv.push_back(a);
  for (const std::string& a : parameter_args(parameters)) argv.push_back(a);
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

// Verilator's __Slow files (construction, the initial blocks, the trace's
// declarations: code run once) compile without optimisation, as Verilator's
// own makefile leaves OPT_SLOW empty: at the default widths 8 s of CPU instead
// of 23 s, 30% of a unit's build, for no loss of speed per cycle.
bool is_slow_source(const fs::path& source) {
  const std::string stem = source.stem().string();
  return stem.size() >= 6 && stem.compare(stem.size() - 6, 6, "__Slow") == 0;
}
std::vector<std::string> slow_flags(std::vector<std::string> flags) {
  flags.erase(std::remove_if(flags.begin(), flags.end(),
                             [](const std::string& f) { return f.rfind("-O", 0) == 0; }),
              flags.end());
  flags.push_back("-O0");
  return flags;
}

// What the model key covers besides the header and the RTL.
std::string model_recipe(CoverageBuild coverage, bool adaptive, const std::vector<UnitParameter>& parameters) {
  std::string recipe = fmt::format(
      "verilator: {} {} --prefix {} --top {} --trace-fst --cc {} {}\ncompiler: {} ({})\nflags: {}\n",
      build::kVerilatorBin, build::kVerilatorVersion, kPrefix, top_of(adaptive),
      joined(strings(build::kVerilatorArgs)), joined(sources_of(adaptive)),
      build::kCompiler, build::kCompilerVersion, joined(model_flags(coverage)));
  recipe += fmt::format("flags of __Slow files: {}\n", joined(slow_flags(model_flags(coverage))));
  if (coverage != CoverageBuild::None)
    recipe += fmt::format("coverage: {} {}\n", joined(coverage_args(coverage)),
                          hex(fnv1a(read_text_file(build::kCoverSource))));
  if (!parameters.empty()) recipe += fmt::format("parameters: {}\n", joined(parameter_args(parameters)));
  return recipe;
}

// The logs of a failed build, kept in <root>/failed-<key>/ (the build's own
// folder goes), and the failure with the log at its new place.
[[noreturn]] void fail_build(const StepFailed& failed, const fs::path& logs, const fs::path& kept) {
  std::error_code ec;
  fs::create_directories(kept, ec);
  for (const fs::path& log : files_in(logs, ".log")) fs::copy_file(log, kept / log.filename(), fs::copy_options::overwrite_existing, ec);
  const fs::path log = kept / failed.step.log.filename();
  throw std::runtime_error(failure_of(failed.step, failed.status, fs::exists(log) ? log : failed.step.log));
}

void build_model(const fs::path& root, const fs::path& model_dir, const std::string& header,
                 const std::string& inputs, CoverageBuild coverage, bool adaptive,
                 const std::vector<UnitParameter>& parameters) {
  const fs::path tmp = root / fmt::format("tmp-{}-{}", model_dir.filename().string(), getpid());
  const fs::path kept_logs = root / ("failed-" + model_dir.filename().string());
  RemoveOnExit remove_tmp(tmp);
  fs::remove_all(tmp);
  fs::create_directories(tmp / "log");
  fs::create_directories(tmp / "obj");
  write_file_atomic(tmp / "cd_widths.svh", header);
  write_file_atomic(tmp / "inputs.txt", inputs);
  const auto start = std::chrono::steady_clock::now();
  try {
    run_steps({{verilator_command(tmp / "verilated", tmp, coverage, adaptive, parameters), tmp / "log/verilator.log",
                "Verilator"}},
              1);
  } catch (const StepFailed& failed) {
    fail_build(failed, tmp / "log", kept_logs);
  }
  std::vector<Step> compiles;
  for (const fs::path& source : files_in(tmp / "verilated", ".cpp")) {
    const std::string name = source.stem().string();
    std::vector<std::string> argv = {build::kCompiler};
    for (const std::string& f : is_slow_source(source) ? slow_flags(model_flags(coverage)) : model_flags(coverage))
      argv.push_back(f);
    argv.insert(argv.end(), {"-I" + (tmp / "verilated").string(), "-c", source.string(), "-o",
                             (tmp / "obj" / (name + ".o")).string()});
    compiles.push_back(
        {argv, tmp / "log" / (name + ".log"), "compiling " + source.filename().string()});
  }
  const size_t jobs = parallel_jobs();
  std::cout << fmt::format("  verilated in {:.1f} s; compiling its {} files, {} at a time\n",
                           seconds_since(start), compiles.size(), jobs);
  std::cout.flush();
  try {
    run_steps(compiles, jobs);
  } catch (const StepFailed& failed) {
    fail_build(failed, tmp / "log", kept_logs);
  }
  // Last: a folder with a manifest is complete.
  std::vector<fs::path> files;
  for (const char* part : {"verilated", "obj"})
    for (const fs::path& f : files_under(tmp / part)) files.push_back(f);
  files.push_back(tmp / "cd_widths.svh");
  files.push_back(tmp / "inputs.txt");
  write_manifest(tmp / "manifest", tmp, files);
  std::error_code ec;
  fs::rename(tmp, model_dir, ec);
  if (ec)
    throw std::runtime_error(fmt::format("cannot rename {} to {}: {}", tmp.string(),
                                         model_dir.string(), ec.message()));
  remove_tmp.release();
  fs::remove_all(kept_logs, ec);
}

std::vector<std::string> bench_flags() {
  std::vector<std::string> flags = strings(build::kBenchFlags);
  flags.push_back("-I" + std::string(build::kBenchSources));
  return flags;
}

void build_bench(const fs::path& root, const fs::path& model_dir, const fs::path& library) {
  const fs::path tmp = model_dir / fmt::format("tmp-bench-{}", getpid());
  const fs::path kept_logs = root / ("failed-" + model_dir.filename().string());
  RemoveOnExit remove_tmp(tmp);
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
  // No -z defs: the SystemC kernel, the Verilator runtime and the model code
  // are undefined here on purpose and come from cdsim when it loads the object.
  std::vector<std::string> link = {build::kCompiler, "-shared"};
  for (const std::string& f : strings(build::kLinkFlags)) link.push_back(f);
  const fs::path built = tmp / library.filename();
  link.insert(link.end(), {"-o", built.string(), object.string()});
  for (const fs::path& o : files_in(model_dir / "obj", ".o")) link.push_back(o.string());
  try {
    run_steps({{compile, tmp / "bench.log", "compiling the bench (bench_entry.cpp)"}}, 1);
    run_steps({{link, tmp / "link.log", "linking the bench"}}, 1);
  } catch (const StepFailed& failed) {
    fail_build(failed, tmp, kept_logs);
  }
  // The manifest first: a library without one is never loaded.
  write_manifest(library.string() + ".manifest", tmp, {built});
  fs::rename(built, library);  // atomic
  // Benches of older cdsim builds, unused for a week.
  const auto week_ago = fs::file_time_type::clock::now() - std::chrono::hours(24 * 7);
  std::error_code ec;
  for (const fs::path& old : files_in(model_dir, ".so"))
    if (old != library && fs::last_write_time(old, ec) < week_ago) {
      fs::remove(old, ec);
      fs::remove(old.string() + ".manifest", ec);
    }
  fs::remove_all(kept_logs, ec);
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
  try {
    run_steps({{argv, log, what}}, 1);
  } catch (const StepFailed& failed) {
    throw std::runtime_error(failure_of(failed.step, failed.status, failed.step.log));
  }
}

RunBench load_custom_rtl(const Widths& widths, const std::string& cache_dir, CoverageBuild coverage,
                         bool adaptive, const std::vector<UnitParameter>& parameters) {
  const std::string header = adaptive ? rtl_header(adaptive_leaf_widths(widths), "custom, adaptive leaf unit")
                                      : rtl_header(widths, "custom");
  const fs::path root = fs::absolute(cache_dir.empty() ? default_rtl_cache_dir() : cache_dir);
  check_cache_folder(root, cache_dir.empty() ? "the RTL cache" : "--rtl-cache");

  std::string inputs = fmt::format("widths: {}\n{}", describe(widths), model_recipe(coverage, adaptive, parameters));
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

  CacheEntryLock lock(root / (hex(model_key) + ".lock"),
                      fmt::format("regress: the RTL for widths {} in {}", describe(widths), model_dir.string()));
  Timings timings = read_timings(root);
  const auto start = std::chrono::steady_clock::now();
  std::error_code ec;
  remove_leftovers(root, model_dir);
  bool bench_corrupt = false;
  if (fs::exists(library)) {
    if (const std::string wrong = verify_manifest(library.string() + ".manifest", model_dir); !wrong.empty()) {
      std::cout << fmt::format("regress: the cached bench {} is corrupt ({}); rebuilding it\n",
                               library.string(), wrong);
      fs::remove(library);
      fs::remove(library.string() + ".manifest", ec);
      bench_corrupt = true;
    }
  }
  // The model's files only matter to a bench still to be linked.
  if (fs::exists(model_dir) && !fs::exists(library)) {
    if (const std::string wrong = verify_manifest(model_dir / "manifest", model_dir); !wrong.empty()) {
      std::cout << fmt::format("regress: the cached RTL in {} is corrupt ({}); rebuilding it\n",
                               model_dir.string(), wrong);
      fs::remove_all(model_dir);
    }
  }
  if (!fs::exists(model_dir)) {
    std::cout << fmt::format(
        "regress: building the RTL{}{}{} for widths {} in {} (first use; about {:.0f} s)\n",
        adaptive ? " of the adaptive unit" : "",
        parameters.empty() ? "" : fmt::format(" of the unit with {}", joined(parameter_args(parameters))),
        coverage == CoverageBuild::All     ? " with coverage"
        : coverage == CoverageBuild::Lines ? " with line coverage"
                                           : "",
        describe(widths), model_dir.string(), timings.model + timings.bench);
    std::cout.flush();
    build_model(root, model_dir, header, inputs, coverage, adaptive, parameters);
    timings.model = seconds_since(start);
    const auto bench_start = std::chrono::steady_clock::now();
    build_bench(root, model_dir, library);
    timings.bench = seconds_since(bench_start);
    write_timings(root, timings);
    std::cout << fmt::format("regress: built in {:.0f} s\n", seconds_since(start));
  } else if (!fs::exists(library)) {
    std::cout << fmt::format(
        "regress: reusing the RTL verilated for these widths in {}; {} (about {:.0f} s)\n",
        model_dir.string(), bench_corrupt ? "relinking its bench" : "a new cdsim build needs its own bench",
        timings.bench);
    std::cout.flush();
    build_bench(root, model_dir, library);
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
