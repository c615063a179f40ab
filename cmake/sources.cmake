# The source lists that the native build (CMakeLists.txt) and the web build
# (web/CMakeLists.txt) share, listed once: both include this file. The
# paths are absolute, so that either build can use them.
get_filename_component(JC_SOURCE_ROOT "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)

set(JC_LIB_SOURCES
  src/status.c src/trigpoly.c src/scan.c src/body.c src/setup.c src/model.c
  src/paper_model.c src/rolling.c src/rolling_phase.c src/sliding.c src/flight.c src/flight_air.c src/impact.c src/mode.c
  src/simulate.c src/run.c src/record.c src/workspace.c src/ode.c src/dop853.c src/dop853_control.c
  src/units.c src/param.c src/param_values.c src/sample_columns.c)
list(TRANSFORM JC_LIB_SOURCES PREPEND "${JC_SOURCE_ROOT}/")

# Studies (include/jumpcyl/study.h): grids, Monte Carlo samples (Random123's
# Philox, src/random.c, which the tracks' fit and synthetic videos use too),
# their statistics, the design search; on every core with OpenMP. The web
# build compiles them too, with JC_LIB_SOURCES (the page's sweep and the
# spread of the jump site, web/jc_web_study.c), on one thread: OpenMP's
# pragmas and calls compile only where _OPENMP is defined.
set(JC_STUDY_SOURCES
  src/random.c src/study/number.c src/study/outcome.c src/study/case.c src/study/threads.c src/study/run.c
  src/study/defaults.c src/study/stats.c src/study/sketch.c src/study/design_scan.c src/study/design_solve.c src/study/design.c
  src/study/design_range.c)
list(TRANSFORM JC_STUDY_SOURCES PREPEND "${JC_SOURCE_ROOT}/")

# Tracked videos (include/jumpcyl/track.h, docs/tracker.md): Tracker's files
# read (.trk through libxml2, exported tables) or the caller's arrays, the
# incline frame and what the video tells; the model compared with them and
# fitted to them (GSL's multifit), synthetic videos (the studies' Philox,
# src/random.c). Part of the library, in a list of its own: the web build, which has no
# libxml2, compiles JC_LIB_SOURCES and JC_STUDY_SOURCES without it.
set(JC_TRACK_SOURCES
  src/track/data.c src/track/read.c src/track/trk.c src/track/table.c src/track/frame.c src/track/surface.c
  src/track/rim.c src/track/derive.c
  src/track/model_path.c src/track/start.c src/track/residuals.c src/track/fit_params.c src/track/fit.c
  src/track/launch.c src/track/fit_video.c src/track/compare.c src/track/synthetic.c)
list(TRANSFORM JC_TRACK_SOURCES PREPEND "${JC_SOURCE_ROOT}/")

# The tool's files that the web page compiles too, so that the page and the
# tool read a setup and write a run the same way: the setup and simulation
# options as text, built without files (setup_args.c; the command line's
# parsing and --config are options.c's, which the page does not compile),
# units (units.c), the experiment-file writer (the page's download), the
# JSON of a run (sim_json.c, report.c) with its exact numbers (json_text.c),
# Table 1's row (paper_row.c) and the tool's one-line errors (error.c). Nothing in them calls outside them and
# the library: the page links them whole (tests: web_link). The native
# tool builds each into its folder's library (CMakeLists.txt: jc_cli_shared).
set(JC_TOOL_SHARED_SOURCES
  cli/inputs/setup_args.c cli/inputs/units.c cli/inputs/config_write.c
  cli/outputs/report.c cli/outputs/json_text.c cli/outputs/sim_json.c cli/figures/paper_row.c cli/process/error.c)
list(TRANSFORM JC_TOOL_SHARED_SOURCES PREPEND "${JC_SOURCE_ROOT}/")
