"""fields.xmf in Debian's ParaView (issue 16 point 5, docs/results.md): a tiny real viscoelastic
run of dlmfd-solve, opened offscreen by pvbatch with each of ParaView's XDMF readers (XDMF2 "Xdmf
Reader", Xdmf3ReaderS, Xdmf3ReaderT). Checks, per reader: the number of time steps and their
times (those of the snapshots), the bounds (the X-Y plane, z = 0, x and y not swapped), the
array names and components (velocity a 3-component vector), the block names (the same at every
time: velocity_mesh, pressure_mesh, particles), at one node its coordinates and every value, and
the disk's point, radius, angle and velocity against the snapshot read with h5py (the same doubles:
compared exactly).

Run by ctest (label paraview) as `python3 paraview_test.py`; exits 77 (skipped) only when
ParaView's pvbatch is not installed (Debian: paraview, python3-paraview; scripts/setup.sh installs
them).
"""

import json
import os
import random
import shutil
import subprocess
import tempfile
import time
import unittest

import support

PVBATCH = shutil.which("pvbatch")
if PVBATCH is None:
    print("SKIPPED: ParaView's pvbatch is not on PATH (Debian 12: apt-get install paraview "
          "python3-paraview; scripts/setup.sh installs them)")
    raise SystemExit(support.SKIP)

import h5py  # noqa: E402  (python3-h5py: with ParaView present, its absence is a failure)

READERS = ("XDMFReader", "Xdmf3ReaderS", "Xdmf3ReaderT")
NX, NY = 16, 32          # settling_scene: 1 x 2 at h = 1/16
NODE = (5, 21)           # (i, j) on the velocity mesh: x = 5/16, y = 21/16
PRESSURE_NODE = (3, 7)   # on the 2h mesh
SCALARS = ("u", "v", "trA", "A11", "A12", "A22")


class ParaViewTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="dlmfd-paraview-test-")
        cls.results = os.path.join(cls.dir, "run")
        support.run_solver(support.settling_scene(end=0.01, fields_every=0.005), cls.results)
        cls.snapshots = sorted(os.listdir(os.path.join(cls.results, "fields")))
        cls.probe()

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    @classmethod
    def probe(cls):
        """What each reader sees, from one pvbatch run."""
        out = os.path.join(cls.dir, "probe.json")
        node = NODE[1] * (NX + 1) + NODE[0]
        pressure_node = PRESSURE_NODE[1] * (NX // 2 + 1) + PRESSURE_NODE[0]
        env = dict(os.environ, OMP_NUM_THREADS="1")
        cls.pvbatch = subprocess.run([PVBATCH, "--force-offscreen-rendering",
                                  os.path.join(os.path.dirname(__file__), "paraview_probe.py"),
                                  ",".join(READERS), os.path.join(cls.results, "fields.xmf"),
                                  str(node), str(pressure_node), out],
                                 capture_output=True, text=True, env=env)
        cls.seen = None
        if cls.pvbatch.returncode == 0:
            with open(out) as f:
                cls.seen = json.load(f)

    @staticmethod
    def kind_order(reader, block):
        return ("particles" if "radius" in block["arrays"] else
                "pressure_mesh" if "p" in block["arrays"] else "velocity_mesh")

    def check_reader(self, reader):
        log = self.pvbatch.stdout + self.pvbatch.stderr
        self.assertEqual(self.pvbatch.returncode, 0, log)
        self.assertNotIn("Skipping unrecognized array type", log)
        seen = self.seen[reader]
        self.assertEqual(self.snapshots, ["snap_000000.h5", "snap_000005.h5", "snap_000010.h5"])
        self.assertEqual(len(seen["times"]), len(self.snapshots))
        for snapshot, step in zip(self.snapshots, seen["steps"]):
            with h5py.File(os.path.join(self.results, "fields", snapshot), "r") as f:
                self.assertEqual(step["time"], f.attrs["time"])
                # The same blocks at every time, in the same order: named velocity_mesh,
                # pressure_mesh, particles by the XDMF Reader (a block selected by name at t = 0
                # is there at every t); the Xdmf3 readers give them no names.
                kinds = [("particles" if "radius" in b["arrays"] else
                          "pressure_mesh" if "p" in b["arrays"] else "velocity_mesh")
                         for b in step["blocks"]]
                names = [b["name"] for b in step["blocks"]]
                self.assertEqual(sorted(kinds), ["particles", "pressure_mesh", "velocity_mesh"])
                self.assertEqual(kinds, [self.kind_order(reader, b) for b in seen["steps"][0]["blocks"]])
                self.assertEqual(names, kinds if reader == "XDMFReader" else ["", "", ""])
                by_name = dict(zip(kinds, step["blocks"]))
                velocity, pressure = by_name["velocity_mesh"], by_name["pressure_mesh"]
                particles = by_name["particles"]
                self.assertEqual(particles["points"], 1)
                self.assertEqual(particles["arrays"], {"radius": 1, "velocity": 3,
                                                       "angular_velocity": 1, "angle": 1, "id": 1,
                                                       "semi_axes": 3})
                g = f["particles"]
                self.assertEqual(particles["point"], [*g["position"][0], 0.0])
                self.assertEqual(particles["values"]["radius"], [g["radius"][0]])
                self.assertEqual(particles["values"]["angle"], [g["angle"][0]])
                # The glyph's scale of an ellipse, (a, b, 0); a disk's (R, R, 0).
                self.assertEqual(particles["values"]["semi_axes"], [*g["semi_axes"][0]])
                self.assertEqual(particles["values"]["semi_axes"], [g["radius"][0]] * 2 + [0.0])
                self.assertEqual(particles["values"]["velocity"], [*g["velocity"][0], 0.0])
                # The X-Y plane at z = 0: x over the width 1, y over the height 2.
                self.assertEqual(velocity["bounds"], [0.0, 1.0, 0.0, 2.0, 0.0, 0.0])
                self.assertEqual(pressure["bounds"], [0.0, 1.0, 0.0, 2.0, 0.0, 0.0])
                self.assertEqual(velocity["points"], (NX + 1) * (NY + 1))
                self.assertEqual(pressure["points"], (NX // 2 + 1) * (NY // 2 + 1))
                self.assertEqual(velocity["arrays"],
                                 {"velocity": 3, **{name: 1 for name in SCALARS}})
                self.assertEqual(pressure["arrays"], {"p": 1})
                i, j = NODE
                self.assertEqual(velocity["point"], [i / 16, j / 16, 0.0])
                for name in SCALARS:
                    self.assertEqual(velocity["values"][name], [f[name][j, i]], name)
                self.assertEqual(velocity["values"]["velocity"],
                                 [f["u"][j, i], f["v"][j, i], 0.0])
                pi, pj = PRESSURE_NODE
                self.assertEqual(pressure["point"], [pi / 8, pj / 8, 0.0])
                self.assertEqual(pressure["values"]["p"], [f["p"][pj, pi]])
        # The run moves: the last step's velocity at the node is not the first's (zero).
        first = seen["steps"][0]["blocks"]
        last = seen["steps"][-1]["blocks"]
        self.assertNotEqual(first, last)

    def pvbatch_under_xvfb(self, xvfb, png, out):
        """paraview_screenshot.py run by pvbatch on a display of a private Xvfb: a display
        number drawn from 100-999 that no lock file or socket claims (not the first free one,
        :0, which is where pvbatch lost its server), and -displayfd to know when it is ready."""
        number = random.choice([n for n in range(100, 1000)
                                if not os.path.exists(f"/tmp/.X{n}-lock")
                                and not os.path.exists(f"/tmp/.X11-unix/X{n}")])
        read_end, write_end = os.pipe()
        server = subprocess.Popen([xvfb, f":{number}", "-displayfd", str(write_end), "-screen", "0",
                                   "640x800x24", "-nolisten", "tcp"], pass_fds=(write_end,),
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(write_end)
        try:
            display = b""
            while not display.endswith(b"\n"):
                chunk = os.read(read_end, 16)
                self.assertTrue(chunk, "Xvfb ended before it took a display")
                display += chunk
            return subprocess.run(
                [PVBATCH, os.path.join(os.path.dirname(__file__), "paraview_screenshot.py"),
                 os.path.join(self.results, "fields.xmf"), png, out],
                capture_output=True, text=True,
                env=dict(os.environ, OMP_NUM_THREADS="1", DISPLAY=":" + display.decode().strip()))
        finally:
            os.close(read_end)
            server.terminate()
            server.wait()

    def test_screenshot_of_trA_with_the_disks(self):
        """trA with the disk as a black glyph, rendered by pvbatch under Xvfb (what a headless
        screenshot needs: scripts/setup.sh installs xvfb): the image is not blank (many colours
        of the trA map) and the pixel at the disk's centre is the glyph's black, the pixels two
        radii to its sides colours of the field."""
        xvfb = shutil.which("Xvfb")
        self.assertIsNotNone(xvfb, "Xvfb is missing (Debian: xvfb; scripts/setup.sh)")
        png = os.path.join(self.dir, "trA.png")
        out = os.path.join(self.dir, "screenshot.json")
        # A fresh Xvfb for each try says its display once it accepts connections. pvbatch still,
        # rarely, found no server there ("bad X server connection": with xvfb-run twice in CI,
        # and once in 3 here with three of these tests started together); in CI runs of
        # 2026-12-06 and 2026-12-07 three and then five tries in a row met it, each on display :0
        # (the first free one, which -displayfd alone takes), with no other X server of ours
        # beside them. So each try draws another display far from :0, and only that failure, the
        # display's and not the screenshot's, is tried again, at most four times, waiting 2, 4,
        # 6, 8 s first.
        for attempt in range(5):
            if attempt:
                time.sleep(2 * attempt)
            shot = self.pvbatch_under_xvfb(xvfb, png, out)
            if shot.returncode == 0 or "bad X server connection" not in shot.stdout + shot.stderr:
                break
        self.assertEqual(shot.returncode, 0, shot.stdout + shot.stderr)
        with open(out) as f:
            seen = json.load(f)
        import numpy  # noqa: E402
        from PIL import Image  # noqa: E402  (python3-pil: scripts/setup.sh)
        image = numpy.asarray(Image.open(png).convert("RGB"))
        self.assertEqual(image.shape[:2], (600, 300))
        colours = {tuple(c) for c in image.reshape(-1, 3)[::7]}
        self.assertGreater(len(colours), 20, "the screenshot is blank or flat")
        # The disk's centre in image rows (VTK's display y goes up) is the glyph's black, and
        # points two radii to its sides are colours of the trA field (neither black nor the
        # white background).
        x, y = seen["display"][0], image.shape[0] - 1 - seen["display"][1]
        self.assertEqual(tuple(image[int(y), int(x)]), (0, 0, 0), seen)
        for side in (-2, 2):
            beside = tuple(image[int(y), int(x + side * seen["display_radius"])])
            self.assertNotIn(beside, ((0, 0, 0), (255, 255, 255)), seen)

    def test_xdmf2_reader(self):
        self.check_reader("XDMFReader")

    def test_xdmf3_reader_s(self):
        self.check_reader("Xdmf3ReaderS")

    def test_xdmf3_reader_t(self):
        self.check_reader("Xdmf3ReaderT")


if __name__ == "__main__":
    unittest.main()
