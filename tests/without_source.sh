#!/bin/sh
# Runs a command as on a machine that installed dstrans and has no source tree: in a private mount
# namespace an empty folder covers SOURCE, and KEEP (a folder inside it: the build folder, which holds the
# installed copy and the test's outputs) is mounted back where it was; the command starts in /.
#   tests/without_source.sh [--strict] SOURCE KEEP COMMAND [ARGUMENT...]
# Where the system lets no process make the namespace, the command runs with the source in place and a
# line on stderr says so; with --strict it prints "skipped: ..." and exits 77 instead.
set -eu
strict=no
if [ "$1" = --strict ]; then strict=yes; shift; fi
source=$1 keep=$2
shift 2
if ! unshare --user --map-root-user --mount true 2>/dev/null; then
  why="this system lets no process make a private mount namespace (unshare --user --mount)"
  if [ $strict = yes ]; then echo "skipped: $why"; exit 77; fi
  echo "without_source.sh: the source tree stays in place: $why" >&2
  cd /
  exec "$@"
fi
exec unshare --user --map-root-user --mount sh -c '
  set -eu
  source=$1 keep=$2
  shift 2
  spare=$(mktemp -d)
  mount --bind "$keep" "$spare"
  mount -t tmpfs -o size=1m tmpfs "$source"
  mkdir -p "$keep"
  mount --bind "$spare" "$keep"
  cd /
  exec "$@"' sh "$source" "$keep" "$@"
