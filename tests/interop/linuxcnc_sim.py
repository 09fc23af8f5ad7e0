#!/usr/bin/env python3
"""Interop test: LinuxCNC's own motion planner runs qmotion's 5-axis G-code, and the
joint positions it commands, mapped through LinuxCNC's table-rotary-tilting kinematics,
keep the tool tip within the chord tolerance of the exact trajectory.

Usage: linuxcnc_sim.py QMOTION DATA WORK_DIR   (DATA: the repository's tests/data)

For an A/C and a B/C table on tilt_150 (the axis tilting 20 to 60 degrees 150 mm off the
pivot) and an A/C table on near_pole (the axis passing 0.2 degrees from vertical):
1. qmotion writes the program (`--rotary`, exact path G61, a high feed so the run is short)
   and a reference: the exact trajectory as CSV points at a 1e-6 mm chord tolerance, a
   polyline certified within 1e-6 of it.
2. LinuxCNC (Debian's linuxcnc-uspace, realtime in user space) runs the program headless:
   a simulator configuration written here (trivkins with coordinates XYZAC or XYZBC: the
   machine has no tool-centre-point control, as the certificate assumes; joints looped back;
   a HAL sampler on the 1 ms servo thread), driven through linuxcncrsh; halsampler records
   every joint's commanded position each servo period.
3. Every sample is mapped to the workpiece by the forward kinematics of LinuxCNC's
   xyzac-trt-kins / xyzbc-trt-kins (the formulas of its trtfuncs.c with the rotation points
   at zero, the built-in tables' pivots), and lies within T of the reference (plus its 1e-6
   and halsampler's 6 printed decimals); the run ends at the program's last block.
Exit 0 pass, 1 fail (a missing linuxcnc fails: QMOTION_LINUXCNC names another), 77 skip
(QMOTION_REAL_CLIENTS=OFF).
"""
import math
import os
import shutil
import signal
import socket
import subprocess
import sys
import time

TOL = 0.01
LINUXCNC = "linuxcnc"  # the program, or what QMOTION_LINUXCNC names
CASES = [("tilt_150", "ac"), ("tilt_150", "bc"), ("near_pole", "ac")]

HAL = """loadrt [KINS]KINEMATICS
loadrt [EMCMOT]EMCMOT servo_period_nsec=[EMCMOT]SERVO_PERIOD num_joints=[KINS]JOINTS
loadrt sampler cfg=fffff depth=65536
addf motion-command-handler servo-thread
addf motion-controller servo-thread
addf sampler.0 servo-thread
""" + "".join(
    "net j%d joint.%d.motor-pos-cmd => joint.%d.motor-pos-fb sampler.0.pin.%d\n" % (i, i, i, i)
    for i in range(5)) + """net estop-loop iocontrol.0.user-enable-out iocontrol.0.emc-enable-in
net tool-prep-loop iocontrol.0.tool-prepare iocontrol.0.tool-prepared
net tool-change-loop iocontrol.0.tool-change iocontrol.0.tool-changed
"""


def ini_text(coords):
    """A simulator whose joints are the program's words: trivkins, limits far away."""
    text = """[EMC]
VERSION = 1.1
MACHINE = qmotion-%s
[DISPLAY]
DISPLAY = linuxcncrsh
[RS274NGC]
PARAMETER_FILE = sim.var
[EMCMOT]
EMCMOT = motmod
SERVO_PERIOD = 1000000
COMM_TIMEOUT = 1.0
[TASK]
TASK = milltask
CYCLE_TIME = 0.001
[EMCIO]
EMCIO = io
CYCLE_TIME = 0.100
TOOL_TABLE = sim.tbl
[KINS]
KINEMATICS = trivkins coordinates=%s
JOINTS = 5
[HAL]
HALFILE = sim.hal
[TRAJ]
COORDINATES = %s
LINEAR_UNITS = mm
ANGULAR_UNITS = degree
DEFAULT_LINEAR_VELOCITY = 1000
MAX_LINEAR_VELOCITY = 100000
DEFAULT_LINEAR_ACCELERATION = 1000000
MAX_LINEAR_ACCELERATION = 1000000
NO_FORCE_HOMING = 1
""" % (coords.lower(), coords, coords)
    for i, a in enumerate(coords):
        kind = "ANGULAR" if a in "ABC" else "LINEAR"
        limits = ("MIN_LIMIT = -100000\nMAX_LIMIT = 100000\nMAX_VELOCITY = 100000\n"
                  "MAX_ACCELERATION = 1000000\n")
        text += "[AXIS_%s]\n%s[JOINT_%d]\nTYPE = %s\n%sHOME_SEQUENCE = 0\n" % (
            a, limits, i, kind, limits)
    return text


def trt_forward(table, j):
    """LinuxCNC's forward kinematics (trtfuncs.c, rotation points and offsets at zero):
    joints (x, y, z, tilt, c) in mm and degrees -> the tool tip in the workpiece."""
    x, y, z, tilt, c = j
    c = math.radians(c)
    t = math.radians(tilt)
    cc, sc, ct, st = math.cos(c), math.sin(c), math.cos(t), math.sin(t)
    if table == "ac":
        return (cc * x + sc * ct * y + sc * st * z,
                -sc * x + cc * ct * y + cc * st * z,
                -st * y + ct * z)
    return (cc * ct * x + sc * y - cc * st * z,
            -sc * ct * x + cc * y + sc * st * z,
            st * x + ct * z)


def segment_distance(p, a, b):
    ab = [b[i] - a[i] for i in range(3)]
    l2 = sum(v * v for v in ab)
    s = 0.0 if l2 == 0 else max(0.0, min(1.0, sum((p[i] - a[i]) * ab[i] for i in range(3)) / l2))
    return math.sqrt(sum((p[i] - a[i] - s * ab[i]) ** 2 for i in range(3)))


class Shell:
    """linuxcncrsh, LinuxCNC's telnet-style command server."""

    def __init__(self, deadline):
        while True:
            try:
                self.sock = socket.create_connection(("localhost", 5007), timeout=5)
                break
            except OSError:
                if time.time() > deadline:
                    raise RuntimeError("linuxcncrsh did not answer on port 5007")
                time.sleep(0.5)
        self.say("hello EMC qmotion 1.0")

    def say(self, line, wait=0.15):
        self.sock.sendall((line + "\r\n").encode())
        time.sleep(wait)
        self.sock.settimeout(0.3)
        out = b""
        try:
            while True:
                d = self.sock.recv(4096)
                if not d:
                    break
                out += d
        except OSError:
            pass
        return out.decode(errors="replace")


def run_program(ngc, coords, work, env):
    """The commanded joint positions of every servo period while LinuxCNC runs ngc."""
    with open(os.path.join(work, "sim.ini"), "w") as f:
        f.write(ini_text(coords))
    with open(os.path.join(work, "sim.hal"), "w") as f:
        f.write(HAL)
    with open(os.path.join(work, "sim.tbl"), "w") as f:
        f.write("T1 P1 Z0 D0\n")
    open(os.path.join(work, "sim.var"), "w").close()
    log = open(os.path.join(work, "linuxcnc.log"), "w")
    proc = subprocess.Popen([LINUXCNC, "sim.ini"], cwd=work, env=env, stdout=log,
                            stderr=subprocess.STDOUT, start_new_session=True)
    samples_path = os.path.join(work, "samples.txt")
    sampler = None
    try:
        sh = Shell(time.time() + 90)
        for line in ("set enable EMCTOO", "set estop off", "set machine on", "set mode auto",
                     "set open " + os.path.abspath(ngc)):
            sh.say(line)
        sampler = subprocess.Popen(["halsampler", "-c", "0"], env=env,
                                   stdout=open(samples_path, "w"), stderr=subprocess.STDOUT)
        time.sleep(0.3)
        sh.say("set run")
        start = time.time()
        status = ""
        while time.time() - start < 120:
            status = sh.say("get program_status", 0.1)
            if "IDLE" in status and time.time() - start > 0.5:
                break
        error = sh.say("get error")
        time.sleep(0.3)
        sampler.terminate()
        sampler.wait(10)
        sh.say("set machine off")
        sh.say("shutdown", 1.0)
        if "IDLE" not in status or "ERROR OK" not in error:
            raise RuntimeError("the program did not run to its end: %s %s" % (status, error))
    finally:
        if sampler and sampler.poll() is None:
            sampler.kill()
        try:
            proc.wait(60)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            subprocess.run(["halrun", "-U"], env=env, stdout=subprocess.DEVNULL,
                           stderr=subprocess.DEVNULL)
    rows = []
    with open(samples_path) as f:
        for line in f:
            v = line.split()
            if len(v) == 5:
                rows.append([float(x) for x in v])
    return rows


def check_case(qmotion, data, work, poses, table, env):
    motion = os.path.join(work, poses + ".json")
    subprocess.run([qmotion, "interpolate", os.path.join(data, "poses", poses + ".json"),
                    "--form", "bspline", "-o", motion], check=True, stdout=subprocess.DEVNULL)
    ngc = os.path.join(work, "%s_%s.ngc" % (poses, table))
    subprocess.run([qmotion, "toolpath", motion, "--point", "0,0,0", "--chord-tol", str(TOL),
                    "--rotary", table, "--feed", "60000", "-o", ngc], check=True,
                   stdout=subprocess.DEVNULL)
    ref_csv = os.path.join(work, poses + "_exact.csv")
    subprocess.run([qmotion, "toolpath", motion, "--point", "0,0,0", "--chord-tol", "1e-6",
                    "-o", ref_csv], check=True, stdout=subprocess.DEVNULL)
    with open(ref_csv) as f:
        ref = [tuple(float(x) for x in line.split(",")[1:4]) for line in f.readlines()[1:]]
    words = []
    with open(ngc) as f:
        for line in f:
            if line.startswith(("G0 ", "G1 ")):
                words.append({w[0]: float(w[1:]) for w in line.split()[1:]})
    tilt = "A" if table == "ac" else "B"
    start = [words[0][k] for k in ("X", "Y", "Z", tilt, "C")]
    end = [words[-1][k] for k in ("X", "Y", "Z", tilt, "C")]
    case_dir = os.path.join(work, "%s_%s" % (poses, table))
    os.makedirs(case_dir, exist_ok=True)
    # A dwell after the rapid move (the only change to qmotion's program) stops the machine
    # at the first block, so that the samples show where cutting starts.
    run_ngc = os.path.join(case_dir, "run.ngc")
    with open(ngc) as f, open(run_ngc, "w") as out:
        for line in f:
            out.write(line)
            if line.startswith("G0 "):
                out.write("G4 P0.05\n")
    rows = run_program(run_ngc, "XYZ%sC" % tilt, case_dir, env)
    # The rapid move to the first block is not cut: start at the first sample there.
    first = next((i for i, r in enumerate(rows)
                  if max(abs(r[k] - start[k]) for k in range(5)) < 1e-5), None)
    if first is None:
        print("FAIL %s %s: LinuxCNC never reached the first block" % (poses, table))
        return False
    reached_end = max(abs(rows[-1][k] - end[k]) for k in range(5)) < 1e-5
    # The tip moves along the trajectory: search the reference near the last match.
    worst, at, j = 0.0, 0, 0
    for n, r in enumerate(rows[first:]):
        p = trt_forward(table, r)
        lo, hi = max(0, j - 20), min(len(ref) - 1, j + 400)
        best, best_k = math.inf, j
        for k in range(lo, hi):
            d = segment_distance(p, ref[k], ref[k + 1])
            if d < best:
                best, best_k = d, k
        j = best_k
        if best > worst:
            worst, at = best, n
    printing = 5e-7 * math.sqrt(3) + 2 * 250 * math.radians(5e-7)
    ok = reached_end and worst <= TOL + 1e-6 + printing
    print("%s %s %s: %d servo periods sampled, %d blocks, tip within %.4f T of the exact "
          "trajectory (worst at sample %d)%s" % (
              "ok" if ok else "FAIL", poses, table, len(rows) - first, len(words) - 1,
              worst / TOL, at, "" if reached_end else "; the run stopped before the end"))
    return ok


def main():
    qmotion, data, work = sys.argv[1:4]
    if os.environ.get("QMOTION_REAL_CLIENTS") == "OFF":
        print("skipped: configured with -DQMOTION_REAL_CLIENTS=OFF, so LinuxCNC is not run")
        return 77
    global LINUXCNC
    LINUXCNC = os.environ.get("QMOTION_LINUXCNC") or shutil.which("linuxcnc") or "linuxcnc"
    for exe in (LINUXCNC, "halsampler", "halrun"):
        if not shutil.which(exe):
            print("FAIL: %s not found: LinuxCNC is required (install linuxcnc-uspace: "
                  "scripts/install-deps.sh --test), or configure with "
                  "-DQMOTION_REAL_CLIENTS=OFF" % exe)
            return 1
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    env = dict(os.environ)
    env.pop("DISPLAY", None)
    if os.geteuid() == 0:  # LinuxCNC's rtapi_app refuses root without a fallback user
        env["RTAPI_UID"] = "65534"
    fifo_dir = os.path.join(work, "rtapi")  # the fallback user binds its socket here
    os.makedirs(fifo_dir)
    os.chmod(fifo_dir, 0o1777)
    env["RTAPI_FIFO_PATH"] = os.path.join(fifo_dir, "fifo")
    ok = True
    for poses, table in CASES:
        ok = check_case(qmotion, data, work, poses, table, env) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
