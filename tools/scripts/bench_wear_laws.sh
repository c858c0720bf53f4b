#!/bin/sh
# Cost of the cross-shear and contact-area wear laws per simulated gait cycle against Archard
# (docs/performance.md, wear laws). Two measures, both load-independent or taken as ratios:
#  1. callgrind instruction counts of `kneesim wear` with 2 and with 6 geometry updates per law;
#     the difference is 4 simulated cycles (each update simulates one cycle with the law's
#     accumulator, then updates the geometry), so (Ir(6) - Ir(2)) / 4 is one cycle's cost
#     without the set-up, and its ratio to archard's is the law's extra cost per cycle;
#  2. user CPU seconds of the default `kneesim wear` (5 Mc, 20 updates, 22 cycles), the laws
#     run alternately, REPEATS times each; the ratio of the medians to archard's.
# Usage: tools/scripts/bench_wear_laws.sh [BUILD_DIR] [REPEATS]   (run with nice on a shared host)
set -eu
BUILD=${1:-build}
REPEATS=${2:-5}
K="$BUILD/tools/kneesim"
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
export OMP_NUM_THREADS=1 KNEESIM_CACHE_DIR=off
LAWS="archard cross_shear contact_area"
law_args() {
  case $1 in
    archard) echo "--wear-law archard" ;;
    cross_shear) echo "--wear-law cross_shear --law-param cross_shear_gain=5.41" ;;
    contact_area) echo "--wear-law contact_area --law-param cross_shear_gain=5.41 --set material.area_wear_coefficient=2e-9" ;;
  esac
}
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), load: $(cut -d' ' -f1-3 /proc/loadavg)"
echo "# 1. callgrind instructions per simulated cycle ((Ir 6 updates - Ir 2 updates) / 4)"
for law in $LAWS; do
  for u in 2 6; do
    # shellcheck disable=SC2046
    valgrind --tool=callgrind --callgrind-out-file="$TMP/cg.$law.$u" "$K" wear \
      --cycles $((u * 1000)) --update-every 1000 --no-plots --no-depth-maps --quiet \
      $(law_args "$law") --out "$TMP/w" >/dev/null 2>"$TMP/err" || { cat "$TMP/err"; exit 1; }
  done
  i2=$(grep '^summary:' "$TMP/cg.$law.2" | cut -d' ' -f2)
  i6=$(grep '^summary:' "$TMP/cg.$law.6" | cut -d' ' -f2)
  echo "$law $(( (i6 - i2) / 4 ))" | tee -a "$TMP/ir"
done
awk 'NR == 1 {a = $2} {printf "%-13s %.4g instructions/cycle, ratio to archard %.3f\n", $1, $2, $2 / a}' "$TMP/ir"
echo "# 2. user CPU seconds of kneesim wear (5 Mc, 20 updates), laws alternated, $REPEATS repeats"
r=1
while [ "$r" -le "$REPEATS" ]; do
  for law in $LAWS; do
    # shellcheck disable=SC2046
    /usr/bin/time -f "$law %U" -a -o "$TMP/cpu" "$K" wear --no-plots --no-depth-maps --quiet \
      $(law_args "$law") --out "$TMP/w" >/dev/null
  done
  r=$((r + 1))
done
for law in $LAWS; do
  grep "^$law " "$TMP/cpu" | cut -d' ' -f2 | sort -n | awk -v law="$law" \
    '{v[NR] = $1} END {m = (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
      printf "%s %.3f %.3f %.3f\n", law, m, v[1], v[NR]}'
done | awk 'NR == 1 {a = $2} {printf "%-13s median %.3f s user (%.3f-%.3f), ratio to archard %.3f\n", $1, $2, $3, $4, $2 / a}'
