#!/bin/sh
# Builds the Python package (python/) against the library of a build tree
# and installs it into BUILD/python-venv, a virtual environment that sees
# Debian's packages (numpy, pandas, cffi, pytest). Offline: pip builds with
# the setuptools and cffi already there (no build isolation, no index).
#   python/venv.sh BUILD              install (again when a source changed)
#   python/venv.sh BUILD --test ARGS  then run the tests (pytest ARGS)
# Exits 77 (ctest: skipped) when Debian's python3 lacks cffi, numpy, pytest
# or venv: `make deps-python` installs them.
set -eu
build=$(cd "$1" && pwd)
shift
here=$(cd "$(dirname "$0")" && pwd)
python=${JC_PYTHON:-/usr/bin/python3}
venv=$build/python-venv
if ! [ -x "$python" ] || ! "$python" -c 'import cffi, numpy, pytest, venv, ensurepip' 2>/dev/null; then
  echo "python tests skipped: $python with cffi, numpy, pytest and venv is missing (make deps-python)"
  exit 77
fi
if ! [ -x "$venv/bin/python" ]; then
  "$python" -m venv --system-site-packages "$venv"
fi
stamp=$venv/.jumpcyl-installed
if ! [ -f "$stamp" ] || [ -n "$(find "$here/jumpcyl" "$here/jumpcyl_build.py" "$here/setup.py" \
      "$here/../include/jumpcyl" "$build/libjumpcyl.so" -newer "$stamp" 2>/dev/null | head -1)" ]; then
  # The repository's headers with this build's library; the build tree is
  # pip's scratch copy in python/build (in-tree build), kept out of git.
  if ! JUMPCYL_BUILD_DIR=$build JUMPCYL_INCLUDE_DIR=$here/../include \
      "$venv/bin/python" -m pip install --no-index --no-build-isolation --no-deps "$here" >"$venv/pip.log" 2>&1; then
    cat "$venv/pip.log" >&2
    exit 1
  fi
  "$venv/bin/python" -c 'import jumpcyl' || exit 1
  touch "$stamp"
fi
if [ "${1:-}" = "--test" ]; then
  shift
  cd "$here/tests"
  JUMPCYL_TOOL=${JUMPCYL_TOOL:-$build/jumpcyl} exec "$venv/bin/python" -m pytest -q -p no:cacheprovider "$@"
fi
