#!/usr/bin/env bash
# RMSE against the truth on the generated maps nobody tuned to (`footprint map synth`), at the
# paper's three pitches: docs/measurements.md's tables of the thin-feature maps (issue 51).
#
# Usage: FOOTPRINT_BIN=… OUT=DIR scripts/synth-rmse.sh [KIND …]
#   KIND: wall wall2 stripes2 stripes4 ridges checker mesas steep (default: all eight). Writes
#   OUT/KIND.png (256², `map synth --kind KIND`) unless it is there, runs `footprint table
#   --dem OUT/KIND.png --modes $MODES --json` (MODES default ps,li,ss16,as,as-exact,as2; the
#   truth at K = 8 is table's default judge) into OUT/KIND.json, and prints one Markdown row per
#   map and pitch: each mode's RMSE in 8-bit levels, and the lowest mode. About 30 s a map on
#   one busy core.
set -euo pipefail
bin=${FOOTPRINT_BIN:?set FOOTPRINT_BIN to a release build of footprint}
out=${OUT:?set OUT to a folder for the maps and the JSON}
modes=${MODES:-ps,li,ss16,as,as-exact,as2}
kinds=("$@")
[ ${#kinds[@]} -gt 0 ] || kinds=(wall wall2 stripes2 stripes4 ridges checker mesas steep)
mkdir -p "$out"
for k in "${kinds[@]}"; do
  [ -e "$out/$k.png" ] || "$bin" map synth --kind "$k" --size 256 --out "$out/$k.png" >/dev/null
  # table's notes and progress go to standard error; a failure is named here.
  "$bin" table --dem "$out/$k.png" --modes "$modes" --json > "$out/$k.json" 2>/dev/null ||
    { echo "synth-rmse.sh: footprint table --dem $out/$k.png failed" >&2; exit 2; }
done
python3 - "$out" "${kinds[@]}" <<'EOF'
import json, sys
out, kinds = sys.argv[1], sys.argv[2:]
first = True
for k in kinds:
    d = json.load(open(f"{out}/{k}.json"))
    for c in d["cases"]:
        rmse = {m["mode"]: m["rmse"] for m in c["modes"]}
        if first:
            print("| map | pitch | " + " | ".join(rmse) + " | lowest |")
            print("|---" * (len(rmse) + 3) + "|")
            first = False
        low = min(rmse, key=rmse.get)
        print(f"| {k} | {c['pitch']:.0f}° | " + " | ".join(f"{v:.2f}" for v in rmse.values())
              + f" | {low} |")
EOF
