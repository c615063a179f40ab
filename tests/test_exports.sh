#!/bin/sh
# The shared library exports exactly the documented API: the functions
# declared JC_API in the public headers (include/jumpcyl/*.h), no more and
# no fewer.
# Usage: test_exports.sh LIBRARY HEADER...
set -eu
lib=$1
shift
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
nm -D --defined-only "$lib" | awk '$2 ~ /^[TDBR]$/ {print $3}' | sort > "$tmp/exported"
sed -n 's/^JC_API .*[ *]\(jc_[a-z_0-9]*\)(.*/\1/p' "$@" | sort > "$tmp/declared"
if ! diff -u "$tmp/declared" "$tmp/exported" > "$tmp/diff"; then
    echo "exports differ from the JC_API declarations (- declared only, + exported only):"
    cat "$tmp/diff"
    echo "0 passed, 1 failed"
    exit 1
fi
echo "exports: $(wc -l < "$tmp/exported") symbols, each a JC_API declaration of the headers"
echo "1 passed, 0 failed"
