#!/usr/bin/env bash
# Instructions and simulated cache misses per particle-step of a gc2d-rs binary on one pile of `gc2d-rs bench`, on one
# thread, from callgrind's cache simulation (docs/performance.md, "The layer's growth: lines from memory"). The counts
# are the same on every run, so they can judge a change of the data layout on a machine whose timings are noisy; but
# callgrind models no hardware prefetcher (a line it counts as missed may have been fetched ahead in time) and counts
# no write-backs of changed lines.
#
#   tools/cache-lines.sh BINARY PILE SIZE [STEPS]
#
# Settles the pile first without callgrind (or reads it from the bench's cache), then runs
# `BINARY bench --pile PILE --size SIZE --threads 1 --steps S` under callgrind for S = STEPS and 2·STEPS (default 20)
# and prints their difference per particle-step (so loading the pile and the untimed steps cancel): in all, and for the
# functions that miss the simulated last level most (then those with the most instructions).
#
# Environment: LL (the simulated last level as callgrind's `--LL=size,associativity,line size`; default
# 33554432,16,64, a 32 MiB L3; 524288,8,64 for a 512 KiB L2), CACHE (the bench's folder of settled piles; default the
# bench's own), TOP (functions listed; default 12), KEEP (a folder to keep the two callgrind files in; default none).
set -eu
if [ $# -lt 3 ]; then
  echo "usage: $0 BINARY PILE SIZE [STEPS]" >&2
  exit 2
fi
# A path, or a name on PATH.
binary=$(command -v "$1" || true)
pile=$2
size=$3
steps=${4:-20}
ll=${LL:-33554432,16,64}
top=${TOP:-12}
[ -n "$binary" ] && [ -x "$binary" ] || { echo "$1 is not an executable gc2d-rs" >&2; exit 2; }
for tool in valgrind callgrind_annotate; do
  command -v "$tool" > /dev/null ||
    { echo "$tool is not installed (Debian and Ubuntu: apt-get install valgrind)" >&2; exit 2; }
done
# Positive whole numbers only (the particle-steps divide the counts).
positive() { case $1 in '' | *[!0-9]*) false ;; *) [ "$((10#$1))" -gt 0 ] ;; esac; }
positive "$size" || { echo "SIZE must be a positive number of grains, not '$size'" >&2; exit 2; }
positive "$steps" || { echo "STEPS must be a positive number of steps, not '$steps'" >&2; exit 2; }
size=$((10#$size))
steps=$((10#$steps))

bench=(bench --pile "$pile" --size "$size" --threads 1 --quiet)
if [ -n "${CACHE:-}" ]; then
  bench+=(--cache "$CACHE")
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Settling under callgrind would take hours: the pile is settled (or read from the cache) natively first.
"$binary" "${bench[@]}" --steps 1 > /dev/null
for run in 1 2; do
  valgrind --tool=callgrind --cache-sim=yes --LL="$ll" --callgrind-out-file="$work/run$run.out" \
    "$binary" "${bench[@]}" --steps $((run * steps)) > /dev/null 2> "$work/run$run.log" ||
    { cat "$work/run$run.log" >&2; exit 1; }
done
# The columns read below, in callgrind's order for a cache simulation.
grep -qx 'events: Ir Dr Dw I1mr D1mr D1mw ILmr DLmr DLmw' "$work/run1.out" ||
  { echo "unexpected events in callgrind's output: $(grep '^events:' "$work/run1.out")" >&2; exit 1; }
if [ -n "${KEEP:-}" ]; then
  mkdir -p "$KEEP"
  cp "$work/run1.out" "$KEEP/$pile-$size-$steps.callgrind"
  cp "$work/run2.out" "$KEEP/$pile-$size-$((2 * steps)).callgrind"
fi

# Each function's cost (own, not inclusive), one line per function: the nine event counts, then the name.
costs() {
  callgrind_annotate --auto=no --inclusive=no --show-percs=no --threshold=100 "$1" |
    awk '$1 ~ /^[0-9,]+$/ && NF >= 10 {
      name = $10; for (k = 11; k <= NF; k++) name = name " " $k
      sub(/ \[[^]]*\]$/, "", name); sub(/^[^:]*:/, "", name)
      line = ""; for (k = 1; k <= 9; k++) { v = $k; gsub(/,/, "", v); if (v == ".") v = 0; line = line v " " }
      print line name
    }'
}
costs "$work/run1.out" > "$work/run1.txt"
costs "$work/run2.out" > "$work/run2.txt"
particle_steps=$((steps * size))
echo "$binary on $pile $size, one thread; per particle-step over $steps steps; last level simulated as --LL=$ll"
printf '%10s %8s %8s %8s %8s  %s\n' instructions L1-read L1-write LL-read LL-write function
awk -v n="$particle_steps" '
  function name_of(line,    k) { for (k = 1; k <= 9; k++) sub(/^[^ ]+ /, "", line); return line }
  FNR == NR { name = name_of($0); for (k = 1; k <= 9; k++) first[name, k] += $k; next }
  { name = name_of($0); names[name] = 1; for (k = 1; k <= 9; k++) second[name, k] += $k }
  END {
    for (name in names) {
      for (k = 1; k <= 9; k++) d[k] = (second[name, k] - first[name, k]) / n
      row = sprintf("%10.1f %8.2f %8.2f %8.2f %8.2f  %s", d[1], d[5], d[6], d[8], d[9], name)
      if (name == "PROGRAM TOTALS") total = row; else print d[8] + d[9], d[1], row
    }
    print 1e300, 0, total
  }' "$work/run1.txt" "$work/run2.txt" | sort -k1,1gr -k2,2gr | head -n $((top + 1)) | cut -d' ' -f3-
