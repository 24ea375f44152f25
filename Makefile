# afv -- Active Finite Voronoi model.  Plain C99 + libm.
#
#   make            the program ./afv and the library libafv.a
#   make test       build and run the test suite (ends "N passed, M failed")
#   make run        build, then run a short default simulation
#   make bench      build and run the benchmark
#   make bench-compare  per-cell cost against N = 400 (and threads, OPENMP=1)
#   make fuzz       every libFuzzer harness fuzz/fuzz_*.c for FUZZ_SECONDS s
#                   (default 60; clang; make -j2 fuzz runs two at a time)
#   make plain      reference/afv_plain: the model in one plain file, to read
#   make twins      the library against the plain file (test/twins.c)
#   make protocol-check  the paper's protocol at N = 400 (~1 hour, 2 cores)
#   make relax-cost  relaxation of the authors' start: CPU and memory against N
#   make diagram-budget  a 20-job sample of the full diagram, its projected
#                   CPU hours (doc/performance.md)
#   make shared     the shared library libafv.so (for Python's ctypes, ...)
#   make install    bin/afv, lib/libafv.a, lib/libafv.so.VERSION (and its
#                   links libafv.so.MAJOR, libafv.so), include/afv.h,
#                   lib/pkgconfig/afv.pc, share/man/man1/afv.1, the Python
#                   package lib/python3/dist-packages/afv/, share/doc/afv/
#                   (README, CHANGELOG, LICENSE, CITATION.cff, examples/)
#                   under $(DESTDIR)$(PREFIX) (PREFIX defaults to /usr/local)
#   make uninstall  removes exactly what make install created
#   make python-test  the Python package's tests, with and without numpy
#   make python-pip-test  the same against the package pip installs
#                   (python3 -m pip install ./python, in a new venv)
#   make -j2 paper SCALE=smoke|quick|paper|full OUT=DIR   reproduce the paper's
#                   figures and claims table (see "Reproducing the paper")
#   make lambda LAMBDA_OUT=DIR  the phase diagram at Lambda 0 and 0.5 and the
#                   time step at Lambda 0 (doc/reproduction/lambda.md)
#   make web        web/afv.wasm: the library as WebAssembly for the page
#                   web/index.html (clang, lld, wasi-libc; doc/web.md)
#   make test-web   the page in headless chromium against afv run
#   make clean
#
# CC and CFLAGS may be overridden (make CC=clang, make CC=tcc).
# OPENMP=1 adds -fopenmp (optional; the default build is plain C99).

# -O3 and -fno-math-errno (sqrt inline, without the errno branch; afv never
# reads errno) take 2-4% fewer instructions per step than -O2 (callgrind)
# and give the same result bits: neither changes floating-point semantics
# (-std=c99 also keeps gcc from contracting a*b+c into an fma).
# -DNDEBUG: the library's asserts of its invariants (doc/design.md) cost
# 9% more instructions per step; a build with its own CFLAGS (make
# CFLAGS="-O1 -g -std=c99", .ci/run's sanitizer section) checks them.
CC      ?= cc
CFLAGS  ?= -O3 -fno-math-errno -std=c99 -pedantic -Wall -Wextra -DNDEBUG
LDLIBS  = -lm
ifeq ($(OPENMP),1)
CFLAGS  += -fopenmp
LDLIBS  += -fopenmp
endif

# The library, one file per idea (doc/reference.md has the reading order);
# afv.h is the API and afv_config.h its constants (statuses, tolerances),
# both installed; afv_internal.h, fastmath.h and rng.h are shared by its
# files only, and afv_tool.h holds what the library does for the program
# alone (line readers, checkpoints, line plots): none of these is installed.
LIB_SRC  = neighbours.c geom.c fastmath.c afv.c dynamics.c rng.c \
           analysis.c svg.c io.c api.c relax_fire.c
LIB_OBJ  = $(LIB_SRC:.c=.o)
LIB_H    = afv.h afv_config.h afv_internal.h afv_tool.h fastmath.h rng.h
# What the program computes from many runs, and the library does not:
# phase diagrams and the paper's fits (cmd/fits.h); the tests and
# tools/lambda_plot link them beside the library.
FITS_SRC = cmd/phase.c cmd/fits.c
FITS_OBJ = $(FITS_SRC:.c=.o)
TEST_SRC = test/main.c test/fixtures.c $(wildcard test/test_*.c)

.PHONY: print-lib-sources all test run bench bench-quick bench-compare fuzz twins plain \
        protocol-check shared python-test python-pip-test install uninstall \
        clean FORCE \
        paper paper-sweeps paper-grid paper-fss paper-claims convergence \
        relax-cost diagram-budget diagram-budget-sweep diagram-budget-project lambda \
        model model-table test-model-study web test-web

all: afv libafv.a

# Every object and program depends on .build-flags, which holds the
# compiler and flags of the last build and is rewritten only when they
# change: switching CC, CFLAGS or OPENMP rebuilds everything.  (Else the
# builds mix: after a serial build, make OPENMP=1 test linked the serial
# library into an OpenMP test program; the other way round, the serial
# programs failed to link the OpenMP library.)
BUILD_FLAGS = $(CC) $(CFLAGS) $(LDLIBS)

.build-flags: FORCE
	@printf '%s\n' '$(BUILD_FLAGS)' | cmp -s - $@ \
	  || printf '%s\n' '$(BUILD_FLAGS)' > $@

FORCE:

$(LIB_OBJ): $(LIB_H)

# (rebuilt whole, and when the Makefile changes: ar would keep the members
# of files no longer listed)
libafv.a: $(LIB_OBJ) Makefile
	rm -f $@
	$(AR) rcs $@ $(LIB_OBJ)

# The library's sources, for scripts that build it their own way
# (test/twins_mutants.sh): make -s print-lib-sources
print-lib-sources:
	@echo $(LIB_SRC)

# The program, in cmd/: main.c dispatches to the commands (cmd/cli.h lists
# their files); they include the library's headers from the top level.
CLI_SRC  = $(addprefix cmd/,main.c cli.c inspect.c run.c run_config.c \
           run_compute.c run_dir.c run_resume.c report.c sweep.c collect.c \
           collect_figures.c sweep_slurm.c \
           paper.c paper_data.c paper_compare.c claims.c dt_study.c \
           figure.c) $(FITS_SRC)
CLI_OBJ  = $(CLI_SRC:.c=.o)

afv: $(CLI_OBJ) libafv.a .build-flags
	$(CC) $(CFLAGS) -o $@ $(CLI_OBJ) libafv.a $(LDLIBS)

%.o: %.c $(LIB_H) .build-flags
	$(CC) $(CFLAGS) -c -o $@ $<

$(CLI_OBJ): cmd/cli.h cmd/fits.h
cmd/paper.o cmd/paper_data.o cmd/paper_compare.o cmd/claims.o cmd/dt_study.o: cmd/paper.h \
  cmd/figure.h
cmd/collect.o cmd/collect_figures.o: cmd/collect.h cmd/figure.h
cmd/figure.o: cmd/figure.h
cmd/sweep.o cmd/sweep_slurm.o: cmd/sweep.h
$(filter cmd/run%,$(CLI_OBJ)): cmd/run.h

cmd/%.o: cmd/%.c $(LIB_H) cmd/cli.h cmd/fits.h .build-flags
	$(CC) $(CFLAGS) -I. -c -o $@ $<

# The git commit of the sources, when built from a git checkout ("-dirty"
# with uncommitted changes): cmd/cli.c records it in params.txt, log.txt and
# afv --version.  A build from a tarball (no git) records the version only.
# .build-commit changes only with the commit, so only cmd/cli.o is rebuilt.
AFV_COMMIT := $(shell git rev-parse --short=12 HEAD 2>/dev/null)$(shell \
  git rev-parse --git-dir >/dev/null 2>&1 && ! git diff-index --quiet HEAD \
  -- 2>/dev/null && echo -dirty)

.build-commit: FORCE
	@printf '%s\n' '$(AFV_COMMIT)' | cmp -s - $@ \
	  || printf '%s\n' '$(AFV_COMMIT)' > $@

cmd/cli.o: cmd/cli.c $(LIB_H) cmd/cli.h .build-flags \
           .build-commit
	$(CC) $(CFLAGS) -I. $(if $(AFV_COMMIT),-DAFV_COMMIT='"$(AFV_COMMIT)"') \
	  -c -o $@ cmd/cli.c

# The shared library: the same sources compiled again as position-
# independent code into *.pic.o, so the static library and the program
# keep their objects (and their speed) exactly as without it.
PIC_OBJ  = $(LIB_SRC:.c=.pic.o)

%.pic.o: %.c $(LIB_H) .build-flags
	$(CC) $(CFLAGS) -fPIC -c -o $@ $<

# Its SONAME is libafv.so.MAJOR (AFV_VERSION_MAJOR in afv.h): a program
# linked against it loads that name, which make install points at
# libafv.so.MAJOR.MINOR.PATCH.
libafv.so: $(PIC_OBJ)
	$(CC) $(CFLAGS) -shared -Wl,-soname,libafv.so.$(VERSION_MAJOR) -o $@ \
	  $(PIC_OBJ) $(LDLIBS)

shared: libafv.so

# The Python module's tests (python/test_afv.py), with numpy if installed
# and without: python/check_driver runs the same scenario through afv.h.
PYTHON ?= python3

python/check_driver: python/check_driver.c libafv.a $(LIB_H) .build-flags
	$(CC) $(CFLAGS) -I. -o $@ python/check_driver.c libafv.a $(LDLIBS)

python-test: afv libafv.so python/check_driver
	$(PYTHON) python/test_afv.py --driver python/check_driver --afv ./afv
	$(PYTHON) python/test_afv.py --driver python/check_driver --afv ./afv \
	  --no-numpy

# The package as pip installs it (python/pyproject.toml, python/setup.py):
# into a new virtual environment that sees the system's site-packages
# (setuptools and wheel, numpy if installed), offline, then its tests from
# another directory against it, with numpy (if installed) and without.
python-pip-test: afv python/check_driver
	@d=$$(mktemp -d) && set -e && \
	$(PYTHON) -m venv --system-site-packages $$d/venv && \
	$$d/venv/bin/python -m pip install -q --no-build-isolation --no-index \
	  ./python && \
	for numpy in "" --no-numpy; do (cd $$d && venv/bin/python \
	  $(CURDIR)/python/test_afv.py --installed $$numpy \
	  --driver $(CURDIR)/python/check_driver --afv $(CURDIR)/afv); done; \
	rm -rf $$d

test/run_tests: $(TEST_SRC) test/test.h $(FITS_OBJ) libafv.a $(LIB_H) \
                 cmd/fits.h .build-flags
	$(CC) $(CFLAGS) -I. -o $@ $(TEST_SRC) $(FITS_OBJ) libafv.a $(LDLIBS)

# The asserts of the library (its invariants, its functions'
# preconditions) are compiled out by -DNDEBUG; make test also runs the
# invariants suite in a build that keeps them: the library and the tests
# compiled again with -UNDEBUG into test/assert/.
ASSERT_OBJ = $(patsubst %.c,test/assert/%.o,$(LIB_SRC) $(FITS_SRC))

test/assert/%.o: %.c $(LIB_H) cmd/fits.h .build-flags
	@mkdir -p $(dir $@)
	$(CC) $(CFLAGS) -UNDEBUG -I. -c -o $@ $<

test/run_tests_assert: $(TEST_SRC) test/test.h $(ASSERT_OBJ) .build-flags
	$(CC) $(CFLAGS) -UNDEBUG -I. -o $@ $(TEST_SRC) $(ASSERT_OBJ) $(LDLIBS)

test: afv test/run_tests test/run_tests_assert
	@sh test/run.sh $(WEB_CC)

# The main job: afv run with its defaults (the paper's protocol and
# parameters, 400 cells, P0 4.8, v0 0.5, 10000 steps; afv run --help), into
# out/run/ (replaced on every make run).  No key is overridden here, so
# make run and afv run always agree.
run: afv
	rm -rf out/run && mkdir -p out
	./afv run --out out/run
	@echo "snapshots:   out/run/snap_*.svg, out/run/final.svg"
	@echo "observables: out/run/observables.csv (trajectory: out/run/trajectory.dat)"
	@echo "next:        ./afv analyze out/run --lag 10  (writes out/run/analysis/)"

# The benchmark (test/bench.c): one line per state and N, see its header.
BENCH_STATES = random cluster

test/bench: test/bench.c libafv.a $(LIB_H) .build-flags
	$(CC) $(CFLAGS) -I. -o $@ test/bench.c libafv.a $(LDLIBS)

bench: test/bench
	@st=0; for s in $(BENCH_STATES); do for n in 400 4000 40000 400000; do \
	  ./test/bench $$s $$n || st=1; done; done; exit $$st

bench-quick: test/bench
	@st=0; for s in $(BENCH_STATES); do for n in 400 40000; do \
	  ./test/bench $$s $$n || st=1; done; done; exit $$st

# Comparisons timed in turn within one process (see test/bench.c): the
# per-cell cost at N = 40000 and 400000 over N = 400 at the same age (one
# thread), and, in an OpenMP build, 1 against 2 threads at N = 40000.
bench-compare: test/bench
	@st=0; for s in $(BENCH_STATES); do for n in 40000 400000; do \
	  OMP_NUM_THREADS=1 ./test/bench --vs-400 $$s $$n || st=1; done; done; \
	if [ "$(OPENMP)" = 1 ]; then for s in $(BENCH_STATES); do \
	  ./test/bench --threads $$s 40000 || st=1; done; fi; exit $$st

# ---- the page: the library as WebAssembly (doc/web.md) ---------------------
# web/afv.wasm is the library's own sources (LIB_SRC, whatever they are
# named) and the glue web/afv_web.c, compiled by clang for wasm32-wasi
# against Debian's wasi-libc and linked by lld (wasm-ld) as a reactor (no
# main; the page calls _initialize, then the glue).  -ffp-contract=off:
# no a*b+c fused, as gcc's -std=c99 build of afv does not fuse either, so
# the page's arithmetic is the program's.  web/index.html and web/afv.js
# are the page; python3 -m http.server -d web -b 127.0.0.1 serves it.
WEB_CC      = clang
WEB_CFLAGS  = --target=wasm32-wasi -O3 -std=c99 -pedantic -Wall -Wextra \
              -fno-math-errno \
              -ffp-contract=off -DNDEBUG -mexec-model=reactor
WEB_EXPORTS = web_reset web_relax_get web_scratch web_step web_bad_cell \
              web_bad_disp web_set web_observe web_shapes web_shape_data \
              afv_strerror
WEB_LDFLAGS = $(addprefix -Wl$(comma)--export=,$(WEB_EXPORTS)) \
              -Wl,--allow-undefined-file=web/imports.txt
comma := ,

web: web/afv.wasm

# (web/.build-flags: as .build-flags, the wasm is rebuilt when they change)
WEB_BUILD = $(WEB_CC) $(WEB_CFLAGS) $(WEB_LDFLAGS)

web/.build-flags: FORCE
	@printf '%s\n' '$(WEB_BUILD)' | cmp -s - $@ \
	  || printf '%s\n' '$(WEB_BUILD)' > $@

web/afv.wasm: $(LIB_SRC) web/afv_web.c web/imports.txt $(wildcard *.h) \
              web/.build-flags
	$(WEB_CC) $(WEB_CFLAGS) -I. -o $@.tmp web/afv_web.c $(LIB_SRC) \
	  $(WEB_LDFLAGS)
	mv $@.tmp $@

# The page in a real browser (test/web_check.py): serves web/ on
# 127.0.0.1, drives Debian's chromium headless through its DevTools
# protocol, loads each preset, compares the page's numbers with afv run's,
# writes a screenshot per preset into out/web/, measures the frame rate.
test-web: afv web
	$(PYTHON) test/web_check.py --afv ./afv --web web --out out/web
# (make test prints one line about it: test/web_needs.sh names the Debian
# packages it lacks, if any.)

# ---- fuzzing: clang's libFuzzer -------------------------------------------
# Every fuzz/fuzz_NAME.c is a harness (LLVMFuzzerTestOneInput), linked with
# the library and cmd/cli.c built apart in fuzz/build/ with AddressSanitizer and
# UndefinedBehaviorSanitizer (any report is a crash).  make fuzz runs each
# for FUZZ_SECONDS s from its committed seed corpus fuzz/corpus/NAME/ (see
# fuzz/run.sh) and fails on any crash, which it leaves in fuzz/build/.
FUZZ_CC      = clang
FUZZ_SECONDS = 60
# (afv_lines reads 61-byte blocks and refuses lines over 3000 bytes here,
# so that inputs of a few KiB reach lines across blocks and over the limit)
FUZZ_CFLAGS  = -O1 -g -std=c99 -fno-omit-frame-pointer \
               -fsanitize=address,undefined -fno-sanitize-recover=all \
               -DAFV_LINES_BLOCK=61 -DAFV_LINE_MAX=3000
FUZZ_NAMES   = $(patsubst fuzz/fuzz_%.c,%,$(wildcard fuzz/fuzz_*.c))
FUZZ_OBJ     = $(patsubst %.c,fuzz/build/%.o,$(LIB_SRC) cmd/cli.c $(FITS_SRC))

fuzz/build/%.o: %.c $(LIB_H) cmd/cli.h cmd/fits.h
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -I. -fsanitize=fuzzer-no-link -c -o $@ $<

fuzz/build/libafv_fuzz.a: $(FUZZ_OBJ)
	$(AR) rcs $@ $(FUZZ_OBJ)

# (cmd/run*.c: the config and collect harnesses include them; cmd/collect*.c
# and cmd/figure.c: the collect harness)
fuzz/build/fuzz_%: fuzz/fuzz_%.c fuzz/build/libafv_fuzz.a $(wildcard fuzz/*.h) \
                   $(wildcard cmd/run*.c) cmd/run.h $(wildcard cmd/collect*.c) \
                   cmd/collect.h cmd/figure.c cmd/figure.h cmd/cli.h \
                   $(LIB_H)
	$(FUZZ_CC) $(FUZZ_CFLAGS) -fsanitize=fuzzer -I. -o $@ $< \
	  fuzz/build/libafv_fuzz.a -lm

fuzz-%: fuzz/build/fuzz_%
	@bash fuzz/run.sh $* $(FUZZ_SECONDS)

fuzz: $(addprefix fuzz-,$(FUZZ_NAMES))

# The plain file (reference/afv_plain.c): the whole model in one C99 file
# for reading, built alone (no library): ./reference/afv_plain [N [P0 [v0
# [steps [seed]]]]] prints E and N_GC/N as a tissue runs.
reference/afv_plain: reference/afv_plain.c .build-flags
	$(CC) $(CFLAGS) -o $@ reference/afv_plain.c $(LDLIBS)

plain: reference/afv_plain

# The twin check (test/twins.c): the library against the plain file, on
# the test configurations and random ones (shapes, energy and forces to
# 1e-12, 100 Euler steps to 1e-9 l); then test/twins_mutants.sh shows that
# one wrong sign in either makes it fail.
test/twins: test/twins.c test/fixtures.c reference/afv_plain.c test/test.h \
            libafv.a $(LIB_H) .build-flags
	$(CC) $(CFLAGS) -I. -o $@ test/twins.c test/fixtures.c libafv.a $(LDLIBS)

twins: test/twins
	./test/twins
	sh test/twins_mutants.sh $(CC)

# ---- Reproducing the paper --------------------------------------------------
# make -j2 paper SCALE=smoke|quick|paper|full OUT=DIR: tools/paper_sweeps.sh writes
# two sweeps (afv sweep) into OUT: grid (the (P0, v0) plane) and fss (the
# finite-size study); their runners are sub-makes that share make's job
# slots (-jN: N runs at a time in all), so the two run side by side; then
# afv collect tables each sweep and afv paper OUT draws the figures
# (OUT/figures/*.svg) and writes OUT/claims.csv.  A killed make resumes
# where it stopped.  SCALE=full writes the paper's 1400-job grid: run its
# runs where there are cores (sh OUT/grid/slurm.sh, or make -C OUT/grid
# -j N), then make paper SCALE=full OUT=DIR again for the figures.
# make paper-sweeps SCALE=... OUT=DIR writes the sweeps and runs nothing.
# Each claim is judged against dt from DT_TABLE (afv paper --dt-table):
# by default the committed dt study (doc/reproduction/model/dt_table.csv)
# at SCALE=paper and full, whose runs have its length; none at smoke and
# quick, whose short runs the study does not measure (their dt_verdict
# says not measured).  DT_TABLE=FILE sets it, DT_TABLE= leaves it out.
# make paper-claims rejudges the committed record (RECORD, its
# grid_table.csv and claims.csv) against DT_TABLE: how the record's
# claims.csv is regenerated when a rule or the dt study changes.
SCALE ?= quick
OUT   ?= paper
RECORD ?= doc/reproduction/paper
DT_STUDY = doc/reproduction/model/dt_table.csv
DT_TABLE ?= $(if $(filter paper full,$(SCALE)),$(DT_STUDY))

paper: paper-grid paper-fss
	st=0; ./afv collect $(OUT)/grid || st=$$?; test $$st -le 1
	st=0; ./afv collect $(OUT)/fss || st=$$?; test $$st -le 1
	./afv paper $(OUT) $(if $(DT_TABLE),--dt-table $(DT_TABLE))

paper-claims: afv
	./afv paper --claims-from $(RECORD) --dt-table $(or $(DT_TABLE),$(DT_STUDY))

paper-sweeps: afv
	sh tools/paper_sweeps.sh $(SCALE) $(OUT) $(CURDIR)/afv

paper-grid: paper-sweeps
	+$(MAKE) -C $(OUT)/grid

paper-fss: paper-sweeps
	+$(MAKE) -C $(OUT)/fss

# The detachment convergence study (doc/reproduction/convergence.md):
# make convergence CONV_OUT=DIR runs tools/convergence.sh (about 1 CPU-hour;
# resumable) and writes DIR/convergence.csv, verdicts.csv and figures/.
CONV_OUT ?= convergence

tools/convergence_plot: tools/convergence_plot.c libafv.a $(LIB_H) \
                        .build-flags
	$(CC) $(CFLAGS) -I. -o $@ tools/convergence_plot.c libafv.a $(LDLIBS)

convergence: afv tools/convergence_plot
	sh tools/convergence.sh $(CONV_OUT)

# The model study (doc/reproduction/model/README.md): make model MODEL_OUT=DIR
# runs tools/model_sweeps.sh (about 15 CPU-hours; resumable, JOBS=K queues),
# then tables and draws what has finished into doc/reproduction/model/.
# make model-table tables and draws without running anything.
MODEL_OUT ?= model

tools/model_plot: tools/model_plot.c $(FITS_OBJ) libafv.a $(LIB_H) \
                  cmd/fits.h .build-flags
	$(CC) $(CFLAGS) -I. -o $@ tools/model_plot.c $(FITS_OBJ) libafv.a \
	  $(LDLIBS)

tools/csd_exponent: tools/csd_exponent.c $(FITS_OBJ) libafv.a $(LIB_H) \
                    cmd/fits.h .build-flags
	$(CC) $(CFLAGS) -I. -o $@ tools/csd_exponent.c $(FITS_OBJ) libafv.a \
	  $(LDLIBS)

model: afv tools/model_plot tools/csd_exponent
	sh tools/model_sweeps.sh $(MODEL_OUT)
	sh tools/model_table.sh $(MODEL_OUT) doc/reproduction/model

model-table: afv tools/model_plot tools/csd_exponent
	sh tools/model_table.sh $(MODEL_OUT) doc/reproduction/model

# tools/model_table.sh (and tools/model_cap.sh) on a mini study of a few
# short runs, partly run (test/model_study.sh, about 10-15 s: .ci/run)
test-model-study: afv tools/model_plot tools/csd_exponent
	sh test/model_study.sh ./afv

# Cost of relaxing the authors' start against N (doc/performance.md,
# "Relaxation: cost against N"): test/bench --relax-vs-400 relaxes the
# square at each N of RELAX_NS and P0 = 4 and 8, with whole 400-cell
# relaxations timed inside the same process, and prints the CPU time per
# cell and step of both, their ratio and the peak memory (about 10 min at
# the defaults on an idle core; RELAX_NS=25600 takes about an hour per P0).
RELAX_NS    ?= 1600 6400

relax-cost: test/bench
	@for n in $(RELAX_NS); do for p0 in 4 8; do \
	  ./test/bench --relax-vs-400 $$n $$p0 || exit 1; done; done

# The full diagram's budget (doc/performance.md): make diagram-budget
# writes a 20-job sample of the full grid into BUDGET_OUT (afv sweep: P0
# 4, 5.2, 6.4, 7.6, 8.8 x v0 0, 0.9, 1.8, 2.7, 1 seed, the paper's 10^6
# steps and analysis, as tools/paper_sweeps.sh's full scale), runs it
# (resumable: make it again after a kill; about 1 CPU-hour, so run it
# in the background: nohup make -j2 diagram-budget > budget.log 2>&1 &),
# then tools/diagram_budget.sh projects the 1400-job diagram's CPU hours
# from its runs.  make diagram-budget-project BUDGET_OUT=SWEEP projects
# from the finished runs of any sweep, and runs nothing new.
BUDGET_OUT ?= budget

diagram-budget-sweep: afv
	@if [ ! -d "$(BUDGET_OUT)" ]; then \
	  ./afv sweep --out "$(BUDGET_OUT)" --P0 4,5.2,6.4,7.6,8.8 \
	    --v0 0,0.9,1.8,2.7 --seeds 1 --N 400 --steps 1000000 \
	    --frame_every 1000 --checkpoint_every 100000 --integrator euler \
	    --dt 0.01 --cap 0 --sample_every 100 --svg_every 0 --quiet 1 \
	    --steady-from 1000 --lag 5000; \
	else echo "$(BUDGET_OUT): kept (its runs resume)"; fi

diagram-budget: diagram-budget-sweep
	+$(MAKE) -C $(BUDGET_OUT)
	sh tools/diagram_budget.sh $(BUDGET_OUT) ./afv

diagram-budget-project: afv
	sh tools/diagram_budget.sh $(BUDGET_OUT) ./afv

# The Lambda study (doc/reproduction/lambda.md): make lambda LAMBDA_OUT=DIR
# runs tools/lambda.sh: the quick grid at Lambda = 0 and 0.5 (make -j2;
# resumable), one figure per Lambda with the three boundaries (0.2 from
# doc/reproduction/grid_table.csv) and the dt check at Lambda = 0.
LAMBDA_OUT ?= lambda

tools/lambda_plot: tools/lambda_plot.c $(FITS_OBJ) libafv.a $(LIB_H) \
                   cmd/fits.h .build-flags
	$(CC) $(CFLAGS) -I. -o $@ tools/lambda_plot.c $(FITS_OBJ) libafv.a \
	  $(LDLIBS)

lambda: afv tools/convergence_plot tools/lambda_plot
	sh tools/lambda.sh $(LAMBDA_OUT)

# Evidence for the paper's protocol (test/protocol_check.c): the authors'
# random start relaxed and run at every P0 and v0 of the paper's range.
# PROTOCOL_ARGS may shrink it (e.g. --N 100 --steps 2000).
PROTOCOL_ARGS = --jobs 2

test/protocol_check: test/protocol_check.c libafv.a $(LIB_H) .build-flags
	$(CC) $(CFLAGS) -I. -o $@ test/protocol_check.c libafv.a $(LDLIBS)

protocol-check: test/protocol_check
	./test/protocol_check $(PROTOCOL_ARGS)

# Installation.  DESTDIR (for packagers) is prepended to every path;
# PREFIX is what afv.pc records.  tools/install.sh copies the files and
# lists what it created (files and directories) in share/afv/installed,
# which make uninstall removes, and nothing else.
PREFIX  ?= /usr/local
DESTDIR ?=
VERSION := $(shell sed -n 's/^\#define AFV_VERSION "\(.*\)"/\1/p' afv.h)
VERSION_MAJOR := $(shell sed -n 's/^\#define AFV_VERSION_MAJOR \([0-9]*\)$$/\1/p' afv.h)

# afv.pc: -lm always (the static library needs it, and pkg-config --libs
# leaves Libs.private out unless --static); -fopenmp for an OpenMP build;
# -Wl,-rpath: a program linked with pkg-config --libs finds libafv.so in
# any PREFIX without LD_LIBRARY_PATH.  Rewritten whenever PREFIX or the
# flags change (FORCE, then cmp: as for .build-flags), so it never records
# the prefix of an earlier install.
afv.pc: FORCE
	@printf '%s\n' 'prefix=$(PREFIX)' 'exec_prefix=$${prefix}' \
	  'libdir=$${exec_prefix}/lib' 'includedir=$${prefix}/include' '' \
	  'Name: afv' \
	  'Description: Active Finite Voronoi model of epithelial and mesenchymal tissue (MIT licence)' \
	  'Version: $(VERSION)' \
	  'License: MIT' \
	  'Libs: -L$${libdir} -Wl,-rpath,$${libdir} -lafv $(LDLIBS)' \
	  'Cflags: -I$${includedir}' > $@.tmp
	@cmp -s $@.tmp $@ || mv $@.tmp $@; rm -f $@.tmp

install: afv libafv.a libafv.so afv.pc doc/afv.1 afv.h afv_config.h
	sh tools/install.sh install '$(DESTDIR)$(PREFIX)' $(VERSION) $(VERSION_MAJOR)

uninstall:
	sh tools/install.sh uninstall '$(DESTDIR)$(PREFIX)'

clean:
	rm -f *.o cmd/*.o libafv.a libafv.so afv.pc afv test/run_tests test/bench \
	  python/check_driver \
	  test/protocol_check tools/convergence_plot tools/lambda_plot \
	  tools/model_plot tools/csd_exponent \
	  .build-flags
	rm -f test/twins reference/afv_plain test/run_tests_assert
	rm -rf test/assert
	rm -rf fuzz/build python/__pycache__ python/afv/__pycache__ \
	  python/build python/afv.egg-info
	rm -f web/afv.wasm web/.build-flags
