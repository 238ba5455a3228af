"""The Python package as a notebook user installs it (issue 35 point 4, docs/python.md): a fresh
venv of Debian's python3 that sees the system's packages, `pip install --no-build-isolation
--no-deps --no-index ./python` (nothing downloaded: the stubs are generated from proto/ by protoc
and grpc_python_plugin), then, from outside the source tree, the installed package: its version,
every dependency pyproject.toml declares importable, `python -m dlmfd --version`, the `dlmfd-py`
script, `dlmfd.open` on a real run, and the health verb against no daemon (exit 5, as the CLI).

Run by ctest (label python); exits 77 (skipped) only when python3-venv or pip is missing.
"""

import os
import re
import shutil
import subprocess
import sys
import tempfile
import tomllib
import unittest

import support

SOURCE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "python")

if subprocess.run([sys.executable, "-c", "import venv, ensurepip"],
                  capture_output=True).returncode != 0:
    print("SKIPPED: python3 has no venv/ensurepip (Debian: python3-venv)")
    raise SystemExit(support.SKIP)


class PackageTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="dlmfd-package-test-")
        cls.venv = os.path.join(cls.dir, "venv")
        subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", cls.venv],
                       check=True)
        cls.python = os.path.join(cls.venv, "bin", "python")
        # A copy of python/ and proto/ side by side, so the install writes nothing in the tree.
        cls.source = os.path.join(cls.dir, "src")
        shutil.copytree(SOURCE, os.path.join(cls.source, "python"),
                        ignore=shutil.ignore_patterns("build", "*.egg-info", "v1", "__pycache__"))
        shutil.copytree(os.path.join(SOURCE, "..", "proto"), os.path.join(cls.source, "proto"))
        cls.install = subprocess.run(
            [cls.python, "-m", "pip", "install", "--no-build-isolation", "--no-deps",
             "--no-index", "--disable-pip-version-check", "-q",
             os.path.join(cls.source, "python")],
            capture_output=True, text=True, cwd=cls.dir)
        cls.run_dir = os.path.join(cls.dir, "run")
        support.run_solver(support.settling_scene(), cls.run_dir)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def python_says(self, code):
        result = subprocess.run([self.python, "-c", code], capture_output=True, text=True,
                                cwd=self.dir, env=dict(os.environ, PYTHONPATH=""))
        self.assertEqual(result.returncode, 0, result.stderr)
        return result.stdout.strip()

    def test_installs_and_imports_from_the_venv(self):
        self.assertEqual(self.install.returncode, 0, self.install.stdout + self.install.stderr)
        with open(os.path.join(SOURCE, "dlmfd", "_version.py")) as f:
            version = re.search(r'__version__ = "([^"]+)"', f.read()).group(1)
        where = self.python_says("import dlmfd; print(dlmfd.__version__, dlmfd.__file__)")
        self.assertEqual(where.split()[0], version)
        self.assertIn(os.path.join("venv", "lib"), where.split()[1])
        # Every declared dependency imports in the venv.
        with open(os.path.join(SOURCE, "pyproject.toml"), "rb") as f:
            declared = tomllib.load(f)["project"]["dependencies"]
        modules = {"grpcio": "grpc", "protobuf": "google.protobuf"}
        for requirement in declared:
            name = requirement.split(">")[0].split("=")[0].split("<")[0].strip()
            self.python_says(f"import {modules.get(name, name)}")
        self.assertEqual(subprocess.run([self.python, "-m", "dlmfd", "--version"],
                                        capture_output=True, text=True).stdout.strip(), version)

    def test_reads_a_run_and_the_cli_answers(self):
        self.assertEqual(self.install.returncode, 0, self.install.stderr)
        said = self.python_says(
            f"import dlmfd; r = dlmfd.open({self.run_dir!r}); "
            "print(r.summary['status'], len(r.fields.time), r.particles.shape[0])")
        self.assertEqual(said.split()[:2], ["completed", "3"])
        script = os.path.join(self.venv, "bin", "dlmfd-py")
        health = subprocess.run([script, "--server", "127.0.0.1:1", "--timeout", "2", "health"],
                                capture_output=True, text=True)
        self.assertEqual(health.returncode, 5, health.stderr)


if __name__ == "__main__":
    unittest.main()
