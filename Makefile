# treesketch — the two commands of the quick start, and a few more.
#   make demo    install what is missing, build, run the main job on the built-in tree -> out/demo/
#   make test    install what is missing, build, run every test (release build, then ASan+UBSan build)
#   make package build the Debian packages treesketch_*.deb, treesketch-dev_*.deb and python3-treesketch_*.deb
#                (when the Python module is built) in $(BUILD)/
#   make fuzz    libFuzzer + ASan/UBSan harnesses of fuzz/ (clang), FUZZ_SECONDS / FUZZ_RUNS each
JOBS ?= $(shell nproc 2>/dev/null || echo 2)
BUILD ?= build
ASAN_BUILD ?= build-asan
CMAKE_FLAGS ?=
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_RUNS ?= -1
FUZZ_HARNESSES ?=

.PHONY: all deps build demo test test-release test-asan test-slurm bench package fuzz clean format

all: build

deps:
	@bash scripts/install_deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_FLAGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	./$(BUILD)/treesketch demo --out out/demo

test: test-release test-asan

test-release: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

$(ASAN_BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTREESKETCH_SANITIZE=ON -DTREESKETCH_BENCH=OFF $(CMAKE_FLAGS)

test-asan: deps $(ASAN_BUILD)/CMakeCache.txt
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		TREESKETCH_SANITIZED=1 ctest --output-on-failure -j $(JOBS)

# A plot as a Slurm job array on a single-node cluster started from Debian's packages (root; not in `make test`).
test-slurm: build
	bash scripts/test_slurm.sh

bench: build
	@for b in $(BUILD)/bench_*; do echo "== $$b"; $$b; done

package: build
	cd $(BUILD) && cpack -G DEB

# Fuzzing (not part of `make test`, which runs every harness's smoke test instead): one harness at
# a time, each for FUZZ_SECONDS seconds or FUZZ_RUNS runs (-1: no run limit), whichever comes
# first; FUZZ_HARNESSES picks some (default all). See fuzz/README.md.
fuzz:
	@bash scripts/install_deps.sh --fuzz
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTREESKETCH_FUZZ=ON \
		-DTREESKETCH_SANITIZE=ON -DTREESKETCH_TESTS=OFF -DTREESKETCH_BENCH=OFF -DTREESKETCH_GUI=OFF $(CMAKE_FLAGS)
	cmake --build $(FUZZ_BUILD) --target fuzz_all -j $(JOBS)
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 bash fuzz/run_fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_RUNS) $(FUZZ_HARNESSES)

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD) out

format:
	clang-format -i $$(git ls-files '*.cpp' '*.h')
