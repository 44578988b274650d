# Two commands do everything on a fresh Debian 12 machine:
#   make test    install missing packages, configure, build, run the whole test suite
#   make bench   same set-up, then the paper's benchmark (Tables 1-3, block with strips) in
#                a new reports/paper-tables-<revision>/: 83 min at levels 0-1 on 2 AVX2 cores
#                (BENCH_LEVELS=0,1,2 for the full tables; scripts/paper-tables.sh lists the
#                settings); scripts/publish-report.sh then replaces reports/paper-tables/
#   make bench-all   every built-in scene x every backend in reports/latest/, and the
#                large-sliding reports (ironing, crossed tubes)
BUILD ?= build
JOBS  ?= 2
# hypre is an OpenMP build and OpenBLAS threads: one thread each unless asked otherwise.
export OMP_NUM_THREADS ?= 1
export OPENBLAS_NUM_THREADS ?= 1

.PHONY: all deps configure build test bench bench-all clean

all: build

deps:
	@bash scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release > /dev/null

build: configure
	@cmake --build $(BUILD) -j $(JOBS)

# OpenBLAS picks its kernels per CPU when it loads, and they round differently, so the same
# run's Krylov counts differ between machines (ironing-2d with schur-lu, level 0 --quick:
# 2 786 GMRES iterations with the SkylakeX kernels an AVX-512 machine gets, 2 417 with the
# Haswell ones, on the same AMD EPYC). The tests pin the Haswell kernels on every x86-64
# CPU with AVX2, so that the iteration baseline holds from one machine to the next;
# benchmarks keep the kernels that OpenBLAS finds fastest.
TEST_BLAS_CORE := $(shell grep -qw avx2 /proc/cpuinfo 2>/dev/null && echo Haswell)

test: build
	@cd $(BUILD) && $(if $(TEST_BLAS_CORE),OPENBLAS_CORETYPE=$${OPENBLAS_CORETYPE:-$(TEST_BLAS_CORE)}) \
	  ctest --output-on-failure -j $(JOBS)

bench: build
	@bash scripts/paper-tables.sh $(BUILD)

bench-all: build
	@bash scripts/bench-all-scenes.sh $(BUILD)

clean:
	rm -rf $(BUILD)
