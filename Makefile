# SPDX-License-Identifier: BSD-3-Clause
# geaware — the two commands of the README, and their parts.
#   make demo   install missing packages, build, run the main job on the default vehicle
#   make test   install missing packages, build, run the whole test suite
#   make test-fuzz      the fuzz targets of the clang-14 tree (build-clang), the fuzz label run
#   make test-sanitize  the whole suite under ASan+UBSan (GCC tree build-asan)
#   make build-clang    the whole project with clang-14 (-Werror, sanitizers)
#   make fuzz           each fuzz target for FUZZ_S seconds (docs/reliability.md, "Fuzzing")
BUILD_DIR  ?= build
BUILD_TYPE ?= Release
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
GENERATOR  := $(shell command -v ninja >/dev/null 2>&1 && echo Ninja || echo "Unix Makefiles")

CLANG_DIR    ?= build-clang
ASAN_DIR     ?= build-asan
FUZZ_S       ?= 600

.PHONY: all deps configure build demo test bench clean \
        configure-clang build-clang test-fuzz configure-asan test-sanitize fuzz

all: build

deps:
	@bash scripts/install-deps

configure: deps
	@if [ ! -f $(BUILD_DIR)/CMakeCache.txt ]; then \
	  cmake -S . -B $(BUILD_DIR) -G "$(GENERATOR)" -DCMAKE_BUILD_TYPE=$(BUILD_TYPE); \
	fi

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	$(BUILD_DIR)/apps/geaware/geaware bench --report $(BUILD_DIR)/bench-report --json $(BUILD_DIR)/bench-results.json
	@echo "report: $(BUILD_DIR)/bench-report/bench.html (open it in a browser)"

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD_DIR)/bench/geaware_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true

# clang-14 with -Werror like GCC; asserts on (-O2 without NDEBUG), sanitizers and libFuzzer's
# coverage instrumentation on everything.
configure-clang: deps
	@if [ ! -f $(CLANG_DIR)/CMakeCache.txt ]; then \
	  CC=clang-14 CXX=clang++-14 cmake -S . -B $(CLANG_DIR) -G "$(GENERATOR)" \
	        -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O2 -g1" \
	        "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O2 -g1" -DGEAWARE_FUZZ=ON \
	        -DGEAWARE_SANITIZE=address,undefined; \
	fi

build-clang: configure-clang
	cmake --build $(CLANG_DIR) -j $(JOBS)

# The whole suite under AddressSanitizer + UndefinedBehaviorSanitizer (+ LeakSanitizer), built
# with GCC in its own tree (docs/reliability.md, "Sanitizers"). Warnings are not errors here:
# GCC's middle-end warnings see the instrumented code and report false positives (its manual
# advises against -Werror with sanitizers); the Release tree of `make test` keeps -Werror.
# No Python module (it would have to be loaded into an uninstrumented interpreter) and no
# benchmarks (nothing tests them; the Release tree builds them). Left to the
# plain run: campaign (minutes of flights, several times slower instrumented), browser (no C++
# under test), docs (compares the numbers of the Release build), install (a consumer project
# against an installed package), fuzz (the clang tree's) and python.
configure-asan: deps
	@if [ ! -f $(ASAN_DIR)/CMakeCache.txt ]; then \
	  cmake -S . -B $(ASAN_DIR) -G "$(GENERATOR)" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	        "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1" \
	        -DGEAWARE_SANITIZE=address,undefined -DGEAWARE_WERROR=OFF -DGEAWARE_PYTHON=OFF \
	        -DGEAWARE_BUILD_BENCH=OFF; \
	fi

test-sanitize: configure-asan
	cmake --build $(ASAN_DIR) -j $(JOBS)
	cd $(ASAN_DIR) && ctest -LE "campaign|browser|docs|install|fuzz|python" --output-on-failure -j $(JOBS)

test-fuzz: configure-clang
	cmake --build $(CLANG_DIR) -j $(JOBS) --target fuzz-targets
	cd $(CLANG_DIR) && ctest -L fuzz --output-on-failure -j $(JOBS)

fuzz: configure-clang
	cmake -DGEAWARE_FUZZ_LONG_S=$(FUZZ_S) $(CLANG_DIR) >/dev/null
	cmake --build $(CLANG_DIR) -j $(JOBS) --target fuzz-long

clean:
	rm -rf $(BUILD_DIR) $(CLANG_DIR) $(ASAN_DIR)
