// ambisim: where should a game engine capture ambient-light probes around a moving camera?
// Thin main: subcommands live in cmd_*.cpp; all the work is in the libraries.
#include <exception>
#include <iostream>

#include "apps/commands.h"
#include "sim/base/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{"ambisim: ambient-light probe planning simulator"};
  app.require_subcommand(1);
  ambisim::cli::add_probe_command(app);
  ambisim::cli::add_world_command(app);
  ambisim::cli::add_run_command(app);
  ambisim::cli::add_planners_command(app);
  ambisim::cli::add_sweep_command(app);
  ambisim::cli::add_compare_command(app);
  ambisim::cli::add_plot_command(app);
  ambisim::cli::add_viz_command(app);
  ambisim::cli::add_film_command(app);
  ambisim::cli::add_bench_chart_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print their text; a usage error is one line, like any bad input.
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "ambisim: error: " << e.what() << " (see --help)\n";
    return 2;
  } catch (const ambisim::InputError& e) {
    std::cerr << "ambisim: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "ambisim: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
