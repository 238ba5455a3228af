"""The Python client (python/dlmfd, docs/python.md) against a real dlmfdd on loopback running the
real dlmfd-solve on a tiny scene: submit, watch to the end, fetch, read particles.h5 and the
snapshots; a study of two points and its table; errors as Python exceptions naming the field.

Run by ctest (label python) as `python3 client_test.py`; exits 77 (skipped) when python3-grpcio,
python3-protobuf, python3-h5py or python3-numpy is missing.
"""

import importlib.util
import json
import os
import tempfile
import unittest

import support

support.skip_unless_importable("grpc", "google.protobuf", "h5py", "numpy")

import numpy as np  # noqa: E402

import dlmfd  # noqa: E402


class ClientTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.daemon = support.Daemon()
        cls.client = dlmfd.Client(cls.daemon.address, token=support.Daemon.TOKEN)

    @classmethod
    def tearDownClass(cls):
        cls.client.close()
        reports = cls.daemon.stop()
        if reports:
            raise AssertionError("the daemon reported a sanitizer error:\n" + reports)

    def test_submit_watch_fetch_and_read_results(self):
        job = self.client.submit(support.settling_scene(), {"time.end": 0.01}, name="settling",
                                 tags=["python"], time_limit_seconds=3600)
        self.assertIn(job.state, (dlmfd.jobs_pb2.QUEUED, dlmfd.jobs_pb2.RUNNING))
        self.assertEqual(list(job.overrides), ["time.end=0.01"])
        self.assertEqual(job.time_limit_seconds, 3600)

        events = list(self.client.watch(job.id))
        kinds = [e.WhichOneof("event") for e in events]
        self.assertEqual(kinds[0], "state")  # the current state comes first
        self.assertIn("progress", kinds)
        self.assertIn("particles", kinds)
        self.assertEqual(events[-1].state.state, dlmfd.jobs_pb2.COMPLETED, events[-1])
        seqs = [e.seq for e in events if e.seq > 0]
        self.assertEqual(seqs, sorted(seqs))
        self.assertEqual(dlmfd.state_name(self.client.job(job.id).state), "COMPLETED")
        self.assertIn(job.id, [j.id for j in self.client.jobs(tag="python")])

        with tempfile.TemporaryDirectory() as out:
            self.client.fetch(job.id, out)
            names = {f.path for f in self.client.files(job.id)}
            for name in ("summary.json", "particles.h5", "fields.xmf", "scene.toml"):
                self.assertIn(name, names)
                self.assertTrue(os.path.isfile(os.path.join(out, name)), name)
            self.assertFalse([n for n in os.listdir(out) if n.endswith(".part")])
            # job.json: the job as `dlmfd fetch` records it, for the captions of `dlmfd plot DIR`.
            with open(os.path.join(out, "job.json")) as f:
                recorded = json.load(f)
            self.assertEqual(recorded["id"], job.id)
            self.assertEqual(recorded["state"], "COMPLETED")
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            self.assertEqual(summary["status"], "completed")

            # particles.h5: the initial record, then one every 0.002 up to t = 0.01.
            p = dlmfd.read_particles(out)
            np.testing.assert_allclose(p.time, [0.0, 0.002, 0.004, 0.006, 0.008, 0.01],
                                       rtol=0, atol=1e-12)
            self.assertEqual(p.position.shape, (6, 1, 2))
            self.assertEqual(p.radius.tolist(), [0.125])
            np.testing.assert_array_equal(p.position[0, 0], [0.5, 1.5])
            # The last record is the run's end, as summary.json and the last particles event say,
            # to the bit (each writes the same doubles).
            last_event = [e for e in events if e.WhichOneof("event") == "particles"][-1].particles
            self.assertEqual(p.position[-1, 0].tolist(), summary["particles"][0]["position"])
            self.assertEqual(p.position[-1, 0].tolist(),
                             [last_event.particles[0].x, last_event.particles[0].y])
            self.assertLess(p.velocity[-1, 0, 1], 0.0)  # a denser disk falls

            # Snapshots at steps 0, 5, 10 (fields_every 0.005, dt 0.001).
            snaps = list(dlmfd.read_snapshots(out))
            self.assertEqual([s.step for s in snaps], [0, 5, 10])
            last = snaps[-1]
            self.assertEqual(last["u"].shape, (33, 17))
            self.assertEqual(last["p"].shape, (17, 9))
            self.assertEqual(last["velocity"].shape, (33, 17, 3))
            np.testing.assert_array_equal(last["velocity"][..., 0], last["u"])
            np.testing.assert_array_equal(last["velocity"][..., 1], last["v"])
            np.testing.assert_array_equal(last["trA"], last["A11"] + last["A22"])
            np.testing.assert_allclose(last.x, np.linspace(0.0, 1.0, 17), rtol=0, atol=1e-15)
            np.testing.assert_allclose(last.y, np.linspace(0.0, 2.0, 33), rtol=0, atol=1e-15)

        self.assertEqual(self.client.read(job.id, "scene.toml").decode().count("[[particles]]"), 1)

    def test_study_of_two_points_and_its_table(self):
        study_id, jobs = self.client.submit_study(support.settling_scene(),
                                           {"fluid.relaxation_time": [0.2, 0.5]},
                                           overrides={"time.end": 0.004}, name="lambda",
                                           labels={"project": "py"}, max_running=1)
        self.assertTrue(study_id)
        self.assertEqual(len(jobs), 2)
        self.assertEqual({j.study_id for j in jobs}, {study_id})
        self.assertEqual(self.client.study(study_id).max_running, 1)
        self.assertIn(study_id, [s.id for s in self.client.studies()])
        finished = [self.client.wait(j.id) for j in jobs]
        self.assertEqual([dlmfd.state_name(j.state) for j in finished], ["COMPLETED"] * 2)
        found = self.client.jobs(labels={"project": "py"}, where={"fluid.relaxation_time": 0.5})
        self.assertEqual([j.id for j in found], [jobs[1].id])
        found = self.client.jobs(study_id=study_id, where=["fluid.relaxation_time<0.3"])
        self.assertEqual([j.id for j in found], [jobs[0].id])

        rows = self.client.table(study_id=study_id, frame=False)
        self.assertEqual([r["job"] for r in rows], [j.id for j in jobs])
        self.assertEqual([r["fluid.relaxation_time"] for r in rows], [0.2, 0.5])
        for row in rows:
            self.assertEqual(row["state"], "COMPLETED")
            self.assertEqual(row["status"], "completed")
            self.assertEqual(row["time.end"], 0.004)
            self.assertEqual(row["steps"], 4)
            self.assertIsNone(row["min_gap"])  # one particle: no pair
            summary = json.loads(self.client.read(row["job"], "summary.json"))
            self.assertEqual([row["p0.x"], row["p0.y"]], summary["particles"][0]["position"])
            self.assertEqual(row["p0.radius"], 0.125)
        self.assertEqual(self.client.table(jobs=[jobs[1].id], frame=False), rows[1:])
        if importlib.util.find_spec("pandas") is not None:
            frame = self.client.table(study_id=study_id)
            self.assertEqual(len(frame), 2)
            self.assertEqual(list(frame["fluid.relaxation_time"]), [0.2, 0.5])

        retried = self.client.retry([jobs[0].id], overrides={"time.end": 0.006})
        self.assertEqual([(j.id, j.attempt) for j in retried], [(jobs[0].id, 2)])
        self.client.wait(jobs[0].id)
        again = self.client.table(study_id=study_id, frame=False)
        self.assertEqual((again[0]["time.end"], again[0]["steps"]), (0.006, 6))

    def test_zipped_axes_and_a_range(self):
        study_id, jobs = self.client.submit_study(
            support.settling_scene(), {"time.dt": dlmfd.Range(1e-3, 2e-3, 2)},
            zip={"fluid.relaxation_time": [0.2, 0.5], "particles.*.density": [1.1, 1.2]},
            overrides={"time.end": 0.002, "output.fields_every": 0}, name="zip")
        self.assertEqual(len(jobs), 4)  # 2 time steps x 2 zipped points
        self.assertEqual(jobs[1].name, "zip[time.dt=0.001,fluid.relaxation_time=0.5,"
                                       "particles.*.density=1.2]")
        self.client.cancel_study(study_id)

    def test_every_verb_of_the_cli(self):
        """health, inputs, logs, priority, hold, release, a study's fetch and delete (the CLI's
        verbs beyond submit, watch, fetch and table)."""
        self.assertEqual(self.client.health(), "SERVING")
        with dlmfd.Client(self.daemon.address, token="") as anonymous:
            self.assertEqual(anonymous.health(), "SERVING")  # needs no token
        # Two points that run one at a time: the second waits, queued, while the first runs.
        study_id, jobs = self.client.submit_study(support.settling_scene(end=1.0, fields_every=0.5),
                                           {"fluid.relaxation_time": [0.2, 0.5]},
                                           name="verbs", max_running=1)
        waiting = jobs[1]
        held = self.client.hold(waiting.id)
        self.assertTrue(held.held)
        self.assertEqual(self.client.set_priority(waiting.id, 7).priority, 7)
        self.assertFalse(self.client.release(waiting.id).held)
        inputs = self.client.inputs(jobs[0].id)
        self.assertEqual(list(inputs.overrides), ["fluid.relaxation_time=0.2"])
        self.assertIn("[[particles]]", inputs.scene)
        finished = [self.client.wait(j.id) for j in jobs]
        self.assertEqual([dlmfd.state_name(j.state) for j in finished], ["COMPLETED"] * 2)
        self.assertIn("relaxation_time = 0.2", self.client.inputs(jobs[0].id).scene_as_run)
        log = self.client.logs(jobs[0].id)
        self.assertIn("step", log)
        with tempfile.TemporaryDirectory() as out:
            fetched = self.client.fetch_study(study_id, out, paths=["summary.json"])
            folders = sorted(os.path.basename(str(p)) for p in fetched)
            self.assertEqual(folders, ["fluid.relaxation_time=0.2", "fluid.relaxation_time=0.5"])
            for folder in fetched:
                self.assertTrue(os.path.exists(os.path.join(folder, "summary.json")))
                self.assertTrue(os.path.exists(os.path.join(folder, "job.json")))
        deleted, freed = self.client.delete(study_id=study_id)
        self.assertEqual(sorted(deleted), sorted(j.id for j in jobs))
        self.assertGreater(freed, 0)
        with self.assertRaises(dlmfd.NotFound):
            self.client.job(jobs[0].id)

    def test_a_job_after_another(self):
        """afterok: the second stage starts once the first COMPLETED; after a cancelled job the
        daemon refuses (FailedPrecondition). Then the runs' accounting and the usage."""
        first = self.client.submit(support.settling_scene(), {"time.end": 0.004}, name="stage1")
        second = self.client.submit(support.settling_scene(), {"time.end": 0.002},
                                    name="stage2", after=[first])
        self.assertEqual(list(second.after), [first.id])
        done = [self.client.wait(j.id) for j in (first, second)]
        self.assertEqual([dlmfd.state_name(j.state) for j in done], ["COMPLETED"] * 2)
        self.assertGreaterEqual(done[1].started_time, done[0].finished_time)
        blocker = self.client.submit(support.settling_scene(end=50.0), name="blocker")
        self.client.cancel(blocker.id)
        self.client.wait(blocker.id)
        with self.assertRaises(dlmfd.FailedPrecondition) as refused:
            self.client.submit(support.settling_scene(), after=blocker.id)
        self.assertIn("after: job " + blocker.id, str(refused.exception))
        # The accounting of a run (wait4's rusage of the solver) and the caller's usage.
        self.assertEqual(done[0].exit_code, 0)
        self.assertTrue(done[0].HasField("exit_code"))
        self.assertGreater(done[0].cpu_seconds, 0)
        self.assertGreater(done[0].peak_memory_bytes, 0)
        usage = self.client.usage()
        self.assertGreaterEqual(usage.completed, 2)
        self.assertGreaterEqual(usage.cancelled, 1)
        self.assertGreater(usage.disk_bytes, 0)

    def test_errors_are_exceptions_naming_the_field(self):
        with self.assertRaises(dlmfd.InvalidArgument) as bad_value:
            self.client.submit(support.settling_scene(), ["fluid.viscosity=-1"])
        self.assertEqual(bad_value.exception.key, "fluid.viscosity")
        self.assertEqual(float(bad_value.exception.value), -1.0)
        self.assertIn(">", bad_value.exception.allowed)
        self.assertIn("fluid.viscosity", str(bad_value.exception))

        with self.assertRaises(dlmfd.InvalidArgument) as unknown_key:
            self.client.submit(support.settling_scene().replace("viscosity", "viscosty"))
        self.assertIn("fluid.viscosty", str(unknown_key.exception))

        with self.assertRaises(dlmfd.InvalidArgument) as bad_point:
            self.client.submit_study(support.settling_scene(), {"fluid.solvent_ratio": [0.5, 2.0]})
        self.assertIn("fluid.solvent_ratio", str(bad_point.exception))

        with self.assertRaises(dlmfd.NotFound):
            self.client.job("no-such-job")
        with dlmfd.Client(self.daemon.address, token="") as anonymous:
            with self.assertRaises(dlmfd.Unauthenticated):
                anonymous.jobs()


if __name__ == "__main__":
    unittest.main()
