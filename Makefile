# brick_pose: the two commands of the README, and a few helpers.
#
#   make demo   install what is missing, build, run the demo on the synthetic D415
#   make test   install what is missing, build, run every unit test (also under ASan/UBSan),
#               every fuzz target for 20 s, and every rostest
#   make bench  build and run the accuracy/speed benchmarks against ground truth
#   make fuzz   longer fuzzing (FUZZ_SECONDS); make soak   the 10-minute soak (not in CI)

SHELL := /bin/bash
export PATH := /usr/bin:/bin:$(PATH)

.PHONY: all deps build test demo bench fuzz soak clean

all: build

deps:
	@scripts/install_deps.sh

build: deps
	@scripts/build.sh

# The AddressSanitizer + UBSan build of the core runs first (ws/sanitize): its
# unit tests, then each fuzz target for SANITIZE_FUZZ_SECONDS (20); then
# every unit test and rostest of the catkin build.
test: build
	@scripts/sanitize.sh >ws/sanitize.log 2>&1 && tail -3 ws/sanitize.log || \
	  { tail -40 ws/sanitize.log; echo "brick_pose: the sanitizer build or its tests FAILED (ws/sanitize.log)"; exit 1; }
	@scripts/run_tests.sh

demo: build
	@scripts/demo.sh

bench: build
	@scripts/bench.sh

# Longer runs than make test's: libFuzzer targets for FUZZ_SECONDS (30) each,
# and the 30 Hz soak of the demo pipeline for SOAK_MINUTES (10, not in CI).
fuzz: deps
	@scripts/fuzz.sh

soak: build
	@bench/soak.sh

clean:
	rm -rf ws
