#!/usr/bin/env bash
# The tables of docs/measurements.md's "Current numbers", re-measured with one binary and
# printed as Markdown.
#
# Usage: FOOTPRINT_BIN=target/release/footprint scripts/docs-numbers.sh [SECTION …]
#   SECTION: coverage | instructions | bench | pyramid | firmware | wasm (default: all, in that
#            order)
#   coverage      the paper's three views: P, L, V and M/V per mode (`footprint table --json`)
#   instructions  instructions per pixel, exact and paper projection (scripts/instructions.sh,
#                 valgrind; a few minutes per mode)
#   bench         ms per frame, one thread, fastest (median) of 15 interleaved rounds, and ×PS
#                 (`footprint bench`; wall-clock: run it on a quiet machine)
#   pyramid       RMSE through the pyramid / at level 0 on six maps (`footprint table --lod`)
#   firmware      docs/embedding.md's cost table and stacks (the firmware under QEMU)
#   wasm          docs/browser.md's module size (the page host/build.rs built)
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

# docs/embedding.md's cost table (its rows are checked against the same run, within 5 %, by
# tests/tests/firmware.rs) and the stacks, from the firmware under QEMU.
firmware() {
  (cd firmware && cargo run --release --quiet 2>/dev/null) > "$tmp/firmware.txt"
  python3 - "$tmp/firmware.txt" <<'EOF'
import re, sys
out = open(sys.argv[1]).read()
rows = [("PS", "ps"), ("SS8", "ss8"), ("`as` (the paper's)", "as"), ("`as-exact`", "as-exact"),
        ("`as2`", "as2"), ("`as` lit, `clamp99` (the glint frame)", "GLINT")]
glint = re.search(r"^# icount (\S+): render \d+ instructions, [\d.]+ per pixel; the same frame unlit", out, re.M)
print("| mode | render, instructions per frame | per pixel | with the frame tables, per pixel |")
print("|---|---|---|---|")
for label, name in rows:
    if name == "GLINT":
        name = glint[1] if glint else "?"
    m = re.search(rf"^# icount {re.escape(name)}: render (\d+) instructions, ([\d.]+) per pixel(?:; with the frame tables \d+ per frame, ([\d.]+) per pixel)?", out, re.M)
    if m is None:
        print(f"| {label} | (no line) | | |")
        continue
    tables = f"{float(m[3]):,.1f}" if m[3] else ""
    print(f"| {label} | {int(m[1]):,} | {float(m[2]):,.1f} | {tables} |")
for line in out.splitlines():
    if line.startswith(("# stack", "# icount frame tables", "# icount pyramid", "# verdict")):
        print(line)
EOF
}

# docs/browser.md's module size (checked within 10 % by host/tests/serve.rs): the page's
# WebAssembly, as host/build.rs builds it for the release binary.
wasm() {
  local f
  f=$(ls -t target/release/build/footprint-host-*/out/footprint_web.wasm 2>/dev/null | head -1)
  [ -n "$f" ] || { echo "no page built: cargo build --release (with the wasm32 target)" >&2; return 1; }
  stat -c '%s bytes: %n' "$f"
}

sections=("$@")
all=(coverage instructions bench pyramid firmware wasm)
[ ${#sections[@]} -gt 0 ] || sections=("${all[@]}")
for s in "${sections[@]}"; do
  case $s in
    coverage | instructions | bench | pyramid | firmware | wasm) echo "## $s"; "$s"; echo ;;
    *) echo "docs-numbers.sh: unknown section $s (${all[*]})" >&2; exit 2 ;;
  esac
done
