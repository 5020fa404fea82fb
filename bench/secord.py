#!/usr/bin/env python3
"""A reference weighted Voronoi stippler (Secord 2002) in numpy + scipy, to
compare with moyo's `[[layers.voronoi]]` stippling on the same image.

    secord.py IMAGE --count N --frame X0,Y0,W,H [--iterations 50]
              [--converge MM] [--px-per-stipple 100 | --scale S]
              [--seed 1] -o OUT.json

Written for bench/stipple_vs_secord.sh from the paper's description, not
from another implementation.

Darkness is moyo's (src/input/image.rs, src/geom/density.rs): 1 − grey/255,
linear, grey being the JPEG's luma as decoded (Pillow here, zune-jpeg in
moyo: the same up to ±1 of IDCT rounding); sampled bilinearly between pixel
centres, clamped at the edges. The image is fitted to the frame (page mm)
as moyo fits it to the region's bounding box: aspect kept, centred.

Working raster. The centroids are sums over pixel centres, so a cell needs
many pixels for its centroid to be finer than a pixel. The image is
resampled (bilinear, as above) by a factor `scale` chosen so that the
non-white pixels number at least `px-per-stipple` (default 100) per
stipple: pixels with zero darkness add nothing to any centroid and are left
out of every query, so counting them would only flatter the resolution.
For the 300 × 400 portrait (48,800 non-white pixels) and 10,000 stipples
that is ×4.53: 1359 × 1811 pixels, about 1.0 million of them non-white
(≈100 per stipple on average, fewer in the darkest parts where the cells
are smallest).

Initial stipples: rejection sampling on darkness, as moyo's `uniform`
distribution with an image: a uniform point of the frame is kept with
probability equal to the darkness under it, until there are N.

Each step (Lloyd, weighted): every non-white working pixel goes to its
nearest stipple (scipy.spatial.cKDTree over the stipples, queried with all
the pixel centres at once, workers=-1); per stipple the mass Σρ and first
moments Σρx, Σρy by np.bincount; each stipple moves to Σρx/Σρ, Σρy/Σρ. A
stipple whose cell holds no darkness stays where it is (as in moyo). The
mean movement of all stipples is measured in mm (the frame's units, as
moyo's `converge`); relaxation stops when it falls below `--converge`, or
after `--iterations` steps.

Output (JSON): count, iterations, seconds (sampling, relaxation, total
after reading the image), the working raster, the mean movement of each
step (mm), and `points`: the stipples in page mm.
"""
import argparse
import json
import math
import sys
import time

import numpy as np
from PIL import Image
from scipy.spatial import cKDTree


def darkness_of(path):
    """The image as darkness (0 white – 1 black), rows from the top."""
    grey = np.asarray(Image.open(path).convert("L"), dtype=np.float64)
    return 1.0 - grey / 255.0


def bilinear(dark, x, y):
    """Darkness at points (pixel units, pixel (i, j) covers [i, i+1) ×
    [j, j+1)), bilinear between pixel centres, clamped at the edges, white
    outside the image (moyo's GreyImage::sample)."""
    h, w = dark.shape
    inside = (x >= 0) & (y >= 0) & (x <= w) & (y <= h)
    fx = np.clip(x - 0.5, 0.0, w - 1)
    fy = np.clip(y - 0.5, 0.0, h - 1)
    x0 = np.floor(fx).astype(np.intp)
    y0 = np.floor(fy).astype(np.intp)
    x1 = np.minimum(x0 + 1, w - 1)
    y1 = np.minimum(y0 + 1, h - 1)
    tx, ty = fx - x0, fy - y0
    top = dark[y0, x0] * (1 - tx) + dark[y0, x1] * tx
    bottom = dark[y1, x0] * (1 - tx) + dark[y1, x1] * tx
    return np.where(inside, top * (1 - ty) + bottom * ty, 0.0)


def resampled(dark, scale):
    """The image resampled by `scale`: each working pixel's centre sampled
    bilinearly in the original. Returns (darkness, working px per image
    px in x and y)."""
    h, w = dark.shape
    ww, wh = round(w * scale), round(h * scale)
    sx, sy = ww / w, wh / h
    # Separable: bilinear weights along x, then along y, on the grid.
    xs = (np.arange(ww) + 0.5) / sx
    ys = (np.arange(wh) + 0.5) / sy
    gx, gy = np.meshgrid(xs, ys)
    return bilinear(dark, gx, gy), sx, sy


def rejection_sample(dark, count, rng):
    """`count` points (image pixel units) spread uniformly over the image
    and kept with probability = darkness."""
    h, w = dark.shape
    points = np.empty((0, 2))
    tries = 0
    while len(points) < count:
        batch = max(count - len(points), 64) * 4
        tries += batch
        if tries > 1000 * count:
            sys.exit(f"the image is too light to place {count} stipples")
        p = rng.random((batch, 2)) * (w, h)
        keep = rng.random(batch) < bilinear(dark, p[:, 0], p[:, 1])
        points = np.vstack([points, p[keep]])
    return points[:count]


def relax(sites, pixels, weights, mm_per_px, iterations, converge):
    """Weighted Lloyd steps on `sites` (working px) over the weighted pixel
    centres; returns the sites and each step's mean movement in mm."""
    n = len(sites)
    wx = weights * pixels[:, 0]
    wy = weights * pixels[:, 1]
    movements = []
    for _ in range(iterations):
        _, nearest = cKDTree(sites).query(pixels, k=1, workers=-1)
        mass = np.bincount(nearest, weights=weights, minlength=n)
        mx = np.bincount(nearest, weights=wx, minlength=n)
        my = np.bincount(nearest, weights=wy, minlength=n)
        moved = sites.copy()
        full = mass > 0
        moved[full, 0] = mx[full] / mass[full]
        moved[full, 1] = my[full] / mass[full]
        step = float(np.mean(np.hypot(*(moved - sites).T))) * mm_per_px
        sites = moved
        movements.append(step)
        if converge is not None and step < converge:
            break
    return sites, movements


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("image")
    ap.add_argument("--count", type=int, required=True)
    ap.add_argument("--frame", required=True, help="X0,Y0,W,H in page mm")
    ap.add_argument("--iterations", type=int, default=50, help="most steps")
    ap.add_argument("--converge", type=float, default=None,
                    help="stop when a step's mean movement is below this (mm)")
    ap.add_argument("--px-per-stipple", type=float, default=100.0)
    ap.add_argument("--scale", type=float, default=None,
                    help="working raster scale (overrides --px-per-stipple)")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("-o", "--output", required=True)
    args = ap.parse_args()

    dark = darkness_of(args.image)
    t0 = time.perf_counter()
    x0, y0, fw, fh = (float(v) for v in args.frame.split(","))
    h, w = dark.shape
    # The image fitted to the frame, aspect kept, centred (Density::fitted).
    mm_per_img_px = min(fw / w, fh / h)
    ox = x0 + fw / 2 - w * mm_per_img_px / 2
    oy = y0 + fh / 2 - h * mm_per_img_px / 2

    scale = args.scale
    if scale is None:
        scale = max(1.0, math.sqrt(args.px_per_stipple * args.count / np.count_nonzero(dark)))
    work, sx, sy = resampled(dark, scale)
    rows, cols = np.nonzero(work > 0)
    pixels = np.column_stack([cols + 0.5, rows + 0.5])
    weights = work[rows, cols]

    rng = np.random.default_rng(args.seed)
    sites = rejection_sample(dark, args.count, rng) * (sx, sy)
    t1 = time.perf_counter()
    # Working pixels are square to within rounding; take the mean side.
    mm_per_px = mm_per_img_px * (1 / sx + 1 / sy) / 2
    sites, movements = relax(sites, pixels, weights, mm_per_px,
                             args.iterations, args.converge)
    t2 = time.perf_counter()

    points = np.column_stack([ox + sites[:, 0] / sx * mm_per_img_px,
                              oy + sites[:, 1] / sy * mm_per_img_px])
    with open(args.output, "w") as f:
        json.dump({
            "count": len(points),
            "iterations": len(movements),
            "seconds": {"sampling": t1 - t0, "relaxation": t2 - t1, "total": t2 - t0},
            "raster": {"width": work.shape[1], "height": work.shape[0],
                       "scale": scale, "weighted_pixels": len(weights)},
            "mean_movement_mm": movements,
            "points": points.round(6).tolist(),
        }, f)


if __name__ == "__main__":
    main()
