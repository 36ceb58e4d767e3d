// The CLI's subcommands. Each file apps/cli/cmd_<name>.cpp registers one subcommand: it adds
// its options to `app` and stores in `action` what to run when that subcommand is chosen.
// Errors are thrown (InputError, OptionsError, OutputError); main maps them to exit codes.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <stdexcept>

namespace treesketch::cli {

using Action = std::function<void()>;

/// Exit codes of the treesketch command.
enum ExitCode : int {
  kExitOk = 0,
  kExitInternal = 1,    ///< an unexpected error (a bug): please report
  kExitUsage = 2,       ///< bad command line or option values
  kExitInput = 3,       ///< an input file could not be read
  kExitOutput = 4,      ///< an output file could not be written (checked before the work starts)
  kExitNoResult = 5,    ///< the input was read but no model or result can be made from it (degenerate)
  kExitSomeFailed = 6,  ///< batch: some trees failed or did not run (see the summary); the rest are done
};

/// Thrown by `batch` when it finished but not every tree is done: main prints it, exits 6.
struct SomeFailed : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// [declare register functions here, one line each]
void registerBatch(CLI::App& app, Action& action);
void registerClassify(CLI::App& app, Action& action);
void registerCompare(CLI::App& app, Action& action);
void registerDemo(CLI::App& app, Action& action);
void registerEvaluate(CLI::App& app, Action& action);
void registerFitReport(CLI::App& app, Action& action);
void registerGui(CLI::App& app, Action& action);
void registerInfo(CLI::App& app, Action& action);
void registerMetrics(CLI::App& app, Action& action);
void registerReconstruct(CLI::App& app, Action& action);
void registerRender(CLI::App& app, Action& action);
void registerScan(CLI::App& app, Action& action);
void registerSketch(CLI::App& app, Action& action);
void registerSplit(CLI::App& app, Action& action);

}  // namespace treesketch::cli
