#!/usr/bin/env bash
# The tables of docs/measurements.md's "Current numbers", re-measured with one binary and
# printed as Markdown.
#
# Usage: FOOTPRINT_BIN=target/release/footprint scripts/docs-numbers.sh [SECTION …]
#   SECTION: coverage | instructions | bench | pyramid (default: all four, in that order)
#   coverage      the paper's three views: P, L, V and M/V per mode (`footprint table --json`)
#   instructions  instructions per pixel, exact and paper projection (scripts/instructions.sh,
#                 valgrind; a few minutes per mode)
#   bench         ms per frame, one thread, fastest (median) of 15 interleaved rounds, and ×PS
#                 (`footprint bench`; wall-clock: run it on a quiet machine)
#   pyramid       RMSE through the pyramid / at level 0 on six maps (`footprint table --lod`)
# DEMS is the folder with msh_2007_10m.tif, bigtujunga_srtm30m.tif, D1.png and C1W.png
# (default /work/dems; see docs/measurements.md for where they come from).
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${FOOTPRINT_BIN:?set FOOTPRINT_BIN to a release build of footprint}
dems=${DEMS:-/work/dems}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

coverage() {
  "$bin" table --modes ps,li,ss8,ss16,ss32,as,as-exact,as2 --json 2>/dev/null > "$tmp/table.json"
  python3 - "$tmp/table.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
modes = [m["mode"] for m in d["cases"][0]["modes"]]
print("| pitch | eye | P | L | V | V level 0 | " + " | ".join(f"M/V {m}" for m in modes)
      + " | hits ss16 | hits as-exact |")
print("|---" * (8 + len(modes)) + "|")
for c in d["cases"]:
    by = {m["mode"]: m for m in c["modes"]}
    print(f"| {c['pitch']:.0f}° | {c['height'] / 1000:.1f} km | {c['P']:.1f} | {c['L']:,.1f} | "
          f"{c['V']:,.1f} | {c['V_level0']:,.1f} | "
          + " | ".join(f"{by[m]['coverage']:.3f}" for m in modes)
          + f" | {by['ss16']['hits']:,.0f} | {by['as-exact']['hits']:,.0f} |")
EOF
}

instructions() {
  FOOTPRINT_BIN=$bin scripts/instructions.sh classic ps li ss8 ss16 as as-exact as2 > "$tmp/exact.txt"
  FOOTPRINT_BIN=$bin FOOTPRINT_ARGS="--projection paper" \
    scripts/instructions.sh classic ps li ss8 ss16 as as-exact as2 > "$tmp/paper.txt"
  python3 - "$tmp/exact.txt" "$tmp/paper.txt" <<'EOF'
import sys
# instructions.sh prints a header, then: mode, instructions, steps, per step, per pixel.
exact, paper = ([line.split() for line in open(f).readlines()[1:]] for f in sys.argv[1:])
num = lambda s: float(s.replace(",", ""))
print("| mode | per pixel, exact | per pixel, paper | exact / paper | per step, exact | per step, paper | steps, exact | steps, paper |")
print("|---" * 8 + "|")
for e, p in zip(exact, paper):
    print(f"| {e[0]} | {num(e[4]):,.1f} | {num(p[4]):,.1f} | {num(e[4]) / num(p[4]):.2f} | "
          f"{num(e[3]):,.1f} | {num(p[3]):,.1f} | {e[2]} | {p[2]} |")
EOF
}

bench() {
  "$bin" bench --repeats 15 --json 2>/dev/null > "$tmp/bench.json"
  python3 - "$tmp/bench.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
modes = [m["mode"] for m in d["cases"][0]["modes"]]
print("| view | " + " | ".join(modes) + " |")
print("|---" * (1 + len(modes)) + "|")
for c in d["cases"]:
    name = f"{c['pitch']:.0f}°" if c["view"] == "paper" else "classic view"
    by = {m["mode"]: m for m in c["modes"]}
    print(f"| {name}, ms | " + " | ".join(f"{by[m]['ms']:.2f} ({by[m]['ms_median']:.2f})" for m in modes) + " |")
    print(f"| {name}, ×PS | " + " | ".join(f"{by[m]['ratio_to_ps']:.2f}" for m in modes) + " |")
EOF
}

pyramid() {
  local names=(mountains eroded plains msh tujunga comanche)
  local maps=("--terrain-size 1024" "--terrain eroded --terrain-size 384"
    "--terrain plains --terrain-size 384" "--dem $dems/msh_2007_10m.tif"
    "--dem $dems/bigtujunga_srtm30m.tif" "--dem $dems/D1.png --color $dems/C1W.png")
  for i in "${!names[@]}"; do
    for lod in on off; do
      # shellcheck disable=SC2086 # the map's options are words
      "$bin" table ${maps[$i]} --case all --modes as,as-exact,ss32,ps --lod "$lod" --json \
        2>/dev/null > "$tmp/${names[$i]}.$lod.json"
    done
  done
  python3 - "$tmp" "${names[@]}" <<'EOF'
import json, sys
tmp, names = sys.argv[1], sys.argv[2:]
modes = ["as", "as-exact", "ss32", "ps"]
print("| map | pitch | pixel / voxel at the first hit | " + " | ".join(modes) + " |")
print("|---" * (3 + len(modes)) + "|")
for name in names:
    on, off = (json.load(open(f"{tmp}/{name}.{lod}.json")) for lod in ("on", "off"))
    for c_on, c_off in zip(on["cases"], off["cases"]):
        a = {m["mode"]: m["rmse"] for m in c_on["modes"]}
        b = {m["mode"]: m["rmse"] for m in c_off["modes"]}
        mag = " (magnified)" if c_on["magnified"] else ""
        cells = [f"{a[m]:.3f} / {b[m]:.3f} = {a[m] / b[m]:.2f}" for m in modes]
        print(f"| {name} | {c_on['pitch']:.0f}° | {c_on['pixel_voxels']:.2f}{mag} | " + " | ".join(cells) + " |")
EOF
}

sections=("$@")
[ ${#sections[@]} -gt 0 ] || sections=(coverage instructions bench pyramid)
for s in "${sections[@]}"; do
  case $s in
    coverage | instructions | bench | pyramid) echo "## $s"; "$s"; echo ;;
    *) echo "docs-numbers.sh: unknown section $s (coverage, instructions, bench, pyramid)" >&2; exit 2 ;;
  esac
done
