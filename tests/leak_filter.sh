#!/bin/sh
# Runs one GPU test under the sanitizers and fails on any sanitizer report, with one exception: leaks
# allocated from code that has no symbol and no caller, which is how Mesa's JIT-compiled shaders look.
# llvmpipe and lavapipe compile shaders into anonymous memory (no symbols, no frame pointers), and that
# code leaves 56-byte objects behind after draws (a bare EGL or Vulkan program that draws shows the
# same). LeakSanitizer cannot name such frames, so suppressions cannot reach them; once the memory is
# reused it even misnames them after whatever library lies there now. A leak with a second frame or a
# named function (anything in dstrans, a test, Mesa's libraries or the loader) still fails.
# Usage: leak_filter.sh TEST_EXECUTABLE [ARGS...]  (CMake's CROSSCOMPILING_EMULATOR)
dir=$(mktemp -d)
LSAN_OPTIONS="${LSAN_OPTIONS:+$LSAN_OPTIONS:}exitcode=0:log_path=$dir/report" "$@"
status=$?
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
