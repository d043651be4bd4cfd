#!/usr/bin/env bash
# Usage: tests/check_packages.sh CMakeCache.txt... -- PACKAGE...
#
# Fails, naming the Debian package to add, when something CMake found (a package configuration, a library,
# a program) belongs to a Debian package that the listed packages do not install, directly or as a
# dependency (Depends and Pre-Depends only: Recommends may be turned off on the user's machine). Such a
# package is on this machine only because somebody installed it by hand; a fresh machine stops at configure.
set -euo pipefail

caches=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do caches+=("$1"); shift; done
[ "${1:-}" = "--" ] || { echo "usage: $0 CMakeCache.txt... -- PACKAGE..." >&2; exit 2; }
shift
[ ${#caches[@]} -gt 0 ] || { echo "$0: no CMakeCache.txt given" >&2; exit 2; }
[ $# -gt 0 ] || { echo "$0: no packages given" >&2; exit 2; }
# 77: nothing to check here (the test is skipped).
command -v dpkg-query >/dev/null || { echo "$0: dpkg-query not found: this check needs Debian" >&2; exit 77; }

# What CMake found: the configuration file in each <Name>_DIR, and every file path (libraries, programs)
# under /usr. Paths under the build trees or elsewhere are the project's own.
found() {
  local cache=$1 line dir
  grep -E '^[A-Za-z0-9_.+-]+_DIR:(PATH|INTERNAL|STATIC)=/usr/' "$cache" | cut -d= -f2- | while read -r dir; do
    ls "$dir"/*[Cc]onfig.cmake "$dir"/*-config.cmake 2>/dev/null | head -n 1 || true
  done
  # FindOpenGL always looks for GLU, which nothing here links: a machine without it configures the same.
  grep -E '^[A-Za-z0-9_]+:FILEPATH=/usr/' "$cache" | grep -v '^OPENGL_glu_LIBRARY:' | cut -d= -f2- || true
}

# The packages that own a path, following symlinks (/usr/bin/c++ -> /etc/alternatives -> g++-12).
owner() {
  local p=$1
  { dpkg-query -S "$p" 2>/dev/null || dpkg-query -S "$(readlink -f "$p")" 2>/dev/null; } | head -n 1 | cut -d: -f1 \
    | tr -d ' ' | tr ',' '\n' | head -n 1
}

# Everything the list installs: the list and the closure of its Depends and Pre-Depends among installed packages.
closure=$(apt-cache depends --recurse --installed --no-recommends --no-suggests --no-conflicts --no-breaks \
            --no-replaces --no-enhances "$@" 2>/dev/null | grep -v '^ ' | sed 's/:any$//; s/:amd64$//' | sort -u)
closure=$(printf '%s\n' "$closure" "$@" | sort -u)

status=0
checked=0
for cache in "${caches[@]}"; do
  [ -f "$cache" ] || { echo "$0: $cache does not exist" >&2; exit 2; }
  while read -r path; do
    [ -n "$path" ] && [ -e "$path" ] || continue
    pkg=$(owner "$path")
    [ -n "$pkg" ] || continue
    checked=$((checked + 1))
    pkg=${pkg%:amd64}
    if ! grep -qxF "$pkg" <<<"$closure"; then
      echo "Debian package '$pkg' is used by the build ($path, from $cache) but the Makefile's PACKAGES does not install it: add $pkg to PACKAGES."
      status=1
    fi
  done < <(found "$cache" | sort -u)
done
[ $checked -gt 0 ] || { echo "$0: nothing CMake found belongs to a Debian package: is this Debian?" >&2; exit 2; }
[ $status -ne 0 ] || echo "Packages: the $checked files CMake found all come from packages the Makefile installs."
exit $status
