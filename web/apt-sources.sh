#!/bin/sh
# Makes sure APT can fetch Debian source packages (apt-get source), which
# web/build-deps.sh builds for WebAssembly: when no deb-src entry exists, one
# is made from the machine's own deb entries (same mirrors, suites and
# components), in /etc/apt/sources.list.d/jumpcyl-deb-src.{sources,list},
# and the lists are updated. Needs root for that; otherwise says what to do.
set -eu

has_src() {
    grep -Eqs '^[[:space:]]*(deb-src[[:space:]]|Types:.*deb-src)' /etc/apt/sources.list /etc/apt/sources.list.d/*.list \
        /etc/apt/sources.list.d/*.sources
}

if has_src; then
    exit 0
fi
if [ "$(id -u)" != 0 ]; then
    echo "apt-sources: APT has no deb-src entry, which 'apt-get source' needs. As root, add one" >&2
    echo "  (a copy of your deb entry with 'deb-src'), run apt-get update, then make web again." >&2
    exit 1
fi
made=""
for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] || continue
    case "$f" in */jumpcyl-deb-src.sources) continue ;; esac
    # deb822 stanzas: "Types: deb" becomes "Types: deb-src".
    sed -E 's/^Types:[[:space:]]*deb[[:space:]]*$/Types: deb-src/' "$f" >>/etc/apt/sources.list.d/jumpcyl-deb-src.sources
    echo >>/etc/apt/sources.list.d/jumpcyl-deb-src.sources
    made="$made $f"
done
if [ -f /etc/apt/sources.list ]; then
    sed -nE 's/^[[:space:]]*deb[[:space:]]/deb-src /p' /etc/apt/sources.list >/etc/apt/sources.list.d/jumpcyl-deb-src.list
    made="$made /etc/apt/sources.list"
fi
if ! has_src; then
    echo "apt-sources: could not make a deb-src entry from$made" >&2
    exit 1
fi
echo "apt-sources: added deb-src entries (copies of$made); apt-get update"
apt-get update -qq
