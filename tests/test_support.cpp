#include "test_support.h"

#include <unistd.h>

#include <atomic>
#include <fstream>
#include <random>
#include <sstream>

namespace treesketch::test {

namespace fs = std::filesystem;

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  std::random_device rd;
  path_ = fs::temp_directory_path() / ("treesketch_test_" + std::to_string(::getpid()) + "_" +
                                       std::to_string(counter++) + "_" + std::to_string(rd() % 100000));
  fs::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

fs::path sharedDataDir() { return fs::path(TS_SHARED_DATA_DIR); }

void writeText(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

std::string readText(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

geom::CylinderModel randomJoinedModel(std::uint64_t seed, int pieces) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> pos(-1, 1), rad(0.01, 0.1), len(0.05, 0.4), u(0, 1);
  geom::CylinderModel m;
  for (int i = 0; i < pieces; ++i) {
    const geom::Vec3 dir = geom::Vec3(pos(rng), pos(rng), pos(rng)).normalized();
    std::int64_t parent = -1;
    geom::Vec3 a(pos(rng), pos(rng), pos(rng));
    double r0 = rad(rng);
    if (i > 0 && u(rng) < 0.85) {
      parent = u(rng) < 0.7 ? i - 1 : static_cast<std::int64_t>(u(rng) * i);
      a = m.cylinders[static_cast<std::size_t>(parent)].end;
      if (u(rng) < 0.5) r0 = m.cylinders[static_cast<std::size_t>(parent)].endRadius;
    }
    m.cylinders.push_back(modelPiece(a, a + len(rng) * dir, r0, rad(rng), parent));
  }
  return m;
}

}  // namespace treesketch::test
