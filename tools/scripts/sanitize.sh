#!/usr/bin/env bash
# The sanitizer suite: a Debug build with AddressSanitizer + UndefinedBehaviorSanitizer
# (-DKNEESIM_SANITIZE=ON, every report fatal) in build-sanitize/, then the default test suite
# under it (`ctest -LE long`; only the targets it needs are built). Any sanitizer report fails
# its test. Builds and runs niced, since the machine is usually shared; extra arguments go to
# ctest (e.g. -R test_engine).
#   bash tools/scripts/sanitize.sh
set -euo pipefail
cd "$(dirname "$0")/../.."
bash tools/scripts/setup.sh --packages-only
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Debug -DKNEESIM_SANITIZE=ON >/dev/null
# only what the default suite runs: its test executables (a test's name is its target's) and
# the kneesim program the CLI tests start; not the long validations or the benchmarks
targets=(kneesim $(ctest --test-dir build-sanitize -N -LE long | awk '/Test +#/ {print $3}'))
nice -n 5 cmake --build build-sanitize -j"$(nproc)" --target "${targets[@]}"
# detect_leaks: the suite must be leak-free too; the OpenMP runtime keeps its thread pool
# until exit, which LeakSanitizer does not count as a leak
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1"
# leaks inside third-party libraries, each with its evidence (tests/fuzz/lsan_suppressions.txt)
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan_suppressions.txt:print_suppressions=0"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
nice -n 5 ctest --test-dir build-sanitize --output-on-failure -LE long -j"$(nproc)" "$@"
