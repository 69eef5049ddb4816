#!/usr/bin/env bash
# Builds the libFuzzer targets under fuzz/ (clang, ASan + UBSan, core-only,
# build dir ws/fuzz or FUZZ_BUILD_DIR; make test runs it on ws/sanitize) and
# runs each for FUZZ_SECONDS (default 30) on its seed corpus fuzz/corpus/<target>/. New inputs go to ws/fuzz/corpus/<target>/ (the
# repository's seeds stay as they are); a crash is saved under
# ws/fuzz/artifacts/<target>/ and makes the script exit non-zero. Inputs under
# fuzz/regressions/<target>/ (past crashes) are replayed first.
#
#   scripts/fuzz.sh                      all targets, 30 s each
#   FUZZ_SECONDS=300 scripts/fuzz.sh fuzz_front_end
set -uo pipefail
root=$(cd -P "$(dirname "$0")/.." && pwd)
export PATH=/usr/bin:/bin:$PATH
build_dir=${FUZZ_BUILD_DIR:-$root/ws/fuzz}
seconds=${FUZZ_SECONDS:-30}
jobs=${FUZZ_BUILD_JOBS:-2}
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}

"$root/scripts/configure_sanitizer_build.sh" "$build_dir" || { echo "fuzz: configure failed" >&2; exit 1; }
cmake --build "$build_dir" --target fuzz_targets -j"$jobs" || { echo "fuzz: build failed" >&2; exit 1; }

if [[ $# -gt 0 ]]; then targets=("$@"); else
  mapfile -t targets < <(cd "$root/fuzz" && ls fuzz_*.cpp | sed 's/\.cpp$//')
fi

status=0
summary=()
for target in "${targets[@]}"; do
  binary=$build_dir/fuzz/$target
  [[ -x "$binary" ]] || { echo "fuzz: $target not built" >&2; status=1; continue; }
  work_corpus=$build_dir/corpus/$target
  artifacts=$build_dir/artifacts/$target
  mkdir -p "$work_corpus" "$artifacts"

  regressions=$root/fuzz/regressions/$target
  if [[ -d "$regressions" ]] && compgen -G "$regressions/*" >/dev/null; then
    echo "== $target: replaying $(ls "$regressions" | wc -l) past crash inputs"
    if ! "$binary" -runs=0 "$regressions"/* >"$artifacts/regressions.log" 2>&1; then
      echo "fuzz: $target still crashes on a past input, see $artifacts/regressions.log"
      summary+=("$target: REGRESSION INPUT STILL CRASHES"); status=1
    fi
  fi

  echo "== $target: ${seconds} s"
  # Inputs of the previous run move aside, so that the verdict is this run's.
  mkdir -p "$artifacts/previous"
  find "$artifacts" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) \
    -exec mv -f {} "$artifacts/previous/" \;
  # -fork=1 -ignore_crashes=1: keep fuzzing after a crash, so that one known
  # bug does not hide the others; the verdict comes from the saved artifacts.
  # -timeout: one input taking 10 s is a hang (Super4PCS has a 20 ms budget).
  # -rss_limit_mb: a frame of a few kB must not need gigabytes.
  "$binary" -fork=1 -ignore_crashes=1 -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len=4096 \
    -artifact_prefix="$artifacts/" "$work_corpus" "$root/fuzz/corpus/$target" >"$artifacts/fuzz.log" 2>&1
  rc=$?
  runs=$(grep -oE '#[0-9]+' "$artifacts/fuzz.log" | tail -1 | tr -d '#')
  found=$(find "$artifacts" -maxdepth 1 -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | wc -l)
  if [[ $found -gt 0 || ( $rc -ne 0 && $rc -ne 1 ) ]]; then
    echo "fuzz: $target: $found crashing input(s) in $artifacts (exit $rc); distinct reports (first 10 replayed):"
    # Fork mode keeps the children's reports out of fuzz.log: replay a few.
    find "$artifacts" -maxdepth 1 -type f -name 'crash-*' | head -10 | while read -r input; do
      "$binary" -runs=0 "$input" 2>&1 | grep -m1 -oE "what\(\): .*|runtime error: .*|ERROR: AddressSanitizer: [a-z-]+|SEGV" || true
    done | sort | uniq -c | sort -rn
    summary+=("$target: $found CRASHING INPUT(S) after ~${runs:-?} runs (see $artifacts/fuzz.log)"); status=1
  else
    summary+=("$target: clean, ~${runs:-?} runs in ${seconds} s")
  fi
done
echo "== fuzz summary"
printf '  %s\n' "${summary[@]}"
exit $status
