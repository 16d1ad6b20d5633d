#!/usr/bin/env bash
# Instructions per traversal step and per pixel of the walk, counted by valgrind's callgrind
# (instructions, not seconds: the same binary and inputs give the same count on a busy machine).
#
# For each mode and each of the paper's three views (pitch 40°, 20°, 5°; 400×400; FOV 10°;
# fit-first-hit; built-in terrain), `footprint render --threads 1` runs under callgrind, which
# collects only inside its one frame render (`footprint_scenes::counted::render_with`, which
# was `footprint_scenes::render::render_with`; the pattern matches both): on one thread the
# frame is walked straight into its image, then the exact projection's resample).
# Until 2026-11-26 `render` drew it three times that way and the script divided by 3; the
# counts are the same. `footprint render --counts` gives the same frames'
# traversal steps `a`, so the script prints instructions per frame (the three views together),
# per traversal step and per pixel (3 × 400 × 400 pixels).
#
# With FOOTPRINT_COLLECT=core, callgrind collects only inside the core's door
# (`Frame::render`): the same frame without the host's allocation of its image and, in the
# exact projection, of its scratch grid, which glibc clears byte by byte (`calloc`'s `rep
# stosb`, one instruction per byte under callgrind: about 3 per pixel for the image and as much
# again for the scratch). An embedder allocates both once.
#
# Usage: scripts/instructions.sh [MODE …]   (default: classic ps li ss8 ss16 as as-exact)
# Needs valgrind (apt-get install -y valgrind). Extra arguments for both commands (a --dem, a
# --seed) can be passed in FOOTPRINT_ARGS.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v valgrind >/dev/null || { echo "instructions.sh: valgrind not found (apt-get install -y valgrind)" >&2; exit 2; }
[ -n "${FOOTPRINT_BIN:-}" ] || cargo build --release --quiet
bin=${FOOTPRINT_BIN:-target/release/footprint}
modes=("$@")
[ ${#modes[@]} -gt 0 ] || modes=(classic ps li ss8 ss16 as as-exact)
args=(${FOOTPRINT_ARGS:-})
collect='footprint_scenes::*render_with*'
[ "${FOOTPRINT_COLLECT:-}" != core ] || collect='footprint_core::terrain::image::*Frame*::render'
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

printf '%-9s %15s %12s %10s %10s\n' mode "instr/3 frames" steps instr/step instr/px
for m in "${modes[@]}"; do
  instr=0
  steps=0
  for p in 40 20 5; do
    # `render` draws the frame once (`render_with` on one thread), which callgrind counts
    # (with FOOTPRINT_COLLECT=core, only the core's `Frame::render` inside it); everything
    # else (the map, the pyramid, the fit-first-hit probe, the PNG) is not collected.
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.out" \
      --toggle-collect="$collect" \
      "$bin" render "${args[@]}" --view paper --threads 1 --pitch "$p" --mode "$m" --out "$tmp/x.png" \
      >/dev/null 2>"$tmp/cg.err"
    i=$(sed -n 's/.*Collected : \([0-9]*\).*/\1/p' "$tmp/cg.err")
    instr=$((instr + i))
    json=$("$bin" render "${args[@]}" --view paper --pitch "$p" --mode "$m" --counts --json --out "$tmp/x.png")
    a=$(printf '%s' "$json" | python3 -c 'import json,sys; print(json.load(sys.stdin)["counts"]["a"])')
    steps=$((steps + a))
  done
  python3 -c "i,s=$instr,$steps; print(f'{\"$m\":<9} {i:>15,} {s:>12,} {i/s:>10.1f} {i/480000:>10.1f}')"
done
