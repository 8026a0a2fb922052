#!/usr/bin/env python3
"""The Python front-end's speed (issue #17, acceptance 5), each figure beside its C++ counterpart in one run.

  crowd     model.poses for 10 000 characters at every aligned frame of the examples' set 'walks',
            against example_crowd_poses (the C++ batch call) on the same database and crowd size;
            target: Python within 1.5x of C++.
  fk        every clip of both shared CMU folders (one database) to numpy joint positions
            (Database.clip + Clip.joint_positions); target <= 2 s. The load and the FK are also
            reported apart.
  sampler   WindowSampler batches of 64-frame windows from the packed tier of the CMU ASF/AMC clips
            (one rig), on one thread; target >= 2 000 windows per second. Lossless source beside it.

Usage: PYTHONPATH=BUILD/python /usr/bin/python3 benchmarks/bench_python.py [BUILD=build/release] [WORK=/tmp/mocapdb-bench-python]
The databases are built once in WORK with the CLI (about a minute).
"""
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

import mocapdb

ROOT = Path(__file__).resolve().parent.parent
SHARED = ROOT.parent / "shared" / "datasets"


def run(*args):
    return subprocess.run([str(a) for a in args], check=True, capture_output=True, text=True).stdout


def build_databases(build, work):
    cli = build / "tools" / "mocapdb"
    work.mkdir(parents=True, exist_ok=True)
    walks = work / "walks.h5"
    if not walks.exists():
        run(ROOT / "examples" / "make_example_db.sh", cli, ROOT.parent / "shared", walks)
    cmu = work / "cmu.h5"
    if not cmu.exists():
        partial = work / "cmu-partial.h5"
        partial.unlink(missing_ok=True)
        run(cli, "import", SHARED / "cmu-asfamc", "-o", partial)
        run(cli, "import", SHARED / "cmu-walkrun-pfnn", "--fps", "60", "-o", partial)
        run(cli, "pack", partial, "--max-error-cm", "1")
        partial.rename(cmu)
    return walks, cmu


def crowd(build, walks, characters=10000, repeats=3):
    example = build / "examples" / "example_crowd_poses"
    cpp = []
    for _ in range(repeats):
        out = run(example, walks, "walks", characters)
        cpp.append(float(re.search(r"\(([0-9.]+) us per pose\)", out).group(1)))
    with mocapdb.open(walks) as db:
        model = db.synthesis_model("walks")
    s = model.sample_parameters
    lo, hi = s.min(axis=0), s.max(axis=0)
    c = lo + np.random.default_rng(1).random((characters, s.shape[1])) * (hi - lo)
    python = []
    for _ in range(repeats):
        start = time.perf_counter()
        for t in range(model.frames):
            model.poses(c, float(t))
        python.append(1e6 * (time.perf_counter() - start) / (characters * model.frames))
    best_cpp, best_python = min(cpp), min(python)
    print(f"crowd: {characters} characters x {model.frames} frames, {model.dofs} values per pose")
    print(f"  C++ example_crowd_poses  {best_cpp:.3f} us per pose (best of {repeats}: {', '.join(f'{x:.3f}' for x in cpp)})")
    print(f"  Python model.poses       {best_python:.3f} us per pose (best of {repeats}: {', '.join(f'{x:.3f}' for x in python)})")
    print(f"  ratio Python / C++       {best_python / best_cpp:.2f} (target <= 1.5)")


def forward_kinematics(cmu, repeats=3):
    totals, fks = [], []
    for _ in range(repeats):
        frames = joints = 0
        fk = 0.0
        start = time.perf_counter()
        with mocapdb.open(cmu) as db:
            infos = db.clips()
            for info in infos:
                clip = db.clip(info.name)
                t0 = time.perf_counter()
                xyz = clip.joint_positions()
                fk += time.perf_counter() - t0
                frames += xyz.shape[0]
                joints += xyz.shape[0] * xyz.shape[1]
        totals.append(time.perf_counter() - start)
        fks.append(fk)
    print(f"fk: {len(infos)} clips, {frames} frames, {joints} joint positions")
    print(f"  open + load + FK to numpy  {min(totals):.2f} s (best of {repeats}; target <= 2 s)")
    print(f"  of which FK                {min(fks):.2f} s ({1e9 * min(fks) / frames:.0f} ns per frame)")


def sampler(cmu, batches=40, batch=64, length=64):
    with mocapdb.open(cmu) as db:
        for source in ("packed", "lossless"):
            for values in ("pose_vectors", "joint_positions"):
                s = db.sampler(length=length, batch=batch, seed=1, values=values, clips=["??_??", "???_??"], source=source)
                s.next()  # first touches: group bytes, caches
                start = time.perf_counter()
                for _ in range(batches):
                    s.next()
                seconds = time.perf_counter() - start
                rate = batches * batch / seconds
                print(f"sampler: {source:8s} {values:15s} {rate:8.0f} windows of {length} frames per second "
                      f"({len(s.clips)} clips, {s.window_count} windows, V = {s.values_per_frame})")


def main():
    build = Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build" / "release").resolve()
    work = Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/mocapdb-bench-python")
    walks, cmu = build_databases(build, work)
    print(f"machine: {os.cpu_count()} cores; {time.strftime('%Y-%m-%d')}")
    crowd(build, walks)
    forward_kinematics(cmu)
    sampler(cmu)


if __name__ == "__main__":
    main()
