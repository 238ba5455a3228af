"""The Python client's own logic, without a daemon: scene and override input, TOML values, the
parts of an InvalidArgument message, table rows from the Table rpc's rows, and study axes.

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

from dlmfd import Range, errors, scene_input  # noqa: E402
from dlmfd import study_table as table  # noqa: E402
from dlmfd.axes import study_axes  # noqa: E402
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

    def test_rows_of_table_rows_have_typed_parameters_and_none_for_no_value(self):
        nan = float("nan")
        done = jobs_pb2.TableRow(
            job_id="j1", name="s[fluid.relaxation_time=1.4]", state=jobs_pb2.COMPLETED,
            parameters=[jobs_pb2.Parameter(key="fluid.relaxation_time", double_value=1.4),
                        jobs_pb2.Parameter(key="n", int_value=3),
                        jobs_pb2.Parameter(key="splitting.advection", text_value="wave")],
            has_summary=True, status="completed", steps=10, time=0.5, wall_seconds=0.25,
            fall_speed=-0.5, min_gap=nan, max_tra=2.5, reynolds=0.125,
            particles=[jobs_pb2.ParticleRow(id=0, radius=0.1, x=0.5, y=1.25, u=0.0, v=-0.5,
                                            angular_velocity=0.25, force_x=0.125, force_y=2.0,
                                            torque=-0.5, fall_speed=-0.5, angle=0.75)])
        queued = jobs_pb2.TableRow(
            job_id="j2", name="s[other=true]", state=jobs_pb2.QUEUED,
            parameters=[jobs_pb2.Parameter(key="other", bool_value=True)])
        rows = table.rows_of([done, queued])
        self.assertEqual(list(rows[0])[:7], ["job", "name", "state", "fluid.relaxation_time", "n",
                                             "splitting.advection", "other"])
        self.assertEqual(list(rows[0]), list(rows[1]))  # every row has every column
        self.assertEqual(rows[0]["state"], "COMPLETED")
        self.assertEqual(rows[0]["fluid.relaxation_time"], 1.4)
        self.assertIs(type(rows[0]["n"]), int)
        self.assertEqual(rows[0]["splitting.advection"], "wave")
        self.assertIsNone(rows[0]["other"])
        self.assertIs(rows[1]["other"], True)
        self.assertEqual((rows[0]["status"], rows[0]["steps"], rows[0]["Re"]),
                         ("completed", 10, 0.125))
        self.assertIsNone(rows[0]["min_gap"])  # NaN: the summary has none
        self.assertEqual(rows[0]["max_trA"], 2.5)
        self.assertEqual((rows[0]["p0.x"], rows[0]["p0.y"], rows[0]["p0.omega"]), (0.5, 1.25, 0.25))
        self.assertEqual(rows[0]["p0.angle"], 0.75)
        self.assertEqual((rows[0]["p0.fx"], rows[0]["p0.fy"], rows[0]["p0.radius"]),
                         (0.125, 2.0, 0.1))
        self.assertIsNone(rows[1]["status"])  # no summary yet
        self.assertIsNone(rows[1]["p0.x"])

    def test_axes_of_a_grid_a_range_and_a_zip(self):
        axes = study_axes({"fluid.relaxation_time": [0.5, 1.4],
                           "time.dt": Range(1e-3, 1e-2, 3, log=True)},
                          zip={"particles.0.density": [1.01, 1.02],
                               "particles.1.density": [1.02, 1.05]})
        self.assertEqual([a.key for a in axes], ["fluid.relaxation_time", "time.dt",
                                                 "particles.0.density", "particles.1.density"])
        self.assertEqual(list(axes[0].values), ["0.5", "1.4"])
        self.assertEqual((axes[1].range.start, axes[1].range.count, axes[1].range.logarithmic),
                         (1e-3, 3, True))
        self.assertEqual([a.zip for a in axes], ["", "", "zip", "zip"])
        with self.assertRaises(TypeError):
            study_axes({"fluid.relaxation_time": "0.5,1.4"})

    def test_list_of_dicts_unless_a_frame_is_asked_for(self):
        rows = [{"a": 1}]
        self.assertIs(table.as_table(rows, frame=False), rows)


if __name__ == "__main__":
    unittest.main()
