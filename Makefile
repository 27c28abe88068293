# bhnsid: the two commands of the quick start are `make run` and `make test`.
BUILD      ?= build
BUILD_ASAN ?= build-asan
BUILD_FUZZ ?= build-fuzz
JOBS       ?= $(shell nproc)
PREFIX     ?= /usr/local
FUZZ_SECONDS ?= 30

CMAKE_FLAGS = -G Ninja -DCMAKE_BUILD_TYPE=Release

.PHONY: all deps build run test test-viz test-slurm test-asan fuzz fuzz-check clean install

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

run: build
	$(BUILD)/bin/bhnsid run parfiles/quickstart.yaml --force

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# ParaView (pvbatch, on a virtual X display) opens a run's data.xdmf, probes it against h5py and
# renders the equatorial plane (tests/viz/check_viz.py).
test-viz: build
	@scripts/install-deps.sh --viz
	mkdir -p $(BUILD)/test-viz
	/usr/bin/python3 tests/viz/check_viz.py $(BUILD)/bin/bhnsid . $(BUILD)/test-viz

# A tiny sequence on a real one-node SLURM cluster (slurmctld, slurmd, munge on this machine, as
# root) against the local pool (tests/slurm/test_slurm.py); the cluster is stopped afterwards.
test-slurm: build
	@scripts/install-deps.sh --slurm
	scripts/slurm-local.sh start
	/usr/bin/python3 tests/slurm/test_slurm.py $(BUILD)/bin . $(BUILD)/test-slurm; rc=$$?; \
		scripts/slurm-local.sh stop; exit $$rc

$(BUILD_ASAN)/build.ninja: | deps
	cmake -S . -B $(BUILD_ASAN) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBHNSID_SANITIZE=ON

test-asan: deps $(BUILD_ASAN)/build.ninja
	cmake --build $(BUILD_ASAN) -j $(JOBS)
	cd $(BUILD_ASAN) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
		ctest --output-on-failure -j $(JOBS)

$(BUILD_FUZZ)/build.ninja: | deps
	CXX=clang++ cmake -S . -B $(BUILD_FUZZ) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBHNSID_FUZZ=ON

fuzz: deps $(BUILD_FUZZ)/build.ninja
	cmake --build $(BUILD_FUZZ) -j $(JOBS) --target fuzz_parfile
	mkdir -p $(BUILD_FUZZ)/corpus
	ASAN_OPTIONS=detect_leaks=1 $(BUILD_FUZZ)/bin/fuzz_parfile -max_total_time=$(FUZZ_SECONDS) -timeout=1 \
		-rss_limit_mb=2048 $(BUILD_FUZZ)/corpus tests/fuzz/corpus

# CI: the fuzz target must keep building with clang, replay the kept corpus and survive a short run.
fuzz-check: deps $(BUILD_FUZZ)/build.ninja
	cmake --build $(BUILD_FUZZ) -j $(JOBS) --target fuzz_parfile
	mkdir -p $(BUILD_FUZZ)/corpus
	ASAN_OPTIONS=detect_leaks=1 $(BUILD_FUZZ)/bin/fuzz_parfile -max_total_time=$(FUZZ_SECONDS) -timeout=1 \
		-rss_limit_mb=2048 $(BUILD_FUZZ)/corpus tests/fuzz/corpus

# The solver (bin/bhnsid, lib/libbhnsid_core.so, lib/bhnsid/ plugins) and the reader (header,
# library, bhnsid_reader.pc, bhnsid-export, the Python module); the reader alone:
# cmake --install build --prefix DIR --component reader.
install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

clean:
	rm -rf $(BUILD) $(BUILD_ASAN) $(BUILD_FUZZ)
