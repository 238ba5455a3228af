"""Test support for the Python tests (ctest labels python and paraview): the binaries of this build,
a tiny scene, a real dlmfd-solve run and a real dlmfdd on a free loopback port.

The build tree comes from $DLMFD_BINARY_DIR (ctest sets it); the solver from $DLMFD_SOLVER_BINARY
when set, as for the C++ server tests (tests/server/support/daemon_process.h).
"""

import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
import time

BINARY_DIR = os.environ.get("DLMFD_BINARY_DIR", "build")
SOLVER = os.environ.get("DLMFD_SOLVER_BINARY") or os.path.join(BINARY_DIR, "solver", "dlmfd-solve")
DAEMON = os.path.join(BINARY_DIR, "server", "dlmfdd")
SKIP = 77  # ctest's SKIP_RETURN_CODE for these tests


def _importable(module):
    try:
        return importlib.util.find_spec(module) is not None
    except ModuleNotFoundError:  # a missing parent package ("google" of google.protobuf)
        return False


def skip_unless_importable(*modules):
    """Exits with SKIP and names the Debian package when a module is missing."""
    missing = [m for m in modules if not _importable(m)]
    if missing:
        packages = {"grpc": "python3-grpcio", "google.protobuf": "python3-protobuf",
                    "h5py": "python3-h5py", "numpy": "python3-numpy"}
        names = ", ".join(packages.get(m, m) for m in missing)
        print(f"SKIPPED: {sys.executable} cannot import {', '.join(missing)} (Debian: {names}; "
              "scripts/setup.sh installs them)")
        sys.exit(SKIP)


def settling_scene(end=0.01, relaxation_time=0.5, fields_every=0.005):
    """One disk (diameter 0.25) settling in a closed 1 x 2 box of 16 x 32 cells; Oldroyd-B unless
    relaxation_time is 0. Ten steps of 1e-3 by default: a few tenths of a second of solver time."""
    return ("title = \"python test\"\n"
            "[domain]\nsize = [1.0, 2.0]\nh = 0.0625\n"
            f"[fluid]\ndensity = 1.0\nviscosity = 0.1\nrelaxation_time = {relaxation_time}\n"
            "solvent_ratio = 0.5\ngravity = [0.0, -981.0]\n"
            f"[time]\ndt = 0.001\nend = {end}\n"
            "[particle_mesh]\nh = 0.08571428571428572\n"
            "[[particles]]\ncenter = [0.5, 1.5]\ndiameter = 0.25\ndensity = 1.1\n"
            f"[output]\nfields_every = {fields_every}\nparticles_every = 0.002\n"
            "checkpoint_every = 0.0\n")


def run_solver(scene, out_dir):
    """Runs dlmfd-solve on the scene text into out_dir; raises on a non-zero exit."""
    scene_path = out_dir + ".toml"
    with open(scene_path, "w") as f:
        f.write(scene)
    env = dict(os.environ, OMP_NUM_THREADS="1")
    subprocess.run([SOLVER, scene_path, "--out", out_dir, "--threads", "1", "--quiet"], check=True,
                   env=env)


class Daemon:
    """A real dlmfdd on 127.0.0.1 with a fresh data directory and a tokens file (one user)."""

    TOKEN = "python-test-token-0123456789"

    def __init__(self):
        self.dir = tempfile.mkdtemp(prefix="dlmfd-python-test-")
        self.tokens = os.path.join(self.dir, "tokens")
        with open(self.tokens, "w") as f:
            f.write(f"{self.TOKEN} alice\n")
        os.chmod(self.tokens, 0o600)
        port_file = os.path.join(self.dir, "port")
        self.log = open(os.path.join(self.dir, "daemon.log"), "w")
        self.process = subprocess.Popen(
            [DAEMON, "--listen", "127.0.0.1:0", "--data-dir", os.path.join(self.dir, "data"),
             "--port-file", port_file, "--solver", SOLVER, "--tokens-file", self.tokens,
             "--solver-threads", "1"],
            stdout=self.log, stderr=subprocess.STDOUT)
        while True:  # no limit on the start: the test has ctest's timeout
            if self.process.poll() is not None:
                raise RuntimeError(f"dlmfdd exited with {self.process.returncode}: "
                                   f"{self.log_text()}")
            if os.path.exists(port_file):
                with open(port_file) as f:
                    text = f.read().strip()
                if text.isdigit() and int(text) > 0:
                    self.address = f"127.0.0.1:{text}"
                    return
            time.sleep(0.02)

    def log_text(self):
        self.log.flush()
        with open(self.log.name) as f:
            return f.read()

    def stop(self):
        """Stops the daemon; returns the sanitizer reports of its log ("" when none), as the C++
        server tests check them (tests/server/support/daemon_process.cc)."""
        self.process.terminate()
        self.process.wait()
        log = self.log_text()
        self.log.close()
        shutil.rmtree(self.dir, ignore_errors=True)
        markers = ("WARNING: ThreadSanitizer", "ERROR: AddressSanitizer", "runtime error:")
        return log if any(m in log for m in markers) else ""
