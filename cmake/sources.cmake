# The library's sources, listed once: the native build (CMakeLists.txt)
# and the web build (web/CMakeLists.txt) both include this file. The
# paths are absolute, so that either build can use them.
get_filename_component(JC_SOURCE_ROOT "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)

set(JC_LIB_SOURCES
  src/status.c src/trigpoly.c src/scan.c src/body.c src/setup.c src/model.c
  src/paper_model.c src/rolling.c src/rolling_phase.c src/sliding.c src/flight.c src/flight_air.c src/impact.c src/mode.c
  src/simulate.c src/run.c src/record.c src/workspace.c src/ode.c src/dop853.c
  src/sample_columns.c)
list(TRANSFORM JC_LIB_SOURCES PREPEND "${JC_SOURCE_ROOT}/")
