"""dlmfd.open and dlmfd.table on real runs of dlmfd-solve (issue 35 points 1, 3 and 4): the files
describe themselves (units, descriptions, coordinates, the scene, a format version), the fields
come as an xarray Dataset with coordinates and the disk at each snapshot's own time when the
field and particle output rates do not line up, the particles as a long-form DataFrame, the
diagnostics with numeric columns, a local table of runs, and errors that name what is missing.

Run by ctest (label python) with Debian's python3; exits 77 (skipped) only when h5py, numpy,
pandas or xarray is missing.
"""

import os
import shutil
import tempfile
import unittest

import support

support.skip_unless_importable("grpc", "google.protobuf", "h5py", "numpy", "pandas", "xarray")

import h5py  # noqa: E402
import numpy as np  # noqa: E402

import dlmfd  # noqa: E402

# A disk held at velocity (0, -10): its centre is y = 1.6 - 10 t exactly.
SCENE = ("title = \"prescribed disk\"\n"
         "[domain]\nsize = [1.0, 2.0]\nh = 0.0625\n"
         "[fluid]\ndensity = 1.0\nviscosity = 0.1\nrelaxation_time = 0.5\n"
         "solvent_ratio = 0.5\ngravity = [0.0, 0.0]\n"
         "[time]\ndt = 0.002\nend = 0.08\n"
         "[particle_mesh]\nh = 0.08571428571428572\n"
         "[[particles]]\ncenter = [0.5, 1.6]\ndiameter = 0.25\ndensity = 1.1\n"
         "velocity = [0.0, -10.0]\nangular_velocity = 3.0\nmotion = \"prescribed\"\n"
         "[output]\nfields_every = 0.06\nparticles_every = 0.04\ncheckpoint_every = 0.0\n")


class RunReaderTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="dlmfd-run-reader-test-")
        cls.results = os.path.join(cls.dir, "run")
        support.run_solver(SCENE, cls.results)
        cls.other = os.path.join(cls.dir, "other")
        support.run_solver(SCENE.replace("viscosity = 0.1", "viscosity = 0.2"), cls.other)

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def test_files_describe_themselves(self):
        snapshot = os.path.join(self.results, "fields", "snap_000030.h5")
        with h5py.File(snapshot, "r") as f:
            self.assertEqual(f.attrs["format_version"], 2)
            self.assertEqual(f.attrs["format"], "dlmfd field snapshot")  # a str, not bytes
            self.assertIn("[domain]", f["scene"][()].decode())
            for name in ("x", "y", "x_pressure", "y_pressure", "u", "v", "velocity", "p", "trA",
                         "A11", "A12", "A22"):
                self.assertIn("units", f[name].attrs, name)
                self.assertGreater(len(f[name].attrs["description"]), 10, name)
            self.assertEqual(f["u"].attrs["units"], "L T-1")
            self.assertEqual(f["u"].attrs["dimensions"], "y x")
            np.testing.assert_array_equal(f["x"][()], 0.0625 * np.arange(17))
            np.testing.assert_array_equal(f["y_pressure"][()], 0.125 * np.arange(17))
            g = f["particles"]
            for name in g:
                self.assertIn("units", g[name].attrs, name)
            self.assertAlmostEqual(g["position"][0, 1], 1.6 - 10 * 0.06, places=12)
            self.assertAlmostEqual(g["angle"][0], 3.0 * 0.06, places=12)
        with h5py.File(os.path.join(self.results, "particles.h5"), "r") as f:
            self.assertEqual(f.attrs["format_version"], 2)
            for name in ("time", "step", "position", "velocity", "angular_velocity", "angle",
                         "force", "torque", "id", "radius"):
                self.assertIn("units", f[name].attrs, name)
            self.assertEqual(f["force"].attrs["units"], "M T-2")

    def test_fields_carry_coordinates_units_and_the_disk_at_their_time(self):
        run = dlmfd.open(self.results)
        fields = run.fields
        self.assertEqual(list(fields.time.values), [0.0, 0.06])
        self.assertEqual(fields["u"].dims, ("time", "y", "x"))
        self.assertEqual(fields["p"].dims, ("time", "y_pressure", "x_pressure"))
        self.assertEqual(fields["u"].attrs["units"], "L T-1")
        self.assertEqual(float(fields.x[16]), 1.0)
        # The disk at t = 0.06, though particles.h5 has records at 0, 0.04 and 0.08 only.
        self.assertAlmostEqual(float(fields["particle_y"].sel(time=0.06)[0]), 1.0, places=12)
        self.assertAlmostEqual(float(fields["particle_angle"].sel(time=0.06)[0]), 0.18,
                               places=12)
        self.assertEqual(fields.attrs["particles_source"], "the snapshot's own step")
        # Selection by coordinates, as xarray users expect.
        value = float(fields["trA"].sel(time=0.06, x=0.5, y=0.5))
        with h5py.File(os.path.join(self.results, "fields", "snap_000030.h5"), "r") as f:
            self.assertEqual(value, f["trA"][8, 8])
        self.assertIn("[fluid]", run.snapshot(-1).attrs["scene"])

    def test_summary_scene_diagnostics_particles(self):
        run = dlmfd.open(self.results)
        self.assertEqual(run.summary["status"], "completed")
        self.assertEqual(run.scene["time"]["dt"], 0.002)
        self.assertEqual(run.diagnostics["step"].iloc[-1], 40)
        numeric = run.diagnostics.select_dtypes(include="number").columns
        self.assertEqual(len(numeric), len(run.diagnostics.columns))
        particles = run.particles
        self.assertEqual(list(particles.columns),
                         ["time", "step", "particle", "radius", "x", "y", "u", "v", "omega",
                          "angle", "fx", "fy", "torque"])
        self.assertEqual(list(particles["time"]), [0.0, 0.04, 0.08])
        np.testing.assert_allclose(particles["y"], 1.6 - 10 * particles["time"], atol=1e-12)
        np.testing.assert_allclose(particles["angle"], 3.0 * particles["time"], atol=1e-12)
        self.assertEqual(particles.attrs["units"]["fx"], "M T-2")

    def test_a_format_1_snapshot_interpolates_the_disk_and_says_so(self):
        old = os.path.join(self.dir, "old")
        shutil.copytree(self.results, old)
        with h5py.File(os.path.join(old, "fields", "snap_000030.h5"), "a") as f:
            del f["particles"]
            del f.attrs["format_version"]
        fields = dlmfd.open(old).fields
        self.assertAlmostEqual(float(fields["particle_y"].sel(time=0.06)[0]), 1.0, places=12)
        self.assertIn("interpolated linearly", fields.attrs["particles_source"])

    def test_a_newer_format_is_refused_by_name(self):
        new = os.path.join(self.dir, "new")
        shutil.copytree(self.results, new)
        with h5py.File(os.path.join(new, "fields", "snap_000000.h5"), "a") as f:
            f.attrs["format_version"] = 99
        with self.assertRaisesRegex(dlmfd.FormatError, "version 99"):
            dlmfd.open(new).fields

    def test_local_table_needs_no_daemon(self):
        table = dlmfd.table([self.results, self.other])
        self.assertEqual(list(table["dir"]), [self.results, self.other])
        self.assertEqual(list(table["fluid.viscosity"]), [0.1, 0.2])
        self.assertNotIn("fluid.density", table.columns)  # the same in both
        self.assertEqual(list(table["status"]), ["completed", "completed"])
        self.assertEqual(table["p0.radius"].dtype.kind, "f")
        self.assertEqual(table["steps"].dtype.kind, "i")
        self.assertEqual(table["min_gap"].dtype.kind, "f")  # one particle: NaN, not object

    def test_errors_name_what_is_missing(self):
        missing = os.path.join(self.dir, "no-such-run")
        with self.assertRaisesRegex(FileNotFoundError, "no-such-run"):
            dlmfd.open(missing)
        with self.assertRaisesRegex(FileNotFoundError, "no-such-run"):
            list(dlmfd.read_snapshots(missing))
        with self.assertRaisesRegex(FileNotFoundError, "no-such-run"):
            dlmfd.read_particles(missing)
        empty = os.path.join(self.dir, "empty")
        os.makedirs(empty, exist_ok=True)
        with self.assertRaisesRegex(FileNotFoundError, "not a results directory"):
            dlmfd.open(empty)
        with self.assertRaisesRegex(FileNotFoundError, "missing.toml"):
            dlmfd.scene_input.scene_text("runs/missing.toml")


if __name__ == "__main__":
    unittest.main()
