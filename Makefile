# catkin, genmsg and the message generators need Debian's python3, not pyenv's.
export PATH := /usr/bin:$(PATH)

BUILD_DIR  ?= build
BUILD_TYPE ?= Release
JOBS       ?= 2
CMAKE_ARGS ?=

.PHONY: all deps configure build test run bench clean fuzz

all: build

deps:
	bash scripts/install_deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DPYTHON_EXECUTABLE=/usr/bin/python3 $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure --no-tests=error

run: build
	bash scripts/run.sh output

# Benchmarks (never part of test), see docs/BENCHMARKS.md: solver_bench (solvers.csv,
# seed_accuracy.csv, seed_stability.csv; docs/SOLVERS.md), sweep_bench (error_time.csv,
# stability_map.csv, scaling.csv, machine_floor.csv), curved_bench (curved_solvers.csv),
# curved_speed_bench (curved_speed.csv, curved_scaling.csv, curved_stability.csv; on one core:
# CHOLMOD's OpenMP loops capped to one thread),
# mesh_bench (meshers.csv, mesh_resolution.csv), then the charts into docs/images/bench/
# and the tables of docs/BENCHMARKS.md (Debian's python3 with python3-matplotlib).
bench: build
	$(BUILD_DIR)/devel/lib/virtual_origami/solver_bench docs/bench
	$(BUILD_DIR)/devel/lib/virtual_origami/sweep_bench docs/bench
	$(BUILD_DIR)/devel/lib/virtual_origami/curved_bench docs/bench/curved_solvers.csv
	OMP_THREAD_LIMIT=1 $(BUILD_DIR)/devel/lib/virtual_origami/curved_speed_bench docs/bench
	$(BUILD_DIR)/devel/lib/virtual_origami/replay_bench docs/bench/replay.csv sequences/crane.json sequences/penguin.json sequences/miura_ori.json
	$(BUILD_DIR)/devel/lib/virtual_origami/mesh_bench docs/bench
	/usr/bin/python3 bench/plot_charts.py docs/bench docs/images/bench docs/BENCHMARKS.md

# libFuzzer targets of test/fuzz/ with ASan + UBSan (clang-14, into build-fuzz/), each for
# FUZZ_SECONDS, one after the other; crashes land in test/fuzz/crashes/ (docs/RELIABILITY.md).
FUZZ_SECONDS ?= 60
fuzz: deps
	FUZZ_SECONDS=$(FUZZ_SECONDS) JOBS=$(JOBS) bash scripts/fuzz.sh

clean:
	rm -rf $(BUILD_DIR) output
