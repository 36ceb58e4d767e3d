// Helpers for the tests that run the `treesketch` executable as a process: running a command line
// while capturing what it prints and its exit code, and quoting paths for the shell.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace treesketch::test {

/// `path` in single quotes, one word for /bin/sh (test paths hold no single quote).
inline std::string quoted(const std::filesystem::path& path) { return "'" + path.string() + "'"; }

/// Runs `commandLine` with /bin/sh; returns its exit code (-1 when it did not exit normally) and
/// puts its stdout and stderr, interleaved as written, in `output`.
inline int runCommand(const std::string& commandLine, std::string* output = nullptr) {
  const std::string cmd = commandLine + " 2>&1";
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return -1;
  std::string out;
  std::array<char, 4096> buf{};
  std::size_t n;
  while ((n = std::fread(buf.data(), 1, buf.size(), pipe)) > 0) out.append(buf.data(), n);
  const int status = ::pclose(pipe);
  if (output) *output = out;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// The treesketch executable of this build.
inline std::filesystem::path cliPath() { return TS_CLI_PATH; }

/// Runs the treesketch CLI with `args` (a shell-quoted string); returns its exit code and puts
/// stdout+stderr in `output`.
inline int runCli(const std::string& args, std::string* output = nullptr) {
  return runCommand(quoted(cliPath()) + " " + args, output);
}

}  // namespace treesketch::test
