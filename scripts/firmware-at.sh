#!/usr/bin/env bash
# The firmware's instructions per pixel at earlier commits: for each COMMIT, a temporary
# worktree, the firmware built and run under QEMU (-icount: deterministic), and one line of
# per-pixel counts per mode. For finding which commit moved a cost (issue 52, item 3).
#
#   scripts/firmware-at.sh COMMIT...        e.g. scripts/firmware-at.sh 42064fc HEAD
#
# Needs qemu-system-arm (on PATH, or unpacked by .ci/run into target/qemu) and the
# thumbv7em-none-eabihf target. Builds share target/firmware-at; the worktree is removed after.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
if [ $# -eq 0 ]; then
  echo "usage: scripts/firmware-at.sh COMMIT..." >&2
  exit 2
fi
if ! command -v qemu-system-arm >/dev/null && [ -x target/qemu/root/usr/bin/qemu-system-arm ]; then
  export PATH="$root/target/qemu/root/usr/bin:$PATH"
  export LD_LIBRARY_PATH="$root/target/qemu/root/usr/lib/x86_64-linux-gnu:$root/target/qemu/root/lib/x86_64-linux-gnu${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
command -v qemu-system-arm >/dev/null || { echo "firmware-at: no qemu-system-arm" >&2; exit 2; }
for commit in "$@"; do
  git rev-parse --verify -q "$commit^{commit}" >/dev/null ||
    { echo "firmware-at: $commit: not a commit" >&2; exit 2; }
done
work=$(mktemp -d "$root/target/firmware-at-tree.XXXXXX")
trap 'git worktree remove --force "$work" 2>/dev/null || rm -rf "$work"; git worktree prune' EXIT
rmdir "$work"
printf '%-9s %s\n' commit "instructions per pixel (render)"
for commit in "$@"; do
  git worktree add -q --detach "$work" "$commit"
  out=$(cd "$work/firmware" && CARGO_TARGET_DIR="$root/target/firmware-at" \
    timeout 900 cargo run -q --release 2>/dev/null || true)
  # Each `# icount NAME: render|walk …, X per pixel; …` line: NAME and its first X.
  counts=$(grep -E '^# icount [a-z0-9-]+: (render|walk) ' <<<"$out" |
    awk '{ name = $3; sub(/:$/, "", name)
           for (i = 4; i <= NF; i++) if ($(i + 1) == "per" && $(i + 2) ~ /^pixel/) { v = $i; break }
           sub(/,$/, "", v); printf "%s %s  ", name, v }' || true)
  printf '%-9s %s %s\n' "$(git rev-parse --short "$commit")" "${counts:-(no counts: the build or the run failed)}" \
    "$(git log -1 --format=%s "$commit" | cut -c1-50)"
  git worktree remove --force "$work"
done
