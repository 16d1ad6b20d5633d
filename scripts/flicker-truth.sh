#!/usr/bin/env bash
# Whole-frame flicker against the truth on the six maps of docs/measurements.md
# ("Whole-frame flicker against the truth" in "Current numbers").
#
# Usage: FOOTPRINT_BIN=… DEMS=/work/dems OUT=DIR FRAMES=N scripts/flicker-truth.sh [MAP …]
#   MAP: mountains eroded plains msh tujunga comanche (default: these six, in that order), or
#        one of `footprint map synth`'s kinds (wall wall2 stripes2 stripes4 ridges checker mesas
#        steep: the generated maps nobody tuned to, written to OUT/KIND.png first)
#   Runs `footprint fly MAP --frames N --modes ps,ss16,as,as-exact,as2 --causes --json` per map
#   (the truth, K = 8, is fly's default reference), writes OUT/MAP.json, then prints the
#   tables from every OUT/MAP.json present (`scripts/flicker-truth.sh --table` prints only).
#   On 2026-11-29 (b08129f, 2 shared cores) FRAMES=80 took 529–744 s a map, 64 min in all.
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
synth=(wall wall2 stripes2 stripes4 ridges checker mesas steep)
for k in "${synth[@]}"; do maps[$k]="--dem $out/$k.png"; done
six=(mountains eroded plains msh tujunga comanche)
order=("${six[@]}" "${synth[@]}")
names=("$@")
[ ${#names[@]} -gt 0 ] || names=("${six[@]}")
if [ "${names[0]}" != --table ]; then
  for n in "${names[@]}"; do
    [ -n "${maps[$n]+set}" ] || { echo "flicker-truth.sh: $n: no such map" >&2; exit 2; }
    start=$(date +%s)
    if [[ " ${synth[*]} " == *" $n "* ]] && [ ! -e "$out/$n.png" ]; then
      "$bin" map synth --kind "$n" --out "$out/$n.png"
    fi
    # shellcheck disable=SC2086 # the map's options are words
    nice -n 10 "$bin" fly ${maps[$n]} --frames "$frames" --modes ps,ss16,as,as-exact,as2 \
      --causes --json > "$out/$n.json.tmp" 2> "$out/$n.err"
    mv "$out/$n.json.tmp" "$out/$n.json"
    echo "$n: $(( $(date +%s) - start )) s" >&2
  done
fi
# Tables: excess large changes over the truth's own and their ratios ("–" where the divisor is
# 0 or negative, or the dividend negative); the raw large changes; the causes (excess per
# class); the mean RMSE against the truth's frames.
python3 - "$out" "${order[@]}" <<'PY'
import json, os, sys
out, order = sys.argv[1], sys.argv[2:]
runs = [(n, json.load(open(f"{out}/{n}.json"))) for n in order if os.path.exists(f"{out}/{n}.json")]
modes = ["ps", "ss16", "as", "as-exact", "as2"]
def ratio(a, b, fmt="{:.1f}"):
    return fmt.format(a / b) if b > 0 and a >= 0 else "–"
print("| map | frames | truth's own | PS | SS16 | `as` | `as-exact` | `as2` | PS / `as` | PS / `as2` | `as2` / `as` | `as2` / SS16 |")
print("|---" * 12 + "|")
for n, d in runs:
    by = {m["mode"]: m for m in d["modes"]}
    ex = {m: by[m]["excess"]["all_columns"] for m in modes}
    print(f"| {n} | {d['frames']} | {d['reference']['large_changes']:,} | "
          + " | ".join(f"{ex[m]:,}".replace("-", "−") for m in modes)
          + f" | {ratio(ex['ps'], ex['as'])} | {ratio(ex['ps'], ex['as2'])} | {ratio(ex['as2'], ex['as'], '{:.2f}')} | {ratio(ex['as2'], ex['ss16'], '{:.2f}')} |")
print()
print("| map | truth | PS | SS16 | `as` | `as-exact` | `as2` | PS / `as` | PS / `as2` | `as2` / `as` | `as2` / SS16 |")
print("|---" * 11 + "|")
for n, d in runs:
    by = {m["mode"]: m for m in d["modes"]}
    lc = {m: by[m]["large_changes"] for m in modes}
    print(f"| {n} | {d['reference']['large_changes']:,} | " + " | ".join(f"{lc[m]:,}" for m in modes)
          + f" | {ratio(lc['ps'], lc['as'])} | {ratio(lc['ps'], lc['as2'])} | {ratio(lc['as2'], lc['as'], '{:.2f}')} | {ratio(lc['as2'], lc['ss16'], '{:.2f}')} |")
print()
print("| map | pixels: seam / magnified / rest | truth's own: seam / magnified / rest | `as`: seam / magnified / rest | `as2`: seam / magnified / rest |")
print("|---" * 5 + "|")
for n, d in runs:
    by = {m["mode"]: m for m in d["modes"]}
    cls = lambda m: {c["class"]: c for c in by[m]["classes"]}
    c = cls("as")
    ks = ("seam", "magnified", "rest")
    tot = sum(c[k]["pixels"] for k in ks)
    share = " / ".join(f"{100 * c[k]['pixels'] / tot:.1f}" for k in ks)
    ref = {c["class"]: c for c in d["reference"].get("classes", [])}
    refs = " / ".join(f"{ref[k]['large_changes']:,}" for k in ks) if ref else "–"
    cells = [" / ".join(f"{cls(m)[k]['excess']:,}".replace("-", "−") for k in ks) for m in ("as", "as2")]
    print(f"| {n} | {share} % | {refs} | " + " | ".join(cells) + " |")
print()
print("| map | " + " | ".join(["PS", "SS16", "`as`", "`as-exact`", "`as2`"]) + " |")
print("|---" * (1 + len(modes)) + "|")
for n, d in runs:
    by = {m["mode"]: m for m in d["modes"]}
    print(f"| {n} | " + " | ".join(f"{by[m]['rmse']:.2f}" for m in modes) + " |")
PY
