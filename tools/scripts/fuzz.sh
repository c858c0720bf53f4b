#!/usr/bin/env bash
# Fuzzing: builds the libFuzzer harnesses of tests/fuzz with clang, ASan and UBSan in
# build-fuzz/ (-DKNEESIM_FUZZ=ON) and runs each for SECONDS (default 600), two at a time,
# niced, starting from the seed corpus in tests/fuzz/corpus/<harness> and growing a working
# corpus in build-fuzz/tests/fuzz/corpus_<harness>. A crash leaves
# build-fuzz/tests/fuzz/crash_<harness>_*: copy it to tests/fuzz/regressions/<harness>/ so
# the default suite replays it (replay_<harness>).
#   bash tools/scripts/fuzz.sh [SECONDS] [HARNESS...]
# Harnesses: config mesh tables diagnosis_csv checkpoint. Needs clang and libclang-rt-14-dev,
# installed here (not by setup.sh: the default build does not need them).
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${1:-600}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -eq 0 ] && harnesses=(config mesh tables diagnosis_csv checkpoint)
bash tools/scripts/setup.sh --packages-only clang libclang-rt-14-dev
CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=Debug -DKNEESIM_FUZZ=ON \
  -DKNEESIM_BUILD_TOOLS=OFF >/dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
nice -n 5 cmake --build build-fuzz -j"$(nproc)" --target "${targets[@]}"
dir=build-fuzz/tests/fuzz
# leaks inside third-party libraries, each with its evidence (tests/fuzz/lsan_suppressions.txt)
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan_suppressions.txt:print_suppressions=0"
run_one() {
  local h=$1
  mkdir -p "$dir/corpus_$h"
  local rc=0
  nice -n 5 "$dir/fuzz_$h" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 \
    -print_final_stats=1 -artifact_prefix="$dir/crash_${h}_" "$dir/corpus_$h" \
    "tests/fuzz/corpus/$h" >"$dir/fuzz_$h.log" 2>&1 || rc=$?
  # the totals libFuzzer prints at the end (executions, exec/s, time) and the corpus grown
  echo "$h: exit $rc," \
    "$(grep -E 'stat::(number_of_executed_units|average_exec_per_sec)' "$dir/fuzz_$h.log" |
       tr -s ' ' | tr '\n' ' ')" \
    "corpus $(ls "$dir/corpus_$h" | wc -l) files (log $dir/fuzz_$h.log)"
  return $rc
}
status=0
for ((i = 0; i < ${#harnesses[@]}; i += 2)); do
  pids=()
  for h in "${harnesses[@]:i:2}"; do run_one "$h" & pids+=($!); done
  for p in "${pids[@]}"; do wait "$p" || status=1; done
done
exit $status
