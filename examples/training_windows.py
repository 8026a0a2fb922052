#!/usr/bin/env python3
"""Training data from Python: random 64-frame windows of joint positions from a database (decoded from
its packed tier when it has one), with per-value mean and standard deviation over a few batches, the
normalization a model would start from. Then, when torch is installed, a tiny next-pose model (an MLP
from one frame's pose vector to the change to the next) trained for a few hundred steps on windows from
mocapdb.torch.WindowDataset, printing its loss as it falls.

    PYTHONPATH=build/python python3 examples/training_windows.py DB.h5 [BATCHES] [STEPS]
"""
import sys
import time

import numpy as np

import mocapdb


def main():
    if len(sys.argv) not in (2, 3, 4):
        sys.exit(f"usage: {sys.argv[0]} DB.h5 [BATCHES] [STEPS]")
    batches = int(sys.argv[2]) if len(sys.argv) >= 3 else 20
    steps = int(sys.argv[3]) if len(sys.argv) == 4 else 300
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
    if not np.isfinite(stacked).all():
        return 1
    return train_next_pose(sys.argv[1], steps)


def train_next_pose(path, steps, length=32, batch=64):
    """A next-pose model: pose vector of frame t -> its change to frame t + 1, both normalized; Adam on
    batches of `batch` windows of `length` frames (B x (L - 1) frame pairs per step). Returns 0 when the
    loss fell."""
    try:
        import torch
        from mocapdb.torch import WindowDataset
    except ImportError:
        print("torch is not installed: no next-pose model (scripts/setup.sh installs python3-torch)")
        return 0
    torch.manual_seed(0)
    torch.set_num_threads(1)
    data = WindowDataset(path, length=length, seed=0, windows_per_epoch=batch * 50)
    loader = torch.utils.data.DataLoader(data, batch_size=batch, drop_last=True)
    first = next(iter(loader))
    mean, std = first.mean(dim=(0, 1)), first.std(dim=(0, 1)) + 1e-3
    delta = first[:, 1:] - first[:, :-1]
    delta_std = delta.std(dim=(0, 1)) + 1e-4
    values = first.shape[2]
    model = torch.nn.Sequential(torch.nn.Linear(values, 128), torch.nn.ReLU(), torch.nn.Linear(128, values))
    optimizer = torch.optim.Adam(model.parameters(), lr=1e-3)
    losses, step, epoch = [], 0, 0
    start = time.perf_counter()
    while step < steps:
        data.set_epoch(epoch)
        for windows in loader:
            x = (windows[:, :-1] - mean) / std
            y = (windows[:, 1:] - windows[:, :-1]) / delta_std
            loss = torch.nn.functional.mse_loss(model(x), y)
            optimizer.zero_grad()
            loss.backward()
            optimizer.step()
            losses.append(loss.item())
            if step % 100 == 0:
                print(f"step {step:4d}: loss {loss.item():.4f}")
            step += 1
            if step == steps:
                break
        epoch += 1
    seconds = time.perf_counter() - start
    before, after = np.mean(losses[:10]), np.mean(losses[-10:])
    print(f"next-pose model: loss fell from {before:.4f} to {after:.4f} over {steps} steps of {batch} windows "
          f"({seconds:.1f} s)" if after < before else f"next-pose model: loss did not fall ({before:.4f} -> {after:.4f})")
    return 0 if after < before else 1


if __name__ == "__main__":
    sys.exit(main())
