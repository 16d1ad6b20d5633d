#!/usr/bin/env python3
"""Writes the GeoTIFF fixtures of maps/tests/fixtures/geotiff/ the way GDAL writes them.

Written with rasterio, whose wheels carry GDAL (these were made with rasterio 1.4.4, GDAL
3.10.3), with GDAL's default creation options unless a file says otherwise, so that the tags are
GDAL's own: a compound CRS gets GeoTIFF 1.1 keys (ProjectedCSTypeGeoKey and
VerticalCSTypeGeoKey, no ProjLinearUnitsGeoKey or VerticalUnitsGeoKey), and a transform with a
positive y step or a rotation gets only a ModelTransformationTag. The tests in
maps/tests/geotiff.rs read these files; run this again only to change them:

    python3 -m venv /tmp/gdalvenv && /tmp/gdalvenv/bin/pip install rasterio numpy
    /tmp/gdalvenv/bin/python scripts/gdal-fixtures.py

Every map is 16 x 12 cells. Its heights are `NW - 3 x - 5 y` in the file's vertical unit, x
east and y south from the north-west cell, whose value NW is the map's highest (1000, or 1500
for the heights in feet), so that a test sees the orientation from one corner.
"""

import os
import sys

import numpy as np
import rasterio
from rasterio.transform import Affine

W, H = 16, 12
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "maps", "tests", "fixtures", "geotiff")


def north_up(nw):
    """The heights, row 0 the north row."""
    y, x = np.mgrid[0:H, 0:W]
    return (nw - 3 * x - 5 * y).astype(np.int16)


def write(name, data, crs, transform, **options):
    path = os.path.join(OUT, name)
    profile = dict(driver=options.pop("driver", "GTiff"), width=W, height=H, count=1,
                   dtype=str(data.dtype), crs=crs, transform=transform)
    profile.update(options)
    with rasterio.open(path, "w", **profile) as f:
        f.write(data, 1)
    print(f"{name}: {os.path.getsize(path)} bytes", file=sys.stderr)


def main():
    os.makedirs(OUT, exist_ok=True)
    # 1. UTM 17N (NAD83) with NAVD88 heights in international feet, 10 m cells: GeoTIFF 1.1
    #    keys only (GDAL's default for a compound CRS). Read right, the heights are 0.3048 x.
    write("utm17n-navd88-ft.tif", north_up(1500), "EPSG:26917+8228",
          Affine(10.0, 0.0, 500_000.0, 0.0, -10.0, 4_000_000.0))
    # 1'. The same with GEOTIFF_VERSION=1.0: GDAL adds the unit keys.
    write("utm17n-navd88-ft-geotiff10.tif", north_up(1500), "EPSG:26917+8228",
          Affine(10.0, 0.0, 500_000.0, 0.0, -10.0, 4_000_000.0), GEOTIFF_VERSION="1.0")
    # 2. North Carolina State Plane (NAD83, US survey feet) with NAVD88 heights in US survey
    #    feet, 30 ftUS cells (9.144 m).
    write("ncsp-ftus-navd88-ftus.tif", north_up(1500), "EPSG:2264+6360",
          Affine(30.0, 0.0, 2_000_000.0, 0.0, -30.0, 700_000.0))
    # 3. South-up: a positive y step, the first row the southern one; 10 m cells in UTM 33N.
    #    GDAL writes a ModelTransformationTag only. Flipped, it is the same map as a north-up.
    write("south-up.tif", north_up(1000)[::-1].copy(), "EPSG:32633",
          Affine(10.0, 0.0, 400_000.0, 0.0, 10.0, 5_000_000.0))
    # 3'. A grid rotated by 30 degrees: a ModelTransformationTag only, which the reader refuses.
    write("rotated.tif", north_up(1000), "EPSG:32633",
          Affine.translation(400_000.0, 5_000_000.0) * Affine.rotation(30.0) * Affine.scale(10.0, -10.0))
    # 4. A Cloud Optimized GeoTIFF (GDAL's COG driver) in metres whose east two thirds are
    #    voids of -32768, with no nodata tag: most of its cells are the sentinel.
    cog = north_up(1000)
    cog[:, 5:] = -32768
    write("cog-undeclared-voids.tif", cog, "EPSG:32633",
          Affine(10.0, 0.0, 400_000.0, 0.0, -10.0, 5_000_000.0), driver="COG", COMPRESS="DEFLATE")


if __name__ == "__main__":
    main()
