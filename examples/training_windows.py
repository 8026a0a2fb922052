#!/usr/bin/env python3
"""Training data from Python: random 64-frame windows of joint positions from a database (decoded from
its packed tier when it has one), with per-value mean and standard deviation over a few batches, the
normalization a model would start from.

    PYTHONPATH=build/python python3 examples/training_windows.py DB.h5 [BATCHES]
"""
import sys
import time

import numpy as np

import mocapdb


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(f"usage: {sys.argv[0]} DB.h5 [BATCHES]")
    batches = int(sys.argv[2]) if len(sys.argv) == 3 else 20
    with mocapdb.open(sys.argv[1]) as db:
        sampler = db.sampler(length=64, batch=32, seed=7, values="joint_positions")
        start = time.perf_counter()
        stacked = np.concatenate([next(sampler) for _ in range(batches)])  # (batches * 32, 64, 3 J)
        seconds = time.perf_counter() - start
    frames = stacked.reshape(-1, stacked.shape[2])
    mean, std = frames.mean(axis=0), frames.std(axis=0)
    source = "packed tier" if sampler.from_packed else "lossless clips"
    print(f"{stacked.shape[0]} windows of {sampler.length} frames x {sampler.values_per_frame} values from "
          f"{len(sampler.clips)} clips ({source}) in {seconds:.2f} s ({stacked.shape[0] / seconds:.0f} windows/s)")
    head = sampler.joint_names.index("head") if "head" in sampler.joint_names else len(sampler.joint_names) - 1
    print(f"joint '{sampler.joint_names[head]}': mean height {mean[3 * head + 1]:.1f} cm, sd {std[3 * head + 1]:.1f} cm")
    return 0 if np.isfinite(stacked).all() else 1


if __name__ == "__main__":
    sys.exit(main())
