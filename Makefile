# jumpcyl front door. `make run` and `make test` on a fresh Debian 12 machine
# install what is missing (as root), configure, build, and run.
BUILD      ?= build
ASAN_BUILD ?= build-asan
WERROR     ?= OFF
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=

# Debian packages the build and tests need.
DEB_PACKAGES := cmake make gcc pkgconf libgsl-dev libcjson-dev

.PHONY: all deps configure build run test asan test-asan bench install-check clean help

all: build

help:
	@echo "make run        install missing packages, build, run 'jumpcyl paper' (the paper's Table 1)"
	@echo "make test       install missing packages, build, run the test suite (ctest)"
	@echo "make test-asan  the test suite built with AddressSanitizer + UndefinedBehaviorSanitizer"
	@echo "make bench      build and run the benchmarks"
	@echo "make install-check  install into a scratch prefix and build a program against it"
	@echo "Variables: BUILD=$(BUILD) WERROR=$(WERROR) JOBS=$(JOBS) CMAKE_ARGS=..."

deps:
	@missing=""; \
	for p in $(DEB_PACKAGES); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q "ok installed" || missing="$$missing $$p"; \
	done; \
	if [ -n "$$missing" ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "Installing Debian packages:$$missing"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends $$missing; \
	  else \
	    echo "jumpcyl needs Debian packages that are missing. Install them with:" >&2; \
	    echo "  sudo apt-get install -y$$missing" >&2; \
	    exit 1; \
	  fi; \
	fi

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)

configure: deps
	cmake -S . -B $(BUILD) -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: build
	./$(BUILD)/jumpcyl paper

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

test-asan: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DJC_SANITIZE=ON -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS)

asan: test-asan

bench: build
	cmake --build $(BUILD) --target jumpcyl_bench -j $(JOBS)
	./$(BUILD)/bench/jumpcyl_bench

# Installs into a scratch prefix, then builds examples/consumer against the
# installed CMake package and the pkg-config file.
install-check: build
	rm -rf $(BUILD)/install-check
	cmake --install $(BUILD) --prefix $(CURDIR)/$(BUILD)/install-check/prefix
	cmake -S examples/consumer -B $(BUILD)/install-check/consumer \
	  -DCMAKE_PREFIX_PATH=$(CURDIR)/$(BUILD)/install-check/prefix -DJC_WERROR=ON
	cmake --build $(BUILD)/install-check/consumer
	LD_LIBRARY_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib ./$(BUILD)/install-check/consumer/roll_example
	PKG_CONFIG_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib/pkgconfig \
	  sh -c 'cc -std=c17 -Wall -Wextra -Wpedantic -Werror examples/roll_example.c $$(pkg-config --cflags --libs --static jumpcyl) -o $(BUILD)/install-check/roll_example_pc'
	LD_LIBRARY_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib ./$(BUILD)/install-check/roll_example_pc

clean:
	rm -rf $(BUILD) $(ASAN_BUILD)
