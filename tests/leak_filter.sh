#!/bin/sh
# Runs one GPU test under the sanitizers and fails on any sanitizer report, with one exception: leaks
# allocated from code that has no symbol and no caller, which is how Mesa's JIT-compiled shaders look.
# llvmpipe and lavapipe compile shaders into anonymous memory (no symbols, no frame pointers), and that
# code leaves 56-byte objects behind after draws (a bare EGL or Vulkan program that draws shows the
# same). LeakSanitizer cannot name such frames, so suppressions cannot reach them; once the memory is
# reused it even misnames them after whatever library lies there now. A leak with a second frame or a
# named function (anything in dstrans, a test, Mesa's libraries or the loader) still fails.
#
# LeakSanitizer's own tracer sometimes crashes as the program exits ("Tracer caught signal 11",
# "LeakSanitizer has encountered a fatal error"; google/sanitizers#1353). It has then checked nothing, and
# it exits with its exitcode, 0 here, in place of the program's status, so a command that must fail would
# pass. Such a run is repeated; after a second crash the command runs once more without the leak check, so
# that its own status and AddressSanitizer's and UBSan's checks still count, and this is said on stderr.
# Only the last run's output is passed on.
# Usage: leak_filter.sh TEST_EXECUTABLE [ARGS...]  (CMake's CROSSCOMPILING_EMULATOR)
dir=$(mktemp -d)
run() {  # run EXTRA_ASAN_OPTIONS COMMAND [ARGS...]
  extra=$1
  shift
  rm -f "$dir"/report.*
  ASAN_OPTIONS="$ASAN_OPTIONS${extra:+${ASAN_OPTIONS:+:}$extra}" LSAN_OPTIONS="${LSAN_OPTIONS:+$LSAN_OPTIONS:}exitcode=0:log_path=$dir/report" \
    "$@" >"$dir/out" 2>"$dir/err"
}
tracer_crashed() { grep -qs "LeakSanitizer has encountered a fatal error" "$dir"/report.*; }
run "" "$@"
status=$?
if tracer_crashed; then
  run "" "$@"
  status=$?
fi
if tracer_crashed; then
  run "detect_leaks=0" "$@"
  status=$?
  echo "leak_filter.sh: LeakSanitizer's tracer crashed twice; ran once more without the leak check" >>"$dir/err"
fi
cat "$dir/out"
cat "$dir/err" >&2
reports=$(ls "$dir"/report.* 2>/dev/null)
if [ -n "$reports" ]; then
  if grep -q "ERROR: AddressSanitizer\|runtime error" $reports; then
    cat $reports >&2
    status=1
  elif ! awk '
      /^(Direct|Indirect) leak/ { block = 1; frames = 0; next }
      block && /^ *#[1-9][0-9]* / { frames++; if (frames > 1 || / in /) bad = 1 }
      /^$/ { block = 0 }
      END { exit bad }' $reports; then
    cat $reports >&2
    status=1
  fi
fi
rm -rf "$dir"
exit $status
