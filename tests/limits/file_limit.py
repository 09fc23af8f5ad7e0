#!/usr/bin/env python3
"""tests/limits/file_limit.py: every file qmotion writes, qmotion reads back, at the real limit.

    file_limit.py QMOTION WORKDIR

On the largest pose file qmotion reads (10^5 poses, a helix), a circle swept along the
interpolated motion is a JSON file just under the limit of 512 MiB: `check` reads it back and
finds it exact. A profile with more poles makes a file over the limit: `sweep` refuses it
(exit 2) with the message `poses` gives for reading a file over the limit at the same path,
and leaves no file. docs/geometry.md, "Limits". The read-back's peak memory (GNU time) is at
most 3x the file.
"""
import json
import math
import os
import shutil
import subprocess
import sys

LIMIT = 512 << 20


def run(*args):
    return subprocess.run(args, capture_output=True, text=True, check=False)


def fail(msg):
    print("file_limit: " + msg)
    sys.exit(1)


def main():
    exe, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    poses_path = os.path.join(work, "poses.json")
    n = 100000
    poses = []
    for i in range(n):
        a = 20 * math.pi * i / (n - 1)
        h, r = (a + math.pi / 2) / 2, 0.1 * math.sin(3 * a) / 2
        q = [math.cos(h) * math.cos(r), math.cos(h) * math.sin(r),
             math.sin(h) * math.sin(r), math.sin(h) * math.cos(r)]
        poses.append({"t": i / (n - 1),
                      "position": [50 * math.cos(a), 50 * math.sin(a), 50 * a / (2 * math.pi)],
                      "rotation": {"quaternion": q}})
    with open(poses_path, "w") as f:
        json.dump({"units": "mm", "poses": poses}, f)
    motion = os.path.join(work, "motion.json")
    p = run(exe, "interpolate", poses_path, "-o", motion)
    if p.returncode != 0:
        fail("interpolate failed: " + p.stderr)

    # At the limit: written, then read back and found exact.
    near = os.path.join(work, "circle.json")
    p = run(exe, "sweep", motion, "--profile", "circle:5", "-o", near)
    if p.returncode != 0:
        fail("the circle sweep failed: " + p.stderr)
    size = os.path.getsize(near)
    print(f"circle sweep: {size} bytes, {size / LIMIT:.3f} of the limit")
    if not 0.9 * LIMIT < size <= LIMIT:
        fail(f"expected a file within 10% under the limit {LIMIT}, got {size} bytes")
    rss = os.path.join(work, "check_rss.txt")
    p = run("/usr/bin/time", "-f", "%M", "-o", rss, exe, "check", "--motion", motion,
            "--profile", "circle:5", near)
    if p.returncode != 0:
        fail("check could not read qmotion's own file back: " + p.stderr)
    with open(rss) as f:
        peak = int(f.read().split()[-1]) * 1024
    print(f"read back: peak RSS {peak / 2**20:.0f} MiB, {peak / size:.2f} x the file")
    if peak > 3 * size:  # issue 56: the read-back at most 3x the file
        fail(f"reading the file back peaked at {peak} bytes, over 3 x its {size}")
    dev = json.loads(p.stdout)["max_deviation"]
    print(f"read back: max deviation {dev:.3g} mm")
    if not dev < 1e-9:
        fail(f"the file read back deviates by {dev} mm")
    os.remove(near)

    # Over the limit: the reader's message, exit 2, nothing left.
    over = os.path.join(work, "polyline.json")
    with open(over, "wb") as f:
        f.truncate(LIMIT + 1)
    p = run(exe, "poses", over)
    os.remove(over)
    read_msg = p.stderr.strip()
    if p.returncode != 2 or over not in read_msg:
        fail(f"reading a file over the limit: exit {p.returncode}, {read_msg!r}")
    polyline = "polyline:" + ":".join(f"{k},0,{k % 2}" for k in range(10))
    p = run(exe, "sweep", motion, "--profile", polyline, "-o", over)
    print(f"polyline sweep: exit {p.returncode}, {p.stderr.strip()!r}")
    if p.returncode != 2:
        fail(f"a sweep over the limit exited {p.returncode}, expected 2")
    if p.stderr.strip() != read_msg:
        fail(f"the writer's message {p.stderr.strip()!r} is not the reader's {read_msg!r}")
    if any(x.startswith("polyline") for x in os.listdir(work)):
        fail("a file was left behind: " + ", ".join(os.listdir(work)))
    shutil.rmtree(work)
    print("file_limit: ok")


if __name__ == "__main__":
    main()
