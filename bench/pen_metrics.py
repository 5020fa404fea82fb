#!/usr/bin/env python3
"""Measures what a pen plotter meets in a layered SVG, per pen layer and in
total, independently of moyo (it reads the file with vpype's reader, not
with moyo's code):

    pen_metrics.py FILE.svg [--tol-share 0.25] [--json] [--travel-only]
    pen_metrics.py --self-test

Layers are the top-level groups, numbered as vpype numbers them (the first
group of digits of `inkscape:label`, else of `id`, else the group's rank);
groups with the same number are one layer. Groups whose label starts with
`%` (AxiDraw's convention for layers that are never plotted: guides, notes,
moyo's preview fills) are left out. A layer's pen width w is the
`stroke-width` of its group's `style` (or its `stroke-width` attribute), in
the SVG's user units converted to mm through `viewBox` against `width` (as
SVG scales it: "0.3mm" in a viewBox of millimetres is 0.3 × 96/25.4 units);
0.3 mm when it has none. Curves are cut into segments of at most 0.01 mm
(`--quantization`). Lengths are mm, the origin (0, 0) is the sheet's
top-left corner; nothing is cropped to the sheet. Each layer's lines are
polylines (one per subpath) in document order. vpype drops subpaths of a
single point ("M x y" alone, or "M x y L x y"), so they are not counted.

Per layer, and in total:

- `paths`: polylines; `pen_down_mm`: their length.
- `pen_up_mm`: travel in document order from the origin to the first
  path's start, then from each path's end to the next path's start (the
  return home is not counted). Every layer starts from the origin (a pen
  change); the total is the sum of the layers'.
- `plot_time_s` = pen_down / 25 mm/s + pen_up / 75 mm/s + 0.3 s per path
  (one pen lift and lowering each). Constants: SPEED_DOWN, SPEED_UP,
  LIFT_S below. (`moyo plot`'s own estimate uses the same speeds but
  0.15 s a lift.)
- `touching_mm`, `touching_pct` (of pen_down): line work that lies on
  line work of the same layer drawn earlier, however briefly. Every
  polyline is resampled at steps of at most w/4 (each sample stands for
  its piece of line, of that length, with its direction). A sample
  touches when it lies across the piece of a sample of an earlier
  polyline, or of the same polyline more than 2·w earlier along it,
  within tol = tol_share·w of that piece (default tol_share 0.25), the
  two running in the same or the opposite direction (|cos angle| >=
  cos 20°). Pieces that only continue each other (end to end) are not on
  one another. Two identical lines are 50 % touching, a line drawn there
  and back again in one path 50 %, two crossing lines 0 %, two lines 10°
  apart only where they are within tol. This counts the ink that lines
  meeting at a shallow angle share: a fork of 20° shares its first
  0.22 mm with a 0.3 mm pen, tangent circles a few tenths, a Paradox
  corner the start of each edge.
- `doubled_mm`, `doubled_pct` (of pen_down): line drawn twice — the
  touching samples that lie in a run of touching samples at least
  RUN_MIN·w = 2·w long along their polyline (a closed polyline's run may
  wrap round its start). Two lines stay within a quarter of a width of
  each other for two widths when they run together, or cross at under
  about 14°; a fork, a corner or a crossing at a wider angle shares less.
  Two identical lines are 50 % doubled, two lines crossing at 10° 2.9·w.
- `debris`, `debris_pct` (of paths): polylines shorter than w in all that
  come within w of other line work of the layer (a crumb stuck to a line;
  an isolated short mark, a dot, is not debris).
- `densest_mm2`: the largest length of line (mm) inside one 1 mm × 1 mm
  cell of a grid aligned to the sheet (exactly: each segment cut at the
  cell borders it crosses), and `densest_solid` = densest_mm2 · w: about 1 when
  the cell is solid ink, 2 when it is inked twice over. The totals take
  the largest of the layers'.

Needs numpy and vpype (in target/vpype-venv, see bench/pen_figures.sh).
Neighbour search is a uniform grid in numpy, so a million samples take a
few seconds.
"""
import argparse
import io
import json
import math
import os
import re
import sys
import tempfile
import xml.etree.ElementTree as ET

import numpy as np

SPEED_DOWN = 25.0  # mm/s, pen down
SPEED_UP = 75.0  # mm/s, pen up
LIFT_S = 0.3  # s per pen lift (and lowering), one per path
DEFAULT_WIDTH = 0.3  # mm, a layer without stroke-width
PARALLEL_DEG = 20.0  # doubled: directions within this angle (or its opposite)
SELF_GAP = 2.0  # touching within one path: more than SELF_GAP·w earlier along it
RUN_MIN = 2.0  # doubled: touching for at least RUN_MIN·w along the line
CELL_MM = 1.0  # density grid
MM_PER_PX = 25.4 / 96.0

SVG_NS = "http://www.w3.org/2000/svg"
INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"
# CSS units in px (user units).
UNIT_PX = {"": 1.0, "px": 1.0, "mm": 96 / 25.4, "cm": 96 / 2.54, "in": 96.0,
           "pt": 96 / 72, "pc": 16.0, "q": 96 / 101.6}
LENGTH_RE = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([a-zA-Z]*)\s*$")


# --- reading -----------------------------------------------------------------

def _length(text, default=None):
    """A CSS length as (number, unit), or default."""
    m = LENGTH_RE.match(text or "")
    if not m:
        return default
    return float(m.group(1)), m.group(2).lower()


def _digits(text):
    m = re.search(r"\d+", text or "")
    return m.group(0) if m else None


def _mm_per_user_unit(root):
    """mm of the sheet per SVG user unit (viewBox against width)."""
    width = _length(root.get("width"))
    vb = (root.get("viewBox") or "").replace(",", " ").split()
    if width and width[1] in UNIT_PX and len(vb) == 4 and float(vb[2]) > 0:
        return width[0] * UNIT_PX[width[1]] * MM_PER_PX / float(vb[2])
    return MM_PER_PX


def _stroke_width(group, mm_per_uu):
    value = None
    for decl in (group.get("style") or "").split(";"):
        key, _, val = decl.partition(":")
        if key.strip() == "stroke-width":
            value = val
    if value is None:
        value = group.get("stroke-width")
    parsed = _length(value)
    if not parsed or parsed[1] not in UNIT_PX or parsed[0] <= 0:
        return DEFAULT_WIDTH
    return parsed[0] * UNIT_PX[parsed[1]] * mm_per_uu


def read_layers(path, quantization_mm=0.01):
    """[(layer id, name, pen width mm, [polyline as (n, 2) array in mm])]."""
    import vpype  # noqa: PLC0415 (only needed here; --self-test writes SVGs too)

    for prefix, uri in (("", SVG_NS), ("inkscape", INKSCAPE_NS),
                        ("sodipodi", "http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"),
                        ("xlink", "http://www.w3.org/1999/xlink")):
        ET.register_namespace(prefix, uri)
    tree = ET.parse(path)
    root = tree.getroot()
    mm_per_uu = _mm_per_user_unit(root)
    hidden = [g for g in root if g.tag == f"{{{SVG_NS}}}g"
              and (g.get(f"{{{INKSCAPE_NS}}}label") or "").lstrip().startswith("%")]
    for g in hidden:
        root.remove(g)
    source = path if not hidden else io.StringIO(ET.tostring(root, encoding="unicode"))

    # Layer ids as vpype gives them (read_multilayer_svg), to match widths.
    info = {}
    for rank, g in enumerate(g for g in root if g.tag == f"{{{SVG_NS}}}g"):
        label = g.get(f"{{{INKSCAPE_NS}}}label")
        lid = _digits(label) or _digits(g.get("id"))
        lid = max(1, int(lid)) if lid else rank + 1
        if lid not in info:
            info[lid] = (label or g.get("id") or "", _stroke_width(g, mm_per_uu))

    doc = vpype.read_multilayer_svg(source, quantization=quantization_mm / MM_PER_PX,
                                    crop=False)
    layers = []
    for lid in sorted(doc.layers):
        name, width = info.get(lid, ("", DEFAULT_WIDTH))
        lines = [np.column_stack((line.real, line.imag)) * MM_PER_PX
                 for line in doc.layers[lid] if len(line) > 0]
        layers.append((lid, name, width, lines))
    return layers


# --- geometry ----------------------------------------------------------------

def near_pairs(query, data, radius, chunk=1 << 17):
    """Yields (qi, dj) index arrays of all query/data point pairs closer than
    radius, chunk by chunk, by a uniform grid of cells radius wide."""
    if len(query) == 0 or len(data) == 0:
        return
    dcell = np.floor(data / radius).astype(np.int64)
    qcell = np.floor(query / radius).astype(np.int64)
    lo_xy = np.minimum(dcell.min(0), qcell.min(0)) - 1
    span_y = int(max(dcell[:, 1].max(), qcell[:, 1].max()) - lo_xy[1]) + 2
    dkey = (dcell[:, 0] - lo_xy[0]) * span_y + (dcell[:, 1] - lo_xy[1])
    order = np.argsort(dkey, kind="stable")
    skey = dkey[order]
    for start in range(0, len(query), chunk):
        q = query[start:start + chunk]
        qc = qcell[start:start + chunk]
        idx = np.arange(start, start + len(q))
        qis, djs = [], []
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                key = (qc[:, 0] + dx - lo_xy[0]) * span_y + (qc[:, 1] + dy - lo_xy[1])
                lo = np.searchsorted(skey, key, "left")
                hi = np.searchsorted(skey, key, "right")
                cnt = hi - lo
                total = int(cnt.sum())
                if total == 0:
                    continue
                qi = np.repeat(idx, cnt)
                first = np.cumsum(cnt) - cnt
                pos = np.arange(total) - np.repeat(first - lo, cnt)
                dj = order[pos]
                d = query[qi] - data[dj]
                keep = np.einsum("ij,ij->i", d, d) <= radius * radius
                qis.append(qi[keep])
                djs.append(dj[keep])
        if qis:
            yield np.concatenate(qis), np.concatenate(djs)


def resample(lines, step):
    """Samples along the polylines, at most `step` apart, each standing for a
    piece of line of length `weight` around it: (points, unit directions,
    weight, polyline index, arc position in its polyline). A polyline of
    length 0 gives one sample of weight 0 and direction 0."""
    counts = np.array([len(l) for l in lines])
    pts = np.concatenate(lines)
    poly_of_pt = np.repeat(np.arange(len(lines)), counts)
    seg_a, seg_b = pts[:-1], pts[1:]
    same = poly_of_pt[:-1] == poly_of_pt[1:]
    seg_a, seg_b, seg_poly = seg_a[same], seg_b[same], poly_of_pt[:-1][same]
    vec = seg_b - seg_a
    seg_len = np.hypot(vec[:, 0], vec[:, 1])
    lengths = np.bincount(seg_poly, seg_len, minlength=len(lines))
    cum = np.concatenate(([0.0], np.cumsum(seg_len)))
    offsets = np.concatenate(([0.0], np.cumsum(lengths)))[:-1]

    n = np.maximum(1, np.ceil(lengths / step - 1e-9)).astype(np.int64)
    poly = np.repeat(np.arange(len(lines)), n)
    k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
    weight = (lengths / n)[poly]
    t = (k + 0.5) * weight
    g = offsets[poly] + t
    seg = np.clip(np.searchsorted(cum, g, "right") - 1, 0, max(len(seg_len) - 1, 0))
    points = np.empty((len(poly), 2))
    dirs = np.zeros((len(poly), 2))
    if len(seg_len):
        ok = weight > 0
        s = seg[ok]
        unit = vec[s] / seg_len[s][:, None]
        points[ok] = seg_a[s] + unit * (g[ok] - cum[s])[:, None]
        dirs[ok] = unit
    firsts = np.cumsum(counts) - counts
    zero = weight == 0
    points[zero] = pts[firsts[poly[zero]]]
    return points, dirs, weight, poly, t, lengths


def cell_lengths(lines):
    """The length of line inside each CELL_MM cell of the sheet that holds
    any, exactly: every segment is cut where it crosses a cell border and
    each piece counted in its own cell. (Counting samples a quarter of a
    pen long in the cell of their middle, as the other figures sample,
    misplaces up to half a sample at each border a line crosses: 2.008×
    solid in a katagami cell that holds 1.927×.)"""
    pts = np.concatenate(lines) / CELL_MM
    counts = np.array([len(l) for l in lines])
    poly_of_pt = np.repeat(np.arange(len(lines)), counts)
    same = poly_of_pt[:-1] == poly_of_pt[1:]
    a, b = pts[:-1][same], pts[1:][same]
    if not len(a):
        return np.zeros(1)
    # The segment parameters where each one crosses a vertical or a
    # horizontal cell border, with 0 and 1, sorted within each segment.
    ts, segs = [np.zeros(len(a)), np.ones(len(a))], [np.arange(len(a))] * 2
    for axis in (0, 1):
        lo, hi = np.minimum(a[:, axis], b[:, axis]), np.maximum(a[:, axis], b[:, axis])
        first = np.floor(lo) + 1
        n = np.maximum(0, np.ceil(hi) - first).astype(np.int64)
        seg = np.repeat(np.arange(len(a)), n)
        k = np.arange(int(n.sum())) - np.repeat(np.cumsum(n) - n, n)
        border = first[seg] + k
        ts.append((border - a[seg, axis]) / (b[seg, axis] - a[seg, axis]))
        segs.append(seg)
    t, seg = np.concatenate(ts), np.concatenate(segs)
    order = np.lexsort((t, seg))
    t, seg = t[order], seg[order]
    piece = seg[1:] == seg[:-1]
    s, t0, t1 = seg[:-1][piece], t[:-1][piece], t[1:][piece]
    d = b[s] - a[s]
    length = (t1 - t0) * np.hypot(d[:, 0], d[:, 1]) * CELL_MM
    mid = a[s] + d * ((t0 + t1) / 2)[:, None]
    cells = np.floor(mid).astype(np.int64)
    _, inverse = np.unique(cells, axis=0, return_inverse=True)
    return np.bincount(inverse.ravel(), length)


def distance_to_piece(p, q, dq, hq):
    """Distance from points p to the pieces of line of half length hq and
    direction dq centred on q (debris: how close a crumb comes to a line)."""
    d = p - q
    along = np.clip(np.einsum("ij,ij->i", d, dq), -hq, hq)
    r = d - along[:, None] * dq
    return np.hypot(r[:, 0], r[:, 1])


def closed(line):
    """Whether a polyline ends where it starts."""
    return len(line) > 2 and np.allclose(line[0], line[-1], atol=1e-6)


def in_long_runs(flag, poly, weight, is_closed, min_len):
    """The flagged samples that lie in a run of flagged samples (consecutive
    along one polyline; across the start of a closed one) whose pieces add
    up to at least min_len."""
    if not flag.any():
        return flag.copy()
    n = len(flag)
    same = np.r_[False, poly[1:] == poly[:-1]]
    start = flag & ~(np.r_[False, flag[:-1]] & same)
    run = np.cumsum(start) - 1
    # A closed polyline flagged at its last and first samples: one run.
    first = np.flatnonzero(np.r_[True, ~same[1:]])
    last = np.r_[first[1:] - 1, n - 1]
    wrap = [(f, l) for f, l in zip(first, last)
            if is_closed[poly[f]] and l > f and flag[f] and flag[l] and run[f] != run[l]]
    for f, l in wrap:
        # The last run lies within the polyline: relabel there only, so
        # many closed polylines cost their own length, not the layer's.
        tail = run[f:l + 1]
        tail[(tail == run[l]) & flag[f:l + 1]] = run[f]
    length = np.bincount(run[flag], weight[flag], minlength=int(run.max()) + 1)
    out = np.zeros(n, bool)
    out[flag] = length[run[flag]] >= min_len - 1e-9
    return out


def measure_layer(lines, width, tol_share=0.25, travel_only=False):
    m = {"paths": len(lines), "pen_down_mm": 0.0, "pen_up_mm": 0.0, "plot_time_s": 0.0,
         "touching_mm": 0.0, "touching_pct": 0.0,
         "doubled_mm": 0.0, "doubled_pct": 0.0, "debris": 0, "debris_pct": 0.0,
         "densest_mm2": 0.0, "densest_solid": 0.0, "samples": 0}
    if not lines:
        return m
    starts = np.array([l[0] for l in lines])
    ends = np.array([l[-1] for l in lines])
    jumps = starts - np.vstack(([0.0, 0.0], ends[:-1]))
    pen_up = float(np.hypot(jumps[:, 0], jumps[:, 1]).sum())
    lengths = np.array([np.hypot(*np.diff(l, axis=0).T).sum() for l in lines])
    pen_down = float(lengths.sum())
    m.update(pen_down_mm=pen_down, pen_up_mm=pen_up,
             plot_time_s=pen_down / SPEED_DOWN + pen_up / SPEED_UP + LIFT_S * len(lines))
    if travel_only:
        return m

    w = width
    step = w / 4
    points, dirs, weight, poly, t, _ = resample(lines, step)
    half = weight / 2
    m["samples"] = len(points)

    # Doubled: pairs (i, j) where j's piece, drawn earlier, lies on i.
    tol = tol_share * w
    cos_min = math.cos(math.radians(PARALLEL_DEG))
    doubled = np.zeros(len(points), bool)
    for i, j in near_pairs(points, points, tol + half.max()):
        earlier = (poly[j] < poly[i]) | ((poly[j] == poly[i]) & (t[j] < t[i] - SELF_GAP * w))
        earlier &= (weight[i] > 0) & (weight[j] > 0)
        i, j = i[earlier], j[earlier]
        parallel = np.abs(np.einsum("ij,ij->i", dirs[i], dirs[j])) >= cos_min
        i, j = i[parallel], j[parallel]
        # i must lie across j's own piece (not beyond its ends: pieces that
        # merely continue each other, as at the start of a closed path, are
        # not on one another), and within tol of it.
        d = points[i] - points[j]
        along = np.einsum("ij,ij->i", d, dirs[j])
        across = np.abs(d[:, 0] * dirs[j][:, 1] - d[:, 1] * dirs[j][:, 0])
        close = (np.abs(along) <= half[j] + 1e-9) & (across <= tol)
        doubled[i[close]] = True
    m["touching_mm"] = float(weight[doubled].sum())
    m["touching_pct"] = 100 * m["touching_mm"] / pen_down if pen_down > 0 else 0.0
    twice = in_long_runs(doubled, poly, weight, [closed(l) for l in lines], RUN_MIN * w)
    m["doubled_mm"] = float(weight[twice].sum())
    m["doubled_pct"] = 100 * m["doubled_mm"] / pen_down if pen_down > 0 else 0.0

    # Debris: short polylines (samples and vertices) within w of other line work.
    short = np.flatnonzero(lengths < w)
    if len(short):
        q = np.concatenate([lines[s] for s in short] + [points[np.isin(poly, short)]])
        q_poly = np.concatenate([np.full(len(lines[s]), s) for s in short]
                                + [poly[np.isin(poly, short)]])
        hit = np.zeros(len(lines), bool)
        for i, j in near_pairs(q, points, w + half.max()):
            other = q_poly[i] != poly[j]
            i, j = i[other], j[other]
            close = distance_to_piece(q[i], points[j], dirs[j], half[j]) <= w
            hit[q_poly[i[close]]] = True
        m["debris"] = int(hit.sum())
        m["debris_pct"] = 100 * m["debris"] / len(lines)

    # Density: line length per 1 mm cell of the sheet.
    per_cell = cell_lengths(lines) / (CELL_MM * CELL_MM)
    m["densest_mm2"] = float(per_cell.max())
    m["densest_solid"] = m["densest_mm2"] * w
    return m


def measure(path, tol_share=0.25, quantization=0.01, travel_only=False):
    layers = []
    for lid, name, width, lines in read_layers(path, quantization):
        m = {"layer": lid, "name": name, "pen_width_mm": width}
        m.update(measure_layer(lines, width, tol_share, travel_only))
        layers.append(m)
    total = {"layer": "total", "name": "", "pen_width_mm": None}
    for key in ("paths", "pen_down_mm", "pen_up_mm", "plot_time_s", "touching_mm", "doubled_mm",
                "debris",
                "samples"):
        total[key] = sum(l[key] for l in layers)
    for key in ("touching", "doubled"):
        total[f"{key}_pct"] = (100 * total[f"{key}_mm"] / total["pen_down_mm"]
                               if total["pen_down_mm"] > 0 else 0.0)
    total["debris_pct"] = 100 * total["debris"] / total["paths"] if total["paths"] else 0.0
    total["densest_mm2"] = max((l["densest_mm2"] for l in layers), default=0.0)
    total["densest_solid"] = max((l["densest_solid"] for l in layers), default=0.0)
    return {"file": path, "tol_share": tol_share, "layers": layers, "total": total}


def table(result):
    cols = [("layer", "layer", "{}"), ("name", "name", "{}"), ("pen mm", "pen_width_mm", "{:.2f}"),
            ("paths", "paths", "{}"), ("pen-down mm", "pen_down_mm", "{:.0f}"),
            ("pen-up mm", "pen_up_mm", "{:.0f}"), ("time", "plot_time_s", None),
            ("touching %", "touching_pct", "{:.2f}"),
            ("doubled mm", "doubled_mm", "{:.0f}"), ("doubled %", "doubled_pct", "{:.2f}"),
            ("debris", "debris", "{}"), ("debris %", "debris_pct", "{:.2f}"),
            ("densest mm/mm²", "densest_mm2", "{:.2f}"), ("×solid", "densest_solid", "{:.2f}")]

    def cell(row, key, fmt):
        v = row[key]
        if v is None:
            return ""
        if fmt is None:
            s = int(round(v))
            return f"{s // 3600}:{s // 60 % 60:02}:{s % 60:02}"
        return fmt.format(v)

    rows = [[c[0] for c in cols]]
    for row in result["layers"] + [result["total"]]:
        rows.append([cell(row, key, fmt) for _, key, fmt in cols])
    widths = [max(len(r[i]) for r in rows) for i in range(len(cols))]
    out = [result["file"]]
    for n, r in enumerate(rows):
        out.append("  ".join(v.ljust(wd) if i < 2 else v.rjust(wd)
                             for i, (v, wd) in enumerate(zip(r, widths))))
        if n == 0 or n == len(rows) - 2:
            out.append("  ".join("-" * wd for wd in widths))
    return "\n".join(out)


# --- self-test ---------------------------------------------------------------

def _svg(layers, width_mm=100, height_mm=100, scale=1.0):
    """An SVG page; layers = [(label, stroke width, [path d])], user units
    `scale` mm each."""
    body = []
    for label, sw, ds in layers:
        style = f' style="fill:none;stroke:#000;stroke-width:{sw}"' if sw is not None else ""
        body.append(f'<g inkscape:groupmode="layer" inkscape:label="{label}"{style}>'
                    + "".join(f'<path d="{d}"/>' for d in ds) + "</g>")
    return (f'<svg xmlns="{SVG_NS}" xmlns:inkscape="{INKSCAPE_NS}" width="{width_mm}mm" '
            f'height="{height_mm}mm" viewBox="0 0 {width_mm / scale:g} {height_mm / scale:g}">'
            + "".join(body) + "</svg>")


def self_test():
    line = "M 10 10 L 90 10"
    circle = "M 50.35 50 A 0.35 0.35 0 1 1 49.65 50 A 0.35 0.35 0 1 1 50.35 50 Z"
    hatch = [f"M 5 {5.05 + 0.1 * k:.2f} L 6 {5.05 + 0.1 * k:.2f}" for k in range(10)]
    cases = [
        # (what, layers, svg kwargs, {key: (expected, tolerance)} on the total)
        ("two identical lines: 50 % doubled", [("1 a", 0.3, [line, line])], {},
         {"doubled_pct": (50, 0.5), "paths": (2, 0), "debris": (0, 0)}),
        ("a line and its reverse: 50 % doubled",
         [("1 a", 0.3, [line, "M 90 10 L 10 10"])], {}, {"doubled_pct": (50, 0.5)}),
        ("there and back in one path: 50 % doubled",
         [("1 a", 0.3, ["M 10 10 L 90 10 L 10 10"])], {}, {"doubled_pct": (50, 0.6)}),
        ("lines end to end: 0 % doubled",
         [("1 a", 0.3, ["M 10 10 L 50 10", "M 50 10 L 90 10"])], {}, {"doubled_pct": (0, 0)}),
        ("lines overlapping by 10 mm of 90: 11.1 % doubled",
         [("1 a", 0.3, ["M 10 10 L 60 10", "M 50 10 L 90 10"])], {},
         {"doubled_mm": (10, 0.1), "doubled_pct": (100 / 9, 0.15)}),
        ("a copy cut at other places (samples out of step): 50 % doubled",
         [("1 a", 0.3, [line, "M 10.03 10 L 37.01 10 L 89.97 10"])], {},
         {"doubled_pct": (50, 0.5)}),
        ("a line 0.05 mm beside another (tol 0.075): 50 % doubled",
         [("1 a", 0.3, [line, "M 10 10.05 L 90 10.05"])], {}, {"doubled_pct": (50, 0.5)}),
        ("a line 0.1 mm beside another: 0 % doubled",
         [("1 a", 0.3, [line, "M 10 10.1 L 90 10.1"])], {}, {"doubled_pct": (0, 0)}),
        ("lines 10° apart through one point: only near the crossing",
         [("1 a", 0.3, ["M 10 50 L 90 50", "M 10.6 43 L 89.4 57"])], {},
         {"doubled_pct": (0.4, 0.4)}),
        ("a fork of 20°: touches for 0.22 mm, not doubled",
         [("1 a", 0.3, ["M 10 50 L 90 50",
                        f"M 50 50 L {50 + 40 * math.cos(math.radians(20)):.4f} "
                        f"{50 - 40 * math.sin(math.radians(20)):.4f}"])], {},
         {"touching_mm": (0.075 / math.sin(math.radians(20)), 0.08), "doubled_pct": (0, 0)}),
        ("a closed path whose start and end lie on a corner drawn before: one run, doubled",
         [("1 a", 0.3, ["M 10 10.4 L 10 10 L 10.4 10", "M 10 10 L 50 10 L 50 50 L 10 50 Z"])], {},
         {"doubled_mm": (0.8, 0.1)}),
        ("two crossing lines: 0 % doubled",
         [("1 a", 0.3, ["M 10 50 L 90 50", "M 50 10 L 50 90"])], {},
         {"doubled_pct": (0, 0.01), "debris": (0, 0)}),
        ("the same line on two pens: 0 % doubled",
         [("1 a", 0.3, [line]), ("2 b", 0.3, [line])], {}, {"doubled_pct": (0, 0)}),
        ("a stipple dot (circle r 0.35): 0 % doubled, no debris",
         [("1 a", 0.3, [circle])], {}, {"doubled_pct": (0, 0), "debris": (0, 0),
                                       "pen_down_mm": (2 * math.pi * 0.35, 0.001)}),
        ("0.1 mm line touching a long line: 1 debris",
         [("1 a", 0.3, [line, "M 50 10 L 50 10.1"])], {}, {"debris": (1, 0),
                                                          "debris_pct": (50, 0)}),
        ("0.1 mm line 0.25 mm from a long line: 1 debris",
         [("1 a", 0.3, [line, "M 50 10.25 L 50 10.35"])], {}, {"debris": (1, 0)}),
        ("isolated 0.1 mm line: 0 debris",
         [("1 a", 0.3, [line, "M 50 20 L 50 20.1"])], {}, {"debris": (0, 0)}),
        ("0.1 mm line on another pen's line: 0 debris",
         [("1 a", 0.3, [line]), ("2 b", 0.3, ["M 50 10 L 50 10.1"])], {}, {"debris": (0, 0)}),
        ("pen-up travel from the origin, time",
         [("1 a", 0.3, ["M 10 0 L 20 0", "M 20 10 L 30 10"])], {},
         {"pen_up_mm": (20, 1e-4), "pen_down_mm": (20, 1e-4),
          "plot_time_s": (20 / SPEED_DOWN + 20 / SPEED_UP + 2 * LIFT_S, 1e-4)}),
        ("two layers each start at the origin",
         [("1 a", 0.3, ["M 3 4 L 10 4"]), ("2 b", 0.3, ["M 6 8 L 10 8"])], {},
         {"pen_up_mm": (15, 1e-4)}),
        ("ten 1 mm lines in one cell: 10 mm/mm², ×3 solid with 0.3 mm",
         [("1 a", 0.3, hatch)], {}, {"densest_mm2": (10, 1e-4), "densest_solid": (3, 1e-4),
                                     "doubled_pct": (0, 0)}),
        ("a line across a cell border counts in each cell what lies there (0.9 + 0.1)",
         [("1 a", 2.0, ["M 10.9 10.5 L 11.9 10.5", "M 30 30 L 30.1 30"])], {},
         {"densest_mm2": (0.9, 1e-4)}),
        ("pen width from style through viewBox (2 mm a unit): 0.25 → 0.5 mm",
         [("1 a", 0.25, ["M 5 5 L 45 5", "M 25 5.2 L 25 5.3"])], {"scale": 2.0},
         {"pen_down_mm": (80.2, 1e-4), "debris": (1, 0), "pen_up_mm": (math.hypot(10, 10) + math.hypot(40, 0.4), 1e-4)}),
        ("no stroke-width: 0.3 mm (a 0.25 mm line is debris)",
         [("1 a", None, [line, "M 50 10 L 50 10.25"])], {}, {"debris": (1, 0)}),
        ("a %-layer is not plotted",
         [("%notes", 0.3, [line]), ("1 a", 0.3, [line])], {},
         {"doubled_pct": (0, 0), "paths": (1, 0)}),
    ]
    failed = 0
    with tempfile.TemporaryDirectory() as tmp:
        for n, (what, layers, kw, expect) in enumerate(cases):
            path = os.path.join(tmp, f"case{n}.svg")
            with open(path, "w") as f:
                f.write(_svg(layers, **kw))
            total = measure(path)["total"]
            bad = [f"{k} = {total[k]:.4g}, expected {v:g} ± {tol:g}"
                   for k, (v, tol) in expect.items() if abs(total[k] - v) > tol]
            failed += bool(bad)
            print(("FAIL " if bad else "ok   ") + what + ("".join("\n     " + b for b in bad)))

        # Speed: a million samples (250 mm of hatching at 0.3 mm, 0.075 mm steps).
        import time  # noqa: PLC0415
        rng = np.random.default_rng(1)
        lines = [np.array([[x, 0.0], [x, 250.0]]) + rng.normal(0, 0.02, (1, 2))
                 for x in np.arange(0, 75, 0.25)]
        started = time.perf_counter()
        m = measure_layer(lines, 0.3)
        took = time.perf_counter() - started
        print(f"ok   speed: {m['samples']:,} samples in {took:.1f} s "
              f"(doubled {m['doubled_pct']:.1f} %)")
    print("self-test:", "FAILED" if failed else "passed", f"({len(cases) - failed}/{len(cases)})")
    return 1 if failed else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("svg", nargs="?")
    ap.add_argument("--tol-share", type=float, default=0.25,
                    help="doubled: tolerance as a share of the pen width (default 0.25)")
    ap.add_argument("--quantization", type=float, default=0.01,
                    help="longest segment of a flattened curve, mm (default 0.01)")
    ap.add_argument("--json", action="store_true", help="print JSON instead of a table")
    ap.add_argument("--travel-only", action="store_true",
                    help="only paths, pen-down, pen-up and time (skip the sampling)")
    ap.add_argument("--self-test", action="store_true", help="run the built-in checks")
    args = ap.parse_args()
    if args.self_test:
        sys.exit(self_test())
    if not args.svg:
        ap.error("an SVG file is needed (or --self-test)")
    result = measure(args.svg, args.tol_share, args.quantization, args.travel_only)
    print(json.dumps(result) if args.json else table(result))


if __name__ == "__main__":
    main()
