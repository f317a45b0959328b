// `cdsim regress`: the RTL (Verilated, under SystemC) against the C++ model.
#pragma once

namespace CLI {
class App;
}

namespace cdsim::rtl {

// Registers the `regress` subcommand and its options on app.
CLI::App* add_regress_command(CLI::App& app);
// Runs it with the parsed options; returns the process exit code.
int run_regress_command();

}  // namespace cdsim::rtl
