#!/usr/bin/env python3
"""Behaviour held fixed: a set of qmotion commands, one per command and option family,
each run in a scratch folder; the SHA-256 of what it prints and of every file it writes is
compared with tests/golden/cli_golden.sha256.

The expected digests were taken from the build before the redesign of the module layout
(main at d0a290e), so this test shows that moving code between modules changed no byte the
program prints or writes. Volatile bytes are blanked before hashing: STEP and IGES header
dates, and the `seconds` a report gives. When a change of behaviour is intended, rerun with
--write and say why in the commit.

Usage: cli_golden.py QMOTION TEST_DATA EXAMPLES [--write]
"""
import hashlib
import os
import re
import subprocess
import sys
import tempfile

# (id, arguments). {d} is tests/data, {e} is examples; files are written into the cwd, and
# later commands read what earlier ones wrote.
COMMANDS = [
    ("demo", ["demo", "-o", "demo"]),
    ("poses", ["poses", "{e}/data/five_positions.json", "-o", "poses.json"]),
    ("poses_csv", ["poses", "{d}/good_poses.csv"]),
    ("interp_default", ["interpolate", "{e}/data/five_positions.json", "-o", "m.json"]),
    ("interp_affine_trt", ["interpolate", "{e}/data/five_positions.json", "--rotation", "affine",
                           "--translation", "trt", "-o", "affine_trt.json"]),
    ("interp_projective_minimal", ["interpolate", "{e}/data/five_positions.json", "--rotation",
                                   "projective", "--translation", "minimal", "-o", "proj.json"]),
    ("interp_param", ["interpolate", "{d}/poses/three_positions_no_t.json", "--param",
                      "chordal", "-o", "chordal.json"]),
    ("interp_bspline", ["interpolate", "{e}/data/helix_40.json", "--form", "bspline",
                        "--degree", "3", "--translation-degree", "2", "-o", "helix.json"]),
    ("interp_c1", ["interpolate", "{e}/data/helix_40.json", "--form", "c1", "-o", "c1.json"]),
    ("interp_exact", ["interpolate", "{d}/poses/rational_exact.json", "--exact", "-o",
                      "exact.json"]),
    ("qspline_kks", ["qspline", "{e}/data/five_positions.json", "--scheme", "kks", "-o",
                     "kks.json"]),
    ("qspline_quintic", ["qspline", "{e}/data/five_positions.json", "--scheme", "quintic",
                         "--tension", "0.3", "-o", "quintic.json"]),
    ("qspline_quartic", ["qspline", "{e}/data/five_positions.json", "--scheme", "quartic", "-o",
                         "quartic.json"]),
    ("info", ["info", "m.json"]),
    ("info_bspline", ["info", "helix.json"]),
    ("info_qspline", ["info", "quintic.json"]),
    ("info_exact", ["info", "exact.json", "--exact"]),
    ("eval", ["eval", "m.json", "--t", "0.5", "--point", "1,2,3"]),
    ("eval_qspline", ["eval", "kks.json", "--t", "0.6"]),
    ("traj_json", ["trajectory", "m.json", "--point", "1,2,3", "-o", "t.json"]),
    ("traj_step", ["trajectory", "helix.json", "--point", "1,0,0", "-o", "t.step"]),
    ("traj_iges_units", ["trajectory", "m.json", "--point", "0,0,0", "--units", "in", "-o",
                         "t.igs"]),
    ("traj_max_degree", ["trajectory", "proj.json", "--point", "1,1,1", "--max-degree", "3",
                         "-o", "t3.json"]),
    ("traj_qspline", ["trajectory", "quartic.json", "--point", "1,0,0", "-o", "tq.json"]),
    ("sweep_json", ["sweep", "m.json", "--profile", "circle:3", "-o", "s.json"]),
    ("sweep_step", ["sweep", "helix.json", "--profile", "segment:0,0,0:5,0,0", "-o", "s.step"]),
    ("sweep_iges", ["sweep", "m.json", "--profile", "{d}/profiles/parabola.json", "-o",
                    "s.igs"]),
    ("interp_screw", ["interpolate", "{d}/poses/screw_three.json", "-o", "screw.json"]),
    ("sweep_solid", ["sweep", "screw.json", "--profile", "circle:3", "--solid", "-o",
                     "solid.step"]),
    ("sweep_stl", ["sweep", "m.json", "--profile", "circle:2", "-o", "s.stl"]),
    ("sweep_qspline", ["sweep", "quintic.json", "--profile", "arc:2,0,90", "-o", "sq.json"]),
    ("check_step", ["check", "s.step", "--motion", "helix.json", "--profile",
                    "segment:0,0,0:5,0,0"]),
    ("check_point", ["check", "t.json", "--motion", "m.json", "--point", "1,2,3"]),
    ("check_exact", ["check", "--exact", "--motion", "exact.json"]),
    ("toolpath_apt", ["toolpath", "m.json", "--point", "0,0,0", "--chord-tol", "0.01", "-o",
                      "tp.apt"]),
    ("toolpath_csv", ["toolpath", "helix.json", "--point", "1,0,0", "--axis", "0,1,1",
                      "--chord-tol", "0.05", "--arc-length", "-o", "tp.csv"]),
    ("toolpath_ac", ["toolpath", "m.json", "--point", "0,0,0", "--chord-tol", "0.01",
                     "--rotary", "ac", "--c-hold", "-o", "tp.ngc"]),
    ("toolpath_bc_g93", ["toolpath", "helix.json", "--point", "1,0,0", "--axis", "0,1,1",
                         "--chord-tol", "0.05", "--rotary", "bc", "--feed-mode", "inverse-time",
                         "--axis-limits", "C=3600", "-o", "tpb.ngc"]),
    ("toolpath_machine", ["toolpath", "helix.json", "--point", "1,0,0", "--axis", "0,1,1",
                          "--chord-tol", "0.05", "--machine", "{d}/machines/head_table.json",
                          "-o", "tpm.ngc"]),
    ("toolpath_nurbs", ["toolpath", "m.json", "--point", "0,0,0", "--chord-tol", "0.01",
                        "--nurbs", "-o", "tpn.nc"]),
    ("render", ["render", "m.json", "--profile", "circle:2", "--point", "0,0,5", "--view",
                "front", "-o", "fig.svg"]),
    ("render_qspline", ["render", "kks.json", "--frames", "3", "-o", "figq.svg"]),
    ("plot", ["plot", "m.json", "--quantity", "curvature", "--point", "1,0,0", "--compare",
              "quartic.json", "-o", "plot.svg"]),
    ("plot_weights", ["plot", "helix.json", "--quantity", "weights", "-o", "w.svg"]),
    ("compare", ["compare", "{e}/data/five_positions.json"]),
    ("refusal", ["eval", "m.json", "--t", "7"]),
]

VOLATILE = [
    (re.compile(rb"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d[^']*"), b"<date>"),  # STEP FILE_NAME
    (re.compile(rb"\d\dH\d{8}\.\d{6}"), b"<date>"),  # IGES global section
    (re.compile(rb'"seconds": ?[-+0-9.eE]+'), b'"seconds": 0'),
]


def digest(data: bytes) -> str:
    for pattern, repl in VOLATILE:
        data = pattern.sub(repl, data)
    return hashlib.sha256(data).hexdigest()


def run_all(exe, data, examples):
    lines = []
    with tempfile.TemporaryDirectory() as tmp:
        # The inputs by relative names, so that messages naming them read the same anywhere.
        os.symlink(os.path.abspath(data), os.path.join(tmp, "data"))
        os.symlink(os.path.abspath(examples), os.path.join(tmp, "examples"))
        for cid, args in COMMANDS:
            before = set(walk(tmp))
            argv = [exe, "--quiet"] + [a.format(d="data", e="examples") for a in args]
            p = subprocess.run(argv, cwd=tmp, capture_output=True, timeout=300)
            lines.append(f"{cid} exit {p.returncode}")
            lines.append(f"{cid} stdout {digest(p.stdout)}")
            lines.append(f"{cid} stderr {digest(p.stderr)}")
            for f in sorted(set(walk(tmp)) - before):
                with open(os.path.join(tmp, f), "rb") as fh:
                    lines.append(f"{cid} {f} {digest(fh.read())}")
    return lines


def walk(root):
    for base, _, files in os.walk(root):  # the input links are not followed
        for f in files:
            yield os.path.relpath(os.path.join(base, f), root)


def main():
    exe, data, examples = sys.argv[1:4]
    here = os.path.dirname(os.path.abspath(__file__))
    expected_path = os.path.join(here, "cli_golden.sha256")
    got = run_all(exe, data, examples)
    if "--write" in sys.argv:
        with open(expected_path, "w") as fh:
            fh.write("\n".join(got) + "\n")
        print(f"wrote {len(got)} digests to {expected_path}")
        return 0
    with open(expected_path) as fh:
        expected = fh.read().split("\n")[:-1]
    if got == expected:
        print(f"{len(got)} digests of {len(COMMANDS)} commands as before")
        return 0
    exp, cur = set(expected), set(got)
    for line in expected:
        if line not in cur:
            print("expected:", line)
    for line in got:
        if line not in exp:
            print("now:     ", line)
    return 1


if __name__ == "__main__":
    sys.exit(main())
