#!/usr/bin/env bash
# Flash and RAM of the firmware binaries, from their ELF files (build them first with
# `cargo build --release` in this folder):
#   * the sections, from `llvm-size -A`;
#   * .vector_table + .text + .rodata split by owner, from the symbol table (`llvm-nm`):
#     footprint-core's own code and tables (its functions, the firmware's `core_calls`
#     wrappers the core's generic walk is inlined into, and its dependencies `fixed` and
#     `heapless`), compiler-builtins (soft double, 64-bit division, memcpy), the Rust core
#     library (formatting, panics), the firmware's own code, and the runtime (cortex-m-rt,
#     cortex-m, semihosting, the panic handler). The scene data has a section of its own,
#     .scene (memory.x).
# Uses llvm-size/llvm-nm from `rustup component add llvm-tools`, else from PATH.
set -euo pipefail
cd "$(dirname "$0")"

bin="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin"
tool() {
  if [ -x "$bin/$1" ]; then echo "$bin/$1"; elif command -v "$1" >/dev/null; then command -v "$1"; else
    echo "sizes.sh: $1 not found: rustup component add llvm-tools" >&2
    exit 1
  fi
}
size=$(tool llvm-size)
nm=$(tool llvm-nm)
dir=${CARGO_TARGET_DIR:-target}/thumbv7em-none-eabihf/release

report() {
  local elf=$dir/$1
  echo "== $1 ($elf)"
  "$size" -A "$elf" | awk '$1 ~ /^\.(vector_table|text|rodata|scene|data|bss)$/ { printf "  %-14s %7d bytes\n", $1, $2 }'
  # Section bounds, then every sized symbol (aliases counted once), owned by its path's crate.
  { "$size" -A "$elf" | awk '$1 ~ /^\.(vector_table|text|rodata|scene|data|bss)$/ { print "SECTION", $1, $2, $3 }'
    "$nm" --print-size --defined-only -C "$elf"; } | awk '
    function hex(h,   i, v) { v = 0; h = tolower(h); for (i = 1; i <= length(h); i++) v = v * 16 + index("0123456789abcdef", substr(h, i, 1)) - 1; return v }
    $1 == "SECTION" { name[++n] = $2; len[n] = $3; start[n] = $4; next }
    NF >= 4 && $2 ~ /^[0-9a-f]+$/ {
      addr = hex($1); sz = hex($2)
      if (sz == 0 || seen[addr]++) next
      sec = ""
      for (i = 1; i <= n; i++) if (addr >= start[i] && addr < start[i] + len[i]) sec = name[i]
      if (sec != ".vector_table" && sec != ".text" && sec != ".rodata") next
      sym = $0; sub(/^[0-9a-f]+ [0-9a-f]+ . /, "", sym)
      s = sym; sub(/^[<&]+/, "", s); sub(/^dyn /, "", s)
      if (s ~ /^(footprint_core|fixed|heapless|az)::/ || s ~ /^footprint_firmware::core_calls::/) who = "core"
      else if (s ~ /^compiler_builtins::/ || s ~ /^(__aeabi|__[a-z]+[sd]f[0-9]|__[a-z]*div|__[a-z]*mod|__mul|__ashl|__lshr|__ashr|__clz|__ctz|mem(cpy|set|move|cmp)|fmax|fmin|__llvm_memcpy|__llvm_memset)/) who = "builtins"
      else if (s ~ /^(core|u8|u16|u32|u64|u128|usize|i8|i16|i32|i64|i128|isize|f32|f64|str|bool|char)( |::|$)/) who = "libcore"
      else if (s ~ /^(cortex_m|cortex_m_rt|cortex_m_semihosting|panic_semihosting|critical_section)::/ || s ~ /^(Reset|DefaultHandler_|DefaultPreInit|HardFault_|__RESET_VECTOR|__EXCEPTIONS|__INTERRUPTS|__pre_init)$/) who = "runtime"
      else if (s ~ /^\.L/) who = "anon"
      else if (s ~ /^(footprint_firmware|minimal)::/ || s ~ /^(SysTick|HardFault|main)$/) who = "firmware"
      else if (s ~ /^(_HardFault|__rustc::rust_begin_unwind)$/) who = "runtime"
      else { who = "other"; other[sym] += sz }
      total[who] += sz
      if (who == "core" && sz >= 1024) big[sym] = sz
    }
    END {
      label["core"] = "footprint-core: code and tables"
      label["builtins"] = "compiler-builtins: soft double, 64-bit division, memcpy"
      label["libcore"] = "Rust core library: formatting, panics"
      label["firmware"] = "the firmware'"'"'s own code"
      label["runtime"] = "runtime: cortex-m-rt, cortex-m, semihosting, panic handler"
      label["anon"] = "anonymous constants: strings, panic locations (any crate)"
      label["other"] = "other"
      split("core builtins libcore firmware runtime anon other", order, " ")
      print "  .vector_table + .text + .rodata by owner:"
      for (k = 1; k <= 7; k++) if (total[order[k]] > 0)
        printf "    %-60s %7d bytes (%.1f KiB)\n", label[order[k]], total[order[k]], total[order[k]] / 1024
      printf "    %-60s %7d bytes (%.1f KiB)\n", "core code and tables + compiler-builtins", total["core"] + total["builtins"], (total["core"] + total["builtins"]) / 1024
      print "  footprint-core functions of 1 KiB or more:"
      for (s in big) printf "    %7d  %s\n", big[s], s | "sort -rn"; close("sort -rn")
      for (s in other) printf "  (unclassified: %d bytes %s)\n", other[s], s
    }'
}

report footprint-firmware
report minimal
