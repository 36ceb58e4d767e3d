// treesketch: command-line entry point. Parses the subcommand, runs it, maps errors to exit
// codes (see commands.h) and prints one line on stderr for any failure.
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>

#include "build_info.h"
#include "commands.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

int main(int argc, char** argv) {
  using namespace treesketch;
  using namespace treesketch::cli;
  CLI::App app{"treesketch: reconstruct tree trunks and branches from point clouds, guided by a sketch"};
  app.set_version_flag("--version", versionString());
  removeTempFilesOnSignals();  // Ctrl-C during a write leaves no hidden temporary file
  app.require_subcommand(1);
  Action action;
  setCreateOutputDirectories(true);  // output folders are created when missing (a file in the way is exit 4)
  // [register subcommands here, one line each]
  registerBatch(app, action);
  registerCompare(app, action);
  registerDemo(app, action);
  registerEvaluate(app, action);
  registerFitReport(app, action);
  registerGui(app, action);
  registerInfo(app, action);
  registerMetrics(app, action);
  registerReconstruct(app, action);
  registerRender(app, action);
  registerScan(app, action);
  registerSketch(app, action);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? kExitOk : kExitUsage;
  }
  try {
    if (action) action();
    return kExitOk;
  } catch (const InputError& e) {
    std::cerr << "treesketch: error: " << e.what() << "\n";
    return kExitInput;
  } catch (const OutputError& e) {
    std::cerr << "treesketch: error: " << e.what() << "\n";
    return kExitOutput;
  } catch (const DegenerateInputError& e) {
    std::cerr << "treesketch: error: " << e.what() << "\n";
    return kExitNoResult;
  } catch (const OptionsError& e) {
    std::cerr << "treesketch: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const SomeFailed& e) {
    std::cerr << "treesketch: " << e.what() << "\n";
    return kExitSomeFailed;
  } catch (const std::bad_alloc&) {
    std::cerr << "treesketch: error: out of memory\n";
    return kExitInternal;
  } catch (const std::exception& e) {
    std::cerr << "treesketch: internal error: " << e.what() << "\n";
    return kExitInternal;
  }
}
