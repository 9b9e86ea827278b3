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

# OpenBLAS picks its kernels by the CPU, and their rounding differs. A few tests sat close to
# tolerances and iteration counts measured with its AVX-512 (SkylakeX) kernels (docs/RELIABILITY.md,
# "BLAS kernels"). Where the CPU has AVX-512, the tests run on the SkylakeX kernels.
TEST_BLAS_CORE := $(shell grep -qw avx512f /proc/cpuinfo 2>/dev/null && echo SkylakeX)

test: build
	$(if $(TEST_BLAS_CORE),OPENBLAS_CORETYPE=$(TEST_BLAS_CORE)) ctest --test-dir $(BUILD_DIR) --output-on-failure --no-tests=error

run: build
	bash scripts/run.sh output

# Benchmarks (never part of test), see docs/BENCHMARKS.md: solver_bench, sweep_bench,
# curved_bench, curved_speed_bench and fold_bench (on one core), replay_bench, mesh_bench and others write CSV into
# docs/bench/, each timed (bench_wall_time.csv); then the charts into docs/images/bench/ and the
# tables of docs/BENCHMARKS.md (Debian's python3 with python3-matplotlib).
bench: build
	bash scripts/run_bench.sh $(BUILD_DIR)

# libFuzzer targets of test/fuzz/ with ASan + UBSan (clang-14, into build-fuzz/), each for
# FUZZ_SECONDS, one after the other; crashes land in test/fuzz/crashes/ (docs/RELIABILITY.md).
FUZZ_SECONDS ?= 60
fuzz: deps
	FUZZ_SECONDS=$(FUZZ_SECONDS) JOBS=$(JOBS) bash scripts/fuzz.sh

clean:
	rm -rf $(BUILD_DIR) output
