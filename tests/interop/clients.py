"""What a test of a real client does when the client is missing (docs/testing.md, "Real
clients"): fail, saying what to install and which CMake option turns the test off, or skip
(exit 77) when the build says -DQMOTION_REAL_CLIENTS=OFF."""
import os


def missing(what, install):
    """Prints why and returns the exit status: 77 under QMOTION_REAL_CLIENTS=OFF, else 1."""
    if os.environ.get("QMOTION_REAL_CLIENTS") == "OFF":
        print("%s is missing; QMOTION_REAL_CLIENTS=OFF: skipped" % what)
        return 77
    print("%s is missing: install %s (scripts/install-deps.sh --test), or configure with "
          "-DQMOTION_REAL_CLIENTS=OFF to turn this test off" % (what, install))
    return 1
