// Every command on hostile copies of real and generated clouds, each run as a child process under
// a time limit and (release build) a 4 GB address-space limit: the clouds scaled by 1e-6, 1e3 and
// 1e9, shifted by 1e6 and 1e12, truncated, with bytes flipped, with NaN or infinite coordinates
// (for a LAS file: a scale factor of NaN or 1e300), and with a header that lies about the points.
// Each run must end by itself (no signal, within the limits) with a documented code that is not a
// failure of the program (0, 3 "could not be read" or 5 "nothing can be made from it"); a data
// error must name the file; a failed run writes nothing; nothing is left half-written (no
// temporary file, every output reads back whole).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.h"
#include "skeleton/synthetic_tree.h"
#include "test_support.h"
#include "treesketch/io/cylinder_table.h"
#include "treesketch/io/mesh_io.h"
#include "treesketch/io/point_cloud_io.h"

namespace treesketch {
namespace {

namespace fs = std::filesystem;

bool sanitized() { return std::getenv("TREESKETCH_SANITIZED") != nullptr; }

/// How a child process ended.
struct ChildRun {
  int exitCode = -1;    ///< -1 when it did not exit by itself
  int signal = 0;       ///< the signal that ended it, 0 when it exited
  bool timedOut = false;
  double seconds = 0;
  std::string output;   ///< stdout and stderr
};

/// Runs the treesketch CLI with `args` in a child process, stdout and stderr to `log`; kills it
/// after `timeoutSeconds`. With `addressSpaceBytes` > 0 the child's RLIMIT_AS is set to it
/// (AddressSanitizer reserves terabytes of address space, so the sanitized build passes 0).
ChildRun runLimited(const std::vector<std::string>& args, const fs::path& log, double timeoutSeconds,
                    rlim_t addressSpaceBytes) {
  const std::string cli = test::cliPath().string();
  std::vector<char*> argv{const_cast<char*>(cli.c_str())};
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const auto start = std::chrono::steady_clock::now();
  const pid_t pid = ::fork();
  if (pid == 0) {  // the child: only async-signal-safe calls until exec
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0) ::_exit(126);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    if (addressSpaceBytes > 0) {
      const rlimit limit{addressSpaceBytes, addressSpaceBytes};
      ::setrlimit(RLIMIT_AS, &limit);
    }
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  ChildRun run;
  if (pid < 0) return run;
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (done == pid) break;
    if (run.seconds > timeoutSeconds) {
      run.timedOut = true;
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(3));
  }
  if (WIFEXITED(status)) run.exitCode = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
  run.output = test::readText(log);
  return run;
}

// ---- the hostile copies --------------------------------------------------------------------------

struct Variant {
  std::string name;  ///< file name, with the source's extension
  std::string bytes;
};

std::string withExtension(const std::string& base, const std::string& what, const std::string& ext) {
  return base + "_" + what + ext;
}

/// Flips one bit in each of `count` bytes chosen by a fixed seed, half of them in the first 300
/// bytes (where the headers are).
std::string flipBytes(std::string bytes, int count, unsigned seed) {
  std::mt19937 rng(seed);
  for (int i = 0; i < count && !bytes.empty(); ++i) {
    const std::size_t range = i % 2 ? bytes.size() : std::min<std::size_t>(300, bytes.size());
    bytes[rng() % range] ^= static_cast<char>(1u << (rng() % 8));
  }
  return bytes;
}

/// Corruptions every format gets: truncated mid-record, bytes flipped.
void addCommonCorruptions(const std::string& base, const std::string& ext, const std::string& bytes,
                          std::vector<Variant>& out) {
  out.push_back({withExtension(base, "truncated", ext), bytes.substr(0, bytes.size() * 3 / 5 + 7)});
  out.push_back({withExtension(base, "flipped", ext), flipBytes(bytes, 16, 7)});
}

const double kScales[] = {1e-6, 1e3, 1e9};
const double kShifts[] = {1e6, 1e12};

std::string figureName(const char* what, double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%s%g", what, v);
  return buf;
}

/// A cloud written by the library (.xyz or .ply): scaled, shifted and corrupted copies.
std::vector<Variant> cloudVariants(const std::string& base, const geom::PointCloud& cloud, const std::string& ext,
                                   const fs::path& scratch) {
  std::vector<Variant> out;
  auto write = [&](const geom::PointCloud& c) {
    const fs::path p = scratch / ("tmp" + ext);
    io::writePointCloud(p, c);
    return test::readText(p);
  };
  auto transformed = [&](const std::function<geom::Vec3(const geom::Vec3&)>& f) {
    geom::PointCloud c = cloud;
    for (auto& p : c.positions) p = f(p);
    return write(c);
  };
  for (double s : kScales)
    out.push_back({withExtension(base, figureName("scale", s), ext), transformed([s](const geom::Vec3& p) { return p * s; })});
  for (double d : kShifts)
    out.push_back({withExtension(base, figureName("shift", d), ext),
                   transformed([d](const geom::Vec3& p) { return geom::Vec3(p.array() + d); })});
  const std::string bytes = write(cloud);
  addCommonCorruptions(base, ext, bytes, out);
  if (ext == ".xyz") {
    std::string nan = bytes;
    nan.insert(nan.find('\n', nan.size() / 3) + 1, "nan 1 2\n");
    nan.insert(nan.find('\n', nan.size() / 2) + 1, "1 2 inf\n");
    out.push_back({withExtension(base, "naninf", ext), nan});
    out.push_back({withExtension(base, "headerlie", ext), "x y z red green blue\n" + bytes});
  } else {  // binary PLY: doubles after "end_header\n"
    const std::size_t body = bytes.find("end_header\n") + 11;
    const std::size_t stride = (bytes.size() - body) / cloud.size();
    std::string nan = bytes;
    const double qnan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    std::memcpy(&nan[body + 10 * stride], &qnan, 8);
    std::memcpy(&nan[body + 20 * stride + 16], &inf, 8);
    out.push_back({withExtension(base, "naninf", ext), nan});
    std::string lie = bytes;
    const std::string count = "element vertex " + std::to_string(cloud.size());
    lie.replace(lie.find(count), count.size(), "element vertex " + std::to_string(cloud.size() * 2));
    out.push_back({withExtension(base, "headerlie", ext), lie});
  }
  return out;
}

// LAS 1.0-1.3 header fields (LAS 1.2 specification, table 4).
constexpr std::size_t kLasCount = 107, kLasScale = 131, kLasOffset = 155, kLasMax = 179;

double getDouble(const std::string& b, std::size_t at) {
  double v;
  std::memcpy(&v, &b[at], 8);
  return v;
}
void putDouble(std::string& b, std::size_t at, double v) { std::memcpy(&b[at], &v, 8); }

/// A real LAS file's own bytes with its header edited: scale factor and offset (and the bounds)
/// multiplied, offset shifted, a scale of NaN or 1e300, a point count ten times the truth.
std::vector<Variant> lasVariants(const std::string& base, const std::string& las) {
  std::vector<Variant> out;
  auto edited = [&](double scale, double shift) {
    std::string b = las;
    for (int k = 0; k < 3; ++k) {
      putDouble(b, kLasScale + 8 * k, getDouble(b, kLasScale + 8 * k) * scale);
      putDouble(b, kLasOffset + 8 * k, getDouble(b, kLasOffset + 8 * k) * scale + shift);
    }
    for (int k = 0; k < 6; ++k) putDouble(b, kLasMax + 8 * k, getDouble(b, kLasMax + 8 * k) * scale + shift);
    return b;
  };
  for (double s : kScales) out.push_back({withExtension(base, figureName("scale", s), ".las"), edited(s, 0)});
  for (double d : kShifts) out.push_back({withExtension(base, figureName("shift", d), ".las"), edited(1, d)});
  addCommonCorruptions(base, ".las", las, out);
  out.push_back({withExtension(base, "scale1e300", ".las"), edited(1e300, 0)});
  std::string nan = las;
  putDouble(nan, kLasScale, std::numeric_limits<double>::quiet_NaN());
  out.push_back({withExtension(base, "scalenan", ".las"), nan});
  std::string lie = las;
  std::uint32_t count;
  std::memcpy(&count, &lie[kLasCount], 4);
  count *= 10;
  std::memcpy(&lie[kLasCount], &count, 4);
  out.push_back({withExtension(base, "headerlie", ".las"), lie});
  return out;
}

// ---- the runs ------------------------------------------------------------------------------------

/// Whether `path` (an output that exists) reads back whole.
std::string incompleteOutput(const fs::path& path) {
  const std::string ext = path.extension().string();
  try {
    if (ext == ".png") {
      const std::string b = test::readText(path);
      static const std::string kIend("\0\0\0\0IEND\xae\x42\x60\x82", 12);
      if (b.compare(0, 4, "\x89PNG") != 0 || b.size() < 12 || b.compare(b.size() - 12, 12, kIend) != 0)
        return "no PNG signature or no IEND chunk at its end";
    } else if (ext == ".json") {
      if (!nlohmann::json::accept(test::readText(path))) return "not whole JSON";
    } else if (ext == ".obj") {
      io::readMesh(path);
    } else if (ext == ".csv") {
      io::readCylinderTable(path);
    } else if (ext == ".ply") {
      io::readPointCloud(path);
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

class HostileFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    // A clean table for `metrics` when a copy gives no model of its own.
    test::writeText(dir / "clean.csv",
                    "ID,parentID,startX,startY,startZ,endX,endY,endZ,radius,length\n"
                    "1,-1,0,0,0,0,0,1,0.1,1\n2,1,0,0,1,0,0.5,2,0.05,1.1\n");
  }

  /// Runs every command on `v` in a folder of its own and checks each run.
  void runCommands(const Variant& v) {
    // A folder not named after the file, so that "names the file" means the file, not its folder.
    const fs::path folder = dir / ("run" + std::to_string(runs));
    fs::create_directories(folder);
    const std::string in = (folder / v.name).string();
    test::writeText(in, v.bytes);
    auto o = [&](const std::string& name) { return (folder / name).string(); };
    check(v, folder, "info", {"info", in}, {});
    check(v, folder, "reconstruct", {"reconstruct", in, "--auto", "-o", o("m.obj"), "--cylinders", o("m.csv"),
                                     "--report", o("r.json")}, {"m.obj", "m.csv", "r.json"});
    // metrics on the copy's own model (its taper steps at the copy's scale), else on a clean table
    const std::string table = fs::exists(folder / "m.csv") ? o("m.csv") : (dir / "clean.csv").string();
    check(v, folder, "metrics", {"metrics", table, "--cloud", in, "--json", o("metrics.json")}, {"metrics.json"});
    check(v, folder, "render", {"render", "--cloud", in, "--size", "160x160", "-o", o("p.png")}, {"p.png"});
    // compare with the model of the unchanged cloud: the copy may lie 1e12 from it
    check(v, folder, "compare", {"compare", sourceModel, in, "--json", o("compare.json")}, {"compare.json"});
    check(v, folder, "classify", {"classify", in, "-o", o("c.ply")}, {"c.ply"});
    check(v, folder, "sketch auto", {"sketch", "auto", in, "-o", o("s.json")}, {"s.json"});
  }

  void check(const Variant& v, const fs::path& folder, const std::string& command, const std::vector<std::string>& args,
             const std::vector<std::string>& outputs) {
    SCOPED_TRACE(v.name + ": " + command);
    // 60 s is the bound for any input of up to 1M points; these have 4,000.
    const double limit = sanitized() ? 300.0 : 60.0;
    const ChildRun r = runLimited(args, dir / "log.txt", limit, sanitized() ? 0 : rlim_t{4} << 30);
    std::printf("%-28s %-12s exit %2d %6.2f s\n", v.name.c_str(), command.c_str(), r.exitCode, r.seconds);
    ++runs;
    slowest = std::max(slowest, r.seconds);
    total += r.seconds;
    if (r.seconds >= slowest) slowestRun = v.name + " " + command;
    EXPECT_FALSE(r.timedOut) << "still running after " << limit << " s";
    EXPECT_EQ(r.signal, 0) << r.output;
    EXPECT_TRUE(r.exitCode == 0 || r.exitCode == 3 || r.exitCode == 5) << "exit " << r.exitCode << "\n" << r.output;
    if (r.exitCode == 3 || r.exitCode == 5) EXPECT_NE(r.output.find(v.name), std::string::npos) << r.output;
    for (const std::string& name : outputs) {
      if (!fs::exists(folder / name)) continue;
      EXPECT_EQ(r.exitCode, 0) << name << " written by a run that failed";
      EXPECT_EQ(incompleteOutput(folder / name), "") << name;
    }
    for (const auto& e : fs::directory_iterator(folder))
      EXPECT_NE(e.path().filename().string()[0], '.') << "left behind: " << e.path().filename();
  }

  /// Models the unchanged cloud `source` (for `compare`), then runs every command on each copy.
  void runAll(const fs::path& source, const std::vector<Variant>& variants) {
    sourceModel = (dir / (source.stem().string() + "_model.obj")).string();
    std::string out;
    ASSERT_EQ(test::runCli("reconstruct " + test::quoted(source) + " --auto -o " + test::quoted(sourceModel), &out), 0)
        << out;
    for (const Variant& v : variants) runCommands(v);
    std::printf("%d runs, %.1f s in all, slowest %.2f s (%s)\n", runs, total, slowest, slowestRun.c_str());
  }

  test::TempDir dir;
  std::string sourceModel;
  int runs = 0;
  double total = 0, slowest = 0;
  std::string slowestRun;
};

// The limits the runs below are held to are real: a run past its time is stopped and said to be,
// and a process under a small address-space limit cannot model a cloud.
TEST_F(HostileFiles, TheLimitsHold) {
  io::writePointCloud(dir / "tree.ply", test::sampleCylinders(test::threeLevelTree(), 0.05, 0.002, 5));
  const std::vector<std::string> args = {"reconstruct", (dir / "tree.ply").string(), "--auto", "-o",
                                         (dir / "m.obj").string()};
  const ChildRun quick = runLimited(args, dir / "log.txt", 0.001, 0);
  EXPECT_TRUE(quick.timedOut);
  EXPECT_EQ(quick.signal, SIGKILL);
  if (sanitized()) GTEST_SKIP() << "an address-space limit cannot hold an AddressSanitizer process";
  const ChildRun small = runLimited(args, dir / "log.txt", 60, rlim_t{32} << 20);  // 32 MB
  EXPECT_FALSE(small.timedOut);
  EXPECT_NE(small.exitCode, 0) << small.output;
  EXPECT_FALSE(fs::exists(dir / "m.obj"));
  const ChildRun enough = runLimited(args, dir / "log.txt", 60, rlim_t{4} << 30);
  EXPECT_EQ(enough.exitCode, 0) << enough.output;
}

// A generated tree (binary PLY, Y up, 2,700 points).
TEST_F(HostileFiles, EveryCommandOnCopiesOfAGeneratedCloud) {
  const geom::PointCloud cloud = test::sampleCylinders(test::threeLevelTree(), 0.05, 0.002, 5);
  io::writePointCloud(dir / "generated.ply", cloud);
  runAll(dir / "generated.ply", cloudVariants("generated", cloud, ".ply", dir.path()));
}

// Two small real scans of ../shared/data/real: a LAS file in projected coordinates (4,040 points)
// and every third point of a text cloud (3,952 points).
TEST_F(HostileFiles, EveryCommandOnCopiesOfTwoRealClouds) {
  const fs::path real = test::sharedDataDir() / "real";
  const fs::path las = real / "pctm_ahn_filtered_tree_121913_487434.las", xyz = real / "adtree_tree1.xyz";
  if (!fs::exists(las) || !fs::exists(xyz)) GTEST_SKIP() << "needs " << las << " and " << xyz;
  geom::PointCloud text = io::readPointCloud(xyz), thinned;
  for (std::size_t i = 0; i < text.size(); i += 3) thinned.positions.push_back(text.positions[i]);
  runAll(las, lasVariants("pctm", test::readText(las)));
  io::writePointCloud(dir / "adtree1.xyz", thinned);
  runAll(dir / "adtree1.xyz", cloudVariants("adtree1", thinned, ".xyz", dir.path()));
}

}  // namespace
}  // namespace treesketch
