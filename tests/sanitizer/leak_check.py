"""The leak checker reports a leak of what qmotion makes (docs/testing.md, "Leaks").

leak_check.py PROBE FOLDER clean    a STEP and an IGES write: exit 0 and no leak reported
                                    (OpenCASCADE's process-lifetime tables are not reported,
                                    and qmotion's writes leak nothing)
leak_check.py PROBE FOLDER leak     the same writes, then the probe leaks the OpenCASCADE
                                    surface qmotion made: the leak checker must fail the run
                                    and name qmotion's make_surface in a leak's stack. Since
                                    the clean run reports nothing, every leak reported here
                                    is the surface and what it owns.
"""
import os
import subprocess
import sys


def main():
    probe, folder, mode = sys.argv[1:4]
    os.makedirs(folder, exist_ok=True)
    args = [probe, folder] + (["leak"] if mode == "leak" else [])
    r = subprocess.run(args, capture_output=True, text=True, timeout=300)
    report = "LeakSanitizer: detected memory leaks" in r.stderr
    if mode == "clean":
        if r.returncode != 0 or report:
            sys.exit(f"the probe without a leak failed (exit {r.returncode}):\n{r.stderr}")
        print("no leak reported after a STEP and an IGES write")
        return
    if "leaked the surface" not in r.stdout:
        sys.exit(f"the probe did not reach its leak (exit {r.returncode}):\n{r.stderr}")
    if r.returncode == 0 or not report:
        sys.exit(f"the leaked surface was not reported (exit {r.returncode}):\n{r.stderr}")
    if "qmotion::io::detail::make_surface" not in r.stderr:
        sys.exit("a leak was reported, but no stack names make_surface:\n" + r.stderr[-4000:])
    blocks = r.stderr.count(" leak of ")
    print(f"reported: {blocks} leaked blocks, make_surface in the stacks; exit {r.returncode}")


if __name__ == "__main__":
    main()
