#!/bin/sh
# Builds the C libraries the WebAssembly build links, for wasm32 with
# Emscripten, from Debian's own source packages (apt-get source: no other
# network), once: a second run finds them and returns at once.
#
#   web/build-deps.sh BUILD_DIR
#
# BUILD_DIR/gsl-wasm/    GSL 2.7.1, only the parts the library uses (roots,
#                        min, poly, integration, rstat, err, sys and what they pull in):
#                        include/gsl/*.h, lib/libgsl.a
# BUILD_DIR/cjson-wasm/  cJSON (Debian's patched cJSON.c): include/cjson/cJSON.h,
#                        lib/libcjson.a
# BUILD_DIR/deps-src/    the unpacked source packages (scratch; may be removed)
#
# Needs emcc/emar (Debian 'emscripten'), dpkg-dev (apt-get source),
# autotools-dev (a config.sub that knows wasm32), and a deb-src line in APT's
# sources (web/apt-sources.sh adds one; 'make deps-web' runs it).
set -eu

build=${1:?usage: web/build-deps.sh BUILD_DIR}
mkdir -p "$build"
build=$(cd "$build" && pwd)
src="$build/deps-src"
gsl="$build/gsl-wasm"
cjson="$build/cjson-wasm"
jobs=${JOBS:-2}
export NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"

for tool in emcc emar emconfigure emmake; do
    command -v "$tool" >/dev/null 2>&1 || { echo "build-deps: $tool not found (make deps-web)" >&2; exit 1; }
done

# The unpacked source package NAME in $src (apt-get source, patches applied).
fetch_source() {
    name=$1
    mkdir -p "$src"
    found=$(find "$src" -maxdepth 1 -type d -name "$name-[0-9]*" | head -n 1)
    if [ -z "$found" ]; then
        (cd "$src" && apt-get source -qq "$name" >&2) || {
            echo "build-deps: 'apt-get source $name' failed: is there a deb-src line? (make deps-web)" >&2
            exit 1
        }
        found=$(find "$src" -maxdepth 1 -type d -name "$name-[0-9]*" | head -n 1)
    fi
    [ -n "$found" ] || { echo "build-deps: no unpacked $name source in $src" >&2; exit 1; }
    echo "$found"
}

# ---- GSL ----
# Sub-libraries the library needs (src/*.c: roots/brent, poly quadratic and
# cubic, integration qng/qag, errno; src/study/design_solve.c: min/brent;
# src/study/sketch.c: rstat's P² quantiles, which sort and take a quantile
# of sorted data below five values) and what they pull in. gsl/ first: it makes the header links. A GSL built
# with another list of directories (its stamp names them) is built again;
# the configured source tree is kept, so only the new directories compile.
GSL_DIRS="gsl utils sys err complex poly roots min integration sort statistics rstat"
if [ -f "$gsl/.built" ] && grep -q "dirs: $GSL_DIRS;" "$gsl/.built"; then
    echo "build-deps: $gsl is there ($(cat "$gsl/.built"))"
else
    start=$(date +%s)
    dir=$(fetch_source gsl)
    # Debian's config.sub is newer than the tarball's and knows wasm32 (as
    # the Debian package's own build updates it).
    if [ -f /usr/share/misc/config.sub ]; then
        cp /usr/share/misc/config.sub /usr/share/misc/config.guess "$dir/"
    fi
    if [ ! -f "$dir/config.status" ]; then
        (cd "$dir" && emconfigure ./configure --host=wasm32 --disable-shared --enable-static \
            CFLAGS="-O2" >"$build/gsl-configure.log" 2>&1) || {
            echo "build-deps: GSL configure failed; see $build/gsl-configure.log" >&2
            exit 1
        }
    fi
    for d in $GSL_DIRS; do
        (cd "$dir" && emmake make -j"$jobs" -C "$d" >>"$build/gsl-make.log" 2>&1) || {
            echo "build-deps: GSL make in $d failed; see $build/gsl-make.log" >&2
            exit 1
        }
    done
    rm -rf "$gsl.tmp"
    mkdir -p "$gsl.tmp/include/gsl" "$gsl.tmp/lib"
    # The headers (gsl/ holds links to them), copied as files.
    for h in "$dir"/gsl/gsl_*.h; do cp -L "$h" "$gsl.tmp/include/gsl/"; done
    # One archive from the sub-libraries (object names repeat across them,
    # so an MRI script, not a merge of extracted files).
    {
        echo "create $gsl.tmp/lib/libgsl.a"
        for d in $GSL_DIRS; do
            for a in "$dir/$d"/.libs/*.a; do [ -f "$a" ] && echo "addlib $a"; done
        done
        echo "save"
        echo "end"
    } | emar -M
    emranlib "$gsl.tmp/lib/libgsl.a" 2>/dev/null || true
    end=$(date +%s)
    echo "GSL $(basename "$dir") for wasm32, dirs: $GSL_DIRS; built in $((end - start)) s on $(date -u +%Y-%m-%d)" \
        >"$gsl.tmp/.built"
    rm -rf "$gsl"
    mv "$gsl.tmp" "$gsl"
    echo "build-deps: $(cat "$gsl/.built")"
fi

# ---- one-file libraries: cJSON ----
# (not inih: the page reads no experiment file, so the reader that needs it,
# cli/inputs/config.c, is not compiled for wasm)
# one_file LABEL PACKAGE OUT HEADER_DIR NAME LIB: OUT/include/HEADER_DIR/NAME.h
# and OUT/lib/libLIB.a from the source package's NAME.c compiled with emcc -O2.
one_file() {
    label=$1 package=$2 out=$3 hdir=$4 name=$5 lib=$6
    if [ -f "$out/.built" ]; then
        echo "build-deps: $out is there ($(cat "$out/.built"))"
        return
    fi
    start=$(date +%s)
    dir=$(fetch_source "$package")
    rm -rf "$out.tmp"
    mkdir -p "$out.tmp/include/$hdir" "$out.tmp/lib"
    cp "$dir/$name.h" "$out.tmp/include/$hdir/"
    emcc -O2 -c "$dir/$name.c" -o "$out.tmp/$name.o"
    emar rcs "$out.tmp/lib/lib$lib.a" "$out.tmp/$name.o"
    rm -f "$out.tmp/$name.o"
    end=$(date +%s)
    echo "$label $(basename "$dir") for wasm32, built in $((end - start)) s on $(date -u +%Y-%m-%d)" >"$out.tmp/.built"
    rm -rf "$out"
    mv "$out.tmp" "$out"
    echo "build-deps: $(cat "$out/.built")"
}
one_file cJSON cjson "$cjson" cjson cJSON cjson
