#!/usr/bin/env python3
"""Measures an SVG the way a plotter would run it, independently of moyo and
of vpype's own statistics: pen-down length (ink) and pen-up travel in file
order, starting and ending nowhere in particular (from the first path's
start; travel is the sum of jumps between consecutive subpaths).

    svg_metrics.py FILE.svg   ->  prints JSON {paths, pen_down_mm, pen_up_mm}

Uses svgelements (installed with vpype). Lengths are in millimetres.
"""
import json
import sys

import svgelements

PX_PER_MM = 96 / 25.4


def main():
    svg = svgelements.SVG.parse(sys.argv[1], reify=True, ppi=96.0)
    pen_down = 0.0
    pen_up = 0.0
    count = 0
    last = None
    for element in svg.elements():
        if not isinstance(element, svgelements.Shape):
            continue
        # vpype writes <polyline>, moyo <path>: measure both as paths.
        if not isinstance(element, svgelements.Path):
            element = svgelements.Path(element)
        for sub in element.as_subpaths():
            sub = svgelements.Path(sub)
            if len(sub) == 0:
                continue
            start, end = sub.first_point, sub.current_point
            if start is None:
                continue
            count += 1
            pen_down += sub.length(error=1e-6)
            if last is not None:
                pen_up += abs(complex(*start) - complex(*last))
            last = end
    print(json.dumps({
        "paths": count,
        "pen_down_mm": pen_down / PX_PER_MM,
        "pen_up_mm": pen_up / PX_PER_MM,
    }))


if __name__ == "__main__":
    main()
