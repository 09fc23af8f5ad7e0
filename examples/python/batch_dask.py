"""A batch of motions on a Dask cluster (docs/library.md, "Batches on a cluster").

    python3 batch_dask.py FOLDER OUT_DIR [--workers N | --scheduler ADDRESS | --serial]
                          [--profile circle:3] [--body cutter:ball,6,20] [--tol 0.05]
                          [--fit TOL]

Every pose file (.json, .csv) and robot program (.src, .mod, .prg, .script) of FOLDER is
made into a motion on a worker: interpolated through its poses, or with --fit TOL (for dense
streams of poses) fitted within TOL and TOL degrees. The motions come back to the client pickled and go out again to the
jobs: the sweep of the profile exported as STEP and checked against the motion, and the
body's certified swept volume. One row per file goes into OUT_DIR/results.json and
results.csv; a file qmotion refuses is a row with its message, not the end of the batch.

--workers N starts a LocalCluster of N worker processes, one thread each (default 2);
--scheduler joins a running cluster (its workers need qmotion on their path); --serial runs
the same functions in this process, for comparison.
"""
import argparse
import csv
import json
import os
import sys
import time

import qmotion

POSES = (".json", ".csv")
PROGRAMS = (".src", ".mod", ".prg", ".script")
# The figures a row holds beside its file, status and message (seconds are not compared).
FIELDS = ("file", "status", "message", "kind", "segments", "degree", "step_faces",
          "relative_deviation", "volume_triangles", "distance_bound", "volume_lower",
          "volume_upper", "seconds")


def make_motion(path, fit=None):
    """The motion of one file, or the refusal's class and message."""
    try:
        if fit:
            return qmotion.fit(path, tol=fit, angle_tol=fit)[0]
        return qmotion.interpolate(path)
    except (ValueError, ArithmeticError) as e:
        return "%s: %s" % (type(e).__name__, e)


def run_jobs(path, motion, out_dir, profile, body, tol):
    """One file's row: what the export and the swept volume report."""
    row = {k: None for k in FIELDS}
    row["file"] = os.path.basename(path)
    start = time.perf_counter()
    if isinstance(motion, str):
        row.update(status="refused", message=motion)
        return row
    try:
        stem = os.path.splitext(row["file"])[0]
        step = os.path.join(out_dir, stem + ".step")
        qmotion.export(motion, step, profile=profile, tol=tol * 1e-3)
        check = qmotion.check(step, motion, profile=profile)
        volume = qmotion.swept_volume(motion, body, tol=tol)
        row.update(status="done", kind=motion.kind, segments=motion.segments,
                   degree=motion.degree, step_faces=check["faces"],
                   relative_deviation=check["relative_deviation"],
                   volume_triangles=len(volume["triangles"]),
                   distance_bound=volume["distance_bound"],
                   volume_lower=volume["volume_bounds"][0],
                   volume_upper=volume["volume_bounds"][1])
    except (ValueError, ArithmeticError) as e:
        row.update(status="refused", message="%s: %s" % (type(e).__name__, e))
    row["seconds"] = time.perf_counter() - start
    return row


def inputs(folder):
    names = sorted(f for f in os.listdir(folder) if f.lower().endswith(POSES + PROGRAMS))
    return [os.path.join(folder, f) for f in names]


def run_serial(files, fit, *job_args):
    return [run_jobs(f, make_motion(f, fit), *job_args) for f in files]


def run_on_cluster(client, files, fit, *job_args):
    # Two stages: the motions are futures that stay on the workers until a job needs them;
    # Dask moves them between worker processes by pickling when it places a job elsewhere.
    motions = client.map(make_motion, files, fit=fit, pure=False)
    rows = client.map(run_jobs, files, motions, *[[a] * len(files) for a in job_args],
                      pure=False)
    return client.gather(rows)


def write_table(rows, out_dir):
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump(rows, f, indent=1)
    with open(os.path.join(out_dir, "results.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("folder")
    p.add_argument("out_dir")
    where = p.add_mutually_exclusive_group()
    where.add_argument("--workers", type=int, default=2)
    where.add_argument("--scheduler")
    where.add_argument("--serial", action="store_true")
    p.add_argument("--profile", default="circle:3")
    p.add_argument("--body", default="cutter:ball,6,20")
    p.add_argument("--tol", type=float, default=0.05)
    p.add_argument("--fit", type=float)
    a = p.parse_args(argv)
    files = inputs(a.folder)
    if not files:
        sys.exit("batch_dask: %s holds no pose file or robot program" % a.folder)
    os.makedirs(a.out_dir, exist_ok=True)
    job_args = (os.path.abspath(a.out_dir), a.profile, a.body, a.tol)
    start = time.perf_counter()
    if a.serial:
        rows, how = run_serial(files, a.fit, *job_args), "serial"
    else:
        from dask.distributed import Client, LocalCluster
        if a.scheduler:
            client, how = Client(a.scheduler), "cluster " + a.scheduler
        else:
            cluster = LocalCluster(n_workers=a.workers, threads_per_worker=1, processes=True,
                                   dashboard_address=None)
            client, how = Client(cluster), "%d local workers" % a.workers
        with client:
            rows = run_on_cluster(client, files, a.fit, *job_args)
    write_table(rows, a.out_dir)
    done = sum(r["status"] == "done" for r in rows)
    print(json.dumps({"files": len(rows), "done": done, "refused": len(rows) - done,
                      "how": how, "seconds": time.perf_counter() - start}))


if __name__ == "__main__":
    main(sys.argv[1:])
