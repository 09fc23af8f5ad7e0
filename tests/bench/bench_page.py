#!/usr/bin/env python3
"""Generates docs/benchmarks.md from one run of the benchmark programs.

Runs every Google Benchmark program of tests/bench (built with QMOTION_BUILD_BENCHMARKS)
in one session, one after the other, with --benchmark_format=json, and writes a page with
the date, the machine, the compiler, the build type and the commit it measured, a table per
program, the peak memory of each command against its largest file at 10^4 poses
(tests/bench/memory.sh, raw figures), and the ratios of qmotion against the peers it is
measured beside (OpenCASCADE's fitting and evaluation, nlohmann-json's tree, a plain
ofstream) from that same run, the viewer's figures in headless Chromium
(viewer_bench.py), and the Dask batch example serial and on local clusters (batch_bench.py). The page is never edited by hand: run this script again.

Usage: bench_page.py --build BUILD [--out docs/benchmarks.md] [--min-time 0.2]
                     [--programs bench_sweep,bench_io,...] [--viewer-runs N]
"""
import argparse
import datetime
import json
import os
import platform
import re
import subprocess
import sys

PROGRAMS = ["bench_kernel", "bench_interpolation", "bench_spline", "bench_qspline",
            "bench_sweep", "bench_toolpath", "bench_io", "bench_fit", "bench_keyframes",
            "bench_volume", "bench_verify"]

# (qmotion's benchmark, the peer beside it, what both do); matched argument for argument.
PEERS = [
    ("BM_Degree16x2SurfaceBuildOnly", "BM_Peer_OcctFitDegree16x2Surface",
     "degree 16 x 2 sweep surface: exact build vs OpenCASCADE's fit to a grid of exact points"),
    ("BM_GridOurs/0", "BM_Peer_GridOcctD0",
     "surface evaluation on a grid: qmotion's batched evaluator vs Geom_BSplineSurface::D0"),
    ("BM_ReadMotion", "BM_ReadMotionNlohmann",
     "reading a motion file: qmotion's reader vs an nlohmann-json tree"),
    ("BM_WriteMotion", "BM_WriteMotionTree",
     "writing a motion file: qmotion's streamed text vs an nlohmann-json tree"),
    ("BM_WriteMotion", "BM_OfstreamSameBytes",
     "writing a motion file: qmotion vs an ofstream writing the same bytes"),
    ("BM_FitPoses", "BM_Peer_InterpolateAll",
     "a dense noisy pose stream: fit within the tolerances vs a B-spline through every pose"),
    ("BM_MachineToolpath", "BM_WorkpieceToolpath",
     "G-code on a table A/C machine, certified for its own interpolation, vs 3-axis G-code "
     "certified on the workpiece alone (tilt_150)"),
    ("BM_Keyframes", "BM_UniformKeyframes",
     "glTF keyframes within a certified tolerance: the greedy placement vs finding the fewest "
     "uniform keys that hold the same certificate (the tables below give both key counts)"),
    ("BM_WriteTrajectoryJson", "BM_OfstreamSameTrajectoryBytes",
     "writing a trajectory: qmotion vs an ofstream writing the same bytes"),
    ("BM_CircleSweep2000/1/1", "BM_Peer_OcctWriteCircleSweep2000/1",
     "a 2000-pose circle sweep to STEP: qmotion (build, default self-intersection check, "
     "write) vs OpenCASCADE's writer alone on the same shell of C1 faces, sewn"),
    ("BM_CircleSweep2000/1/0", "BM_Peer_OcctWriteCircleSweep2000/1",
     "the same without qmotion's check, vs the same shell"),
    ("BM_CircleSweep2000/1/1", "BM_Peer_OcctWriteCircleSweep2000/0",
     "the same sweep to STEP vs OpenCASCADE's writer alone on the surface as one face, C0 "
     "across the circle's arcs (its fewest bytes)"),
]


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def machine():
    model = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            m = re.search(r"model name\s*:\s*(.*)", f.read())
            if m:
                model = m.group(1).strip()
    except OSError:
        pass
    mem = ""
    try:
        with open("/proc/meminfo") as f:
            kb = int(re.search(r"MemTotal:\s*(\d+)", f.read()).group(1))
            mem = ", %.0f GiB" % (kb / 2 ** 20)
    except (OSError, AttributeError):
        pass
    return "%s, %d cores%s, %s" % (model, os.cpu_count(), mem, platform.platform())


def cache_value(build, key):
    try:
        with open(os.path.join(build, "CMakeCache.txt")) as f:
            m = re.search(r"^%s:[A-Z]+=(.*)$" % re.escape(key), f.read(), re.M)
            return m.group(1) if m else ""
    except OSError:
        return ""


def compiler(build):
    cxx = cache_value(build, "CMAKE_CXX_COMPILER")
    try:
        return run([cxx, "--version"]).stdout.splitlines()[0]
    except (OSError, IndexError):
        return cxx


def fmt_time(ns):
    for unit, k in (("s", 1e9), ("ms", 1e6), ("us", 1e3)):
        if ns >= k:
            return "%.3g %s" % (ns / k, unit)
    return "%.3g ns" % ns


def to_ns(b):
    k = {"ns": 1, "us": 1e3, "ms": 1e6, "s": 1e9}[b.get("time_unit", "ns")]
    return b["real_time"] * k, b["cpu_time"] * k


def counters(b):
    skip = {"name", "run_name", "run_type", "repetitions", "repetition_index", "threads",
            "iterations", "real_time", "cpu_time", "time_unit", "family_index",
            "per_family_instance_index", "aggregate_name", "aggregate_unit", "label",
            "error_occurred", "error_message"}
    out = []
    for k, v in b.items():
        if k not in skip and isinstance(v, (int, float)):
            out.append("%s %.4g" % (k, v))
    if b.get("label"):
        out.insert(0, b["label"])
    return ", ".join(out)


VERIFY_PEERS_TEXT = (
    "`tests/bench/verify_peers`: `qmotion verify` against what a CAM programmer has without "
    "it. Gouges: the ball stamped at N instants of every block, its depth at each stamp exact "
    "(its radius less its centre's signed distance to the part), the peer at its best; a "
    "voxel grid of the 100 x 100 mm part at T would hold about 10^8 voxels. Stock left: "
    "OpenVDB's in-process stock, the stock's level set less the ball's at N stamps spread "
    "evenly along the program (`csgDifference`), sampled trilinearly at 400 x 400 points of "
    "the part's top. Holder collisions: FCL's `continuousCollide` of a cylinder and a box "
    "with each of its solvers and motions, each run in a child process (two of its modes can "
    "stop on an assertion inside its GJK); the truth is worked out apart from both programs "
    "(the distance from the holder's axis to the stock's rectangle is convex along a straight "
    "move). Late is worse than early: a contact reported late by d mm lets the holder in by "
    "up to d mm first.")


def peer_tables(a, build, name):
    """The Markdown tables a peer program prints (its one short case under
    --volume-peer-smoke)."""
    print("running %s ..." % name, file=sys.stderr)
    if cache_value(a.build, "QMOTION_WITH_CGAL") == "OFF":
        return "Not measured: this build has no CGAL (-DQMOTION_WITH_CGAL=OFF)."
    exe = os.path.join(build, "tests", "bench", name)
    if not os.path.exists(exe):
        sys.exit("%s: not built (it needs libopenvdb-dev and libfcl-dev)" % exe)
    r = run([exe] + (["--smoke"] if a.volume_peer_smoke else []), cwd=a.build)
    if r.returncode != 0:
        sys.exit("%s failed:\n%s" % (name, r.stderr))
    return r.stdout.strip()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", required=True)
    ap.add_argument("--out", default="docs/benchmarks.md")
    ap.add_argument("--min-time", default="0.2")
    ap.add_argument("--programs", default=",".join(PROGRAMS))
    ap.add_argument("--viewer-runs", default="31")
    ap.add_argument("--volume-peer-smoke", action="store_true",
                    help="run the peer programs' short cases and a two-file batch only (CTest)")
    a = ap.parse_args()
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    commit = run(["git", "rev-parse", "--short=12", "HEAD"], cwd=root).stdout.strip()
    dirty = run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=root).stdout
    results = {}
    for prog in a.programs.split(","):
        exe = os.path.abspath(os.path.join(a.build, "tests", "bench", prog))
        if not os.path.exists(exe):
            sys.exit("%s: not built (configure with -DQMOTION_BUILD_BENCHMARKS=ON)" % exe)
        print("running %s ..." % prog, file=sys.stderr)
        r = run([exe, "--benchmark_format=json", "--benchmark_min_time=%s" % a.min_time],
                cwd=a.build)
        if r.returncode != 0:
            sys.exit("%s failed:\n%s" % (prog, r.stderr))
        results[prog] = json.loads(r.stdout)
    print("running memory.sh ...", file=sys.stderr)
    mem = run(["bash", os.path.join(root, "tests", "bench", "memory.sh"),
               os.path.join(os.path.abspath(a.build), "qmotion"), "10000"])
    if mem.returncode != 0:
        sys.exit("memory.sh failed:\n%s" % mem.stderr)
    print("running viewer_bench.py ...", file=sys.stderr)
    build = os.path.abspath(a.build)
    if cache_value(a.build, "QMOTION_VIEWER") == "OFF":
        viewer = "Not measured: this build has no viewer (-DQMOTION_VIEWER=OFF)."
    else:
        v = run([sys.executable, os.path.join(root, "tests", "bench", "viewer_bench.py"),
                 os.path.join(build, "qmotion"), build, os.path.join(build, "tests", "bench", "viewer"),
                 "--runs", a.viewer_runs])
        if v.returncode != 0:
            sys.exit("viewer_bench.py failed:\n%s%s" % (v.stdout, v.stderr))
        viewer = v.stdout.strip()
    volume_peer = peer_tables(a, build, "openvdb_peer")
    verify_peer = peer_tables(a, build, "verify_peers")
    print("running batch_bench.py ...", file=sys.stderr)
    batch = run([sys.executable, os.path.join(root, "tests", "bench", "batch_bench.py"), build]
                + (["--smoke"] if a.volume_peer_smoke else []))
    if batch.returncode != 0:
        sys.exit("batch_bench.py failed:\n%s" % batch.stderr)
    first = next(iter(results.values()))["context"]
    lines = ["# Benchmarks", "",
             "Generated by `tests/bench/bench_page.py --build %s` in one session; do not edit: "
             "run it again. Peers run in the same programs as qmotion, so their ratios come "
             "from one machine in one run." % os.path.basename(os.path.abspath(a.build)), "",
             "| | |", "| --- | --- |",
             "| date | %s |" % datetime.datetime.now(datetime.timezone.utc).strftime(
                 "%Y-%m-%d %H:%M UTC"),
             "| commit | `%s`%s |" % (commit, " (with uncommitted changes)" if dirty else ""),
             "| machine | %s |" % machine(),
             "| compiler | %s, %s build |" % (compiler(a.build),
                                             cache_value(a.build, "CMAKE_BUILD_TYPE")),
             "| benchmark library | %s build, min time %s s per benchmark |" %
             (first.get("library_build_type", "?"), a.min_time), ""]
    by_name = {}
    for prog, res in results.items():
        for b in res["benchmarks"]:
            if b.get("run_type") != "aggregate":
                by_name[b["name"]] = b
    lines += ["## qmotion against its peers", "",
              "| what | qmotion | peer | peer / qmotion |", "| --- | --- | --- | --- |"]
    for ours, peer, what in PEERS:
        for name, b in sorted(by_name.items()):
            if name != ours and not name.startswith(ours + "/"):
                continue
            suffix = name[len(ours):]
            p = by_name.get(peer + suffix) or by_name.get(peer)
            if not p:
                continue
            t0, t1 = to_ns(b)[0], to_ns(p)[0]
            lines.append("| %s (`%s` vs `%s`) | %s | %s | %.2f |" %
                         (what, name, p["name"], fmt_time(t0), fmt_time(t1), t1 / t0))
    lines.append("")
    lines += ["## Peak memory against the largest file", "",
              "`tests/bench/memory.sh` at 10^4 poses: peak resident memory (GNU `time -v`) of "
              "each command against the largest file it reads or writes, raw. The target is 3x "
              "for `info`, `eval` and `trajectory` and `sweep` to JSON (CTest's "
              "`bench.memory_target` holds it); each STEP row is followed by OpenCASCADE's "
              "writer alone on the same geometry, the floor of a STEP file written through it.",
              "", mem.stdout.strip(), ""]
    lines += ["## Swept volumes against OpenVDB stamping", "",
              "`tests/bench/openvdb_peer`: qmotion's certified enclosing mesh (`volume`) "
              "against the body stamped at N + 1 even times and unioned by OpenVDB "
              "(`meshToLevelSet`, `csgUnion`, `volumeToMesh`) with voxel size T, the route a "
              "user takes today. Both are asked about one sample of 20 000 points of the true "
              "swept volume (on and inside the body at random times): a missed point lies "
              "outside the result (qmotion's mesh by CGAL's `Side_of_triangle_mesh`, the "
              "level set by its own trilinear sign, which also gives how far outside). The "
              "vertex distance is the largest distance to the swept volume over at most 4 000 "
              "vertices (an upper bound: the body placed at the best time found).",
              "", volume_peer, ""]
    lines += ["## Verification against stamping, OpenVDB and FCL", "", VERIFY_PEERS_TEXT, "",
              verify_peer, ""]
    lines += ["## Batches on a Dask cluster", "",
              "`tests/bench/batch_bench.py`: `examples/python/batch_dask.py` over the 10 pose "
              "files of `tests/data/poses` (interpolate, export the sweep of `circle:3` as "
              "STEP and check it, the swept volume of `cutter:flat,6,20` at T = 0.2), in this "
              "process and on `LocalCluster`s of one-threaded worker processes; a cluster's "
              "time includes starting it. The mesher is itself parallel (TBB), so the serial "
              "run already uses both cores for part of its time.", "", batch.stdout.strip(), ""]
    lines += ["## The viewer in headless Chromium", "",
              "`tests/bench/viewer_bench.py`: the kernel's WebAssembly module, and the page of "
              "`qmotion view` for 100 poses on a helix (a cubic B-spline motion, 99 segments) "
              "with a rectangle profile, in Debian's Chromium (SwiftShader, no GPU). The timed "
              "work is what editing a pose does: interpolate in the page, then evaluate both "
              "trajectories and the four exact sweep surfaces on their grids and build the "
              "three.js geometry. `bench.viewer_budget` holds the budgets.", "", viewer, ""]
    for prog, res in results.items():
        lines += ["## %s" % prog, "", "| benchmark | real | CPU | iterations | counters |",
                  "| --- | --- | --- | --- | --- |"]
        for b in res["benchmarks"]:
            if b.get("run_type") == "aggregate":  # a complexity fit over the arguments
                if "big_o" in b:
                    what = "fit O(%s), %s per unit of N" % (b["big_o"],
                                                           fmt_time(b["real_coefficient"]))
                else:
                    what = "%s %.3g" % (b.get("aggregate_name", ""), b.get("rms", 0))
                lines.append("| `%s` | | | | %s |" % (b["name"], what))
                continue
            real, cpu = to_ns(b)
            lines.append("| `%s` | %s | %s | %d | %s |" % (b["name"], fmt_time(real),
                                                            fmt_time(cpu), b["iterations"],
                                                            counters(b).replace("|", "\\|")))
        lines.append("")
    with open(a.out, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))
    print("wrote %s" % a.out, file=sys.stderr)


if __name__ == "__main__":
    main()
