# jumpcyl front door. `make run` and `make test` on a fresh Debian 12 machine
# install what is missing (as root), configure, build, and run.
BUILD      ?= build
ASAN_BUILD ?= build-asan
WERROR     ?= OFF
JOBS       ?= $(shell nproc 2>/dev/null || echo 2)
CMAKE_ARGS ?=

# Debian packages that building, running and `make test` need (`make run`
# and `make test` install only these). Each developer tool comes with the
# target that uses it (DEV_PACKAGES below).
# (python3: the docs' examples, tests/docs/check_examples.py.)
DEB_PACKAGES := cmake make gcc pkgconf libgsl-dev libcjson-dev libinih-dev libcairo2-dev librandom123-dev \
                libxml2-dev gnuplot-nox ffmpeg python3
# make fuzz: clang and its libFuzzer runtime; make test-valgrind; make lint;
# make test-mpi: the optional MPI build; make install: the man page.
FUZZ_PACKAGES     := clang libclang-rt-14-dev
VALGRIND_PACKAGES := valgrind
LINT_PACKAGES     := cppcheck python3
MPI_PACKAGES      := libopenmpi-dev openmpi-bin
INSTALL_PACKAGES  := help2man
# make python, make test-python: the Python package (docs/python.md), built
# offline against this build with Debian's cffi, numpy, pandas and pytest.
PYTHON_PACKAGES   := python3-dev python3-cffi python3-numpy python3-pandas python3-pytest python3-venv \
                     python3-pip python3-setuptools
# make notebook: examples/jumpcyl.ipynb executed (matplotlib, nbconvert, a kernel).
NOTEBOOK_PACKAGES := python3-matplotlib jupyter-nbconvert python3-ipykernel
MPI_BUILD    ?= build-mpi
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := options config simulate names batch track part
LINT_SOURCES := src cli fuzz tests/test_bad_input.c tests/test_config.c tests/test_signals.c tests/test_closed_stdout.c tests/test_fuzz_findings.c tests/cli_run.h \
                tests/test_safe_output.c tests/test_waits.c tests/test_sim_json.c tests/test_json_text.c tests/sim/test_stream.c tests/batch/test_map.c tests/batch/test_part.c tests/design/test_design.c tests/track \
                tests/fit/test_fit_cli.c tests/fit/test_fit_stats.c tests/fit/make_track.c tests/fit/test_fit_api.c \
                tests/test_study.c examples/mc_example.c

.PHONY: all deps configure build run test test-long asan test-asan bench install-check clean help
.PHONY: test-valgrind fuzz lint lint-layers test-mpi install deps-fuzz deps-valgrind deps-lint deps-mpi deps-install
.PHONY: python test-python deps-python notebook deps-notebook docs-examples docs-timing

all: build

help:
	@echo "make run        install missing packages, build, run 'jumpcyl paper' (the paper's Table 1),"
	@echo "                write the figures out/overview-{15,30,45}.png, out/trajectory-{15,30,45,hoop}.png"
	@echo "                and the films out/jump-45.gif, out/hoop.gif"
	@echo "make test       install missing packages, build, run the test suite (ctest) but its long"
	@echo "                cases, and the web tests when Chromium and a built page are there"
	@echo "make test-long  the long cases make test leaves out (ctest label long; CI runs both)"
	@echo "make web        the page in out/web/ (WebAssembly, Emscripten); make test-web-all: its tests"
	@echo "make test-asan  the test suite but its long cases, built with AddressSanitizer + UBSan"
	@echo "make test-valgrind  the CLI tests with every run of the tool under valgrind"
	@echo "make fuzz       build the libFuzzer targets (clang) and run each FUZZ_SECONDS=$(FUZZ_SECONDS) s"
	@echo "make test-mpi   the MPI build (-DJUMPCYL_MPI=ON): sweep and mc under mpirun -n 2 equal one process"
	@echo "make lint       cppcheck on the sources, zero findings (lint/cppcheck-suppressions.txt), and"
	@echo "                the layering check (lint/layers.py: no loops, no call or include upwards)"
	@echo "make bench      build and run the benchmarks"
	@echo "make docs-examples  run every '\$$ jumpcyl ...' example of README.md and docs/*.md and write"
	@echo "                what it prints into the docs (the test docs_examples checks them)"
	@echo "make docs-timing  measure the figures' and films' CPU times and write docs/figures.md's table"
	@echo "make python     the Python package (python/, docs/python.md) in $(BUILD)/python-venv;"
	@echo "                make test-python: its tests (make test runs them when Python is there);"
	@echo "                make notebook: examples/jumpcyl.ipynb executed into $(BUILD)/notebook/"
	@echo "make install    install the tool, man page, bash completion and library (PREFIX=/usr/local, DESTDIR=)"
	@echo "make install-check  install into a scratch prefix and build a program against it"
	@echo "Variables: BUILD=$(BUILD) WERROR=$(WERROR) JOBS=$(JOBS) CMAKE_ARGS=..."

# $(call need,PACKAGES): installs the missing ones when root, or prints the
# apt-get line to run and fails.
need = missing=""; \
	for p in $(1); do \
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

deps:
	@$(call need,$(DEB_PACKAGES))
deps-fuzz: deps
	@$(call need,$(FUZZ_PACKAGES))
deps-valgrind: deps
	@$(call need,$(VALGRIND_PACKAGES))
deps-lint:
	@$(call need,$(LINT_PACKAGES))
deps-mpi: deps
	@$(call need,$(MPI_PACKAGES))
deps-install: deps
	@$(call need,$(INSTALL_PACKAGES))
deps-python: deps
	@$(call need,$(PYTHON_PACKAGES))
deps-notebook: deps-python
	@$(call need,$(NOTEBOOK_PACKAGES))

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)

configure: deps
	cmake -S . -B $(BUILD) -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

run: build
	./$(BUILD)/jumpcyl paper
	@# Figures and a film (docs/figures.md): each command prints the file it wrote.
	@mkdir -p out
	@for a in 15 30 45; do ./$(BUILD)/jumpcyl plot --incline $$a --what overview --output out/overview-$$a.png || exit 1; done
	@for a in 15 30 45; do ./$(BUILD)/jumpcyl plot --incline $$a --what trajectory --output out/trajectory-$$a.png || exit 1; done
	@./$(BUILD)/jumpcyl plot --preset hoop --what trajectory --output out/trajectory-hoop.png
	@./$(BUILD)/jumpcyl animate --incline 45 --size 640x360 --fps 25 --slowmo 6 --output out/jump-45.gif
	@./$(BUILD)/jumpcyl animate --preset hoop --size 640x360 --fps 25 --slowmo 6 --output out/hoop.gif

# The test suite without its long cases (ctest label "long") and the
# valgrind runs (label "valgrind", make test-valgrind): about a minute on 2
# idle cores (docs/performance.md), a line as each test ends.
test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) -LE '^(valgrind|long)$$'
	@$(MAKE) --no-print-directory test-web-present

# The long cases make test leaves out (tests/CMakeLists.txt: the fit's
# coverage over 200 videos, the hoop's example fit, the full-size film's
# signals, the docs' slow examples); CI runs both.
test-long: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) -L '^long$$' --no-tests=error

# The sanitizer build's tests but the long ones: those repeat code paths
# the others run under the sanitizers too (the full-size film's signals,
# the hoop's example fit, the docs' slow examples; the fit's coverage runs
# there as 24 trials, not long).
test-asan: deps
	cmake -S . -B $(ASAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DJC_SANITIZE=ON -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)
	cmake --build $(ASAN_BUILD) -j $(JOBS)
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  ctest --test-dir $(ASAN_BUILD) --output-on-failure -j $(JOBS) -LE '^long$$'

asan: test-asan

# The CLI tests (bad inputs, experiment files) again, with every run of the
# tool under valgrind --error-exitcode=1 --leak-check=full (ctest label
# "valgrind", registered when valgrind was found at configure time: the
# build is configured again, as valgrind may have come after its first
# configuration).
test-valgrind: deps-valgrind
	cmake -S . -B $(BUILD) -UJC_VALGRIND -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)
	cmake --build $(BUILD) -j $(JOBS)
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS) -L valgrind --no-tests=error

# The batch commands built with MPI, run under mpirun -n 2 against one process.
test-mpi: deps-mpi build
	cmake -S . -B $(MPI_BUILD) -DJUMPCYL_MPI=ON -DJC_BUILD_TESTS=OFF -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)
	cmake --build $(MPI_BUILD) -j $(JOBS) --target jumpcyl_cli
	tests/batch/test_mpi.sh $(MPI_BUILD)/jumpcyl $(BUILD)/jumpcyl

# libFuzzer targets (fuzz/) in their own build directory, each run for
# FUZZ_SECONDS from its corpus (fuzz/run.sh); skipped, with a message, where
# clang is missing.
fuzz: deps-fuzz
	@if ! command -v clang >/dev/null 2>&1; then echo "make fuzz: clang not found, fuzzing skipped"; exit 0; fi; \
	set -e; \
	CC=clang cmake -S . -B $(FUZZ_BUILD) -DJC_FUZZ=ON -DJC_BUILD_TESTS=OFF -DJC_WERROR=$(WERROR) $(CMAKE_ARGS); \
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS)); \
	fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# Static analysis: every finding fails, unless lint/cppcheck-suppressions.txt
# says why it is not a defect. Then the layers (lint-layers).
lint: deps-lint lint-layers
	cppcheck --enable=warning,style,performance,portability --std=c11 --error-exitcode=1 --inline-suppr --quiet \
	  -I include -I cli -I src --suppressions-list=lint/cppcheck-suppressions.txt $(LINT_SOURCES)

# The layering check (docs/architecture.md, Layers): includes read from the
# sources, calls from the build's objects (nm); a loop between files, or a
# call or include from a lower layer to a higher one, fails unless
# lint/layers-allow.txt lists it with its reason. All of them:
# python3 lint/layers.py --report $(BUILD). The build as it is configured
# (not configured again: its objects are what is read).
lint-layers: $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)
	python3 lint/layers.py $(BUILD) --allow lint/layers-allow.txt

bench: build
	cmake --build $(BUILD) --target jumpcyl_bench -j $(JOBS)
	@# The batch commands too (and under mpirun when the MPI build is there: make test-mpi).
	@# One jc.simulate from Python (python_simulate_us), when the package builds here (python/venv.sh).
	@py_us=$$(python/venv.sh $(BUILD) >/dev/null 2>&1 && $(BUILD)/python-venv/bin/python -P python/bench_simulate.py); \
	JC_BENCH_PYTHON_US="$$py_us" ./$(BUILD)/bench/jumpcyl_bench ./$(BUILD)/jumpcyl \
	  $$(test -x $(MPI_BUILD)/jumpcyl && echo ./$(MPI_BUILD)/jumpcyl)

# The docs' examples: every block of README.md and docs/*.md that starts
# with `$ jumpcyl ...` run, and what it prints written into it, the slow
# ones too (tests/docs/check_examples.py; the test docs_examples compares
# them). Typed numbers drift; these are regenerated.
docs-examples: build
	python3 tests/docs/check_examples.py $(BUILD)/jumpcyl --update --slow

# docs/figures.md's timing table: each figure and film job's CPU time, the
# least of three runs, measured and written (tests/docs/figures_timing.py).
docs-timing: build
	python3 tests/docs/figures_timing.py $(BUILD)/jumpcyl

# The Python package built against this build's library and installed into
# $(BUILD)/python-venv (python/venv.sh): $(BUILD)/python-venv/bin/python -c 'import jumpcyl'.
python: build deps-python
	python/venv.sh $(BUILD)
	@echo "jumpcyl for Python installed in $(BUILD)/python-venv: $(BUILD)/python-venv/bin/python"

# Its tests (the ctest test python_tests, which make test runs when Python is there).
test-python: build deps-python
	ctest --test-dir $(BUILD) --output-on-failure -R '^python_tests$$' --no-tests=error

# The example notebook run top to bottom with nbconvert on a kernel of the
# venv's Python (its kernelspec, found first through JUPYTER_PATH); any
# failing cell fails. The executed copy, with its figures, goes to $(BUILD)/notebook/.
notebook: build deps-notebook
	python/venv.sh $(BUILD)
	$(BUILD)/python-venv/bin/python -m ipykernel install --sys-prefix --name python3 \
	  --display-name "Python 3 (jumpcyl)" >/dev/null
	JUPYTER_PATH=$(CURDIR)/$(BUILD)/python-venv/share/jupyter PYDEVD_DISABLE_FILE_VALIDATION=1 \
	  $(BUILD)/python-venv/bin/python -m nbconvert --to notebook --execute examples/jumpcyl.ipynb \
	  --output-dir $(BUILD)/notebook

# make install [PREFIX=/usr/local] [DESTDIR=...]: the tool, its man page and
# bash completion, the library, headers, pkg-config and CMake files. The
# build is configured again so that help2man, installed just before, is found.
PREFIX ?= /usr/local
install: deps-install
	cmake -S . -B $(BUILD) -UHELP2MAN -DJC_WERROR=$(WERROR) $(CMAKE_ARGS)
	cmake --build $(BUILD) -j $(JOBS)
	DESTDIR=$(DESTDIR) cmake --install $(BUILD) --prefix $(PREFIX)
	@echo "Installed under $(DESTDIR)$(PREFIX): bin/jumpcyl, share/man/man1/jumpcyl.1,"
	@echo "share/bash-completion/completions/jumpcyl, the library, headers, pkg-config and CMake files."

# Installs into a scratch prefix, then builds examples/consumer (the roll,
# fit and Monte Carlo examples) against the installed CMake package and the
# pkg-config file, and runs them.
install-check: build
	rm -rf $(BUILD)/install-check
	cmake --install $(BUILD) --prefix $(CURDIR)/$(BUILD)/install-check/prefix
	cmake -S examples/consumer -B $(BUILD)/install-check/consumer \
	  -DCMAKE_PREFIX_PATH=$(CURDIR)/$(BUILD)/install-check/prefix -DJC_WERROR=ON
	cmake --build $(BUILD)/install-check/consumer
	LD_LIBRARY_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib ./$(BUILD)/install-check/consumer/roll_example
	LD_LIBRARY_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib ./$(BUILD)/install-check/consumer/fit_example \
	  examples/tracker/incline.trk
	LD_LIBRARY_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib ./$(BUILD)/install-check/consumer/mc_example
	PKG_CONFIG_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib/pkgconfig \
	  sh -c 'cc -std=c17 -Wall -Wextra -Wpedantic -Werror examples/roll_example.c $$(pkg-config --cflags --libs --static jumpcyl) -o $(BUILD)/install-check/roll_example_pc'
	LD_LIBRARY_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib ./$(BUILD)/install-check/roll_example_pc
	@# The fit example calls GSL (its error handler): gsl's flags come with --static (Requires.private).
	PKG_CONFIG_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib/pkgconfig \
	  sh -c 'cc -std=c17 -Wall -Wextra -Wpedantic -Werror examples/fit_example.c $$(pkg-config --cflags --libs --static jumpcyl) -o $(BUILD)/install-check/fit_example_pc'
	LD_LIBRARY_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib ./$(BUILD)/install-check/fit_example_pc examples/tracker/incline.trk
	PKG_CONFIG_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib/pkgconfig \
	  sh -c 'cc -std=c17 -Wall -Wextra -Wpedantic -Werror examples/mc_example.c $$(pkg-config --cflags --libs --static jumpcyl) -o $(BUILD)/install-check/mc_example_pc'
	LD_LIBRARY_PATH=$(CURDIR)/$(BUILD)/install-check/prefix/lib ./$(BUILD)/install-check/mc_example_pc
	@# make install itself, into a staging DESTDIR: the tool, its man page, bash completion.
	$(MAKE) install DESTDIR=$(CURDIR)/$(BUILD)/install-check/destdir PREFIX=/usr/local
	tests/test_install.sh $(CURDIR)/$(BUILD)/install-check/destdir /usr/local

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(FUZZ_BUILD) $(MPI_BUILD)

# ---- WebAssembly (docs/web.md) ----
# make web: the library with its studies and its browser entry point
# (web/jc_web.c, web/jc_web_study.c) compiled with Emscripten into
# $(WEB_OUT): jumpcyl.js + jumpcyl.wasm, the one-file
# jumpcyl-single.js, the page (index.html, app.js, style.css) and the
# self-contained jumpcyl.html. GSL and cJSON are built for wasm32 from
# Debian's source packages once, into $(WEB_BUILD) (web/build-deps.sh).
# make test-web: the wasm against the native tool. make test-page: the page
# in headless Chromium. make test-web-all: both, installing what they need
# (CI runs it).
WEB_BUILD    ?= build-web
WEB_OUT      ?= out/web
CHROMIUM     ?= /usr/bin/chromium
# (librandom123-dev: the studies' Philox headers, copied into the wasm build.)
WEB_PACKAGES := emscripten dpkg-dev autotools-dev nodejs librandom123-dev
# Debian's chromium for make test-page; npm when node came without it.
WEB_TEST_PACKAGES := chromium
# Debian's emscripten finds its node modules (acorn, ...) there.
WEB_ENV      := NODE_PATH=/usr/share/nodejs
.PHONY: deps-web deps-web-test web test-web test-page test-web-all test-web-present clean-web

deps-web:
	@$(call need,$(WEB_PACKAGES))
	@web/apt-sources.sh

# Chromium, and playwright-core at the version web/package-lock.json pins,
# installed with npm ci into $(WEB_BUILD)/node_modules (not into the
# repository), again only when the lock file changed.
deps-web-test: deps-web
	@$(call need,$(WEB_TEST_PACKAGES))
	@if ! command -v npm >/dev/null 2>&1; then $(call need,npm); fi
	@mkdir -p $(WEB_BUILD)
	@if ! cmp -s web/package-lock.json $(WEB_BUILD)/package-lock.json || \
	    [ ! -f $(WEB_BUILD)/node_modules/playwright-core/package.json ]; then \
	  cp web/package.json web/package-lock.json $(WEB_BUILD)/ && \
	  npm ci --prefix $(WEB_BUILD) --ignore-scripts --no-audit --no-fund; \
	fi

web: deps-web
	$(WEB_ENV) JOBS=$(JOBS) web/build-deps.sh $(WEB_BUILD)
	$(WEB_ENV) emcmake cmake -S web -B $(WEB_BUILD)/wasm -DJC_WEB_DEPS=$(CURDIR)/$(WEB_BUILD) \
	  -DJC_WEB_OUT=$(CURDIR)/$(WEB_OUT)
	$(WEB_ENV) cmake --build $(WEB_BUILD)/wasm -j $(JOBS)
	@ls -l $(WEB_OUT)

test-web: web build
	node web/test_web.mjs --native ./$(BUILD)/jumpcyl --web $(WEB_OUT)

# The page in headless Chromium (playwright-core), against the native tool;
# screenshots in $(WEB_OUT)/screenshots/.
test-page: web build deps-web-test
	node web/test_page.mjs --native ./$(BUILD)/jumpcyl --web $(WEB_OUT) \
	  --modules $(WEB_BUILD)/node_modules --chromium $(CHROMIUM)

test-web-all: test-web test-page

# What make test runs after ctest: both web tests when Chromium,
# playwright-core and a configured wasm build are there (the page rebuilt
# first if a source changed), else a line saying why not. Installs nothing.
test-web-present:
	@if [ -x $(CHROMIUM) ] && [ -f $(WEB_BUILD)/node_modules/playwright-core/package.json ] && \
	    [ -f $(WEB_BUILD)/wasm/CMakeCache.txt ] && command -v emcc >/dev/null 2>&1; then \
	  set -e; \
	  $(WEB_ENV) cmake --build $(WEB_BUILD)/wasm -j $(JOBS); \
	  node web/test_web.mjs --native ./$(BUILD)/jumpcyl --web $(WEB_OUT); \
	  node web/test_page.mjs --native ./$(BUILD)/jumpcyl --web $(WEB_OUT) \
	    --modules $(WEB_BUILD)/node_modules --chromium $(CHROMIUM); \
	else \
	  echo "make test: web tests skipped (they need $(CHROMIUM), a built page and playwright-core: make test-web-all)"; \
	fi

clean-web:
	rm -rf $(WEB_BUILD)/wasm $(WEB_OUT)
