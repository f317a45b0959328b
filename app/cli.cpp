#include "cli.hpp"

#include "cli_checks.hpp"

namespace cdsim {

std::unique_ptr<Cli> make_cli() {
  auto cli = std::make_unique<Cli>();
  CLI::App& app = cli->app;
  app.require_subcommand(0, 1);

  cli->run_command = app.add_subcommand("run", "run a scene through the designs (the default command)");
  add_common(cli->run_command, cli->run);
  cli->run_command->add_option("--json", cli->json_path, "also write the results as JSON to this file");
  cli->run_command->add_flag("--worst", cli->show_worst, "print each design's worst pixel");
  cli->run_command->add_option("--dump", cli->dump_path,
                               "write every fragment of the first design as CSV: triangle, x, y, u, v, "
                               "the exact u and v, flags (docs/scenes.md)");
  cli->run_command->add_option("--flagged", cli->flagged_path,
                               "write every triangle with a datapath-flagged pixel, per design, as CSV with its "
                               "geometry (depth ratio, distance to its horizon, the T and S bits its lines need); "
                               "the worst ten per design also on stdout (docs/robustness.md)");
  cli->run_command->add_flag("--area", cli->run_area,
                             "also synthesise each design at these widths (cdsim area, cached; "
                             "all cores) and report its area");
  add_area_flow_option(cli->run_command, cli->run_area_flow);
  cli->run_command->add_option("--jobs", cli->run_jobs, "designs evaluated at a time (default: all cores)")
      ->check(cli::integer_in(1, 1024));

  cli->bench_command = app.add_subcommand("bench", "model throughput per design, in M pixels/s");
  add_common(cli->bench_command, cli->bench);
  cli->bench_command->add_option("--seconds", cli->bench_seconds, "minimum time per design")
      ->check(cli::number_in(0, 3600, true))
      ->capture_default_str();

  cli->widths_command =
      app.add_subcommand("widths", "list the width and microarchitecture parameters");
  cli->widths_command->add_option("--set", cli->widths.settings,
                                  "NAME=VALUE, as for run; repeatable, each parameter once");
  cli->widths_command->add_option("--sv", cli->sv_path,
                                  "write the RTL's cd_widths.svh (parameters, derived widths, "
                                  "flags, word layout) to this file, or - for stdout");

  cli->regress_command = rtl::add_regress_command(app, cli->regress);
  cli->coverage_command = rtl::add_coverage_command(app, cli->coverage);
  cli->vectors_command = rtl::add_vectors_command(app, cli->vectors);
  cli->sweep_command = add_sweep_command(app, cli->sweep);
  cli->merge_command = add_merge_command(app, cli->merge);
  cli->designs_command = app.add_subcommand("designs", "list the designs (model/designs.def)");
  cli->designs_command->add_option("--json", cli->designs_json_path,
                                   "also write each design's kind, options, RTL, sized widths and default sweep "
                                   "axes as JSON to this file");
  cli->hard_cases_command =
      app.add_subcommand("hard-cases", "list the named hard cases (--scene hard:NAME, hard:all)");
  cli->render_command = add_render_command(app, cli->render);
  cli->size_command = add_size_command(app, cli->size);
  cli->area_command = add_area_command(app, cli->area);
  cli->choose_command = add_choose_command(app, cli->choose);
  cli->area_model_command = add_area_model_command(app, cli->area_model);

  cli::make_strict(app);
  return cli;
}

}  // namespace cdsim
