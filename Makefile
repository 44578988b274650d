# Two commands do everything on a fresh Debian 12 machine:
#   make test    install missing packages, configure, build, run the whole test suite
#   make bench   same set-up, then run the default benchmark and write reports/
BUILD ?= build
JOBS  ?= 2
# hypre is an OpenMP build and OpenBLAS threads: one thread each unless asked otherwise.
export OMP_NUM_THREADS ?= 1
export OPENBLAS_NUM_THREADS ?= 1

.PHONY: all deps configure build test bench clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

test: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	@bash scripts/bench.sh $(BUILD)

clean:
	rm -rf $(BUILD)
