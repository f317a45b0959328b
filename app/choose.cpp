#include "choose.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <limits>
#include <optional>
#include <stdexcept>
#include <thread>

#include "area.hpp"
#include "cache_files.hpp"
#include "cli_checks.hpp"
#include "common.hpp"
#include "interrupt.hpp"
#include "progress.hpp"
#include "regress.hpp"
#include "report.hpp"
#include "size.hpp"

namespace cdsim {

namespace {

// One design's answer.
struct Candidate {
  Design design;
  bool meets = false;
  Widths widths;
  double error = 0;          // the worst scene's measure
  int64_t cycles = 0;        // summed over the scenes
  int64_t pixels = 0;
  int64_t unbanded_cycles = 0;  // with a table deep enough for every band (table designs)
  std::optional<AreaReport> area;
  std::string table;         // "sram", "flops" or "" (no table)
  double total_area_um2 = 0;  // logic + the cheaper table
  std::string rtl_verified = "not run";  // "yes", "no", "not run", "no RTL"
  double min_px_per_clk = 0;    // the slowest scene's
  std::string slowest_scene;
  bool meets_rate = true;       // min_px_per_clk >= --min-rate
  bool meets_clock = true;      // f_max >= --clock-mhz (known once synthesised)
};

int64_t total(const std::vector<DesignResult>& results, int64_t DesignResult::*field) {
  int64_t sum = 0;
  for (const DesignResult& r : results) sum += r.*field;
  return sum;
}

// The widths sizing chose, as NAME=VALUE for the ones the design's accuracy
// or table depends on, and any the user set.
std::string sized_widths(const Candidate& c) {
  const Widths defaults;
  std::string out;
  for (const auto& p : param_table()) {
    const int value = c.widths.*(p.field);
    if (value == defaults.*(p.field)) continue;
    out += fmt::format("{}{}={}", out.empty() ? "" : " ", p.name, value);
  }
  return out.empty() ? "defaults" : out;
}

nlohmann::json widths_json(const Widths& w) {
  nlohmann::json out;
  for (const auto& p : param_table()) out[p.name] = w.*(p.field);
  return out;
}

// "correction_stages=2", the parameters in which two widths differ.
std::string pipeline_settings(const Widths& to, const Widths& from) {
  std::string out;
  for (const auto& p : param_table())
    if (to.*(p.field) != from.*(p.field)) out += fmt::format("{}{}={}", out.empty() ? "" : " ", p.name, to.*(p.field));
  return out;
}

}  // namespace

CLI::App* add_choose_command(CLI::App& app, ChooseOptions& options) {
  CLI::App* cmd = app.add_subcommand(
      "choose", "the cheapest design for an accuracy target: size, synthesise and rank every design");
  cmd->add_option("scenes", options.scenes,
                  "scenes the target must hold on, each as for --scene (default: the embedded scene)");
  cmd->add_option("--camera", options.scene_options.camera, "as for run, applied to every scene");
  cmd->add_option("--spawn", options.scene_options.spawn, "as for run, applied to every scene")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--resolution", options.scene_options.resolution, "WxH viewport, every scene");
  cmd->add_option("--design", options.designs, "comma-separated designs, or all (the default)");
  cmd->add_option("--set", options.settings,
                  "NAME=VALUE: a width sizing keeps (the output format, subpixel and input bits, "
                  "latencies); repeatable");
  cmd->add_option("--max-error", options.max_error, "error target, > 0 (texels, or footprint-normalised)")
      ->required()
      ->check(cli::number_in(0, std::numeric_limits<double>::infinity(), true));
  cmd->add_option("--metric", options.metric, "texels, or footprint (error / max(1, rho))")
      ->check(CLI::IsMember({"texels", "footprint"}))
      ->capture_default_str();
  cmd->add_option("--statistic", options.statistic, "which per-pixel statistic must meet it")
      ->check(CLI::IsMember({"max", "p99", "mean"}))
      ->capture_default_str();
  cmd->add_option("--max-slowdown", options.max_slowdown,
                  "a setup engine of fewer shared multipliers (1, 2, 4, 8), then a smaller table that "
                  "bands and refills, is taken while the cycles stay within this factor of the fully "
                  "parallel setup engine's with an unbanded table (a --set setup_multipliers stays)")
      ->check(cli::number_in(1.0, 1000.0))
      ->capture_default_str();
  cmd->add_option("--min-rate", options.min_rate,
                  "px/clk every scene must reach (0: none, the area-only ranking); a smaller setup engine or "
                  "table is taken only while it keeps the rate")
      ->check(cli::number_in(0.0, 1000.0))
      ->capture_default_str();
  cmd->add_option("--clock-mhz", options.clock_mhz,
                  "the clock the synthesised unit must reach: f_max by OpenSTA (0: none)")
      ->check(cli::number_in(0.0, 100000.0))
      ->capture_default_str();
  cmd->add_option("--pipeline-steps", options.pipeline_steps,
                  "pipelining steps a design below --clock-mhz may take, each one synthesis more (0: none)")
      ->check(CLI::Range(0u, 16u))
      ->capture_default_str();
  cmd->add_option("--json", options.json_path, "also write the ranking as JSON to this file");
  cmd->add_flag("!--no-verify", options.verify, "do not regress the winner on the RTL");
  cmd->add_option("--verify-random", options.verify_random,
                  "random triangles the winner's RTL check adds after the scenes")
      ->check(cli::unsigned_in(0, 10'000'000))
      ->capture_default_str();
  cmd->add_option("--verify-backpressure", options.verify_backpressure,
                  "probability that the fragment sink stalls a cycle in the RTL check")
      ->check(cli::number_in(0.0, 0.95))
      ->capture_default_str();
  cmd->add_option("--rtl-cache", options.rtl_cache, "folder of verilated units (as cdsim regress)");
  cmd->add_option("--area-cache", options.area_cache, "folder of synthesis results (as cdsim area --cache)");
  add_area_flow_option(cmd, options.area_flow);
  cmd->add_option("--jobs", options.jobs, "designs sized and configurations synthesised at a time (default: all cores)")
      ->check(CLI::Range(1u, 256u));
  return cmd;
}

std::optional<Widths> deeper_pipeline(const Design& design, const Widths& w, const std::string& block,
                                      const std::vector<std::string>& settings, const std::string& path_end) {
  const auto user_sets = [&](const char* name) {
    return std::any_of(settings.begin(), settings.end(),
                       [&](const std::string& s) { return s.rfind(std::string(name) + "=", 0) == 0; });
  };
  Widths next = w;
  if ((block == "correction adder" || block == "control") && design.kind == Design::Kind::ConstantDepth) {
    const int most = design.persp ? 2 : 1;
    if (w.correction_stages >= most || user_sets("correction_stages")) return std::nullopt;
    next.correction_stages = most;
  } else if (block == "scanline table" && design.kind == Design::Kind::ConstantDepth) {
    // The paths into the table: the fill's products and their rounding; a
    // register between them (a cycle more a band's fill).
    if (w.fill_product_register || user_sets("fill_product_register")) return std::nullopt;
    next.fill_product_register = 1;
  } else if (block == "reciprocal") {
    // Each stage resolves ceil((recip_bits + 1) / recip_latency) quotient
    // bits (rtl/reciprocal.sv): at recip_bits + 1 stages (at most 33, within
    // recip_latency's 64) one bit each, and more would be registers that cut
    // nothing.
    const int one_bit_a_stage = w.recip_bits + 1;
    if (w.recip_latency >= one_bit_a_stage || user_sets("recip_latency")) return std::nullopt;
    next.recip_latency = std::min(one_bit_a_stage, 2 * w.recip_latency);
  } else if (block == "setup engine" && path_end.find("u_multipliers/") != std::string::npos) {
    // Into the multipliers' own registers (shared multipliers' accumulators,
    // or the sums with setup_product_register): a multiply itself, which no
    // knob cuts.
    return std::nullopt;
  } else if (block == "setup engine" && path_end.find("_divider/") == std::string::npos) {
    // A stage's multiply-add and what follows it (the serial dividers are
    // instances named u_*_divider, rtl/setup_dividers.sv): first a register
    // after each stage's sums of products, a cycle a stage (shared
    // multipliers have it already); then stage D's line range, which bounds
    // the engine once its sums are registered (docs/area.md), a cycle of its
    // own.
    const bool product_step = w.setup_multipliers == 0 && !w.setup_product_register;
    if (product_step && !user_sets("setup_product_register")) {
      next.setup_product_register = 1;
    } else {
      if (w.setup_line_register || user_sets("setup_line_register")) return std::nullopt;
      next.setup_line_register = 1;
    }
  } else if (block == "setup engine" || block == "affine setup") {
    // Serial dividers (the affine setup's, or the setup engine's when the
    // path ends in one) resolve their quotient bits over div_cycles, which
    // div_bits_per_cycle sets: half as many bits a cycle, a shorter path
    // (affine at default widths 4 -> 2: 21.35 -> 17.29 ns, docs/choose.md).
    if (w.div_bits_per_cycle <= 1 || user_sets("div_bits_per_cycle")) return std::nullopt;
    next.div_bits_per_cycle = w.div_bits_per_cycle / 2;
  } else {
    return std::nullopt;
  }
  try {
    validate(next);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  return next;
}

PipeliningVerdict pipelining_verdict(double kept_fmax_mhz, double stepped_fmax_mhz, bool on_trial) {
  if (stepped_fmax_mhz > kept_fmax_mhz) return PipeliningVerdict::Keep;
  return on_trial ? PipeliningVerdict::Stop : PipeliningVerdict::Trial;
}

int run_choose_command(const ChooseOptions& options) {
  if (options.metric == "footprint" && options.statistic != "max")
    throw std::invalid_argument("the footprint metric is kept as a maximum only: use --statistic max");
  Widths user;
  apply_settings(user, options.settings);
  validate(user);
  const std::vector<Design> designs = options.designs.empty() ? all_designs() : designs_from(options.designs);
  if (!options.json_path.empty()) check_output_folder("--json", options.json_path);
  const std::vector<std::string> scene_names =
      options.scenes.empty() ? std::vector<std::string>{"default"} : options.scenes;
  std::vector<NamedFile> inputs;
  for (const std::string& name : scene_names) inputs.push_back({"SCENE", scene_input_file(name)});
  check_distinct_files({{"--json", options.json_path}}, inputs);
  std::vector<PreparedScene> scenes;
  for (const std::string& name : scene_names)
    scenes.push_back(prepare(load_scene(name, options.scene_options), user));
  std::vector<const PreparedScene*> scene_list;
  for (const PreparedScene& s : scenes) scene_list.push_back(&s);

  const ErrorTarget target{options.max_error, options.metric, options.statistic};
  // A setup engine the user names (--set setup_multipliers=M, 0 included, or
  // setup_product_register) is kept.
  const bool user_sets_setup = std::any_of(options.settings.begin(), options.settings.end(), [](const std::string& s) {
    return s.rfind("setup_multipliers=", 0) == 0 || s.rfind("setup_product_register=", 0) == 0;
  });
  fmt::print("choose: the cheapest design with {} {} error <= {} on every scene{}{}\n", options.statistic,
             options.metric, options.max_error,
             options.min_rate > 0 ? fmt::format(", {:g} px/clk or more on every scene", options.min_rate) : "",
             options.clock_mhz > 0 ? fmt::format(", f_max {:g} MHz or more", options.clock_mhz) : "");
  for (const PreparedScene& s : scenes)
    fmt::print("scene: {} ({} triangles, {}x{}; {})\n", s.scene.name, s.scene.triangles.size(),
               s.scene.width, s.scene.height, s.scene.description);
  fmt::print("fixed widths: {}\nbuild: {}\nsynthesis flow: {}\nseed: none (deterministic); RTL check seed 1\n\n",
             options.settings.empty() ? "defaults" : describe(user), build_id(), options.area_flow);
  std::fflush(stdout);

  // A candidate's cycles, pixels and slowest scene, from its results per scene.
  const auto take_rates = [&](Candidate& c, const std::vector<DesignResult>& results) {
    c.cycles = total(results, &DesignResult::cycles);
    c.pixels = total(results, &DesignResult::pixels);
    c.min_px_per_clk = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < results.size(); ++i)
      if (results[i].pixels_per_clock() < c.min_px_per_clk) {
        c.min_px_per_clk = results[i].pixels_per_clock();
        c.slowest_scene = scenes[i].scene.name;
      }
    c.meets_rate = c.min_px_per_clk >= options.min_rate;
  };
  const auto take_area = [&](Candidate& c, const AreaReport& area) {
    c.area = area;
    c.meets_clock = c.area->fmax_mhz >= options.clock_mhz;
    c.total_area_um2 = c.area->logic_area_um2;
    c.table.clear();
    if (c.area->sram_bits > 0) {
      const bool flops = c.area->flop_table_area_um2 < c.area->sram_area_um2;
      c.table = flops ? "flops" : "sram";
      c.total_area_um2 += flops ? c.area->flop_table_area_um2 : c.area->sram_area_um2;
    }
  };

  // Size every design; for a table design, shrink the table while banding
  // keeps the cycles within the budget (shrink_table). The designs are sized
  // independently, `--jobs` at a time.
  std::vector<Candidate> candidates(designs.size());
  std::vector<double> seconds(designs.size());
  std::vector<int> evaluations(designs.size());
  // Each design's error measurement may take every core too: at the end,
  // when fewer designs than cores are left, the last ones use them all.
  const unsigned threads = options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  run_parallel(designs.size(), options.jobs, "choose", "designs sized", [&](size_t k) {
    const Design& d = designs[k];
    const auto start = std::chrono::steady_clock::now();
    Candidate& c = candidates[k];
    c.design = d;
    Sizing sizing = size_design(d, scene_list, user, target, {}, threads);
    // One budget for both: the cycles of the fully parallel setup engine (or
    // the user's) and the unbanded table, times --max-slowdown.
    c.unbanded_cycles = total(sizing.results, &DesignResult::cycles);
    if (!user_sets_setup)
      shrink_setup(d, scene_list, target, options.max_slowdown, c.unbanded_cycles, sizing, options.min_rate, threads);
    shrink_table(d, scene_list, target, options.max_slowdown, c.unbanded_cycles, sizing, options.min_rate, threads);
    c.meets = sizing.reachable && sizing.error <= target.max_error;
    c.widths = sizing.widths;
    c.error = sizing.error;
    take_rates(c, sizing.results);
    seconds[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    evaluations[k] = sizing.evaluations;
  }, ProgressShown::Always);
  for (size_t k = 0; k < designs.size(); ++k)
    fmt::print(stderr, "choose: {} {} in {:.1f} s ({} model runs)\n", designs[k].name,
               candidates[k].meets ? "sized" : "cannot meet the target", seconds[k], evaluations[k]);

  // Synthesise every design that meets the target and has RTL.
  AreaOptions area_options;
  area_options.cache_dir = options.area_cache;
  area_options.flow = options.area_flow;
  std::vector<AreaJob> jobs;
  // A design below the rate is not synthesised: no area makes it fast enough.
  for (const Candidate& c : candidates)
    if (c.meets && c.meets_rate && has_rtl(c.design)) jobs.push_back({c.design, c.widths});
  const std::vector<AreaReport> areas = synthesise_areas(jobs, area_options, options.jobs);
  for (size_t i = 0, a = 0; i < candidates.size(); ++i) {
    Candidate& c = candidates[i];
    if (!c.meets || !c.meets_rate) continue;
    if (!has_rtl(c.design)) {
      c.rtl_verified = "no RTL";
      continue;
    }
    take_area(c, areas[a++]);
  }
  // The pipelining: a design below the clock takes, up to --pipeline-steps
  // times (3 by default), one more step of the pipelining of the block that
  // sets its clock (deeper_pipeline), runs its scenes again for the cycles
  // that adds (the values are the same), and is synthesised again. A step is
  // kept if the design still meets the rate and its f_max rose. One that did
  // not raise it is tried once more with the next step on top (of the block
  // that now sets the clock: when two paths are close, cutting one only
  // shows the other); both are kept if that raised f_max, and the search
  // ends for the design otherwise.
  std::vector<bool> spent(candidates.size(), false);
  std::vector<std::optional<Candidate>> trial(candidates.size());  // a step kept on trial
  for (unsigned round = 0; round < options.pipeline_steps && options.clock_mhz > 0; ++round) {
    std::vector<size_t> retried;
    std::vector<AreaJob> jobs_again;
    std::vector<Candidate> deeper;
    for (size_t i = 0; i < candidates.size(); ++i) {
      if (spent[i] || !candidates[i].area || candidates[i].meets_clock) continue;
      const Candidate& c = trial[i] ? *trial[i] : candidates[i];
      const std::optional<Widths> next = deeper_pipeline(c.design, c.widths, critical_block(*c.area), options.settings,
                                                                c.area->critical_path_to);
      if (!next) {
        spent[i] = true;
        continue;
      }
      Candidate p = c;
      p.widths = *next;
      std::vector<DesignResult> results;
      for (const PreparedScene* scene : scene_list)
        results.push_back(evaluate(*scene, p.design, p.widths, /*measure_error=*/false, nullptr, threads));
      take_rates(p, results);
      if (!p.meets_rate) {
        spent[i] = true;
        continue;
      }
      fmt::print(stderr, "choose: {} below {:g} MHz ({:.1f}, the {}){}: synthesised again with {}\n", c.design.name,
                 options.clock_mhz, c.area->fmax_mhz, critical_block(*c.area),
                 trial[i] ? fmt::format(", on trial over {:.1f}", candidates[i].area->fmax_mhz) : "",
                 pipeline_settings(p.widths, candidates[i].widths));
      retried.push_back(i);
      jobs_again.push_back({p.design, p.widths});
      deeper.push_back(p);
    }
    if (jobs_again.empty()) break;
    const std::vector<AreaReport> areas_again = synthesise_areas(jobs_again, area_options, options.jobs);
    for (size_t k = 0; k < retried.size(); ++k) {
      const size_t i = retried[k];
      take_area(deeper[k], areas_again[k]);
      switch (pipelining_verdict(candidates[i].area->fmax_mhz, deeper[k].area->fmax_mhz, trial[i].has_value())) {
        case PipeliningVerdict::Keep:
          candidates[i] = deeper[k];
          trial[i].reset();
          break;
        case PipeliningVerdict::Trial:
          trial[i] = deeper[k];
          break;
        case PipeliningVerdict::Stop:
          spent[i] = true;
          trial[i].reset();
          break;
      }
    }
  }
  // Ranked: designs that meet every target with an area, by area then
  // cycles; then those without RTL; then those that meet the error target
  // but not the rate or the clock; then those that cannot meet the error.
  const auto group = [](const Candidate& c) {
    return !c.meets ? 3 : !c.meets_rate || !c.meets_clock ? 2 : c.area ? 0 : 1;
  };
  std::stable_sort(candidates.begin(), candidates.end(), [&](const Candidate& a, const Candidate& b) {
    if (group(a) != group(b)) return group(a) < group(b);
    if (group(a) == 0 && a.total_area_um2 != b.total_area_um2) return a.total_area_um2 < b.total_area_um2;
    return a.cycles < b.cycles;
  });

  // The winner on the RTL: every scene, then random triangles, with back-pressure.
  if (options.verify && !candidates.empty() && group(candidates.front()) == 0) {
    Candidate& winner = candidates.front();
    fmt::print("verify: {} on the RTL at its widths, against the model\n", winner.design.name);
    std::fflush(stdout);
    rtl::VerifyRequest request;
    request.widths = winner.widths;
    request.scenes = scene_names;
    request.scene_options = options.scene_options;
    request.design = winner.design.name;
    request.random = options.verify_random;
    request.backpressure = options.verify_backpressure;
    request.rtl_cache = options.rtl_cache;
    request.jobs = threads;  // in shards, one a core
    winner.rtl_verified = rtl::verify_widths(request) == 0 ? "yes" : "no";
    fmt::print("\n");
  }

  // The rates: px/clk over all the scenes, f_max from the synthesis's timing.
  const auto px_per_clk = [](const Candidate& c) { return c.cycles ? double(c.pixels) / double(c.cycles) : 0.0; };
  const auto timed = [](const Candidate& c) { return c.area && c.area->critical_path_ns > 0; };
  fmt::print("{:<4} {:<17} {:<5} {:>13} {:>13} {:<6} {:>12} {:>9} {:>7} {:>6} {:>7} {:>10}  {}\n", "rank", "design",
             "meets", "total um^2", "logic um^2", "table", "cycles", "cyc/pixel", "px/clk", "f_max", "Mpx/s", "error",
             "widths (other than default)");
  int rank = 0;
  for (const Candidate& c : candidates) {
    const std::string place = group(c) == 0 ? fmt::format("{}", ++rank) : "-";
    if (!c.meets) {
      fmt::print("{:<4} {:<17} {:<5} {:>13} {:>13} {:<6} {:>12} {:>9} {:>7} {:>6} {:>7} {:>10.4g}  {}\n", place,
                 c.design.name, "no", "-", "-", "-", "-", "-", "-", "-", "-", c.error,
                 "not reachable: the error at the widest widths");
      continue;
    }
    const std::string area = c.area ? fmt::format("{:.0f}", c.total_area_um2) : c.meets_rate ? "no RTL" : "-";
    const std::string logic = c.area ? fmt::format("{:.0f}", c.area->logic_area_um2) : "-";
    const std::string fmax = timed(c) ? fmt::format("{:.1f}", c.area->fmax_mhz) : "-";
    const std::string rate = timed(c) ? fmt::format("{:.1f}", px_per_clk(c) * c.area->fmax_mhz) : "-";
    const std::string meets = !c.meets_rate ? "rate" : !c.meets_clock ? "clock" : "yes";
    const std::string why =
        !c.meets_rate ? fmt::format("too slow: {:.3f} px/clk on {} < {:g}", c.min_px_per_clk, c.slowest_scene, options.min_rate)
        : !c.meets_clock ? fmt::format("too slow: f_max {:.1f} MHz < {:g} (the {}'s {:.2f} ns); {}",
                                       c.area->fmax_mhz, options.clock_mhz, critical_block(*c.area),
                                       c.area->critical_path_ns, sized_widths(c))
                         : sized_widths(c);
    fmt::print("{:<4} {:<17} {:<5} {:>13} {:>13} {:<6} {:>12} {:>9.3f} {:>7.3f} {:>6} {:>7} {:>10.4g}  {}\n", place,
               c.design.name, meets, area, logic, c.table.empty() ? "none" : c.table, c.cycles,
               c.pixels ? double(c.cycles) / double(c.pixels) : 0.0, px_per_clk(c), fmax, rate, c.error, why);
  }
  fmt::print("(px/clk over all the scenes; f_max in MHz, OpenSTA on the synthesised netlist; Mpx/s = px/clk x f_max; "
             "docs/area.md)\n");
  if (!candidates.empty() && group(candidates.front()) == 0)
    fmt::print("\nwinner: {} at {:.0f} um^2 ({} cycles); RTL check: {}\n", candidates.front().design.name,
               candidates.front().total_area_um2, candidates.front().cycles,
               candidates.front().rtl_verified);
  else
    fmt::print("\nno design with RTL meets the target{}\n", options.min_rate > 0 || options.clock_mhz > 0 ? "s" : "");

  if (!options.json_path.empty()) {
    nlohmann::json json;
    json["target"] = {{"max_error", options.max_error}, {"metric", options.metric},
                      {"statistic", options.statistic}, {"max_slowdown", options.max_slowdown},
                      {"min_rate", options.min_rate}, {"clock_mhz", options.clock_mhz},
                      {"pipeline_steps", options.pipeline_steps}, {"area_flow", options.area_flow}};
    json["scenes"] = nlohmann::json::array();
    for (const PreparedScene& s : scenes)
      json["scenes"].push_back({{"name", s.scene.name}, {"triangles", s.scene.triangles.size()},
                                {"resolution", {s.scene.width, s.scene.height}}});
    json["build"] = build_id();
    json["ranking"] = nlohmann::json::array();
    for (const Candidate& c : candidates) {
      nlohmann::json row = {{"design", c.design.name},
                            {"meets", c.meets && c.meets_rate && c.meets_clock},
                            {"meets_error", c.meets},
                            {"total_area_um2", c.area ? nlohmann::json(c.total_area_um2) : nlohmann::json()},
                            {"cycles", c.cycles},
                            {"pixels", c.pixels},
                            {"error", c.error},
                            {"widths", widths_json(c.widths)},
                            {"rtl_verified", c.rtl_verified == "yes"},
                            {"px_per_clk", c.meets ? nlohmann::json(px_per_clk(c)) : nlohmann::json()},
                            {"fmax_mhz", timed(c) ? nlohmann::json(c.area->fmax_mhz) : nlohmann::json()},
                            {"mpix_per_s", timed(c) ? nlohmann::json(px_per_clk(c) * c.area->fmax_mhz)
                                                    : nlohmann::json()}};
      row["rtl_check"] = c.rtl_verified;
      // Rate and clock are judged only for designs that meet the error; the
      // clock only for those synthesised (a design below the rate is not).
      row["min_px_per_clk"] = c.meets ? nlohmann::json(c.min_px_per_clk) : nlohmann::json();
      row["slowest_scene"] = c.meets ? nlohmann::json(c.slowest_scene) : nlohmann::json();
      row["meets_rate"] = c.meets ? nlohmann::json(c.meets_rate) : nlohmann::json();
      row["meets_clock"] = c.area ? nlohmann::json(c.meets_clock) : nlohmann::json();
      if (c.area) {
        row["area"] = area_summary_json(*c.area, px_per_clk(c));
        row["table"] = c.table.empty() ? nlohmann::json() : nlohmann::json(c.table);
        row["unbanded_cycles"] = c.unbanded_cycles;
      }
      json["ranking"].push_back(row);
    }
    write_file_atomic(options.json_path, json.dump(2) + '\n');
    fmt::print("wrote {}\n", options.json_path);
  }
  const bool winner_failed = !candidates.empty() && candidates.front().rtl_verified == "no";
  return winner_failed ? 1 : 0;
}

}  // namespace cdsim
