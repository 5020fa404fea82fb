#!/usr/bin/env python3
"""Synthetic plotter SVGs for bench/vs_vpype.sh and bench/limits.sh
(standard library only).

    gen_paths.py random N OUT.svg   N short cubic Bézier paths scattered on A3
    gen_paths.py chains N OUT.svg   N short pieces forming chains whose pieces
                                    share endpoints, some pieces reversed and
                                    shuffled (what line merging is for)
    gen_paths.py lines N OUT.svg K  N random walks of K line segments each
                                    (the heaviest paths per element)

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


def main():
    kind, n, path = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    rng = random.Random(20261121)
    with open(path, "w") as out:
        header(out)
        if kind == "lines":
            lines(n, out, rng, int(sys.argv[4]))
        else:
            {"random": random_paths, "chains": chains}[kind](n, out, rng)
        out.write("</g>\n</svg>\n")


if __name__ == "__main__":
    main()
