#!/usr/bin/env bash
# Thread scaling of one or more gc2d-rs binaries, side by side on the same machine (docs/performance.md,
# "Sixteen cores"): each pile is measured by every binary in turn, on 1, 2, 4, … threads, with the time of each stage
# of the step (`gc2d-rs bench --stages`), in one or more rounds.
#
#   tools/bench-threads.sh OUT_DIR BINARY [BINARY …]
#
# Environment: PILES (default "squares:12800 layer:100000 dense7:10000"), THREADS (default 1,2,4,8,16, trimmed to
# the cores), ROUNDS (default 1), LATER_THREADS (the thread counts of the rounds after the first, e.g. "1,16" for many
# short rounds after one full one; default THREADS), STOP_AFTER (seconds: no round starts after this many, so that a
# script fits a lease of a borrowed machine; default none), PARTICLE_STEPS (default the bench's own), CACHE (a folder of
# settled piles to start from, e.g. carried from another machine; default none).
#
# Each binary settles and reads its piles in a cache folder of its own, OUT_DIR/cache-NAME (NAME: the binary's file
# name, or its folder's and file name where two binaries share a file name), seeded from CACHE, so that binaries of
# different checkpoint formats never overwrite each other's settled states; a pile the first binary settles is copied to
# the others' folders before they need it (the 100,000-grain layer: about 20 s on 16 cores, minutes on 2). Writes
# OUT_DIR/NAME-PILE-SIZE-rROUND.csv, all rows in one OUT_DIR/all.csv (the bench's columns after `binary,round`), and the
# tables to OUT_DIR/log.txt.
set -eu
if [ $# -lt 2 ]; then
  echo "usage: $0 OUT_DIR BINARY [BINARY …]" >&2
  exit 2
fi
OUT_DIR=$1
shift
# Each binary's name in the CSVs and cache folders: its file name, or its folder and file name where two binaries
# share a file name (before/gc2d-rs and after/gc2d-rs are "before-gc2d-rs" and "after-gc2d-rs").
binaries=("$@")
names=()
for binary in "$@"; do
  [ -x "$binary" ] || { echo "$binary is not an executable gc2d-rs" >&2; exit 2; }
  names+=("$(basename "$binary")")
done
if [ "$(printf '%s\n' "${names[@]}" | sort | uniq -d)" ]; then
  names=()
  for binary in "$@"; do
    names+=("$(basename "$(dirname "$binary")")-$(basename "$binary")")
  done
fi
if [ "$(printf '%s\n' "${names[@]}" | sort | uniq -d)" ]; then
  echo "the binaries need different file or folder names (they name the CSVs and cache folders): ${names[*]}" >&2
  exit 2
fi
CORES=$(nproc)
THREADS=${THREADS:-$(for t in 1 2 4 8 16; do [ "$t" -le "$CORES" ] && printf '%s,' "$t"; done | sed 's/,$//')}
PILES=${PILES:-"squares:12800 layer:100000 dense7:10000"}
ROUNDS=${ROUNDS:-1}
LATER_THREADS=${LATER_THREADS:-$THREADS}
started=$(date +%s)
mkdir -p "$OUT_DIR"
for name in "${names[@]}"; do
  mkdir -p "$OUT_DIR/cache-$name"
  if [ -n "${CACHE:-}" ]; then cp -R "$CACHE/." "$OUT_DIR/cache-$name/"; fi
done
steps_args=()
[ -n "${PARTICLE_STEPS:-}" ] && steps_args=(--particle-steps "$PARTICLE_STEPS")
{ echo "$CORES cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2-), load average $(cut -d' ' -f1-3 /proc/loadavg)"; } |
  tee -a "$OUT_DIR/log.txt"
for round in $(seq "$ROUNDS"); do
  if [ -n "${STOP_AFTER:-}" ] && [ $(($(date +%s) - started)) -gt "$STOP_AFTER" ]; then
    echo "stopped before round $round: more than $STOP_AFTER s have passed" | tee -a "$OUT_DIR/log.txt"
    break
  fi
  threads=$THREADS
  [ "$round" -gt 1 ] && threads=$LATER_THREADS
  for pile_size in $PILES; do
    pile=${pile_size%%:*}
    size=${pile_size##*:}
    for index in "${!names[@]}"; do
      name=${names[$index]}
      binary=${binaries[$index]}
      csv="$OUT_DIR/$name-$pile-$size-r$round.csv"
      echo "=== $name $pile $size round $round" | tee -a "$OUT_DIR/log.txt"
      "$binary" bench --pile "$pile" --size "$size" --threads "$threads" --stages --quiet "${steps_args[@]}" \
        --cache "$OUT_DIR/cache-$name" --csv "$csv" 2>&1 | tee -a "$OUT_DIR/log.txt"
      [ -s "$OUT_DIR/all.csv" ] || echo "binary,round,$(head -n 1 "$csv")" > "$OUT_DIR/all.csv"
      tail -n +2 "$csv" | sed "s/^/$name,$round,/" >> "$OUT_DIR/all.csv"
      # Share what this binary settled with the others that have no settled state of that pile yet.
      for other in "${names[@]}"; do
        for settled in "$OUT_DIR/cache-$name/$pile-$size-"*; do
          if [ -e "$settled" ] && [ ! -e "$OUT_DIR/cache-$other/$(basename "$settled")" ]; then
            cp "$settled" "$OUT_DIR/cache-$other/"
          fi
        done
      done
    done
  done
done
