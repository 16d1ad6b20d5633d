#!/usr/bin/env bash
# Instructions per traversal step and per pixel of the walk, counted by valgrind's callgrind
# (instructions, not seconds: the same binary and inputs give the same count on a busy machine).
#
# For each mode, `footprint bench` renders the paper's three frames (pitch 40°, 20°, 5°; 400×400;
# FOV 10°; fit-first-hit; built-in terrain; one thread, no counting) once under callgrind, which
# collects only inside `footprint_core::column::render`. `footprint render --counts` gives the
# same frames' traversal steps `a` and pixels, so the script prints instructions per frame, per
# step and per pixel, summed over the three frames.
#
# Usage: scripts/instructions.sh [MODE …]   (default: ps li ss8 ss16 as)
# Needs valgrind (apt-get install -y valgrind). Extra arguments for both commands (a --dem, a
# --seed) can be passed in FOOTPRINT_ARGS.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v valgrind >/dev/null || { echo "instructions.sh: valgrind not found (apt-get install -y valgrind)" >&2; exit 2; }
cargo build --release --quiet
bin=target/release/footprint
modes=("$@")
[ ${#modes[@]} -gt 0 ] || modes=(ps li ss8 ss16 as)
args=(${FOOTPRINT_ARGS:-})
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

printf '%-6s %14s %12s %10s %12s %10s\n' mode "instr/3 frames" steps "instr/step" pixels "instr/px"
for m in "${modes[@]}"; do
  valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" \
    --toggle-collect='footprint_core::column::render*' \
    "$bin" bench "${args[@]}" --modes "$m" --repeats 1 >/dev/null 2>"$tmp/cg.err"
  instr=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/cg.err")
  steps=0
  pixels=0
  for p in 40 20 5; do
    json=$("$bin" render "${args[@]}" --pitch "$p" --mode "$m" --counts --json --out "$tmp/x.png")
    a=$(printf '%s' "$json" | python3 -c 'import json,sys; print(json.load(sys.stdin)["counts"]["a"])')
    steps=$((steps + a))
    pixels=$((pixels + 160000))
  done
  python3 -c "i,s,p=$instr,$steps,$pixels; print(f'{\"$m\":<6} {i:>14,} {s:>12,} {i/s:>10.1f} {p:>12,} {i/p:>10.1f}')"
done
