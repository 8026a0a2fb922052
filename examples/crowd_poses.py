#!/usr/bin/env python3
"""A crowd from Python: N characters at random control parameters inside a set's parameter box, posed at
every aligned frame with one batched call per frame, then as joint positions for the first character.

    PYTHONPATH=build/python python3 examples/crowd_poses.py DB.h5 SET [N]
"""
import sys
import time

import numpy as np

import mocapdb


def main():
    if len(sys.argv) not in (3, 4):
        sys.exit(f"usage: {sys.argv[0]} DB.h5 SET [N]")
    path, set_name = sys.argv[1], sys.argv[2]
    n = int(sys.argv[3]) if len(sys.argv) == 4 else 1000
    with mocapdb.open(path) as db:
        model = db.synthesis_model(set_name)
    samples = model.sample_parameters
    lo, hi = samples.min(axis=0), samples.max(axis=0)
    crowd = lo + np.random.default_rng(1).random((n, samples.shape[1])) * (hi - lo)

    start = time.perf_counter()
    poses = np.stack([model.poses(crowd, float(t)) for t in range(model.frames)])  # (T, N, D)
    seconds = time.perf_counter() - start
    rho = model.reliability(crowd)
    print(f"set {set_name}: {n} characters x {model.frames} aligned frames = {poses.shape[0] * poses.shape[1]} poses "
          f"of {model.dofs} values in {seconds:.3f} s ({1e6 * seconds / (n * model.frames):.2f} us per pose)")
    print(f"mean root height {poses[:, :, 1].mean():.1f} cm; reliability {rho.min():.2f} .. {rho.max():.2f}")

    # The first character's poses as joint positions: pose vectors -> channels -> forward kinematics.
    skeleton = model.skeleton
    clip = mocapdb.Clip(skeleton, skeleton.channels_from_pose_vectors(poses[:, 0, :]), model.frame_rate)
    xyz = clip.joint_positions()
    print(f"character 0: {xyz.shape[1]} joints, travels {np.linalg.norm(xyz[-1, 0] - xyz[0, 0]):.1f} cm "
          f"over the aligned frames")
    return 0 if np.isfinite(poses).all() else 1


if __name__ == "__main__":
    sys.exit(main())
