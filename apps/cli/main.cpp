// treesketch: command-line entry point. Parses the subcommand, runs it, maps errors to exit
// codes (see commands.h) and prints one line on stderr for any failure.
#include <cstdio>
#include <algorithm>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "build_info.h"
#include "commands.h"
#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace {

/// Edit distance (insertions, deletions, substitutions, adjacent swaps) between two words.
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::vector<std::size_t>> d(a.size() + 1, std::vector<std::size_t>(b.size() + 1));
  for (std::size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
    for (std::size_t j = 1; j <= b.size(); ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[a.size()][b.size()];
}

/// The first argument names no command (a typo, or options in the wrong place): say which word,
/// and the nearest command. Empty when the first argument is an option or a command.
std::string unknownCommandMessage(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-' || argv[1][0] == '\0') return {};
  const std::string word = argv[1];
  std::string nearest;
  std::size_t best = std::string::npos;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->get_name() == word) return {};
    const std::size_t d = editDistance(word, sub->get_name());
    if (d < best) {
      best = d;
      nearest = sub->get_name();
    }
  }
  std::string message = "unknown command '" + word + "'";
  if (best <= std::max<std::size_t>(2, word.size() / 3)) message += "; did you mean '" + nearest + "'?";
  return message + " ('treesketch --help' lists the commands)";
}

}  // namespace

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
  registerClassify(app, action);
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
  registerSplit(app, action);
  if (const std::string unknown = unknownCommandMessage(app, argc, argv); !unknown.empty()) {
    std::cerr << "treesketch: error: " << unknown << "\n";
    return kExitUsage;
  }
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
