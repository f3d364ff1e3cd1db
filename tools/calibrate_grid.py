"""Calibrate how often a lattice placed where no grid is printed looks printed (hamta.core.grid.evidence).

Lattices are fitted from random hints (two points, a random turn, a random step of 24-400 px) on images that
carry no printed grid: windows of the real imagery in ../shared/data (Landsat, NAIP of several dates) and of the
multimodal set's maps, and synthetic sheets drawn without a grid (hamta.bench.random_sheets, style 'none').
Each family's lines are judged as hamta.core.grid.evidence.evidence judges them (a line stands where it, a piece
around a crossing, or a tick, holds more ink than every copy of itself moved across by part of a step). Printed:

- the share of lines that stand, per family: P_CHANCE is set above its 99th percentile (a binomial with it
  then overstates the chance of a printed-looking family, never understates it);
- how many lattices the evidence calls printed at the current constants (the false alarms: the goal is none);
- the share of crossings the crossing search finds on such lattices (MIN_SHARE in hamta.core.grid.check).

Usage: python tools/calibrate_grid.py [--data ../shared/data] [--trials 300] [--seed 0]
"""
from __future__ import annotations

import argparse
import glob
import math
import os

import numpy as np


def images(data: str, rng, count: int):
    """Grey windows (uint8) of images without a printed grid."""
    import rasterio
    from rasterio.windows import Window

    from hamta.bench.random_sheets import draw_spec, render_random

    files = sorted(glob.glob(os.path.join(data, "timeseries", "*.tif")) + glob.glob(os.path.join(data, "landsat",
                                                                                                  "*.tif")))
    maps = sorted(glob.glob(os.path.join(data, "multimodal", "Optical-Map", "*.jpg")))
    out = []
    for k in range(count):
        kind = k % 3
        if kind == 0 and files:
            path = files[rng.integers(len(files))]
            with rasterio.open(path) as ds:
                w, h = min(ds.width, 1600), min(ds.height, 1200)
                x0, y0 = rng.integers(0, ds.width - w + 1), rng.integers(0, ds.height - h + 1)
                a = ds.read(window=Window(int(x0), int(y0), w, h)).astype(np.float32)
            grey = a[:3].mean(axis=0) if a.shape[0] >= 3 else a[0]
            grey = 255 * (grey - grey.min()) / max(float(np.ptp(grey)), 1e-6)
            out.append(("imagery", grey.astype(np.uint8)))
        elif kind == 1 and maps:
            import cv2

            grey = cv2.imread(maps[rng.integers(len(maps))], cv2.IMREAD_GRAYSCALE)
            if grey is not None:
                out.append(("map", grey))
        else:
            seed = int(rng.integers(10000, 20000))
            spec = draw_spec(seed)
            while spec.style != "none":
                seed += 1
                spec = draw_spec(seed)
            import cv2

            sheet = render_random(spec, "/tmp/hamta-calibrate-grid", data)
            out.append(("sheet without grid", cv2.imread(sheet.path, cv2.IMREAD_GRAYSCALE)))
    return out


def trial(grey, rng):
    """Families (printed, lines) and whether the lattice is called printed, for one random lattice."""
    from pyproj import CRS

    from hamta.core.grid.finding import find_crossings
    from hamta.core.grid.placing import place_lattice
    from hamta.core.grid.planes import planes_for
    from hamta.core.grid.scan import LineSource

    h, w = grey.shape
    spacing = float(np.exp(rng.uniform(math.log(24), math.log(min(400, min(h, w) / 3)))))
    turn = rng.uniform(-math.pi, math.pi)
    step = 1000.0
    p0 = np.array([rng.uniform(0.3, 0.7) * w, rng.uniform(0.3, 0.7) * h])
    d = np.array([math.cos(turn), math.sin(turn)]) * spacing * 3
    hints = np.array([[*p0, 500000.0, 5000000.0], [*(p0 + d), 503000.0, 5000000.0]])
    plane = planes_for(CRS.from_user_input("EPSG:32633"), None)[0]
    source = LineSource.from_array(grey)
    placed = place_lattice(source, {}, plane, hints, (step, step))
    if placed is None:
        return None
    ev = placed.evidence
    share = None
    if ev.printed:
        fit = find_crossings(source, plane, placed, _Silent())
        share = fit.share
    return [(f.printed, f.lines) for f in ev.families], ev.printed, share


class _Silent:
    def check(self):
        pass

    def report(self, *_):
        pass


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--data", default=os.path.join(os.path.dirname(__file__), "..", "..", "shared", "data"))
    parser.add_argument("--trials", type=int, default=300)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--z", type=float, nargs="+", default=[4.0], help="Z_LINE values to measure")
    args = parser.parse_args()
    rng = np.random.default_rng(args.seed)
    pool = images(args.data, rng, max(args.trials // 5, 12))
    from hamta.core.grid import evidence

    for z in args.z:
        evidence.Z_LINE = z
        trials = np.random.default_rng(args.seed + 1)
        shares, alarms, found, done = [], 0, [], 0
        for k in range(args.trials):
            kind, grey = pool[k % len(pool)]
            got = trial(grey, trials)
            if got is None:
                continue
            done += 1
            families, printed, share = got
            shares += [p / n for p, n in families if n >= 3]
            alarms += printed
            if share is not None:
                found.append(share)
        shares = np.array(shares)
        print(f"Z_LINE {z:g}: {done} lattices on {len(pool)} images without a grid; share of a family's lines "
              f"standing: mean {shares.mean():.3f}, 95th percentile {np.percentile(shares, 95):.3f}, 99th "
              f"{np.percentile(shares, 99):.3f}; lattices called printed at the current constants: {alarms}"
              + (f"; share of crossings found on them: median {np.median(found):.2f}, max {max(found):.2f}"
                 if found else ""), flush=True)


if __name__ == "__main__":
    main()
