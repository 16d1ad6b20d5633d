#!/usr/bin/env bash
# footprint against two voxel-space ("Comanche") renderers, voxelspace-sdl (C,
# github.com/gustavopezzi/voxelspace-sdl) and mountain (Rust, github.com/Blizarre/mountain),
# at equal work: the same map pair, view and image. Prints Markdown: instructions per frame
# (valgrind's callgrind), ms per frame (wall clock, interleaved rounds, fastest and median),
# and the ratios issue 52 sets targets for.
#
# Usage: VOXELSPACE_SDL=BIN MOUNTAIN=BIN FOOTPRINT_BIN=BIN scripts/voxel-space.sh
#   FRAMES (100) frames a timed run adds, ROUNDS (10) interleaved rounds, CG_FRAMES (3) frames
#   a counted run adds, MODES footprint's modes (default "classic ps as as-exact as2 ps:paper
#   as:paper as-exact:paper as2:paper"; MODE:paper is MODE with `--projection paper`, which at
#   pitch 0 gives the same image without the exact projection's resampling), DEMS (/work/dems)
#   the folder with D1.png and C1W.png, BREAKDOWN=1 also prints the top 15 functions of one
#   frame of footprint `as` and `ps` (both projections). Needs valgrind and callgrind_annotate.
#
# Building the two comparison renderers is NOT in this repository, on purpose: their code is
# fetched from elsewhere, and neither it, nor a binary built from it, nor a recipe that builds
# it may be committed here. This script only runs binaries it is given. Their contract:
# `BIN N` renders the equal-work view below N times, headless, at 400×400 into a buffer in
# memory, then prints a checksum of the image (so the work cannot be optimised away); `BIN 0`
# does the start-up (loading the map) and nothing else. What was changed to get that, in prose:
# every SDL call (window, renderer, texture upload, present, event polling, frame-rate delay,
# input and player movement) removed, the framebuffer or SDL surface replaced by a plain array,
# the HUD cross-hair dropped; the main loop replaced by a loop of N calls of the renderers' own
# `draw` functions (unchanged inner loops); the camera constants set as below; voxelspace-sdl
# reads D1/C1W as raw bytes (heights, colour indices, a 768-byte palette) converted from the
# PNGs instead of its GIFs, in daylight colours (its NIGHT_MODE off); mountain's `draw` with
# fog and bilinear filtering off (its near rows otherwise interpolate, its far ones fade).
#
# The equal-work view (the map's units are voxels: heights of the 8-bit PNG are voxel-space
# units, one height unit one voxel wide, so footprint gets `--spacing 1 --height-scale 1`):
#   eye at voxel (512, 512), 130 height units above height 0 (the map's top is 118), looking
#   east: voxelspace-sdl's own default place, angle 0; mountain's camera angle -pi/2; footprint
#   `--heading 90`.
#   90° horizontal field of view on 400 columns, square pixels: the focal length is 200 px, so
#   voxelspace-sdl's VERTICAL_SCALE_FACTOR is 200 (was 35) and mountain's scale_height 0.5
#   (0.5 × 400 rows = 200). footprint's --fov is vertical; on a square image it is the same 90°.
#   The horizon on the middle row. Voxel-space renderers shift the image by a horizon offset
#   instead of pitching the camera: row = horizon + 200·(eye − h)/z. A pitched pinhole puts
#   the horizon at 200 − 200·tan(pitch), so footprint's pitch is atan((200 − horizon)/200);
#   only at horizon 200 (pitch 0) are the sheared and the pitched camera the same image, so
#   that is the view (voxelspace-sdl's pitch = 200 − 400/12, which its zero-roll tilt of
#   rows/12 brings to 200; mountain's horizon 200, counted from the bottom).
#   Far: the voxel-space renderers step the depth z = 1, 2, …, 999 (a far plane at 1,000, one
#   sample per column per unit of depth, the edge columns reaching 1,414 voxels); footprint's
#   --far 1000 is a horizontal distance along each column, a circular arc (π/4 of the ground of
#   the voxel-space renderers' triangle). Beyond the map's edge they wrap it, footprint mirrors.
set -euo pipefail
command -v valgrind >/dev/null || { echo "voxel-space.sh: valgrind not found" >&2; exit 2; }
vs=${VOXELSPACE_SDL:?set VOXELSPACE_SDL to the headless voxelspace-sdl binary}
mt=${MOUNTAIN:?set MOUNTAIN to the headless mountain binary}
fp=${FOOTPRINT_BIN:?set FOOTPRINT_BIN to a release build of footprint}
dems=${DEMS:-/work/dems}
frames=${FRAMES:-100}
rounds=${ROUNDS:-10}
cg_frames=${CG_FRAMES:-3}
read -r -a modes <<< "${MODES:-classic ps as as-exact as2 ps:paper as:paper as-exact:paper as2:paper}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
view=(--dem "$dems/D1.png" --color "$dems/C1W.png" --spacing 1 --height-scale 1 --x 512 --y 512
      --height 130 --heading 90 --pitch 0 --fov 90 --size 400x400 --far 1000 --threads 1)
names=(voxelspace-sdl mountain "${modes[@]}")

# cmd NAME K: the command line that starts up and renders K frames (footprint: K ≥ 1 repeats).
cmd() {
  case $1 in
    voxelspace-sdl) argv=("$vs" "$2") ;;
    mountain) argv=("$mt" "$2") ;;
    *:paper) argv=("$fp" render "${view[@]}" --mode "${1%:paper}" --projection paper --repeats "$2" --out "$tmp/fp.png") ;;
    *) argv=("$fp" render "${view[@]}" --mode "$1" --repeats "$2" --out "$tmp/fp.png") ;;
  esac
}
run() { cmd "$1" "$2"; "${argv[@]}" >/dev/null; }
commas() { sed ':a;s/\B[0-9]\{3\}\>/,&/;ta' <<< "$1"; }

# Instructions per frame: (run with 1 + CG_FRAMES frames − run with 1) / CG_FRAMES, so the
# start-up (map loading, footprint's pyramid) and the image write cancel.
instr() {
  cmd "$1" "$2"
  valgrind --tool=callgrind --callgrind-out-file=/dev/null "${argv[@]}" 2>&1 >/dev/null |
    sed -n 's/.*Collected : \([0-9]*\).*/\1/p'
}
declare -A ipf
for n in "${names[@]}"; do
  a=$(instr "$n" 1)
  b=$(instr "$n" $((1 + cg_frames)))
  ipf[$n]=$(( (b - a) / cg_frames ))
done

# Time per frame: (wall time of 1 + FRAMES frames − of 1 frame) / FRAMES, every renderer once a
# round, ROUNDS rounds; the fastest and the median round.
for ((r = 0; r < rounds; r++)); do
  for n in "${names[@]}"; do
    t0=${EPOCHREALTIME/./}; run "$n" 1; t1=${EPOCHREALTIME/./}
    run "$n" $((1 + frames)); t2=${EPOCHREALTIME/./}
    echo "$(( (t2 - t1) - (t1 - t0) ))" >> "$tmp/t.$n"
  done
done
declare -A tmin tmed
for n in "${names[@]}"; do
  read -r tmin[$n] tmed[$n] < <(sort -n "$tmp/t.$n" | awk -v f="$frames" \
    '{ v[NR] = $1 } END { m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2;
       printf "%.3f %.3f\n", v[1] / f / 1000, m / f / 1000 }')
done

echo "| renderer | instructions / frame | ms / frame, fastest | ms / frame, median |"
echo "|---|---:|---:|---:|"
for n in "${names[@]}"; do
  label=$n; [[ $n == voxelspace-sdl || $n == mountain ]] || label="footprint \`$n\`"
  printf '| %s | %s | %s | %s |\n' "$label" \
    "$(commas "${ipf[$n]}")" "${tmin[$n]}" "${tmed[$n]}"
done
echo
ratio() { # LABEL A B TARGET
  awk -v l="$1" -v a="$2" -v b="$3" -v t="$4" 'BEGIN { x = a / b;
    printf "| %s | %.2f | ≤ %.1f | %s |\n", l, x, t, (x <= t ? "yes" : "no") }'
}
echo "| ratio | value | target | holds |"
echo "|---|---:|---:|---|"
for p in "" :paper; do
  [[ -n ${ipf[as$p]:-} && -n ${ipf[ps$p]:-} ]] || continue
  as="\`as$p\`" ps="\`ps$p\`"
  ratio "$as / mountain, time (median)" "${tmed[as$p]}" "${tmed[mountain]}" 1.5
  ratio "$as / mountain, time (fastest)" "${tmin[as$p]}" "${tmin[mountain]}" 1.5
  ratio "$as / mountain, instructions" "${ipf[as$p]}" "${ipf[mountain]}" 1.5
  ratio "$as / $ps, instructions" "${ipf[as$p]}" "${ipf[ps$p]}" 3.0
  ratio "$ps / mountain, time (median)" "${tmed[ps$p]}" "${tmed[mountain]}" 0.8
  ratio "$ps / mountain, time (fastest)" "${tmin[ps$p]}" "${tmin[mountain]}" 0.8
  ratio "$ps / mountain, instructions" "${ipf[ps$p]}" "${ipf[mountain]}" 0.8
done
echo
echo "FRAMES=$frames ROUNDS=$rounds CG_FRAMES=$cg_frames; $("$fp" --version)"

# Where footprint's instructions go in one frame: callgrind collecting only inside the frame
# render (`footprint_scenes::counted::render_with`, formerly `render::render_with`; the pattern
# matches both), the top 15 of callgrind_annotate's file:function lines (code inlined into a
# function is counted under its own source file).
if [[ ${BREAKDOWN:-0} == 1 ]]; then
  for m in as ps as:paper ps:paper; do
    cmd "$m" 1
    valgrind --tool=callgrind --callgrind-out-file="$tmp/cg.$m" \
      --toggle-collect='footprint_scenes::*render_with*' "${argv[@]}" >/dev/null 2>&1
    callgrind_annotate --auto=no "$tmp/cg.$m" | awk '
      /PROGRAM TOTALS/ { gsub(",", "", $1); print "total\t" $1 }
      /^ *[0-9,]+ \( *[0-9.]+%\) +[^ ]*:/ {
        n = $1; gsub(",", "", n)
        f = $0; sub(/^ *[0-9,]+ \( *[0-9.]+%\) +/, "", f); sub(/ \[[^]]*\]$/, "", f)
        if (!sub(/^\/rustc\/[0-9a-f]+\/library\//, "std:", f) &&
            match(f, /(core|scenes|host)\/src\/[^:]*:/)) f = substr(f, RSTART)
        print f "\t" n }' > "$tmp/fn.$m"
    echo
    echo "| footprint \`$m\`, one frame: file:function | instructions | share |"
    echo "|---|---:|---:|"
    total=$(awk -F '\t' '$1 == "total" { print $2 }' "$tmp/fn.$m")
    grep -v '^total' "$tmp/fn.$m" | sort -t "$(printf '\t')" -k2,2nr | awk 'NR <= 15' |
      while IFS=$'\t' read -r f n; do
        printf '| `%s` | %s | %s %% |\n' "$f" "$(commas "$n")" "$(awk "BEGIN { printf \"%.1f\", 100 * $n / $total }")"
      done
  done
  # Where `as` spends its extra instructions: the largest differences, `as` − `ps`.
  for p in "" :paper; do
    echo
    echo "| \`as$p\` − \`ps$p\`: file:function | \`as$p\` | \`ps$p\` | difference |"
    echo "|---|---:|---:|---:|"
    awk -F '\t' 'FNR == NR { a[$1] = $2; next } { b[$1] = $2 }
      END { for (f in a) if (f != "total") print f "\t" a[f] "\t" b[f] + 0 "\t" a[f] - b[f];
            for (f in b) if (!(f in a)) print f "\t0\t" b[f] "\t" -b[f];
            print "total\t" a["total"] "\t" b["total"] "\t" a["total"] - b["total"] }' \
      "$tmp/fn.as$p" "$tmp/fn.ps$p" | sort -t "$(printf '\t')" -k4,4nr | awk 'NR <= 9' |
      while IFS=$'\t' read -r f a b d; do
        printf '| `%s` | %s | %s | %s |\n' "$f" "$(commas "$a")" "$(commas "$b")" "$(commas "$d")"
      done
  done
fi
