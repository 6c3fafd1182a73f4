#!/usr/bin/env bash
# Runs the libFuzzer harnesses of fuzz/ one after another (or --parallel N at a
# time), building the fuzz tree (build-fuzz/, clang, LUCENT_FUZZ=ON) when
# needed, and prints a table: executions, coverage (cov/ft of libFuzzer's final
# stats), time, and whether a crash, leak or UB report ended the run.
#
#   packaging/fuzz.sh 600                 600 s per harness
#   packaging/fuzz.sh --runs 1000000      one million executions per harness
#   packaging/fuzz.sh --runs 1000000 --seconds 1800 fuzz_dicom fuzz_nifti
#   packaging/fuzz.sh --report            the table of the last runs, running nothing
#   --ignore-leaks: no leak check (to go on past a known third-party leak); the
#   table says so
#
# Seeds: fuzz/corpus/<name>/ (committed, small and synthetic; the DICOM ones are made
# by fuzz/seeds/make_seeds.py into build-fuzz/fuzz-seeds/dicom), plus at run time
# the real DICOM of ../shared/data, the quirks corpus made from it
# (tests/core/dicom/quirks/make_quirks.py) and the presets of resources/presets; what
# the fuzzer finds goes to build-fuzz/fuzz-corpus/<name>/ and is reused next
# time. A crashing input is saved under build-fuzz/fuzz-artifacts/<name>/, the
# whole output under build-fuzz/fuzz-logs/<name>.log. Exits 1 when any harness
# found something.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
build="${LUCENT_FUZZ_BUILD:-$root/build-fuzz}"
shared="$root/../shared/data"
seconds=0
runs=-1
parallel=1
report_only=0
leaks=1
names=()

usage() {
  sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
}
while [ $# -gt 0 ]; do
  case "$1" in
    --runs) runs="$2"; shift 2 ;;
    --seconds) seconds="$2"; shift 2 ;;
    --parallel) parallel="$2"; shift 2 ;;
    --report) report_only=1; shift ;;
    --ignore-leaks) leaks=0; shift ;;
    -h|--help) usage ;;
    [0-9]*) seconds="$1"; shift ;;
    fuzz_*) names+=("$1"); shift ;;
    *) echo "fuzz.sh: unknown argument '$1'" >&2; usage ;;
  esac
done
if [ "$report_only" -eq 0 ] && [ "$seconds" -eq 0 ] && [ "$runs" -lt 0 ]; then
  usage
fi

all=(fuzz_dicom fuzz_protocol fuzz_http_head fuzz_upload_parts fuzz_multipart fuzz_tf_json
     fuzz_metaimage fuzz_nifti fuzz_inv3 fuzz_plist fuzz_recording)
[ ${#names[@]} -eq 0 ] && names=("${all[@]}")

# Per harness: largest input (bytes), committed seeds, dictionary, extra seeds.
max_len() {
  case "$1" in
    fuzz_dicom) echo 16384 ;;          # real headers (most); their pixels are cut
    fuzz_upload_parts) echo 16384 ;;
    fuzz_multipart) echo 16384 ;;      # a few parts, chunked many ways
    fuzz_http_head) echo 17000 ;;      # the front door's head limit is 16 KiB
    fuzz_metaimage|fuzz_nifti|fuzz_inv3|fuzz_plist|fuzz_recording) echo 8192 ;;
    *) echo 4096 ;;
  esac
}
extra_seeds() {
  case "$1" in
    fuzz_dicom) [ -d "$shared" ] && echo "$shared" ;;
    fuzz_tf_json) echo "$root/resources/presets" ;;
  esac
  return 0
}

if [ "$report_only" -eq 0 ]; then
  if [ ! -f "$build/build.ninja" ]; then
    CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -G Ninja -DLUCENT_FUZZ=ON >/dev/null
  fi
  cmake --build "$build" --target "${names[@]}"

  run_one() {
    local name="$1" corpus="$build/fuzz-corpus/${1#fuzz_}" artifacts="$build/fuzz-artifacts/$1/"
    local log="$build/fuzz-logs/$1.log" seeds="$root/fuzz/corpus/${1#fuzz_}"
    local quirks=""
    if [ "$name" = fuzz_dicom ]; then # DICOM seeds are made, never committed
      python3 "$root/fuzz/seeds/make_seeds.py" --out "$build/fuzz-seeds" dicom
      seeds="$build/fuzz-seeds/dicom"
      if [ -d "$shared" ]; then # the quirks corpus of test_dicom_quirks, made from shared data
        quirks="$build/fuzz-seeds/quirks"
        python3 "$root/tests/core/dicom/quirks/make_quirks.py" "$quirks" "$shared"
      fi
    fi
    mkdir -p "$corpus" "$artifacts" "$(dirname "$log")"
    rm -f "$log.status"
    local args=(-max_len="$(max_len "$name")" -rss_limit_mb=2048 -timeout=20 -print_final_stats=1
                -artifact_prefix="$artifacts" -runs="$runs" -detect_leaks="$leaks")
    [ "$seconds" -gt 0 ] && args+=(-max_total_time="$seconds")
    local dict="$root/fuzz/dict/${name#fuzz_}.dict"
    [ -f "$dict" ] && args+=(-dict="$dict")
    local dirs=("$corpus")
    [ -d "$seeds" ] && dirs+=("$seeds")
    local extra
    extra="$(extra_seeds "$name")"
    [ -n "$extra" ] && dirs+=("$extra")
    [ -n "$quirks" ] && dirs+=("$quirks")
    local start end status=0
    start=$(date +%s)
    ASAN_OPTIONS="detect_leaks=$leaks:allocator_may_return_null=0:malloc_context_size=10" \
    UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
      "$build/bin/$name" "${args[@]}" "${dirs[@]}" >"$log" 2>&1 || status=$?
    end=$(date +%s)
    echo "$status $((end - start)) $leaks" >"$log.status"
  }

  for name in "${names[@]}"; do
    run_one "$name" &
    while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do
      wait -n || true
    done
  done
  wait

fi

found=0
printf '%-18s %12s %7s %8s %8s  %s\n' harness executions cov ft time result
for name in "${names[@]}"; do
  log="$build/fuzz-logs/$name.log"
  if [ ! -f "$log.status" ]; then
    printf '%-18s %12s %7s %8s %8s  %s\n' "$name" - - - - "not run (or still running)"
    continue
  fi
  read -r status elapsed checked <"$log.status"
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  # The last status line ("#N DONE cov: C ft: F ..." or the last progress line).
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  result=ok
  [ "${checked:-1}" = 0 ] && result="ok (leaks not checked)"
  if [ "$status" -ne 0 ] || grep -qE 'ERROR: (AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|libFuzzer)|runtime error:' "$log"; then
    found=1
    what=$(grep -m1 -oE 'SUMMARY: [A-Za-z]+: [^ ]+|runtime error: .*|ERROR: libFuzzer: [a-z-]+' "$log" || true)
    artifact=$(sed -n 's/.*Test unit written to //p' "$log" | tail -1)
    result="FOUND (${what:-exit $status}) ${artifact}"
  fi
  printf '%-18s %12s %7s %8s %7ss  %s\n' "$name" "${execs:-?}" "${cov:-?}" "${ft:-?}" "$elapsed" "$result"
done
exit $found
