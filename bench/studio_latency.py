#!/usr/bin/env python3
"""Edit-to-preview latency of `moyo studio` in a real browser (stdlib only).

    bench/studio_latency.py [TEMPLATE] [EDITS]   default: kimono-2, 20 edits
    bench/studio_latency.py TEMPLATE BATCHES stroke

Starts `target/release/moyo studio -t TEMPLATE` on a free port in a new
folder and a headless Chromium through chromedriver (MOYO_CHROMEDRIVER,
MOYO_CHROMIUM, default /usr/bin/chromedriver and /usr/bin/chromium), then
changes the seed EDITS times two ways and reads the time the page itself
measures from the edit to the new picture on screen (`data-latency`):

  typed  - the TOML text changed and an input event sent, as a keystroke
           does (this includes the page's 25 ms wait for more typing);
  form   - a field set as the form and the handles set one (no wait).

Prints the median, 90th percentile and maximum of each, in ms.

With `stroke`, no browser: a pen stroke is drawn through the studio's API
as the page sends one (POST /api/stroke/begin, BATCHES batches of 8 points
1.5 mm apart, /end), growing the template's first sketch table or, without
one, a new sketch in its first layer; it prints the time of each batch
(the sketch extended and its limbs drawn) and of the render when the pen
lifts.
"""
import json
import math
import os
import re
import socket
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.request

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def call(base, method, path, body=None):
    data = None if body is None else json.dumps(body).encode()
    req = urllib.request.Request(base + path, data=data, method=method,
                                 headers={"Content-Type": "application/json"})
    with urllib.request.urlopen(req, timeout=120) as r:
        return json.loads(r.read())["value"]


def summary(label, ms):
    ms = sorted(ms)
    p90 = ms[min(len(ms) - 1, int(round(0.9 * (len(ms) - 1))))]
    return (f"{label}  {len(ms):3}  median {statistics.median(ms):6.0f} ms  "
            f"p90 {p90:6.0f} ms  max {ms[-1]:6.0f} ms")


def stroke(port, template, batches):
    studio = f"http://127.0.0.1:{port}"

    def post(path, body):
        req = urllib.request.Request(studio + path, data=json.dumps(body).encode(), method="POST",
                                     headers={"Content-Type": "application/json"})
        start = time.perf_counter()
        with urllib.request.urlopen(req, timeout=120) as r:
            answer = json.loads(r.read())
        return answer, (time.perf_counter() - start) * 1000

    with urllib.request.urlopen(studio + "/api/targets") as r:
        targets = json.loads(r.read())
    target = targets["sketch"][0]["field"] if targets["sketch"] else None
    post("/api/stroke/begin", {"target": target, "layer": 0, "at": [60, 180]})
    times, k = [], 0
    for _ in range(batches):
        points = []
        for _ in range(8):
            k += 1
            points.append([60 + 20 * math.sin(k / 40), 180 - 1.5 * k * 0.2])
        answer, ms = post("/api/stroke/extend", {"points": points})
        times.append(ms)
    steps = answer["steps"]
    _, end = post("/api/stroke/end", {})
    print(summary(f"{template} stroke batch", times) + f"  ({steps} steps)")
    print(f"{template} pen lifts: rendered in {end:.0f} ms")


def main():
    template = sys.argv[1] if len(sys.argv) > 1 else "kimono-2"
    edits = int(sys.argv[2]) if len(sys.argv) > 2 else 20
    folder = tempfile.mkdtemp()
    port = free_port()
    studio = subprocess.Popen(
        [os.path.join(ROOT, "target/release/moyo"), "studio", "-t", template, "--port", str(port)],
        cwd=folder, stderr=subprocess.PIPE, text=True)
    studio.stderr.readline()  # "moyo studio: open http://…"
    if sys.argv[3:4] == ["stroke"]:
        try:
            stroke(port, template, edits)
        finally:
            studio.terminate()
        return
    driver_port = free_port()
    driver = subprocess.Popen(
        [os.environ.get("MOYO_CHROMEDRIVER", "/usr/bin/chromedriver"), f"--port={driver_port}"],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    base = f"http://127.0.0.1:{driver_port}"
    for _ in range(100):
        try:
            socket.create_connection(("127.0.0.1", driver_port), timeout=1).close()
            break
        except OSError:
            time.sleep(0.1)
    profile = tempfile.mkdtemp()
    session = call(base, "POST", "/session", {"capabilities": {"alwaysMatch": {
        "browserName": "chrome",
        "goog:chromeOptions": {
            "binary": os.environ.get("MOYO_CHROMIUM", "/usr/bin/chromium"),
            "args": ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                     "--no-first-run", "--disable-background-networking",
                     "--disable-component-update", "--disable-sync",
                     "--window-size=1400,900", f"--user-data-dir={profile}"]}}}})["sessionId"]
    s = f"/session/{session}"

    def run(script, *args):
        return call(base, "POST", s + "/execute/sync", {"script": script, "args": list(args)})

    def wait(script, *args):
        for _ in range(2400):
            got = run(script, *args)
            if got:
                return got
            time.sleep(0.025)
        raise SystemExit("gave up waiting")

    try:
        call(base, "POST", s + "/url", {"url": f"http://127.0.0.1:{port}/"})
        wait("return document.querySelector('#preview svg') && document.querySelector('#form input');")
        seed = int(re.search(r"^seed = (\d+)", run("return document.getElementById('text').value;"), re.M).group(1))
        results = {"typed": [], "form": []}
        for i in range(edits):
            for way in ("typed", "form"):
                seed += 1
                run("document.getElementById('preview').dataset.latency = '';")
                if way == "typed":
                    run("const t = document.getElementById('text');"
                        "t.value = t.value.replace(/^seed = \\d+/m, 'seed = ' + arguments[0]);"
                        "t.dispatchEvent(new Event('input'));", seed)
                else:
                    run("setField('seed', arguments[0], true);", seed)
                results[way].append(int(wait("return document.getElementById('preview').dataset.latency;")))
        for way, ms in results.items():
            print(summary(f"{template} {way:5}  edits", ms))
    finally:
        try:
            call(base, "DELETE", s)
        except Exception:
            pass
        driver.terminate()
        studio.terminate()


if __name__ == "__main__":
    main()
