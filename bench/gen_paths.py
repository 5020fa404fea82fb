#!/usr/bin/env python3
"""Synthetic plotter SVGs for bench/vs_vpype.sh and bench/limits.sh
(standard library only).

    gen_paths.py random N OUT.svg   N short cubic Bézier paths scattered on A3
    gen_paths.py chains N OUT.svg   N short pieces forming chains whose pieces
                                    share endpoints, some pieces reversed and
                                    shuffled (what line merging is for)
    gen_paths.py lines N OUT.svg K  N random walks of K line segments each
                                    (the heaviest paths per element)
    gen_paths.py doubled N OUT.svg [MM]
                                    N line segments (of MM/2 to 3·MM/2 mm,
                                    MM 0.4 unless given) in paths of 10, a
                                    fifth of the paths drawn again over an
                                    earlier one (what deduplication is for):
                                    exactly, reversed, shifted along it (a
                                    partial overlap, cut at other places)
                                    or moved 0.02 mm; shuffled

Deterministic: the same arguments give the same file.
"""
import math
import random
import sys

W, H = 420.0, 297.0


def header(out):
    out.write('<?xml version="1.0" encoding="UTF-8"?>\n')
    out.write(
        f'<svg xmlns="http://www.w3.org/2000/svg" '
        f'xmlns:inkscape="http://www.inkscape.org/namespaces/inkscape" '
        f'width="{W}mm" height="{H}mm" viewBox="0 0 {W} {H}">\n'
        '<g id="layer1" inkscape:groupmode="layer" inkscape:label="1 black" '
        'style="fill:none;stroke:#000000;stroke-width:0.3">\n'
    )


def cubic(out, p0, p1, p2, p3):
    out.write(
        '<path d="M %.3f %.3f C %.3f %.3f %.3f %.3f %.3f %.3f"/>\n'
        % (*p0, *p1, *p2, *p3)
    )


def random_paths(n, out, rng):
    for _ in range(n):
        x, y = rng.uniform(10, W - 10), rng.uniform(10, H - 10)
        a = rng.uniform(0, 2 * math.pi)
        r = rng.uniform(1, 6)
        p3 = (x + r * math.cos(a), y + r * math.sin(a))
        bend = rng.uniform(-1, 1)
        p1 = (x + r / 3 * math.cos(a + bend), y + r / 3 * math.sin(a + bend))
        p2 = (x + 2 * r / 3 * math.cos(a - bend), y + 2 * r / 3 * math.sin(a - bend))
        cubic(out, (x, y), p1, p2, p3)


def chains(n, out, rng):
    pieces = []
    while len(pieces) < n:
        x, y = rng.uniform(10, W - 10), rng.uniform(10, H - 10)
        a = rng.uniform(0, 2 * math.pi)
        for _ in range(rng.randint(3, 20)):
            a += rng.uniform(-0.6, 0.6)
            r = rng.uniform(1, 4)
            nx, ny = x + r * math.cos(a), y + r * math.sin(a)
            if not (0 < nx < W and 0 < ny < H):
                break
            p = [(x, y), (x + (nx - x) / 3, y + (ny - y) / 3 + 0.3),
                 (x + 2 * (nx - x) / 3, y + 2 * (ny - y) / 3 - 0.3), (nx, ny)]
            if rng.random() < 0.5:
                p.reverse()
            pieces.append(p)
            x, y = nx, ny
    pieces = pieces[:n]
    rng.shuffle(pieces)
    for p in pieces:
        cubic(out, *p)


def lines(n, out, rng, segments):
    for _ in range(n):
        x, y = rng.uniform(10, W - 10), rng.uniform(10, H - 10)
        steps = []
        # segments + 1 points: the first is where the pen moves to.
        for _ in range(segments + 1):
            x = min(max(x + rng.uniform(-2, 2), 0.0), W)
            y = min(max(y + rng.uniform(-2, 2), 0.0), H)
            steps.append("%.2f %.2f" % (x, y))
        out.write('<path d="M %s L %s"/>\n' % (steps[0], " ".join(steps[1:])))


def walk(rng, x, y, a, segments, mm):
    """A random walk of `segments` steps of mm/2 to 3·mm/2 from (x, y), with
    heading a (radians) turning by up to 0.06/mm a step (a smooth curve
    flattened to within about 0.01 mm), kept on the sheet: its points."""
    turn = min(0.6, 0.06 / mm)
    pts = [(x, y)]
    for _ in range(segments):
        a += rng.uniform(-turn, turn)
        r = rng.uniform(mm / 2, 1.5 * mm)
        nx, ny = x + r * math.cos(a), y + r * math.sin(a)
        if not (1 < nx < W - 1 and 1 < ny < H - 1):
            a += math.pi / 2  # a rare turn at the edge (not back on itself)
            nx, ny = x + r * math.cos(a), y + r * math.sin(a)
        x, y = nx, ny
        pts.append((x, y))
    return pts


def along(p, i, f):
    """The point a share f of the way along segment i of polyline p."""
    (x0, y0), (x1, y1) = p[i], p[i + 1]
    return (x0 + f * (x1 - x0), y0 + f * (y1 - y0))


def doubled(n, out, rng, mm=0.4, segments=10, share=0.2):
    """n segments of about mm (rounded down to whole paths of `segments`):
    originals, each followed by a copy of it with probability
    share / (1 - share), so that about `share` of the paths are copies, of
    one of four kinds (a quarter each). Every path has `segments` segments."""
    paths = []
    while len(paths) < n // segments:
        a = rng.uniform(0, 2 * math.pi)
        margin = 10 + 1.5 * mm * segments
        p = walk(rng, rng.uniform(margin, W - margin), rng.uniform(margin, H - margin), a,
                 segments, mm)
        paths.append(p)
        if len(paths) == n // segments or rng.random() >= share / (1 - share):
            continue
        kind = rng.choice(("exact", "reversed", "shifted", "moved"))
        if kind == "exact":
            q = list(p)
        elif kind == "reversed":
            q = p[::-1]
        elif kind == "moved":
            b = rng.uniform(0, 2 * math.pi)
            q = [(x + 0.02 * math.cos(b), y + 0.02 * math.sin(b)) for x, y in p]
        else:
            # Shifted: the same line cut at other places, as a curve
            # flattened twice: from 30 to 70 % of the way along segments k
            # to segments - 1 of p (vertices at least 0.15·mm from p's, so
            # that hardly a segment has both ends within 0.075 mm of a
            # segment of p's; the copy cuts p's corners by at most 0.03 mm),
            # then on along a new walk to `segments` segments: overlaps p
            # over about segments - 1 - k of its segments.
            k = rng.randrange(1, segments - 1)
            q = [along(p, i, rng.uniform(0.3, 0.7)) for i in range(k, segments)]
            heading = math.atan2(p[-1][1] - p[-2][1], p[-1][0] - p[-2][0])
            q += walk(rng, *q[-1], heading, segments + 1 - len(q), mm)[1:]
        paths.append(q)
    rng.shuffle(paths)
    for p in paths:
        out.write('<path d="M %.3f %.3f L %s"/>\n'
                  % (*p[0], " ".join("%.3f %.3f" % xy for xy in p[1:])))


def main():
    kind, n, path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    rng = random.Random(20261121)
    with open(path, "w") as out:
        header(out)
        if kind == "lines":
            lines(n, out, rng, int(sys.argv[4]))
        elif kind == "doubled":
            doubled(n, out, rng, *map(float, sys.argv[4:5]))
        else:
            {"random": random_paths, "chains": chains}[kind](n, out, rng)
        out.write("</g>\n</svg>\n")


if __name__ == "__main__":
    main()
