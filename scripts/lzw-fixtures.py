#!/usr/bin/env python3
"""Writes maps/tests/fixtures/lzw/: LZW-compressed TIFF height maps as tifffile (with
imagecodecs' LZW, libtiff's layout) writes them, tiled with partial edge tiles and in strips,
with the predictors 1, 2 (integers) and 3 (floats), both byte orders. The tiff crate 0.11
refused 6 of 16 such tiled files as truncated (image-rs/image-tiff#395); maps/src/tiff_lzw.rs
decodes them, and maps/tests/lzw.rs reads every file here against the formula below. Run it
again only to change them:

    python3 -m venv /tmp/gdalvenv && /tmp/gdalvenv/bin/pip install tifffile imagecodecs numpy
    /tmp/gdalvenv/bin/python scripts/lzw-fixtures.py

A file is named `H x W _ TYPE _ pPRED _ LAYOUT _ ORDER .tif`; its sample at column x, row y
(from the top) is `200 + (7 x + 13 y) % 97`, plus `(x % 4) / 4` for float32, minus 300 for
int16 and int32 (negative heights).
"""

import os

import numpy as np
import tifffile

OUT = os.path.join(os.path.dirname(__file__), "..", "maps", "tests", "fixtures", "lzw")


def heights(h, w, dtype):
    y, x = np.mgrid[0:h, 0:w]
    v = 200 + (7 * x + 13 * y) % 97
    if dtype == np.float32:
        return (v + (x % 4) / 4).astype(np.float32)
    if dtype in (np.int16, np.int32):
        return (v - 300).astype(dtype)
    return v.astype(dtype)


def main():
    os.makedirs(OUT, exist_ok=True)
    for old in os.listdir(OUT):
        os.remove(os.path.join(OUT, old))
    for h, w in [(33, 40), (17, 19), (20, 37)]:
        for dtype in (np.int16, np.uint16, np.int32, np.float32):
            for pred in (1, 3 if dtype == np.float32 else 2):
                for layout in ("tiled", "strips"):
                    for order in ("<", ">"):
                        if order == ">" and (h, w) != (33, 40):
                            continue
                        name = (f"{h}x{w}_{np.dtype(dtype).name}_p{pred}_{layout}_"
                                f"{'be' if order == '>' else 'le'}.tif")
                        kw = dict(compression="lzw", predictor=pred, byteorder=order)
                        if layout == "tiled":
                            kw["tile"] = (16, 16)
                        else:
                            kw["rowsperstrip"] = 7
                        tifffile.imwrite(os.path.join(OUT, name), heights(h, w, dtype), **kw)


if __name__ == "__main__":
    main()
