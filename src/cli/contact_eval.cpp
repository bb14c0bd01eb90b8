// contact_eval: the core models from the command line, JSON on stdout, SI units; the paper frame, or REP 103 with
// --frame ros.
// Bad input: a message on stderr and a non-zero exit status (CLI11's for usage, 2 for values).

// STL
#include <exception>
#include <iostream>

// CLI11
#include <CLI/CLI.hpp>

// Package
#include "cli/brush_commands.h"
#include "cli/cylinder_command.h"

int main(int argc, char** argv)
{
  namespace cli = sphere_contact_estimator::cli;
  CLI::App app{ "contact_eval: evaluate the contact models of sphere_contact_estimator (JSON out)" };
  app.require_subcommand(1);
  cli::CylinderOptions cylinder;
  CLI::App* cylinder_command = cli::addCylinderCommand(app, cylinder);
  cli::SlipsOptions slips;
  CLI::App* slips_command = cli::addSlipsCommand(app, slips);
  cli::BrushOptions brush;
  CLI::App* brush_command = cli::addBrushCommand(app, brush);

  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::ParseError& e)
  {
    return app.exit(e);
  }

  try
  {
    if (cylinder_command->parsed())
      cli::runCylinderCommand(cylinder, std::cout);
    else if (slips_command->parsed())
      cli::runSlipsCommand(slips, std::cout);
    else if (brush_command->parsed())
      cli::runBrushCommand(brush, std::cout);
  }
  catch (const std::exception& e)
  {
    std::cerr << "contact_eval: error: " << e.what() << '\n';
    return 2;
  }
  return 0;
}
