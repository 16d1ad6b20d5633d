#!/usr/bin/env bash
# Whole-frame flicker against the truth on the six maps of docs/measurements.md
# ("Whole-frame flicker against the truth" in "Current numbers").
#
# Usage: FOOTPRINT_BIN=… DEMS=/work/dems OUT=DIR FRAMES=N scripts/flicker-truth.sh [MAP …]
#   MAP: mountains eroded plains msh tujunga comanche (default: all six, in that order)
#   Runs `footprint fly MAP --frames N --modes ps,ss16,as,as-exact,as2 --causes --json` per map
#   (the truth, K = 8, is fly's default reference), writes OUT/MAP.json, then prints the
#   tables from every OUT/*.json present (`scripts/flicker-truth.sh --table` prints only).
set -euo pipefail
bin=${FOOTPRINT_BIN:?set FOOTPRINT_BIN to a release build of footprint}
dems=${DEMS:-/work/dems}
out=${OUT:?set OUT to a folder for the JSON}
frames=${FRAMES:-100}
mkdir -p "$out"
declare -A maps=(
  [mountains]=""
  [eroded]="--terrain eroded --terrain-size 384"
  [plains]="--terrain plains --terrain-size 384"
  [msh]="--dem $dems/msh_2007_10m.tif"
  [tujunga]="--dem $dems/bigtujunga_srtm30m.tif"
  [comanche]="--dem $dems/D1.png --color $dems/C1W.png")
order=(mountains eroded plains msh tujunga comanche)
names=("$@")
[ ${#names[@]} -gt 0 ] || names=("${order[@]}")
if [ "${names[0]}" != --table ]; then
  for n in "${names[@]}"; do
    start=$(date +%s)
    # shellcheck disable=SC2086 # the map's options are words
    nice -n 10 "$bin" fly ${maps[$n]} --frames "$frames" --modes ps,ss16,as,as-exact,as2 \
      --causes --json > "$out/$n.json.tmp" 2> "$out/$n.err"
    mv "$out/$n.json.tmp" "$out/$n.json"
    echo "$n: $(( $(date +%s) - start )) s" >&2
  done
fi
python3 - "$out" "${order[@]}" <<'PY'
import json, os, sys
out, order = sys.argv[1], sys.argv[2:]
runs = [(n, json.load(open(f"{out}/{n}.json"))) for n in order if os.path.exists(f"{out}/{n}.json")]
modes = ["ps", "ss16", "as", "as-exact", "as2"]
print("| map | frames | truth's own | " + " | ".join(modes)
      + " | PS/as | PS/as2 | as2/as | as2/SS16 |")
print("|---" * (6 + len(modes)) + "|")
for n, d in runs:
    by = {m["mode"]: m for m in d["modes"]}
    ex = {m: by[m]["excess"]["all_columns"] for m in modes}
    r = lambda a, b: f"{ex[a] / ex[b]:.1f}" if ex[b] > 0 else "∞"
    r2 = lambda a, b: f"{ex[a] / ex[b]:.2f}" if ex[b] > 0 else "∞"
    print(f"| {n} | {d['frames']} | {d['reference']['large_changes']:,} | "
          + " | ".join(f"{ex[m]:,}" for m in modes)
          + f" | {r('ps', 'as')} | {r('ps', 'as2')} | {r2('as2', 'as')} | {r2('as2', 'ss16')} |")
print()
print("| map | pixels: seam / magnified / rest | as: seam / magnified / rest | as2: seam / magnified / rest |")
print("|---" * 4 + "|")
for n, d in runs:
    by = {m["mode"]: m for m in d["modes"]}
    cls = lambda m: {c["class"]: c for c in by[m]["classes"]}
    c = cls("as")
    tot = sum(c[k]["pixels"] for k in ("seam", "magnified", "rest"))
    share = " / ".join(f"{100 * c[k]['pixels'] / tot:.1f}" for k in ("seam", "magnified", "rest"))
    cells = [" / ".join(f"{cls(m)[k]['excess']:,}" for k in ("seam", "magnified", "rest")) for m in ("as", "as2")]
    print(f"| {n} | {share} % | " + " | ".join(cells) + " |")
print()
print("| map | " + " | ".join(f"RMSE {m}" for m in modes) + " |")
print("|---" * (1 + len(modes)) + "|")
for n, d in runs:
    by = {m["mode"]: m for m in d["modes"]}
    print(f"| {n} | " + " | ".join(f"{by[m]['rmse']:.2f}" for m in modes) + " |")
PY
