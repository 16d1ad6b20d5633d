#!/usr/bin/env python3
"""A hostile battery over footprint's readers, its numbers and its server (issue 54).

Usage: FOOTPRINT_BIN=target/release/footprint scripts/hostile-battery.py [--seed N] [--cases N]

Three groups, reproducible from --seed:
  readers  every map reader (PNG, TIFF/GeoTIFF, ASCII grid, BIL, .hgt, baked .fpmap, .vrt)
           given a valid file mutated: cut short, bytes flipped, bytes inserted, a region
           zeroed or set to 0xff, a header field changed; `map info` on each
  numbers  `render` on the 16² built-in terrain with extreme values of every view option
           (NaN, ±inf, 1e308, −0, huge integers, empty, text)
  server   `serve` on the 16² terrain, given malformed, huge, pipelined, slow and foreign
           requests on loopback; after every tenth, `GET /` must still be answered
Each command runs with a 30 s bound. A case fails if it exits other than 0, 1, 2 or 130, is
killed by a signal, runs past the bound, or exits 2 with more than one line on stderr; the
server fails a case if it stops answering. Prints one line per failure and a summary; exits 1
if any case failed.
"""

import argparse
import os
import random
import shutil
import socket
import struct
import subprocess
import sys
import tempfile
import time
import zlib

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
BIN = os.environ.get("FOOTPRINT_BIN", os.path.join(ROOT, "target", "release", "footprint"))
BOUND_S = 30
OK_CODES = {0, 1, 2, 130}


def run(args, stdin=None):
    """Runs footprint ARGS: (code or None if killed, stderr text, seconds, timed out)."""
    t = time.monotonic()
    try:
        p = subprocess.run([BIN, *args], input=stdin, capture_output=True, timeout=BOUND_S)
        return p.returncode, p.stderr.decode("utf-8", "replace"), time.monotonic() - t, False
    except subprocess.TimeoutExpired as e:
        return None, (e.stderr or b"").decode("utf-8", "replace"), BOUND_S, True


def verdict(code, err, timed_out):
    """None if the outcome is acceptable, else why not."""
    if timed_out:
        return f"ran past {BOUND_S} s"
    if code is None or code < 0:
        return f"killed by signal {-code if code else '?'}"
    if code not in OK_CODES:
        return f"exit {code}: {err.strip()[:200]!r}"
    if code == 2:
        lines = [l for l in err.splitlines() if l.strip() and not l.startswith("warning:")]
        if len(lines) != 1:
            return f"exit 2 with {len(lines)} lines: {err.strip()[:200]!r}"
    return None


# --- seeds: one valid file per format -------------------------------------------------------


def png_bytes(w, h, rows):
    """A 16-bit greyscale PNG."""
    raw = b"".join(b"\0" + b"".join(struct.pack(">H", v) for v in row) for row in rows)

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    ihdr = struct.pack(">IIBBBBB", w, h, 16, 0, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b"")


def seeds(d):
    """Valid inputs, one or more per format: (name, bytes, extra map-info arguments)."""
    w, h = 24, 18
    rows = [[(100 + 7 * x + 5 * y) % 400 for x in range(w)] for y in range(h)]
    out = [("grid.png", png_bytes(w, h, rows), ["--spacing", "10"])]
    asc = f"ncols {w}\nnrows {h}\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n"
    asc += "\n".join(" ".join(str(v) for v in r) for r in rows) + "\n"
    out.append(("grid.asc", asc.encode(), []))
    bil = b"".join(struct.pack("<h", v) for r in rows for v in r)
    hdr = f"BYTEORDER I\nLAYOUT BIL\nNROWS {h}\nNCOLS {w}\nNBANDS 1\nNBITS 16\nPIXELTYPE SIGNEDINT\nULXMAP 0\nULYMAP 0\nXDIM 10\nYDIM 10\n"
    out.append(("grid.bil", bil, []))
    with open(os.path.join(d, "grid.hdr"), "w") as f:
        f.write(hdr)
    for sub in ("geotiff", "lzw"):
        folder = os.path.join(ROOT, "maps", "tests", "fixtures", sub)
        if os.path.isdir(folder):
            for name in sorted(os.listdir(folder))[:6]:
                with open(os.path.join(folder, name), "rb") as f:
                    out.append((f"{sub}-{name}", f.read(), ["--spacing", "10"]))
    vrt = (f'<VRTDataset rasterXSize="{w}" rasterYSize="{h}"><GeoTransform>0, 10, 0, 180, 0, -10'
           '</GeoTransform><VRTRasterBand band="1"><SimpleSource><SourceFilename relativeToVRT="1">'
           f'grid.asc</SourceFilename><SourceBand>1</SourceBand><SrcRect xOff="0" yOff="0" '
           f'xSize="{w}" ySize="{h}"/><DstRect xOff="0" yOff="0" xSize="{w}" ySize="{h}"/>'
           "</SimpleSource></VRTRasterBand></VRTDataset>")
    out.append(("mosaic.vrt", vrt.encode(), []))
    baked = os.path.join(d, "seed.fpmap")
    with open(os.path.join(d, "grid.asc"), "wb") as f:
        f.write(asc.encode())
    code, err, _, _ = run(["map", "bake", os.path.join(d, "grid.asc"), "--out", baked])
    if code == 0:
        with open(baked, "rb") as f:
            out.append(("grid.fpmap", f.read(), []))
    return out


def mutate(rng, data):
    """One hostile change of `data`."""
    b = bytearray(data)
    kind = rng.randrange(7)
    if not b:
        return bytes(rng.randrange(256) for _ in range(rng.randrange(64)))
    if kind == 0:  # cut short
        return bytes(b[: rng.randrange(len(b))])
    if kind == 1:  # flip bytes
        for _ in range(rng.randrange(1, 9)):
            b[rng.randrange(len(b))] ^= 1 << rng.randrange(8)
        return bytes(b)
    if kind == 2:  # insert bytes
        at = rng.randrange(len(b) + 1)
        return bytes(b[:at] + bytes(rng.randrange(256) for _ in range(rng.randrange(1, 64))) + b[at:])
    if kind in (3, 4):  # a region zeroed or set to 0xff
        at = rng.randrange(len(b))
        n = rng.randrange(1, 64)
        b[at : at + n] = (b"\0" if kind == 3 else b"\xff") * len(b[at : at + n])
        return bytes(b)
    if kind == 5:  # a 32-bit field near the start set to an extreme
        at = rng.randrange(min(len(b), 512))
        b[at : at + 4] = rng.choice([b"\xff\xff\xff\xff", b"\0\0\0\x80", b"\x7f\xff\xff\xff", b"\0\0\0\0"])
        return bytes(b)
    # a text number changed (ASCII grids, headers, .vrt)
    text = b.decode("latin-1")
    digits = [i for i, c in enumerate(text) if c.isdigit()]
    if not digits:
        return bytes(b)
    at = rng.choice(digits)
    new = rng.choice(["-1", "0", "99999999999", "1e308", "nan", "-inf", "4294967297", ""])
    return (text[:at] + new + text[at + 1 :]).encode("latin-1")


def readers(rng, d, n):
    cases, failures = 0, []
    base = seeds(d)
    for i in range(n):
        name, data, extra = base[i % len(base)]
        path = os.path.join(d, name)
        with open(path, "wb") as f:
            f.write(mutate(rng, data))
        code, err, _, timed_out = run(["map", "info", path, *extra])
        cases += 1
        why = verdict(code, err, timed_out)
        if why:
            kept = os.path.join(d, f"fail-{i}-{name}")
            shutil.copy(path, kept)
            failures.append(f"readers {i} {name}: {why} (kept as {kept})")
    return cases, failures


NUMBERS = ["nan", "inf", "-inf", "1e308", "-1e308", "-0", "0", "1e-320", "99999999999999999999",
           "-99999999999999999999", "", "x", "1,2", "0x10", "١٢", "4294967296", "1e9", "-1e9",
           "180", "-180", "90", "-90", "89.9999999", "360", "1e-9"]
OPTIONS = ["--pitch", "--heading", "--roll", "--fov", "--x", "--y", "--height", "--far"]
SIZES = ["0x0", "1x1", "65536x1", "1x65536", "99999x99999", "16x16", "-1x4", "4x", "x4", "3x3x3"]


def numbers(rng, d, n):
    cases, failures = 0, []
    out = os.path.join(d, "n.png")
    for i in range(n):
        args = ["render", "--terrain-size", "16", "--size", rng.choice(SIZES[4:6] + SIZES), "--out", out,
                "--mode", rng.choice(["ps", "as", "as2", "classic", "ss4", "as-exact"])]
        for _ in range(rng.randrange(1, 4)):
            args += [rng.choice(OPTIONS), rng.choice(NUMBERS)]
        if rng.random() < 0.3:
            args += ["--view", "paper"]
        code, err, _, timed_out = run(args)
        cases += 1
        why = verdict(code, err, timed_out)
        if why:
            failures.append(f"numbers {i} {' '.join(args)}: {why}")
    return cases, failures


def request(port, data, read=True, timeout=5.0):
    """Sends `data` to the server; its answer (bytes; b'' if it closed or none came)."""
    s = socket.create_connection(("127.0.0.1", port), timeout=timeout)
    try:
        s.sendall(data)
        if not read:
            return b""
        s.shutdown(socket.SHUT_WR)
        chunks = []
        while True:
            try:
                c = s.recv(65536)
            except (socket.timeout, ConnectionResetError):
                break
            if not c:
                break
            chunks.append(c)
        return b"".join(chunks)
    except (BrokenPipeError, ConnectionResetError):
        return b""
    finally:
        s.close()


def hostile_request(rng):
    host = b"Host: 127.0.0.1\r\n"
    choices = [
        lambda: bytes(rng.randrange(256) for _ in range(rng.randrange(1, 4096))),
        lambda: b"GET /" + b"A" * rng.randrange(1, 70000) + b" HTTP/1.1\r\n" + host + b"\r\n",
        lambda: b"GET / HTTP/1.1\r\n" + host + b"X: " + b"y" * rng.randrange(1, 40000) + b"\r\n\r\n",
        lambda: rng.choice([b"POST", b"PUT", b"DELETE", b"TRACE", b"CONNECT", b"G\0T", b""]) + b" / HTTP/1.1\r\n" + host + b"\r\n",
        lambda: b"GET " + rng.choice([b"/../../etc/passwd", b"/%2e%2e/%2e%2e/etc/passwd", b"http://evil/", b"*", b"/\0", b"//", b"/app.js?" + b"&" * 5000]) + b" HTTP/1.1\r\n" + host + b"\r\n",
        lambda: b"GET / HTTP/1.1\r\nHost: " + rng.choice([b"evil.example", b"", b"127.0.0.1:99999", b"[::1", b"\xff\xfe"]) + b"\r\n\r\n",
        lambda: (b"GET / HTTP/1.1\r\n" + host + b"\r\n") * rng.randrange(2, 200),
        lambda: b"GET / HTTP/" + rng.choice([b"0.9", b"2.0", b"9.9", b"1.1\n", b"1.1\r\r"]) + b"\r\n" + host + b"\r\n",
        lambda: b"GET / HTTP/1.1\r\n" + host + b"Content-Length: " + rng.choice([b"-1", b"99999999999999999999", b"abc", b"5"]) + b"\r\n\r\nhello",
        lambda: b"GET / HTTP/1.1\r\n" + host + b"Transfer-Encoding: chunked\r\n\r\nffffffffffffffff\r\n",
    ]
    return rng.choice(choices)()


def server(rng, d, n):
    cases, failures = 0, []
    p = subprocess.Popen([BIN, "serve", "--port", "0", "--terrain-size", "16"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    line = p.stdout.readline().decode()
    # "serving the page at http://127.0.0.1:PORT/ (Ctrl-C stops)"
    port = int(line.split("127.0.0.1:", 1)[1].split("/", 1)[0]) if "127.0.0.1:" in line else None
    if port is None:
        p.kill()
        return 1, [f"server: did not start: {line!r} {p.stderr.read()[:200]!r}"]
    for i in range(n):
        try:
            request(port, hostile_request(rng), read=rng.random() < 0.8, timeout=2.0)
        except OSError as e:
            failures.append(f"server {i}: cannot connect: {e}")
        cases += 1
        if i % 10 == 9:
            page = b""
            try:
                page = request(port, b"GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n", timeout=5.0)
            except OSError as e:
                failures.append(f"server after case {i}: GET / failed: {e}")
            if not page.startswith(b"HTTP/1.1 200"):
                failures.append(f"server after case {i}: GET / answered {page[:40]!r}")
        if p.poll() is not None:
            failures.append(f"server {i}: exited {p.returncode}: {p.stderr.read()[:300]!r}")
            return cases, failures
    p.send_signal(2)
    try:
        code = p.wait(10)
    except subprocess.TimeoutExpired:
        p.kill()
        code = None
    if code not in (0, 130):
        failures.append(f"server: SIGINT ended it with {code}")
    return cases, failures


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--cases", type=int, default=2000, help="in all, split 3 : 1 : 1")
    a = ap.parse_args()
    rng = random.Random(a.seed)
    d = tempfile.mkdtemp(prefix="footprint-battery-")
    total, failures = 0, []
    per = a.cases // 5
    for group, n in ((readers, 3 * per), (numbers, per), (server, a.cases - 4 * per)):
        started = time.monotonic()
        c, f = group(rng, d, n)
        total += c
        failures += f
        print(f"{group.__name__}: {c} cases, {len(f)} failed, {time.monotonic() - started:.0f} s", flush=True)
    for f in failures:
        print(f)
    print(f"{total} cases, {len(failures)} failed (seed {a.seed}; kept inputs in {d})")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
