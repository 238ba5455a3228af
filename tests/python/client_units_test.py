"""The Python client's own logic, without a daemon: scene and override input, TOML values, the
parts of an InvalidArgument message, and table rows from a Job and a summary.

Run by ctest (label python) as `python3 client_units_test.py`; exits 77 (skipped) when
python3-grpcio or python3-protobuf is missing.
"""

import os
import pathlib
import tempfile
import unittest

import support

support.skip_unless_importable("grpc", "google.protobuf", "h5py", "numpy")

import grpc  # noqa: E402

from dlmfd import errors, scene_input, table  # noqa: E402
from dlmfd.v1 import jobs_pb2  # noqa: E402


class SceneInputTest(unittest.TestCase):

    def test_toml_values_of_python_values(self):
        self.assertEqual(scene_input.toml_value(True), "true")
        self.assertEqual(scene_input.toml_value(False), "false")
        self.assertEqual(scene_input.toml_value(3), "3")
        self.assertEqual(scene_input.toml_value(1 / 32), "0.03125")
        self.assertEqual(scene_input.toml_value(1e-5), "1e-05")
        self.assertEqual(scene_input.toml_value([0.0, -981.0]), "[0.0, -981.0]")
        self.assertEqual(scene_input.toml_value('"wave"'), '"wave"')
        with self.assertRaises(TypeError):
            scene_input.toml_value(object())

    def test_overrides_from_a_dict_or_a_list(self):
        self.assertEqual(scene_input.override_texts(None), [])
        self.assertEqual(scene_input.override_texts({"time.end": 0.5, "fluid.gravity": [0, -1]}),
                         ["time.end=0.5", "fluid.gravity=[0, -1]"])
        self.assertEqual(scene_input.override_texts(["a.b=1"]), ["a.b=1"])
        with self.assertRaises(TypeError):
            scene_input.override_texts("a.b=1")  # a str would be split into characters

    def test_scene_from_text_or_path(self):
        text = "[time]\ndt = 0.01\n"
        self.assertEqual(scene_input.scene_text(text), text)
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "s.toml")
            with open(path, "w") as f:
                f.write(text)
            self.assertEqual(scene_input.scene_text(path), text)
            self.assertEqual(scene_input.scene_text(pathlib.Path(path)), text)
        self.assertEqual(scene_input.scene_text('title = "one line"'), 'title = "one line"')
        with self.assertRaises(TypeError):
            scene_input.scene_text(b"[time]")


class FakeRpcError(grpc.RpcError):
    def __init__(self, code, details):
        self._code, self._details = code, details

    def code(self):
        return self._code

    def details(self):
        return self._details


class ErrorsTest(unittest.TestCase):

    def test_invalid_argument_names_key_value_and_allowed(self):
        e = errors.from_rpc_error(FakeRpcError(
            grpc.StatusCode.INVALID_ARGUMENT,
            "fluid.viscosity = -1 is not allowed: expected a number > 0"), "Submit")
        self.assertIsInstance(e, errors.InvalidArgument)
        self.assertEqual((e.key, e.value, e.allowed), ("fluid.viscosity", "-1", "a number > 0"))
        self.assertEqual(str(e), "Submit: invalid argument: fluid.viscosity = -1 is not allowed: "
                                 "expected a number > 0")

    def test_other_messages_keep_their_text(self):
        e = errors.from_rpc_error(FakeRpcError(grpc.StatusCode.INVALID_ARGUMENT,
                                               "override \"x\" has no '='"))
        self.assertIsNone(e.key)
        self.assertIn("no '='", e.message)

    def test_classes_by_status_code(self):
        cases = {grpc.StatusCode.NOT_FOUND: errors.NotFound,
                 grpc.StatusCode.UNAUTHENTICATED: errors.Unauthenticated,
                 grpc.StatusCode.PERMISSION_DENIED: errors.Unauthenticated,
                 grpc.StatusCode.RESOURCE_EXHAUSTED: errors.ResourceExhausted,
                 grpc.StatusCode.ALREADY_EXISTS: errors.FailedPrecondition,
                 grpc.StatusCode.UNAVAILABLE: errors.Unavailable,
                 grpc.StatusCode.INTERNAL: errors.DlmfdError}
        for code, cls in cases.items():
            e = errors.from_rpc_error(FakeRpcError(code, "m"))
            self.assertIs(type(e), cls, code)
            self.assertEqual(e.code, code)


class TableTest(unittest.TestCase):

    def test_row_of_job_overrides_and_summary(self):
        job = jobs_pb2.Job(id="j1", name="s[fluid.relaxation_time=1.4]", state=jobs_pb2.COMPLETED,
                           sweep_id="s1", step=10, overrides=["fluid.relaxation_time=1.4",
                                                              "splitting.advection=\"wave\"",
                                                              "odd=not toml"])
        summary = {"status": "completed", "steps": 10, "wall_seconds": 0.5, "ms_per_step": 50.0,
                   "particles": [{"id": 0, "position": [0.5, 1.25], "velocity": [0.0, -0.5],
                                  "angular_velocity": 0.25, "force": [0.125, 2.0],
                                  "torque": -0.5}]}
        row = table.job_row(job, summary)
        self.assertEqual(row["state"], "COMPLETED")
        self.assertEqual(row["fluid.relaxation_time"], 1.4)
        self.assertEqual(row["splitting.advection"], "wave")
        self.assertEqual(row["odd"], "not toml")
        self.assertEqual((row["particles.0.x"], row["particles.0.y"]), (0.5, 1.25))
        self.assertEqual((row["particles.0.u"], row["particles.0.v"]), (0.0, -0.5))
        self.assertEqual((row["particles.0.fx"], row["particles.0.fy"]), (0.125, 2.0))
        self.assertEqual(row["particles.0.angular_velocity"], 0.25)
        self.assertEqual(row["particles.0.torque"], -0.5)
        self.assertEqual(row["ms_per_step"], 50.0)
        self.assertNotIn("status", table.job_row(job))  # no summary: no summary columns

    def test_list_of_dicts_unless_a_frame_is_asked_for(self):
        rows = [{"a": 1}]
        self.assertIs(table.as_table(rows, frame=False), rows)


if __name__ == "__main__":
    unittest.main()
