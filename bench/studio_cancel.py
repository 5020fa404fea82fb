#!/usr/bin/env python3
"""How soon a newer edit stops the studio's render before it, and what a
render past the memory budget answers (stdlib only; RELIABILITY.md, "The
studio").

    bench/studio_cancel.py [ROUNDS]   default 5 rounds of each case

Starts `target/release/moyo studio` on a free port in a new folder. For
each heavy description below, ROUNDS times: PUT it, wait WAIT seconds
(it is then deep in its long loop), PUT a light edit, and time from
sending the light edit to the heavy one's answer (409 when it was called
off): the latency of the cancellation, the light edit's request included.
Prints the median and maximum of each, in ms.

Then a studio started with `--memory-mb 512` is sent the Hilbert curve
at 11 iterations for its preview (a peak of 723 MB): its answer, its
time, and the studio's resident memory after it.
"""
import os
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import urllib.error
import urllib.request

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
MOYO = os.path.join(ROOT, "target", "release", "moyo")
WAIT = 1.5

def scene(size, table, body, head=""):
    """A description of one layer holding one `table` (its TOML `body`)."""
    return (f"version = 1\n{head}[page]\nsize = \"{size}\"\n[[layers]]\nname = \"front\"\n"
            f"[[layers.{table}]]\n{body}")


LIGHT = scene("A5", "trees", 'id = "pine"\nrule = "tree1"\ncount = 2\n'
              "centre = [[20, 150], [120, 150]]\n", head="seed = {seed}\n")


def hilbert(iterations):
    text = open(os.path.join(ROOT, "templates", "lsystem-hilbert.toml")).read()
    return text.replace("iterations = 6", f"iterations = {iterations}")


def zentangle():
    path = os.path.join(ROOT, "tests", "data", "hostile",
                        "zentangle-5000-steps-at-scale-0.05.toml")
    text = open(path).read()
    return text.replace("scale = 0.05", "scale = 0.35")


FORMULA = "+".join(["u"] * 100)[:199]

HEAVY = {
    "relax: 9,000 sites, 110 steps": scene(
        "A5", "voronoi", 'id = "heavy"\nrelax = 110\n[layers.voronoi.sites]\n'
        'distribution = "uniform"\ncount = 9000\n'),
    "formula: Poisson sites 0.3 mm apart by a 199-character formula, A4": scene(
        "A4", "voronoi", 'id = "heavy"\n[layers.voronoi.sites]\ndistribution = "poisson"\n'
        f'spacing = 0.3\ndensity = "{FORMULA}"\n', head="[limits]\nmax_paths = 1000000\n"),
    "zentangle: 5,000 steps at scale 0.35, smallest 0.2, A4": zentangle(),
    "lsystem: the Hilbert curve at 11 iterations": hilbert(11),
}


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def put(base, text, query=""):
    req = urllib.request.Request(base + "/api/scene" + query, data=text.encode(), method="PUT")
    try:
        with urllib.request.urlopen(req, timeout=600) as r:
            return r.status, r.read().decode()
    except urllib.error.HTTPError as e:
        return e.code, e.read().decode()


def start(*args):
    folder = tempfile.mkdtemp()
    port = free_port()
    proc = subprocess.Popen([MOYO, "studio", "--port", str(port), *args], cwd=folder,
                            stderr=subprocess.PIPE, text=True)
    proc.stderr.readline()
    return proc, f"http://127.0.0.1:{port}"


def resident_mb(pid):
    status = open(f"/proc/{pid}/status").read()
    return int(re.search(r"VmRSS:\s+(\d+)", status).group(1)) // 1024


def main():
    rounds = int(sys.argv[1]) if len(sys.argv) > 1 else 5
    proc, base = start()
    try:
        for name, text in HEAVY.items():
            latencies = []
            for k in range(rounds):
                answer = {}
                heavy = threading.Thread(
                    target=lambda: answer.update(
                        zip(("status", "body"), put(base, text)), at=time.monotonic()))
                heavy.start()
                time.sleep(WAIT)
                sent = time.monotonic()
                light = threading.Thread(target=put, args=(base, LIGHT.format(seed=k + 10)))
                light.start()
                heavy.join()
                light.join()
                if answer["status"] != 409:
                    print(f"{name}: answered {answer['status']} before the light edit "
                          f"(raise WAIT): {answer['body'][:200]}")
                    break
                latencies.append((answer["at"] - sent) * 1000)
            if latencies:
                print(f"{name}: {len(latencies)} cancelled, median "
                      f"{statistics.median(latencies):.0f} ms, max {max(latencies):.0f} ms")
    finally:
        proc.kill()
        proc.wait()
    proc, base = start("--memory-mb", "512")
    try:
        before = time.monotonic()
        status, body = put(base, hilbert(11), "?view=preview")
        took = time.monotonic() - before
        print(f"memory: the Hilbert curve at 11 iterations to --memory-mb 512: {status} "
              f"after {took:.1f} s, the studio at {resident_mb(proc.pid)} MB after: {body[:160]}")
        status, _ = put(base, LIGHT.format(seed=1))
        print(f"memory: a light edit after it: {status}, alive: {proc.poll() is None}")
    finally:
        proc.kill()
        proc.wait()


if __name__ == "__main__":
    main()
