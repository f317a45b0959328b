// The command line, sweep files, output files and the interrupt flag
// (app/cli.cpp, cli_checks.cpp, sweep_file.cpp, support/cache_files.cpp,
// support/interrupt.cpp): bad input is refused naming the option and the value
// or the file and line; outputs are whole or absent; a folder takes one run
// at a time; a signal stops with 128 + its number.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "cache_files.hpp"
#include "child_process.hpp"
#include "cli.hpp"
#include "interrupt.hpp"
#include "regress.hpp"
#include "sweep_file.hpp"

namespace fs = std::filesystem;

namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Parses args as cdsim does.
void parse(cdsim::Cli& cli, std::vector<std::string> args) {
  args.insert(args.begin(), "cdsim");
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  cli.app.parse(int(argv.size()), argv.data());
}

// CLI11's message, or "" if the command line is accepted.
std::string parse_error(const std::vector<std::string>& args) {
  const std::unique_ptr<cdsim::Cli> cli = cdsim::make_cli();
  try {
    parse(*cli, args);
  } catch (const CLI::ParseError& e) {
    return e.what();
  }
  return "";
}

std::string sweep_file_error(const std::string& text) {
  std::istringstream in(text);
  try {
    cdsim::parse_sweep_file(in, "t.sweep");
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

std::string what_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("cdsim_cli_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

size_t files_in(const fs::path& dir) {
  size_t n = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST(CommandLine, RefusesNonFiniteNumbersNamingOptionAndValue) {
  EXPECT_PRED2(contains, parse_error({"size", "--max-error", "nan"}), "--max-error: 'nan' is not a finite number");
  EXPECT_PRED2(contains, parse_error({"size", "--max-error", "inf"}), "--max-error: 'inf' is not a finite number");
  EXPECT_PRED2(contains, parse_error({"regress", "--backpressure", "nan"}), "--backpressure: 'nan'");
  EXPECT_PRED2(contains, parse_error({"bench", "--seconds", "inf"}), "--seconds: 'inf'");
  EXPECT_PRED2(contains, parse_error({"size", "--max-error", "1e999"}), "--max-error: '1e999'");
  // Options declared outside app/ are made strict too (area, scene options).
  EXPECT_PRED2(contains, parse_error({"area", "--sram-cell-um2", "nan"}), "--sram-cell-um2: 'nan'");
}

TEST(CommandLine, RefusesZeroAndNegativeWhereTheyMeanNothing) {
  EXPECT_PRED2(contains, parse_error({"size", "--max-error", "0"}), "--max-error: 0 is out of range: must be > 0");
  EXPECT_PRED2(contains, parse_error({"size", "--max-error", "-1"}), "--max-error: -1 is out of range");
  EXPECT_PRED2(contains, parse_error({"regress", "--random", "0"}), "--random: 0 is out of range: must be in [1, 10000000]");
  EXPECT_PRED2(contains, parse_error({"regress", "--random", "-5"}), "--random: '-5' is negative");
  EXPECT_PRED2(contains, parse_error({"regress", "--only", "-1"}), "--only: -1 is out of range");
  EXPECT_PRED2(contains, parse_error({"sweep", "--jobs", "0"}), "--jobs: 0 is out of range");
  EXPECT_PRED2(contains, parse_error({"render", "--checker", "0"}), "--checker: 0 is out of range");
  EXPECT_PRED2(contains, parse_error({"bench", "--seconds", "0"}), "--seconds: 0 is out of range");
  EXPECT_PRED2(contains, parse_error({"size", "--max-error", "1", "--verify", "--verify-backpressure", "1"}),
               "--verify-backpressure: 1 is out of range: must be in [0, 0.95]");
}

TEST(CommandLine, SeedsAreAnyUint64AndNothingElse) {
  const std::unique_ptr<cdsim::Cli> cli = cdsim::make_cli();
  parse(*cli, {"regress", "--seed", "18446744073709551615"});
  EXPECT_EQ(cli->regress.seed, std::numeric_limits<uint64_t>::max());
  EXPECT_PRED2(contains, parse_error({"regress", "--seed", "18446744073709551616"}),
               "--seed: 18446744073709551616 is out of range: must be in [0, 18446744073709551615]");
  EXPECT_PRED2(contains, parse_error({"regress", "--seed", "-1"}), "--seed: '-1' is negative");
  EXPECT_PRED2(contains, parse_error({"regress", "--seed", "0x10"}), "--seed: '0x10' is not a decimal integer");
  EXPECT_PRED2(contains, parse_error({"regress", "--seed", "1e3"}), "--seed: '1e3' is not a decimal integer");
}

TEST(CommandLine, IntegersArePlainDecimal) {
  // strtol's base 0, which CLI11 uses, would read 010 as 8.
  EXPECT_PRED2(contains, parse_error({"render", "--checker", "010"}), "--checker: '010' is not a decimal integer");
  EXPECT_PRED2(contains, parse_error({"run", "--spawn", "0x1"}), "--spawn: '0x1' is not a decimal integer");
  EXPECT_PRED2(contains, parse_error({"run", "--spawn", " 5"}), "--spawn: ' 5' is not a decimal integer");
  EXPECT_EQ(parse_error({"render", "--checker", "10"}), "");
}

TEST(CommandLine, RefusesASingleValuedOptionGivenTwice) {
  EXPECT_PRED2(contains, parse_error({"run", "--json", "a.json", "--json", "b.json"}), "--json");
  EXPECT_PRED2(contains, parse_error({"run", "--worst", "--worst"}), "--worst");
  EXPECT_PRED2(contains, parse_error({"size", "--max-error", "1", "--max-error", "2"}), "--max-error");
  EXPECT_PRED2(contains, parse_error({"regress", "--seed", "1", "--seed", "2"}), "--seed");
  EXPECT_NE(parse_error({"sweep", "--out", "a", "--out", "b"}), "");
}

TEST(CommandLine, SetIsRepeatableButEachParameterOnce) {
  const std::unique_ptr<cdsim::Cli> cli = cdsim::make_cli();
  parse(*cli, {"run", "--set", "g_frac=8", "--set", "t_frac=10", "--set", "g_frac=12"});
  ASSERT_EQ(cli->run.settings.size(), 3u);
  EXPECT_PRED2(contains, what_of([&] { cdsim::widths_from(cli->run); }),
               "--set g_frac=8 and --set g_frac=12 both set parameter g_frac");
  EXPECT_PRED2(contains, what_of([] { cdsim::designs_from("cd-linear,divide,cd-linear"); }),
               "design 'cd-linear' is listed twice");
}

TEST(CommandLine, DesignAllIsEveryDesign) {
  std::vector<std::string> names;
  for (const cdsim::Design& d : cdsim::designs_from("all")) names.push_back(d.name);
  std::vector<std::string> every;
  for (const cdsim::Design& d : cdsim::all_designs()) every.push_back(d.name);
  EXPECT_EQ(names, every);
  EXPECT_GE(names.size(), 16u);
  EXPECT_PRED2(contains, what_of([] { cdsim::designs_from("all,divide"); }), "all");
}

TEST(CommandLine, RefusesOptionsThatWouldBeIgnored) {
  EXPECT_PRED2(contains, parse_error({"regress", "--random", "5", "--scene", "hard:all"}), "excludes --random");
  EXPECT_PRED2(contains, parse_error({"size", "--max-error", "1", "--verify-random", "5"}),
               "--verify-random requires --verify");
  EXPECT_PRED2(contains, parse_error({"run", "--json", ""}), "--json: the value is empty");
}

TEST(CommandLine, AcceptsWhatTheReadmeShows) {
  EXPECT_EQ(parse_error({}), "");
  EXPECT_EQ(parse_error({"regress", "--random", "10000", "--seed", "1", "--backpressure", "0.5"}), "");
  EXPECT_EQ(parse_error({"size", "--max-error", "0.2", "--statistic", "p99", "--design", "cd-linear"}), "");
  EXPECT_EQ(parse_error({"sweep", "--set", "g_frac=8:12:2", "--set", "kim_frac=2,6", "--jobs", "2", "--yes"}), "");
  EXPECT_EQ(parse_error({"bench", "--seconds", "0.01"}), "");
}

TEST(SweepFile, AcceptsAByteOrderMarkAndWindowsLineEnds) {
  std::istringstream in("\xEF\xBB\xBFg_frac=8:12:2\r\ndesign cd-linear\r\n");
  const cdsim::SweepFile file = cdsim::parse_sweep_file(in, "t.sweep");
  ASSERT_EQ(file.axes.size(), 1u);
  EXPECT_EQ(file.axes[0].name, "g_frac");
  EXPECT_EQ(file.axes[0].values, (std::vector<int>{8, 10, 12}));
  EXPECT_EQ(file.designs, "cd-linear");
  EXPECT_EQ(file.design_line, 2);
}

TEST(SweepFile, RefusesAParameterOrDesignLineTwiceNamingBothLines) {
  EXPECT_EQ(sweep_file_error("g_frac=8\n# c\ns_frac=10\ng_frac=12\n"),
            "t.sweep:4: parameter g_frac is swept twice (first at line 1)");
  EXPECT_EQ(sweep_file_error("design cd-linear\ng_frac=8\ndesign divide\n"),
            "t.sweep:3: a second 'design' line (the first is line 1)");
  EXPECT_PRED2(contains, sweep_file_error("g_frac=8,10,8\n"), "t.sweep:1: ");
  EXPECT_PRED2(contains, sweep_file_error("g_frac=8,10,8\n"), "the value 8 is listed twice");
}

TEST(SweepFile, NumbersAreStrictAndRangesCheckedBeforeExpanding) {
  EXPECT_PRED2(contains, sweep_file_error("\n\ng_frac=8:1e1\n"), "t.sweep:3: ");
  EXPECT_PRED2(contains, sweep_file_error("g_frac=8:1e1\n"), "'1e1' is not an integer");
  EXPECT_PRED2(contains, sweep_file_error("g_frac=+8\n"), "'+8' is not an integer");
  EXPECT_PRED2(contains, sweep_file_error("g_frac=0x8\n"), "'0x8' is not an integer");
  EXPECT_PRED2(contains, sweep_file_error("g_frac=8:99999999999\n"), "99999999999 is out of range");
  // A huge range is refused by its ends, not expanded first.
  EXPECT_PRED2(contains, sweep_file_error("g_frac=2:2147483647\n"), "g_frac=2147483647 is out of range [2, 30]");
  EXPECT_PRED2(contains, sweep_file_error("g_frac=12:8\n"), "t.sweep:1: sweep setting 'g_frac=12:8': HI is below LO");
  EXPECT_PRED2(contains, sweep_file_error("g_frac=8:12:0\n"), "STEP must be positive");
  EXPECT_PRED2(contains, sweep_file_error("design cd-cubic\n"), "t.sweep:1: unknown design 'cd-cubic'");
  EXPECT_PRED2(contains, sweep_file_error("# only a comment\n"), "t.sweep:1: no parameter and no 'design' line");
  EXPECT_PRED2(contains, sweep_file_error("g_frac\n"), "t.sweep:1: ");
}

TEST(SweepFile, SizeSaturatesInsteadOfOverflowing) {
  std::vector<cdsim::SweepAxis> axes(20, cdsim::SweepAxis{"g_frac", std::vector<int>(29, 8)});
  EXPECT_EQ(cdsim::sweep_size(11, axes), std::numeric_limits<uint64_t>::max());
  EXPECT_EQ(cdsim::sweep_size(11, {axes[0], axes[1]}), 11u * 29 * 29);
}

TEST(OutputFiles, AtomicWriteReplacesWholeAndLeavesNoTemporary) {
  const fs::path dir = fresh_folder("atomic");
  cdsim::write_file_atomic(dir / "a.txt", "old\n");
  cdsim::write_file_atomic(dir / "a.txt", "new\n");
  EXPECT_EQ(cdsim::read_text_file(dir / "a.txt"), "new\n");
  EXPECT_EQ(files_in(dir), 1u);
  fs::remove_all(dir);
}

TEST(OutputFiles, FailedWritesNameThePathAndTheReason) {
  const fs::path dir = fresh_folder("fail");
  EXPECT_PRED2(contains, what_of([&] { cdsim::write_file_atomic(dir / "missing" / "a.txt", "x"); }),
               (dir / "missing").string() + " does not exist");
  EXPECT_PRED2(contains, what_of([] { cdsim::write_file_atomic("/dev/full", "x"); }),
               "/dev/full: cannot write: No space left on device");
  EXPECT_PRED2(contains, what_of([&] { cdsim::write_file_atomic(dir, "x"); }), "Is a directory");
  EXPECT_EQ(files_in(dir), 0u);
  fs::remove_all(dir);
}

TEST(OutputFiles, SeveralFilesAreAllWrittenOrNoneChanged) {
  const fs::path dir = fresh_folder("several");
  cdsim::write_file_atomic(dir / "sweep.csv", "old csv\n");
  EXPECT_NE(what_of([&] {
              cdsim::write_files_atomic({{dir / "sweep.csv", "new csv\n"}, {dir / "no" / "sweep.json", "{}"}});
            }),
            "");
  EXPECT_EQ(cdsim::read_text_file(dir / "sweep.csv"), "old csv\n");
  EXPECT_EQ(files_in(dir), 1u);  // no temporary left behind
  fs::remove_all(dir);
}

TEST(OutputFiles, AFolderTakesOneRunAtATime) {
  const fs::path dir = fresh_folder("lock");
  {
    const cdsim::OutputFolderLock first(dir);
    EXPECT_PRED2(contains, what_of([&] { cdsim::OutputFolderLock second(dir); }),
                 dir.string() + ": another cdsim run is writing into this folder");
  }
  EXPECT_EQ(what_of([&] { cdsim::OutputFolderLock again(dir); }), "");
  fs::remove_all(dir);
}

TEST(Interrupt, SigintSetsTheFlagAndThrowsWithStatus130) {
  EXPECT_EXIT(
      {
        cdsim::install_interrupt_handlers();
        const bool before = cdsim::interrupted();
        std::raise(SIGINT);
        int status = 0;
        try {
          cdsim::throw_if_interrupted();
        } catch (const cdsim::Interrupted& e) {
          status = e.exit_status();
        }
        std::exit(!before && cdsim::interrupted() && status == 130 ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

TEST(Interrupt, ASecondSignalKillsAtOnce) {
  EXPECT_EXIT(
      {
        cdsim::install_interrupt_handlers();
        std::raise(SIGTERM);
        std::raise(SIGTERM);
        std::exit(0);
      },
      ::testing::KilledBySignal(SIGTERM), "");
}

TEST(RegressHangLimit, ScalesWithTheModelsCyclesAndTheBackPressure) {
  EXPECT_EQ(cdsim::rtl::hang_cycle_limit(100, 10, 0.0), 4 * 100 + 1000);
  // 720,000 pixels at p = 0.95 stall about 13.7 M cycles: the limit is well above.
  const int64_t cycles = 800'000, pixels = 720'000;
  const double mean = double(cycles) + double(pixels) * 0.95 / 0.05;
  EXPECT_GT(double(cdsim::rtl::hang_cycle_limit(cycles, pixels, 0.95)), 3 * mean);
  EXPECT_GT(cdsim::rtl::hang_cycle_limit(2 * cycles, 2 * pixels, 0.5),
            cdsim::rtl::hang_cycle_limit(cycles, pixels, 0.5));
}

// Outputs never name an input or each other, however the path is spelled.
TEST(OutputFiles, AnOutputThatIsAnInputOrAnotherOutputIsRefused) {
  const fs::path dir = fresh_folder("distinct");
  cdsim::write_file_atomic(dir / "scene.tri", "x\n");
  fs::create_symlink(dir / "scene.tri", dir / "link.tri");
  fs::create_hard_link(dir / "scene.tri", dir / "hard.tri");
  const std::vector<cdsim::NamedFile> scene = {{"--scene", dir / "scene.tri"}};
  for (const fs::path& out : {dir / "scene.tri", dir / "link.tri", dir / "hard.tri", dir / "." / "scene.tri"})
    EXPECT_PRED2(contains, what_of([&] { cdsim::check_distinct_files({{"--json", out}}, scene); }),
                 "is the input --scene " + (dir / "scene.tri").string())
        << out;
  // Two outputs, neither there yet, spelled differently.
  EXPECT_PRED2(contains,
               what_of([&] { cdsim::check_distinct_files({{"--json", dir / "r.json"}, {"--dump", dir / "sub" / ".." / "r.json"}}, {}); }),
               "both name one file");
  fs::create_directory(dir / "sub");
  EXPECT_PRED2(contains,
               what_of([&] { cdsim::check_distinct_files({{"--json", dir / "r.json"}, {"--dump", dir / "sub" / ".." / "r.json"}}, {}); }),
               "both name one file");
  EXPECT_EQ(what_of([&] { cdsim::check_distinct_files({{"--json", dir / "r.json"}, {"--dump", dir / "r.csv"}}, scene); }), "");
  // Devices replace nothing: /dev/null may take every output.
  EXPECT_EQ(what_of([] { cdsim::check_distinct_files({{"--json", "/dev/null"}, {"--dump", "/dev/null"}}, {}); }), "");
  fs::remove_all(dir);
}

// --trace: the FST library seeks and renames, so a device or a pipe is refused
// before the run, never replaced by a regular file.
TEST(OutputFiles, AWaveformIsRefusedADeviceOrAPipe) {
  const fs::path dir = fresh_folder("trace");
  EXPECT_PRED2(contains, what_of([] { cdsim::check_regular_output("--trace", "/dev/null"); }),
               "--trace /dev/null: is a character device");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
  EXPECT_PRED2(contains, what_of([&] { cdsim::check_regular_output("--trace", dir / "fifo"); }), "is a pipe");
  EXPECT_EQ(what_of([&] { cdsim::check_regular_output("--trace", dir / "new.fst"); }), "");
  const fs::path temporary = cdsim::temporary_beside(dir / "w.fst");
  EXPECT_EQ(temporary.parent_path(), dir);
  cdsim::write_file_atomic(temporary, "fst");
  cdsim::publish_file(temporary, dir / "w.fst");
  EXPECT_EQ(cdsim::read_text_file(dir / "w.fst"), "fst");
  EXPECT_FALSE(fs::exists(temporary));
  fs::remove_all(dir);
}

// A cache folder is this user's alone: created 0700, refused when others can write it.
TEST(CacheFiles, ACacheFolderIsCreatedPrivateAndCheckedBeforeUse) {
  const fs::path dir = fresh_folder("cache");
  cdsim::check_cache_folder(dir / "a" / "rtl", "--rtl-cache");
  EXPECT_EQ(fs::status(dir / "a").permissions() & fs::perms::all, fs::perms::owner_all);
  EXPECT_EQ(fs::status(dir / "a" / "rtl").permissions() & fs::perms::all, fs::perms::owner_all);
  fs::permissions(dir / "a" / "rtl", fs::perms::all);
  EXPECT_PRED2(contains, what_of([&] { cdsim::check_cache_folder(dir / "a" / "rtl", "--rtl-cache"); }),
               "is writable by every user (mode 0777)");
  fs::permissions(dir / "a" / "rtl", fs::perms::owner_all | fs::perms::group_all);
  EXPECT_PRED2(contains, what_of([&] { cdsim::check_cache_folder(dir / "a" / "rtl", "--rtl-cache"); }),
               "is writable by its group");
  if (::geteuid() == 0) {  // only root can give a folder away
    fs::create_directory(dir / "theirs");
    ASSERT_EQ(::chown((dir / "theirs").c_str(), 65534, 65534), 0);
    fs::permissions(dir / "theirs", fs::perms::owner_all);
    EXPECT_PRED2(contains, what_of([&] { cdsim::check_cache_folder(dir / "theirs", "--cache"); }),
                 "belongs to user 65534");
  }
  cdsim::write_file_atomic(dir / "file", "x");
  EXPECT_PRED2(contains, what_of([&] { cdsim::check_cache_folder(dir / "file", "--cache"); }), "is not a folder");
  fs::remove_all(dir);
}

// Without XDG_CACHE_HOME and HOME: the home folder of the password database,
// never a folder of /tmp that another user may own.
TEST(CacheFiles, TheCacheRootIsPerUserWithoutHome) {
  EXPECT_EXIT(
      {
        ::unsetenv("XDG_CACHE_HOME");
        ::unsetenv("HOME");
        const std::string root = cdsim::cache_root("rtl").string();
        const bool in_tmp = root.rfind(fs::temp_directory_path().string(), 0) == 0;
        std::exit(!in_tmp && contains(root, "/.cache/cdsim/rtl") ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
}

// A file that a full disk truncated, or anything changed, fails its manifest.
TEST(CacheFiles, TheManifestCatchesATruncatedOrChangedFile) {
  const fs::path dir = fresh_folder("manifest");
  cdsim::write_file_atomic(dir / "bench.so", std::string(5000, 'x'));
  cdsim::write_manifest(dir / "manifest", dir, {dir / "bench.so"});
  EXPECT_EQ(cdsim::verify_manifest(dir / "manifest", dir), "");
  fs::resize_file(dir / "bench.so", 1000);
  EXPECT_EQ(cdsim::verify_manifest(dir / "manifest", dir), "bench.so: 1000 bytes, 5000 when built");
  cdsim::write_file_atomic(dir / "bench.so", std::string(4999, 'x') + "y");
  EXPECT_PRED2(contains, cdsim::verify_manifest(dir / "manifest", dir), "bench.so: its content changed");
  fs::remove(dir / "bench.so");
  EXPECT_EQ(cdsim::verify_manifest(dir / "manifest", dir), "bench.so: missing");
  EXPECT_EQ(cdsim::verify_manifest(dir / "none", dir), "none: missing");
  fs::remove_all(dir);
}

// Two cdsim that want one cache entry: the second waits for the first.
TEST(CacheFiles, TheEntryLockMakesASecondBuilderWait) {
  const fs::path dir = fresh_folder("lock");
  auto first = std::make_unique<cdsim::CacheEntryLock>(dir / "e.lock", "entry");
  const int fd = ::open((dir / "e.lock").c_str(), O_RDWR);
  EXPECT_NE(::flock(fd, LOCK_EX | LOCK_NB), 0);
  first.reset();
  EXPECT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
  ::close(fd);
  fs::remove_all(dir);
}

// What a tool started (a shell's children here) goes with it; so does the
// tool when the cdsim that started it dies at once.
// A sleep with a duration of this test process's own, to find it by.
std::string unique_sleep() { return "sleep " + std::to_string(100000 + ::getpid()); }
bool sleep_left(const std::string& sleep) {
  for (int i = 0; i < 100; ++i) {
    if (std::system(("pgrep -fx '" + sleep + "' >/dev/null").c_str()) != 0) return false;
    ::usleep(20000);
  }
  return true;
}

TEST(ChildProcess, StopEndsTheToolAndEverythingItStarted) {
  const fs::path dir = fresh_folder("child");
  const fs::path marker = dir / "started";
  const std::string sleep = unique_sleep();
  cdsim::ChildProcess child({"sh", "-c", sleep + " & " + sleep + " & touch " + marker.string() + "; wait"},
                            dir / "log");
  for (int i = 0; i < 500 && !fs::exists(marker); ++i) ::usleep(10000);
  ASSERT_TRUE(fs::exists(marker));
  child.stop();
  EXPECT_FALSE(sleep_left(sleep)) << sleep << " outlived stop()";
  fs::remove_all(dir);
}

// run_children: every status in the commands' order; after a failure either
// none starts (the RTL cache's build steps) or all run (the sharded check).
TEST(ChildProcess, RunChildrenGivesEveryStatusOrStopsAtAFailure) {
  const fs::path dir = fresh_folder("children");
  const std::vector<cdsim::ChildCommand> commands = {{{"sh", "-c", "exit 0"}, dir / "0.log"},
                                                     {{"sh", "-c", "echo two; exit 3"}, dir / "1.log"},
                                                     {{"sh", "-c", "sleep 0.3; touch " + (dir / "ran").string()},
                                                      dir / "2.log"}};
  const auto stopped = cdsim::run_children(commands, 1, /*stop_at_failure=*/true);
  ASSERT_EQ(stopped.size(), 3u);
  ASSERT_TRUE(stopped[0] && stopped[1]);
  EXPECT_TRUE(WIFEXITED(*stopped[0]) && WEXITSTATUS(*stopped[0]) == 0);
  EXPECT_TRUE(WIFEXITED(*stopped[1]) && WEXITSTATUS(*stopped[1]) == 3);
  EXPECT_FALSE(stopped[2]) << "a command started after a failure";
  EXPECT_FALSE(fs::exists(dir / "ran"));
  EXPECT_EQ(cdsim::read_text_file(dir / "1.log"), "two\n");
  size_t calls = 0, most_done = 0;
  const auto all = cdsim::run_children(commands, 2, /*stop_at_failure=*/false, [&](double seconds, size_t done) {
    EXPECT_GE(seconds, 0.0);
    ++calls;
    most_done = std::max(most_done, done);
  });
  ASSERT_TRUE(all[0] && all[1] && all[2]);
  EXPECT_TRUE(WIFEXITED(*all[2]) && WEXITSTATUS(*all[2]) == 0);
  EXPECT_TRUE(fs::exists(dir / "ran"));
  EXPECT_GT(calls, 0u) << "no progress call while the 0.3 s command ran";
  EXPECT_GE(most_done, 2u);
  fs::remove_all(dir);
}

TEST(ChildProcess, AToolDiesWithTheProcessThatStartedIt) {
  const fs::path dir = fresh_folder("orphan");
  const std::string sleep = unique_sleep();
  const pid_t parent = ::fork();
  if (parent == 0) {
    cdsim::ChildProcess child({"sh", "-c", sleep + " & wait"}, dir / "log");
    ::usleep(300000);
    _exit(0);  // no destructor runs: as after SIGKILL
  }
  int status = 0;
  ::waitpid(parent, &status, 0);
  EXPECT_FALSE(sleep_left(sleep)) << sleep << " outlived the process that started it";
  fs::remove_all(dir);
}
