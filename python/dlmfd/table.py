"""A table of jobs (a study): one row per job, as dicts, or a pandas DataFrame when pandas is
importable.

Columns, in this order: the job's fields (id, name, state, sweep_id, reason, step, time,
end_time, attempts, created_time, started_time, finished_time), then one column per override key
(the swept parameters and the base overrides, values read as TOML: 1.4, not "1.4"), then, for a job
whose summary.json was fetched, the run's end (status, steps, wall_seconds, ms_per_step) and each
particle's final state: particles.ID.x, .y, .u, .v, .angular_velocity, .fx, .fy, .torque.
A job whose results hold no summary.json yet (queued, running, or killed before writing it) has
none of the summary columns (None in a DataFrame).
"""

import json
import tomllib

from .v1 import jobs_pb2

_JOB_FIELDS = ("id", "name", "state", "sweep_id", "reason", "step", "time", "end_time", "attempts",
               "created_time", "started_time", "finished_time")
_SUMMARY_FIELDS = ("status", "steps", "wall_seconds", "ms_per_step")


def override_value(text):
    """The value of an override's TOML value text (the text itself when it is not TOML)."""
    try:
        return tomllib.loads("v = " + text)["v"]
    except tomllib.TOMLDecodeError:
        return text


def job_row(job, summary=None):
    """One row: the job's fields, its overrides, and the summary's (a dict parsed from JSON)."""
    row = {}
    for name in _JOB_FIELDS:
        value = getattr(job, name)
        row[name] = jobs_pb2.JobState.Name(value) if name == "state" else value
    for override in job.overrides:
        key, _, text = override.partition("=")
        row[key] = override_value(text)
    if summary is not None:
        for name in _SUMMARY_FIELDS:
            row[name] = summary.get(name)
        for p in summary.get("particles", []):
            prefix = f"particles.{p['id']}."
            (row[prefix + "x"], row[prefix + "y"]) = p["position"]
            (row[prefix + "u"], row[prefix + "v"]) = p["velocity"]
            row[prefix + "angular_velocity"] = p["angular_velocity"]
            (row[prefix + "fx"], row[prefix + "fy"]) = p["force"]
            row[prefix + "torque"] = p["torque"]
    return row


def parse_summary(data):
    """summary.json bytes as a dict."""
    return json.loads(data.decode("utf-8"))


def as_table(rows, frame=None):
    """rows as a pandas DataFrame when frame is True, or None and pandas imports; else the list."""
    if frame is False:
        return rows
    try:
        import pandas
    except ImportError:
        if frame:
            raise
        return rows
    return pandas.DataFrame(rows)
