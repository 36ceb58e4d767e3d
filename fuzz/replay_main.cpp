// The smoke driver of the fuzz harnesses for `make test` (no clang or libFuzzer needed): runs
// every file of the given corpus directories through LLVMFuzzerTestOneInput, then a fixed number
// of deterministic mutations of them (bit flips, byte sets, truncations, insertions, deletions,
// duplications; xorshift with a fixed seed), so the same inputs run on every machine and in the
// ASan/UBSan build. A harness failure aborts, which CTest reports with the harness's message; the
// driver then names the input and writes it to <program>-crash.bin in the working directory (from
// a signal handler, or the sanitizers' death callback), to be kept as a regression.
//
// Usage: fuzz_smoke_<harness> [--mutations N] [--seed S] [--verbose] DIR...
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);
// Present when linked with ASan/UBSan (called before the sanitizer exits); absent otherwise.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace {

struct XorShift {
  std::uint64_t s;
  std::uint64_t next() {
    s ^= s << 13;
    s ^= s >> 7;
    s ^= s << 17;
    return s;
  }
  std::size_t below(std::size_t n) { return n == 0 ? 0 : static_cast<std::size_t>(next() % n); }
};

using Bytes = std::vector<std::uint8_t>;

Bytes readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Bytes that often matter to parsers: separators, signs, digits, exponent, quotes, brackets, extremes.
constexpr std::uint8_t kInteresting[] = {0,   1,   0x7f, 0x80, 0xff, '\n', '\r', ' ', ',',
                                         '-', '.', '0',  '9',  'e',  '"',  '[',  '{', '}'};

void mutate(Bytes& b, XorShift& rng) {
  const int ops = 1 + static_cast<int>(rng.below(4));
  for (int k = 0; k < ops; ++k) {
    const std::size_t at = rng.below(b.size() + 1);
    switch (rng.below(6)) {
      case 0:  // flip a bit
        if (!b.empty()) b[std::min(at, b.size() - 1)] ^= static_cast<std::uint8_t>(1u << rng.below(8));
        break;
      case 1:  // set an interesting byte
        if (!b.empty()) b[std::min(at, b.size() - 1)] = kInteresting[rng.below(sizeof kInteresting)];
        break;
      case 2:  // truncate
        b.resize(at);
        break;
      case 3: {  // insert random bytes
        Bytes ins(1 + rng.below(8));
        for (auto& c : ins) c = static_cast<std::uint8_t>(rng.next());
        b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), ins.begin(), ins.end());
        break;
      }
      case 4: {  // delete a run
        const std::size_t n = std::min(b.size() - std::min(at, b.size()), 1 + rng.below(16));
        b.erase(b.begin() + static_cast<std::ptrdiff_t>(at), b.begin() + static_cast<std::ptrdiff_t>(at + n));
        break;
      }
      case 5: {  // duplicate a run in place
        const std::size_t n = std::min(b.size() - std::min(at, b.size()), 1 + rng.below(64));
        const Bytes run(b.begin() + static_cast<std::ptrdiff_t>(at), b.begin() + static_cast<std::ptrdiff_t>(at + n));
        b.insert(b.begin() + static_cast<std::ptrdiff_t>(at), run.begin(), run.end());
        break;
      }
    }
  }
}

// The input being run and its name, for the crash handler (set before each run).
const Bytes* current = nullptr;
std::string currentName;
std::string crashPath;

// Async-signal-safe enough: open/write only, buffers prepared beforehand.
void saveCurrent() {
  if (!current) return;
  const std::string msg = "fuzz smoke: failed on " + currentName + "; input written to " + crashPath + "\n";
  (void)!::write(2, msg.data(), msg.size());
  const int fd = ::open(crashPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    (void)!::write(fd, current->data(), current->size());
    ::close(fd);
  }
  current = nullptr;
}

void onSignal(int sig) {
  saveCurrent();
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

void run(const Bytes& input, bool verbose, const std::string& what) {
  if (verbose) std::fprintf(stderr, "run %s (%zu bytes)\n", what.c_str(), input.size());
  current = &input;
  currentName = what;
  LLVMFuzzerTestOneInput(input.data(), input.size());
  current = nullptr;
}

}  // namespace

int main(int argc, char** argv) {
  long mutations = 2000;
  std::uint64_t seed = 0x5eed;
  bool verbose = false;
  std::vector<std::filesystem::path> files;
  crashPath = std::filesystem::path(argv[0]).filename().string() + "-crash.bin";
  for (int sig : {SIGABRT, SIGSEGV, SIGFPE, SIGILL, SIGBUS}) std::signal(sig, onSignal);
  if (__sanitizer_set_death_callback) __sanitizer_set_death_callback(saveCurrent);
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--mutations" && i + 1 < argc) {
      mutations = std::atol(argv[++i]);
    } else if (a == "--seed" && i + 1 < argc) {
      seed = std::strtoull(argv[++i], nullptr, 10) | 1;
    } else if (a == "--verbose") {
      verbose = true;
    } else if (std::filesystem::is_directory(a)) {
      for (const auto& e : std::filesystem::directory_iterator(a))
        if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
    } else if (std::filesystem::is_regular_file(a)) {
      files.push_back(a);
    } else if (a.rfind("--", 0) == 0) {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }  // a missing directory (no regressions yet) is fine
  }
  std::sort(files.begin(), files.end());  // directory order differs between machines
  std::vector<Bytes> seeds;
  for (const auto& f : files) {
    seeds.push_back(readBytes(f));
    run(seeds.back(), verbose, f.string());
  }
  if (seeds.empty()) seeds.emplace_back();
  XorShift rng{seed};
  for (long m = 0; m < mutations; ++m) {
    Bytes b = seeds[rng.below(seeds.size())];
    mutate(b, rng);
    run(b, verbose, "mutation " + std::to_string(m));
  }
  std::printf("fuzz smoke: %zu files and %ld mutations passed\n", files.size(), mutations);
  return 0;
}
