#!/usr/bin/env python3
"""Measures stipplings of an image the same way whoever made them: moyo's
SVG (the `…site-<i>` circles of `draw = ["sites"]`) or the JSON of
bench/secord.py (`points`, page mm).

    stipple_quality.py IMAGE X0,Y0,W,H STIPPLES...   ->  one JSON line each
    stipple_quality.py IMAGE X0,Y0,W,H A.svg B.json --draw OUT.png

X0,Y0,W,H is the rectangle (page mm) the image was fitted to, aspect kept
and centred, as moyo fits an image to its region's bounding box. A
stipple's centre in the SVG is the middle of its circle's coordinates,
through the `translate(…)` of its groups (the layer's shift by the page
margins), in the SVG's millimetres (viewBox against width in mm).

Darkness is 1 − grey/255 of the image's own pixels (no resampling), as
moyo and secord.py define it. The figures:

- `count`: stipples read.
- Tone fidelity, over a grid of square blocks laid on the image (20 along
  its longer side, 15 × 20 for a 3:4 portrait, each 20 × 20 pixels there):
  a block's stipple share s_b (its stipples / all) against its darkness
  share d_b (its darkness / all darkness).
  `fidelity_mad` = mean |s_b − d_b| / mean d_b: the typical error of a
  block's stipple count as a fraction of an average block's (0 = stipple
  density exactly in proportion to darkness);
  `fidelity_r` = Pearson correlation of s_b and d_b.
  `tone_exponent` = the slope γ of log s_b against log d_b (least squares
  weighted by d_b, blocks with both shares above 0): stipple density goes
  as darkness^γ. 1 reproduces tone; rejection sampling is 1 up to noise;
  Lloyd relaxation lowers it, slowly (the optimum of the energy it
  descends, a centroidal Voronoi tessellation in the plane, has density ∝
  darkness^½: Gersho; Du, Faber & Gunzburger 1999), which flattens
  contrast; capacity-constrained methods (LBG) aim at 1.
- Evenness within a tone: `evenness_cv` = the coefficient of variation of
  e_i = nn(i) / mean of nn(j) over i's 6 nearest neighbours j, nn being
  the distance to the nearest other stipple. Each gap is compared with
  the gaps around it, so a smooth change of tone does not count, only
  irregularity: clumps and holes of random points give about 0.5, the
  blue-noise spacing of converged Lloyd stipples 0.1 or less (0 for a
  perfect lattice). `nn_sqrt_darkness_cv`, the CV of nn(i) × √darkness
  under i, is also given; it assumes density ∝ darkness (γ = 1), so it
  mixes the tone error above into the evenness and is not in the table.
- `stray`: stipples on paper the image leaves white (darkness under them,
  bilinear as moyo samples it, below 0.01): dots outside the picture's
  outlines. Rejection sampling puts a few there (darkness is rarely exactly
  0 near an edge); exact weighted centroids pull them back in, as the dark
  part of a cell has its centroid over it wherever the dark shape is
  convex.
"""
import argparse
import json
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np
from PIL import Image, ImageDraw
from scipy.spatial import cKDTree

# The darkness both stipplers aim at, defined once (moyo's, see secord.py).
from secord import bilinear, darkness_of

SITE = re.compile(r"\.site-\d+$")
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
TRANSLATE = re.compile(r"^\s*translate\(\s*([^,\s)]+)[,\s]*([^,\s)]*)\s*\)\s*$")


def svg_stipples(path):
    """Centres (page mm) of the `site-` circles of a moyo SVG."""
    root = ET.parse(path).getroot()
    width = root.get("width", "")
    view = [float(v) for v in root.get("viewBox", "0 0 1 1").replace(",", " ").split()]
    if not width.endswith("mm"):
        sys.exit(f"{path}: width {width!r} is not in mm")
    mm_per_unit = float(width[:-2]) / view[2]
    out = []

    def walk(node, dx, dy):
        t = node.get("transform")
        if t:
            m = TRANSLATE.match(t)
            if not m:
                sys.exit(f"{path}: transform {t!r} is not a translation")
            dx += float(m.group(1))
            dy += float(m.group(2) or 0)
        if node.tag.endswith("path") and SITE.search(node.get("id", "")):
            d = node.get("d", "")
            if re.search(r"[a-y]", d.replace("e", "")):
                sys.exit(f"{path}: relative path commands in {node.get('id')}")
            xy = np.array([float(v) for v in NUMBER.findall(d)]).reshape(-1, 2)
            c = (xy.min(axis=0) + xy.max(axis=0)) / 2
            out.append((c[0] + dx, c[1] + dy))
        for child in node:
            walk(child, dx, dy)

    walk(root, 0.0, 0.0)
    return np.array(out).reshape(-1, 2) * mm_per_unit


def stipples(path):
    if path.endswith(".svg"):
        return svg_stipples(path)
    with open(path) as f:
        return np.array(json.load(f)["points"], dtype=float).reshape(-1, 2)


def to_image(points, frame, shape):
    """Page mm to image pixel units (fitted, centred)."""
    x0, y0, fw, fh = frame
    h, w = shape
    s = min(fw / w, fh / h)
    ox, oy = x0 + fw / 2 - w * s / 2, y0 + fh / 2 - h * s / 2
    return (points - (ox, oy)) / s


def measure(px, dark):
    h, w = dark.shape
    n = len(px)
    side = max(w, h) / 20
    bx, by = max(1, round(w / side)), max(1, round(h / side))
    # Darkness share per block (pixel centres binned), stipple share.
    ys, xs = np.mgrid[0:h, 0:w]
    d = np.histogram2d((ys.ravel() + 0.5), (xs.ravel() + 0.5), bins=(by, bx),
                       range=((0, h), (0, w)), weights=dark.ravel())[0].ravel()
    s = np.histogram2d(px[:, 1], px[:, 0], bins=(by, bx),
                       range=((0, h), (0, w)))[0].ravel()
    d /= d.sum()
    s /= max(n, 1)
    mad = float(np.mean(np.abs(s - d)) / np.mean(d))
    r = float(np.corrcoef(s, d)[0, 1])
    both = (s > 0) & (d > 0)
    gamma = float(np.polyfit(np.log(d[both]), np.log(s[both]), 1, w=np.sqrt(d[both]))[0])

    tree = cKDTree(px)
    dist, idx = tree.query(px, k=8)
    nn = dist[:, 1]
    local = nn[idx[:, 1:7]].mean(axis=1)
    ok = (nn > 0) & (local > 0)
    e = nn[ok] / local[ok]
    under = bilinear(dark, px[:, 0], px[:, 1])
    scaled = nn * np.sqrt(under)
    scaled = scaled[scaled > 0]
    return {
        "count": n,
        "outside_frame": int(np.count_nonzero((px < 0).any(axis=1) | (px[:, 0] > w) | (px[:, 1] > h))),
        "blocks": f"{bx}x{by}",
        "fidelity_mad": mad,
        "fidelity_r": r,
        "tone_exponent": gamma,
        "evenness_cv": float(e.std() / e.mean()),
        "nn_sqrt_darkness_cv": float(scaled.std() / scaled.mean()),
        "stray": int(np.count_nonzero(under < 0.01)),
    }


def draw(panels, frame, out, px_per_mm=10, radius=0.5):
    """The stipples of each input as filled dots of `radius` mm, panels
    side by side, each the frame with a 3 mm border."""
    x0, y0, fw, fh = frame
    border = 3
    pw, ph = round((fw + 2 * border) * px_per_mm), round((fh + 2 * border) * px_per_mm)
    sheet = Image.new("L", (pw * len(panels), ph), 255)
    pen = ImageDraw.Draw(sheet)
    r = radius * px_per_mm
    for k, (name, pts) in enumerate(panels):
        q = (pts - (x0 - border, y0 - border)) * px_per_mm + (k * pw, 0)
        for x, y in q:
            pen.ellipse((x - r, y - r, x + r, y + r), fill=29)
        pen.text((k * pw + 8, 4), name, fill=0)
    sheet.save(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("image")
    ap.add_argument("frame", help="X0,Y0,W,H in page mm")
    ap.add_argument("stipples", nargs="+", help="moyo .svg or secord.py .json")
    ap.add_argument("--draw", help="also draw them side by side into this PNG")
    ap.add_argument("--dot-radius", type=float, default=0.5,
                    help="radius of the drawn dots, mm (moyo's dot + half the pen)")
    args = ap.parse_args()
    frame = tuple(float(v) for v in args.frame.split(","))
    dark = darkness_of(args.image)
    panels = []
    for path in args.stipples:
        pts = stipples(path)
        if len(pts) < 8:
            sys.exit(f"{path}: {len(pts)} stipples, need 8 or more")
        print(json.dumps({"file": path, **measure(to_image(pts, frame, dark.shape), dark)}))
        panels.append((path.rsplit("/", 1)[-1].rsplit(".", 1)[0], pts))
    if args.draw:
        draw(panels, frame, args.draw, radius=args.dot_radius)


if __name__ == "__main__":
    main()
