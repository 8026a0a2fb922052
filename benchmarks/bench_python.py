#!/usr/bin/env python3
"""The Python front-end's speed , each figure beside its C++ counterpart in one run.

  crowd     model.poses for 10 000 characters at every aligned frame of the examples' set 'walks',
            against example_crowd_poses (the C++ batch call) on the same database and crowd size;
            target: Python within 1.5x of C++.
  fk        every clip of both shared CMU folders (one database) to numpy joint positions
            (Database.clip + Clip.joint_positions); target <= 2 s. The load and the FK are also
            reported apart.
  sampler   WindowSampler batches of 256 64-frame windows, float32, from the packed tier and from the
            lossless CMU ASF/AMC clips (one rig), one thread, against numpy fancy indexing of the same
            pose vectors in memory, plain and canonicalized (target: >= 50 000 windows/s, within 2x
            of canonicalized numpy).

Usage: PYTHONPATH=BUILD/python /usr/bin/python3 benchmarks/bench_python.py [BUILD=build/release] [WORK=/tmp/mocapdb-bench-python] [crowd|fk|sampler ...]
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


def rate(step, batch, seconds=3.0):
    """Windows per second of step() (one batch per call), over about `seconds` after one warm-up call."""
    step()
    done, start = 0, time.perf_counter()
    while True:
        step()
        done += batch
        elapsed = time.perf_counter() - start
        if elapsed >= seconds:
            return done / elapsed


def canonicalize(w):
    """The sampler's canonical frame on (B, L, D) pose vectors in place: each window's first root above
    the origin, turned about +Y by its heading twist psi (x, z and the root swing turned, psi shifted)."""
    yaw = w[:, 0, 4].copy()
    c, s = np.cos(yaw)[:, None], np.sin(yaw)[:, None]
    x = w[:, :, 0] - w[:, :1, 0]
    z = w[:, :, 2] - w[:, :1, 2]
    w[:, :, 0] = c * x - s * z
    w[:, :, 2] = s * x + c * z
    sx, sz = w[:, :, 3].copy(), w[:, :, 5].copy()
    w[:, :, 3] = c * sx - s * sz
    w[:, :, 5] = s * sx + c * sz
    w[:, :, 4] -= yaw[:, None]
    return w


def sampler(cmu, batch=256, length=64):
    """Random windows of the 182 ASF clips (one rig), float32, one thread, in one run: the sampler from
    the packed tier and from the lossless clips (into one preallocated batch, after each clip was decoded
    once into its cache), against numpy fancy indexing of the same clips' pose vectors held in memory as
    one float32 array, plain and with the sampler's canonicalization. Target: >= 50 000 windows/s and
    within 2x of canonicalized numpy."""
    results = {}
    with mocapdb.open(cmu) as db:
        for source in ("packed", "lossless"):
            for values in ("pose_vectors", "joint_positions"):
                s = db.sampler(length=length, batch=batch, seed=1, values=values, clips=["??_??", "???_??"], source=source)
                start = time.perf_counter()
                for name in s.clips:
                    s.window(name, 0)  # decodes the clip into the cache
                decode = time.perf_counter() - start
                out = np.empty((batch, length, s.values_per_frame), np.float32)
                results[source, values] = rate(lambda: s.next(out=out), batch)
                print(f"sampler: {source:8s} {values:15s} {results[source, values]:8.0f} windows/s, float32 ({len(s.clips)} "
                      f"clips, {s.window_count} windows, V = {s.values_per_frame}; decoding every clip first: "
                      f"{decode:.2f} s, cache {s.cache_bytes / 1e6:.1f} MB)")
        poses = [db.clip(name).pose_vectors().astype(np.float32) for name in s.clips]
    big = np.concatenate(poses)
    offsets = np.cumsum([0] + [len(p) for p in poses[:-1]])
    starts = np.concatenate([o + np.arange(len(p) - length + 1) for o, p in zip(offsets, poses)])
    rng = np.random.default_rng(1)
    frames = np.arange(length)

    def gather():
        return big[starts[rng.integers(0, len(starts), batch)][:, None] + frames]

    plain = rate(gather, batch)
    canonical = rate(lambda: canonicalize(gather()), batch)
    print(f"sampler: numpy    plain           {plain:8.0f} windows/s, float32 (fancy indexing of the pose vectors in memory)")
    print(f"sampler: numpy    canonical       {canonical:8.0f} windows/s, float32 (the same, canonicalized)")
    for source in ("packed", "lossless"):
        print(f"  {source} pose vectors / canonicalized numpy: {results[source, 'pose_vectors'] / canonical:.2f} "
              f"(target >= 0.5; >= 50 000 windows/s)")


def main():
    build = Path(sys.argv[1] if len(sys.argv) > 1 else ROOT / "build" / "release").resolve()
    work = Path(sys.argv[2] if len(sys.argv) > 2 else "/tmp/mocapdb-bench-python")
    walks, cmu = build_databases(build, work)
    print(f"machine: {os.cpu_count()} cores; {time.strftime('%Y-%m-%d')}")
    parts = sys.argv[3:] or ["crowd", "fk", "sampler"]
    if "crowd" in parts:
        crowd(build, walks)
    if "fk" in parts:
        forward_kinematics(cmu)
    if "sampler" in parts:
        sampler(cmu)


if __name__ == "__main__":
    main()
