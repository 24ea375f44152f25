# afv -- Active Finite Voronoi model.  Plain C99 + libm.
#
#   make            the program ./afv and the library libafv.a
#   make test       build and run the test suite (ends "N passed, M failed")
#   make run        build, then run a short default simulation
#   make bench      build and run the benchmark
#   make clean
#
# CC and CFLAGS may be overridden (make CC=clang, make CC=tcc).
# OPENMP=1 adds -fopenmp (optional; the default build is plain C99).

CC      ?= cc
CFLAGS  ?= -O2 -std=c99 -pedantic -Wall -Wextra
LDLIBS  = -lm
ifeq ($(OPENMP),1)
CFLAGS  += -fopenmp
LDLIBS  += -fopenmp
endif

LIB_SRC  = geom.c afv.c dynamics.c analysis.c svg.c io.c
LIB_OBJ  = $(LIB_SRC:.c=.o)
TEST_SRC = test/main.c $(wildcard test/test_*.c)

.PHONY: all test clean

all: afv libafv.a

libafv.a: $(LIB_OBJ)
	$(AR) rcs $@ $(LIB_OBJ)

afv: main.o libafv.a
	$(CC) $(CFLAGS) -o $@ main.o libafv.a $(LDLIBS)

%.o: %.c afv.h
	$(CC) $(CFLAGS) -c -o $@ $<

test/run_tests: $(TEST_SRC) test/test.h libafv.a afv.h
	$(CC) $(CFLAGS) -I. -o $@ $(TEST_SRC) libafv.a $(LDLIBS)

test: afv test/run_tests
	./test/run_tests

clean:
	rm -f *.o libafv.a afv test/run_tests
