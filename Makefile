# brick_pose: the two commands of the README, and a few helpers.
#
#   make demo   install what is missing, build, run the demo on the synthetic D415
#   make test   install what is missing, build, run every unit test and rostest
#   make bench  build and run the accuracy/speed benchmarks against ground truth

SHELL := /bin/bash
export PATH := /usr/bin:/bin:$(PATH)

.PHONY: all deps build test demo bench clean

all: build

deps:
	@scripts/install_deps.sh

build: deps
	@scripts/build.sh

test: build
	@scripts/run_tests.sh

demo: build
	@scripts/demo.sh

bench: build
	@scripts/bench.sh

clean:
	rm -rf ws
