"""A slider move of `mocapdb serve`'s set explorer, end to end over HTTP: GET /api/synth (kriging at new
parameters from the stored model, the motion's FK, the binary reply) for a set with 3 parameters, timed
from the request to the last byte received, as the page asks for it.

  /usr/bin/python3 benchmarks/bench_serve.py BUILD_DIR [--requests 200] [--shared ../shared]

The set: subject 16's walks and runs (cmu-asfamc 16_*) cut into 2 s windows (window:240:120 at 120 Hz),
parameters displacement (dx, dz) and speed measured on each window, aligned to 60 frames, compressed to
1 cm. Prints the build's steps, then the reply time (median, p95, max) and bytes per reply."""
import argparse
import json
import random
import re
import statistics
import subprocess
import tempfile
import time
import urllib.request
from pathlib import Path


def run(cli, *args):
    return subprocess.run([str(cli), *map(str, args)], capture_output=True, text=True, check=True).stdout


def main():
    p = argparse.ArgumentParser()
    p.add_argument("build")
    p.add_argument("--requests", type=int, default=200)
    p.add_argument("--shared", default=str(Path(__file__).resolve().parents[2] / "shared"))
    a = p.parse_args()
    cli = Path(a.build) / "tools" / "mocapdb"
    with tempfile.TemporaryDirectory() as tmp:
        db = Path(tmp) / "walks.h5"
        source = Path(a.shared) / "datasets" / "cmu-asfamc"
        run(cli, "import", *sorted(source.glob("16_*.amc")), "-o", db)
        made = json.loads(run(cli, "set", "create", db, "--name", "windows", "--clips", "16_*", "--segment",
                              "window:240:120", "--extract", "displacement", "speed", "--json"))
        run(cli, "align", db, "--set", "windows", "--frames", "60")
        run(cli, "compress", db, "--set", "windows", "--max-error-cm", "1")
        samples = made["samples"] if isinstance(made.get("samples"), int) else len(made.get("samples", []))
        server = subprocess.Popen([str(cli), "serve", str(db), "--port", "0"], stdout=subprocess.PIPE, text=True)
        try:
            url = re.search(r"http://\S+/", server.stdout.readline()).group(0)
            sets = json.loads(urllib.request.urlopen(url + "api/sets").read())["sets"][0]
            boxes = [(q["min"], q["max"]) for q in sets["parameters"]]
            rng = random.Random(1)
            urllib.request.urlopen(url + "api/synth?set=windows&c=" + ",".join(str((lo + hi) / 2) for lo, hi in boxes)).read()
            times, sizes, durations = [], [], []
            for _ in range(a.requests):
                c = ",".join(repr(rng.uniform(lo, hi)) for lo, hi in boxes)
                t = time.perf_counter()
                body = urllib.request.urlopen(url + "api/synth?set=windows&c=" + c).read()
                times.append(1e3 * (time.perf_counter() - t))
                sizes.append(len(body))
                n = int.from_bytes(body[:4], "little")
                durations.append(json.loads(body[4:4 + n])["duration_s"])
        finally:
            server.send_signal(2)
            server.wait(timeout=30)
        times.sort()
        print(f"set: {samples} samples, parameters {[q['name'] for q in sets['parameters']]}")
        print(f"motion duration s: median {statistics.median(durations):.2f} (min {min(durations):.2f}, max {max(durations):.2f})")
        print(f"reply ms over {a.requests} slider moves: median {statistics.median(times):.1f}, "
              f"p95 {times[int(0.95 * len(times)) - 1]:.1f}, max {times[-1]:.1f}; bytes per reply {statistics.median(sizes):.0f}")


if __name__ == "__main__":
    main()
