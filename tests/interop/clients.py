"""What a test of a real client does when the client is missing (docs/testing.md, "Real
clients"): fail, saying what to install and which CMake option turns the test off, or skip
(exit 77) when the build says -DQMOTION_REAL_CLIENTS=OFF."""
import os
import shutil


def missing(what, install):
    """Prints why and returns the exit status: 77 under QMOTION_REAL_CLIENTS=OFF, else 1."""
    if os.environ.get("QMOTION_REAL_CLIENTS") == "OFF":
        print("%s is missing; QMOTION_REAL_CLIENTS=OFF: skipped" % what)
        return 77
    print("%s is missing: install %s (scripts/install-deps.sh --test), or configure with "
          "-DQMOTION_REAL_CLIENTS=OFF to turn this test off" % (what, install))
    return 1


def freecad():
    """FreeCAD's freecadcmd (QMOTION_FREECADCMD names another), or the exit status when it
    is missing or the build turned real clients off (an int)."""
    if os.environ.get("QMOTION_REAL_CLIENTS") == "OFF":
        print("skipped: configured with -DQMOTION_REAL_CLIENTS=OFF, so FreeCAD is not run")
        return 77
    exe = os.environ.get("QMOTION_FREECADCMD") or shutil.which("freecadcmd")
    if not exe or not os.path.exists(exe):
        return missing("freecadcmd (FreeCAD)", "freecad-python3")
    return exe
