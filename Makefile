# brick_pose: the two commands of the README, and a few helpers.
#
#   make demo   install what is missing, build, run the demo on the synthetic D415
#   make test   install what is missing, build, run every unit test (also under ASan/UBSan) and rostest
#   make bench  build and run the accuracy/speed benchmarks against ground truth
#   make fuzz, make soak   the reliability runs (not in CI)

SHELL := /bin/bash
export PATH := /usr/bin:/bin:$(PATH)

.PHONY: all deps build test demo bench fuzz soak clean

all: build

deps:
	@scripts/install_deps.sh

build: deps
	@scripts/build.sh

# The AddressSanitizer + UBSan build of the core and its unit tests runs
# first (ws/sanitize), then every unit test and rostest of the catkin build.
test: build
	@scripts/sanitize.sh >ws/sanitize.log 2>&1 && tail -3 ws/sanitize.log || \
	  { tail -40 ws/sanitize.log; echo "brick_pose: the sanitizer build or its tests FAILED (ws/sanitize.log)"; exit 1; }
	@scripts/run_tests.sh

demo: build
	@scripts/demo.sh

bench: build
	@scripts/bench.sh

# Not part of make test: libFuzzer targets for FUZZ_SECONDS (30) each, and the
# 30 Hz soak of the demo pipeline for SOAK_MINUTES (10).
fuzz: deps
	@scripts/fuzz.sh

soak: build
	@bench/soak.sh

clean:
	rm -rf ws
