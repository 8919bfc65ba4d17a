#pragma once
// Subcommands of the ambisim CLI: each registers its options and a callback on the app.
// The callbacks throw ambisim::InputError for bad input; main() turns that into exit code 2.
#include <CLI/CLI.hpp>

namespace ambisim::cli {

void add_probe_command(CLI::App& app);
void add_world_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_planners_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
void add_plot_command(CLI::App& app);
void add_viz_command(CLI::App& app);
void add_bench_chart_command(CLI::App& app);
void add_compare_command(CLI::App& app);
void add_film_command(CLI::App& app);

}  // namespace ambisim::cli
