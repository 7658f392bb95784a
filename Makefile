# The two commands of the README: `make run` and `make test`. Both install what is missing first.
SHELL := /bin/bash
ROOT := $(abspath .)
# The pipeline's command (src/hideseek_pipeline), run from the checkout: it needs no build.
PIPELINE := PYTHONPATH=$(ROOT)/src/hideseek_pipeline/python /usr/bin/python3 -m hideseek_pipeline
CATKIN := source scripts/env.sh && catkin_make -DCMAKE_BUILD_TYPE=Release \
	-DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 -DCATKIN_ENABLE_TESTING=ON
JOBS ?= $(shell nproc)

.PHONY: deps build run test bench reproduce sweep clean test-sanitize fuzz

deps:
	scripts/install_deps.sh

build: deps
	$(CATKIN) -j$(JOBS)

# The basic game: rviz when a display is available, otherwise headless with one line per episode.
run: build
	source scripts/env.sh && src/hideseek_world/scripts/run_basic.sh

# Both pause a running sweep (hideseek_pipeline sweep) while they run, and resume it after.
test: build
	$(PIPELINE) test

bench: build
	$(PIPELINE) bench

# Table 2, Table 3, the claims and the figures across training seeds, from the committed records, into
# docs/report (hideseek_pipeline report --from-scratch evaluates and analyses the shipped policies anew).
reproduce: build
	$(PIPELINE) report

# The sweep's queue (config/sweep.yaml's phases) in the background, each phase from its own worktree
# at its pinned commit: $(PIPELINE) sweep status | pause | resume | stop | --help.
sweep: deps
	$(PIPELINE) sweep start

# The cores and their gtests under AddressSanitizer and UndefinedBehaviorSanitizer (clang, its own
# build_sanitize/); make fuzz runs them too, then each fuzz target for FUZZ_SECONDS
# (docs/reliability.md). Neither is part of make test: CI's 90 minutes hold make test, not a second
# build of every core under the sanitizers.
test-sanitize: deps
	test/sanitize/test_sanitize.sh

fuzz: deps
	test/sanitize/test_sanitize.sh
	test/sanitize/fuzz.sh

clean:
	rm -rf build devel install build_sanitize devel_sanitize
