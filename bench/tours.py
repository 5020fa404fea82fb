#!/usr/bin/env python3
"""Pen-up tours measured and solved without moyo's code, for
bench/tour_vs_lkh.sh.

    tours.py segments N OUT.svg     N random line segments on A3 (both ends
                                    uniform on the sheet inside a 10 mm
                                    margin; fixed seed)
    tours.py lkh IN.svg [RUNS]      the pen-up travel of LKH's tour through
                                    IN's paths (mm, JSON)
    tours.py largest IN.svg OUT.svg the plotted layer of IN with the most
                                    paths, alone, its paths shuffled (fixed
                                    seed): prints its label and path count

Travel is measured as bench/svg_metrics.py does: the straight moves between
consecutive subpaths, from the first one's start; the first move from home
is not counted.

The LKH model (elkai, LKH-3): every path is two nodes, its start and its
end, joined by an edge of weight 0 while every other weight has BIG added
(elkai's LKH crashes on FIXED_EDGES_SECTION), so a best tour draws each path
whole, either way round (checked); one more node Z is at distance 0 from
every node, so the tour through Z is a path that starts and ends anywhere,
and its length is the pen-up travel. Other weights are Euclidean distances
between the end points in units of 10 µm (LKH needs integers), written as a
full matrix (elkai reads no other explicit format); the travel printed is
recomputed from the points. A closed path's two nodes are one point: LKH may not
start it elsewhere (moyo may: at any vertex).
"""
import json
import random
import re
import sys
import xml.etree.ElementTree as ET

import numpy as np
import vpype as vp

W, H = 420.0, 297.0
# Added to every weight but a path's own (start, end) edge: a tour that
# leaves one out pays BIG once more, far more than any travel it could save.
BIG = 1_000_000
SVG = "http://www.w3.org/2000/svg"
INKSCAPE = "http://www.inkscape.org/namespaces/inkscape"


def segments(n, path):
    rng = random.Random(20261128)
    with open(path, "w") as out:
        out.write(
            '<?xml version="1.0" encoding="UTF-8"?>\n'
            f'<svg xmlns="{SVG}" xmlns:inkscape="{INKSCAPE}" width="{W}mm" '
            f'height="{H}mm" viewBox="0 0 {W} {H}">\n'
            '<g id="layer1" inkscape:groupmode="layer" inkscape:label="1 black" '
            'style="fill:none;stroke:#000000;stroke-width:0.3">\n'
        )
        for _ in range(n):
            x0, y0, x1, y1 = (rng.uniform(10, W - 10), rng.uniform(10, H - 10),
                              rng.uniform(10, W - 10), rng.uniform(10, H - 10))
            out.write(f'<path d="M {x0:.3f} {y0:.3f} L {x1:.3f} {y1:.3f}"/>\n')
        out.write("</g>\n</svg>\n")


def end_points(path):
    """Start and end (mm) of every subpath of every layer of an SVG, read by
    vpype (which splits paths into subpaths and keeps their end points)."""
    doc = vp.read_multilayer_svg(path, quantization=0.1)
    ends = []
    for layer in doc.layers.values():
        for line in layer:
            if len(line):
                ends.append((line[0], line[-1]))
    scale = 1 / vp.convert_length("mm")
    return np.array([[a, b] for a, b in ends], dtype=complex) * scale


def lkh(path, runs):
    import elkai._elkai as lkh_solver

    ends = end_points(path)
    n = len(ends)
    pts = ends.reshape(-1)  # node 2i: start of path i, 2i + 1: its end
    # Weights in units of 10 µm: LKH multiplies them by its PRECISION (100)
    # and must stay within 32-bit integers.
    cost = np.rint(np.abs(pts[:, None] - pts[None, :]) * 100).astype(np.int64) + BIG
    dim = 2 * n + 1  # the last node is Z
    full = np.full((dim, dim), BIG, dtype=np.int64)
    full[: 2 * n, : 2 * n] = cost
    full[np.arange(0, 2 * n, 2), np.arange(1, 2 * n, 2)] = 0
    full[np.arange(1, 2 * n, 2), np.arange(0, 2 * n, 2)] = 0
    np.fill_diagonal(full, 0)
    rows = [" ".join(map(str, row)) for row in full.tolist()]
    problem = (
        f"TYPE : TSP\nDIMENSION : {dim}\nEDGE_WEIGHT_TYPE : EXPLICIT\n"
        "EDGE_WEIGHT_FORMAT : FULL_MATRIX\nEDGE_WEIGHT_SECTION\n"
        + "\n".join(rows)
        + "\nEOF\n"
    )
    params = f"RUNS = {runs}\nPROBLEM_FILE = :stdin:\n"
    tour = [i - 1 for i in lkh_solver.solve_problem(params, problem)]
    z = tour.index(dim - 1)
    order = tour[z + 1:] + tour[:z]
    # The fixed edges must pair up: start/end of one path, then the next.
    assert len(order) == 2 * n and all(order[k] // 2 == order[k + 1] // 2
                                       for k in range(0, 2 * n, 2)), "fixed edges broken"
    travel = sum(abs(pts[order[k]] - pts[order[k + 1]]) for k in range(1, 2 * n - 1, 2))
    print(json.dumps({"paths": n, "pen_up_mm": travel}))


def largest(src, dst):
    ET.register_namespace("", SVG)
    ET.register_namespace("inkscape", INKSCAPE)
    root = ET.parse(src).getroot()
    layers = [g for g in root.findall(f"{{{SVG}}}g")
              if g.get(f"{{{INKSCAPE}}}groupmode") == "layer"
              and not g.get(f"{{{INKSCAPE}}}label", "").startswith("%")]

    def paths(g):
        """(path element, transforms of the groups above it) of a layer."""
        out = []

        def walk(node, transforms):
            for child in node:
                if child.tag == f"{{{SVG}}}path":
                    out.append((child, transforms))
                elif child.tag == f"{{{SVG}}}g":
                    t = child.get("transform")
                    if t and not re.fullmatch(r"translate\(0[ ,]+0\)", t):
                        transforms = transforms + (t,)
                    walk(child, transforms)

        walk(g, ())
        return out

    layer = max(layers, key=lambda g: len(paths(g)))
    items = paths(layer)
    transforms = {t for _, t in items}
    if len(transforms) > 1:
        sys.exit(f"{src}: the paths of the largest layer are under different transforms")
    random.Random(20261128).shuffle(items)
    out_root = ET.Element(root.tag, {k: v for k, v in root.attrib.items()
                                     if k in ("width", "height", "viewBox")})
    g = ET.SubElement(out_root, f"{{{SVG}}}g", {
        "id": "largest", f"{{{INKSCAPE}}}groupmode": "layer",
        f"{{{INKSCAPE}}}label": layer.get(f"{{{INKSCAPE}}}label", "1"),
        "style": layer.get("style", "fill:none;stroke:#000000"),
    })
    for t in next(iter(transforms), ()):
        g = ET.SubElement(g, f"{{{SVG}}}g", {"transform": t})
    for p, _ in items:
        ET.SubElement(g, f"{{{SVG}}}path", {"d": p.get("d")})
    ET.ElementTree(out_root).write(dst, xml_declaration=True, encoding="UTF-8")
    print(layer.get(f"{{{INKSCAPE}}}label", "?"), len(items))


def main():
    cmd = sys.argv[1]
    if cmd == "segments":
        segments(int(sys.argv[2]), sys.argv[3])
    elif cmd == "lkh":
        lkh(sys.argv[2], int(sys.argv[3]) if len(sys.argv) > 3 else 1)
    elif cmd == "largest":
        largest(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
