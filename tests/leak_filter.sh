#!/bin/sh
# Runs one GPU test under the sanitizers and fails on any sanitizer report, with one exception:
# leaks allocated by code that belongs to no loaded module. Mesa's llvmpipe and lavapipe JIT-compile
# shaders into anonymous memory, and that code leaves two 56-byte objects behind after the first draw
# (a bare EGL or Vulkan program that draws shows the same); LeakSanitizer cannot name such frames, so
# suppressions cannot reach them. A leak with any frame in dstrans, a test, Mesa's libraries or the
# loader still fails. (With UBSan loaded, LeakSanitizer misnames those JIT frames as libubsan.so.)
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
      /^(Direct|Indirect) leak/ { block = 1; next }
      block && /^ *#[1-9][0-9]* / && !/<unknown module>/ && !/libubsan\.so/ { bad = 1 }
      /^$/ { block = 0 }
      END { exit bad }' $reports; then
    cat $reports >&2
    status=1
  fi
fi
rm -rf "$dir"
exit $status
