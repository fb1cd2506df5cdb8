#!/usr/bin/env bash
# Thread scaling of one or more gc2d-rs binaries, side by side on the same machine (docs/performance.md,
# "Sixteen cores"): each pile is measured by every binary in turn, on 1, 2, 4, … threads, with the time of each stage
# of the step (`gc2d-rs bench --stages`).
#
#   tools/bench-threads.sh OUT_DIR BINARY [BINARY …]
#
# Environment: PILES (default "squares:12800 layer:100000 dense7:10000"), THREADS (default 1,2,4,8,16, trimmed to
# the cores), CACHE (the folder of settled piles; default the bench's own). Each binary writes OUT_DIR/NAME-PILE-SIZE.csv
# (NAME: the binary's file name) and the tables to OUT_DIR/log.txt. Settled piles are shared through the cache, so
# the binaries must have the same checkpoint format; the first to need a pile settles it (the 100,000-grain layer:
# about 30 s on 16 cores, minutes on 2).
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 OUT_DIR BINARY [BINARY …]" >&2
  exit 2
fi
OUT_DIR=$1
shift
for binary in "$@"; do
  [ -x "$binary" ] || { echo "$binary is not an executable gc2d-rs" >&2; exit 2; }
done
CORES=$(nproc)
THREADS=${THREADS:-$(for t in 1 2 4 8 16; do [ "$t" -le "$CORES" ] && printf '%s,' "$t"; done | sed 's/,$//')}
PILES=${PILES:-"squares:12800 layer:100000 dense7:10000"}
mkdir -p "$OUT_DIR"
cache_args=()
[ -n "${CACHE:-}" ] && cache_args=(--cache "$CACHE")
{ echo "$CORES cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-), load average $(cut -d' ' -f1-3 /proc/loadavg)"; } |
  tee -a "$OUT_DIR/log.txt"
for pile_size in $PILES; do
  pile=${pile_size%%:*}
  size=${pile_size##*:}
  for binary in "$@"; do
    name=$(basename "$binary")
    echo "=== $name $pile $size" | tee -a "$OUT_DIR/log.txt"
    "$binary" bench --pile "$pile" --size "$size" --threads "$THREADS" --stages --quiet "${cache_args[@]}" \
      --csv "$OUT_DIR/$name-$pile-$size.csv" 2>&1 | tee -a "$OUT_DIR/log.txt"
  done
done
