"""A table of a study: one row per job, as dicts, or a pandas DataFrame when pandas is importable.

The rows are the daemon's (the Table rpc, docs/api.md), with the columns of ``dlmfd table``
(docs/cli.md), in this order: ``job``, ``name``, ``state``; one column per override key (the swept
parameters and the base overrides, typed as TOML reads them: 1.4, not "1.4"); from the job's
summary.json (docs/results.md) ``status``, ``reason``, ``steps``, ``time``, ``wall_seconds``,
``fall_speed``, ``min_gap`` (the true smallest surface gap over the run), ``min_wall_gap``,
``max_trA``, ``min_eig_A``, ``Re``, ``De``, ``E``, ``M``; and per particle N ``pN.radius``, ``pN.x``,
``pN.y`` (final position), ``pN.angle`` (final orientation, radians), ``pN.u``, ``pN.v``,
``pN.omega``, ``pN.fx``, ``pN.fy``, ``pN.torque``, ``pN.fall_speed``. None where there is no
value: a job without a summary yet (queued, running), a Newtonian run's trA, a parameter or a
particle another job has not.
"""

import math

from .v1 import jobs_pb2

SUMMARY_COLUMNS = (("status", "status"), ("reason", "reason"), ("steps", "steps"),
                   ("time", "time"), ("wall_seconds", "wall_seconds"),
                   ("fall_speed", "fall_speed"), ("min_gap", "min_gap"),
                   ("min_wall_gap", "min_wall_gap"), ("max_trA", "max_tra"),
                   ("min_eig_A", "min_eig_a"), ("Re", "reynolds"), ("De", "deborah"),
                   ("E", "elasticity"), ("M", "mach"))
PARTICLE_COLUMNS = (("radius", "radius"), ("x", "x"), ("y", "y"), ("angle", "angle"), ("u", "u"),
                    ("v", "v"), ("omega", "angular_velocity"), ("fx", "force_x"), ("fy", "force_y"),
                    ("torque", "torque"), ("fall_speed", "fall_speed"))


def _value(value):
    """None for the rpc's NaN (no value), else the value."""
    return None if isinstance(value, float) and math.isnan(value) else value


def parameter_value(parameter):
    """The typed value of a Parameter: int, float, bool or str; None when it has none."""
    kind = parameter.WhichOneof("value")
    return None if kind is None else _value(getattr(parameter, kind))


def rows_of(table_rows):
    """Dicts, one per TableRow, every row with the same columns (in the order above)."""
    keys, particles = {}, 0
    for row in table_rows:
        for parameter in row.parameters:
            keys.setdefault(parameter.key, None)
        particles = max(particles, len(row.particles))
    rows = []
    for row in table_rows:
        out = {"job": row.job_id, "name": row.name, "state": jobs_pb2.JobState.Name(row.state)}
        values = {p.key: parameter_value(p) for p in row.parameters}
        for key in keys:
            out[key] = values.get(key)
        for column, field in SUMMARY_COLUMNS:
            out[column] = _value(getattr(row, field)) if row.has_summary else None
        for n in range(particles):
            particle = row.particles[n] if n < len(row.particles) else None
            for column, field in PARTICLE_COLUMNS:
                value = None if particle is None else _value(getattr(particle, field))
                out[f"p{n}.{column}"] = value
        rows.append(out)
    return rows


TEXT_COLUMNS = ("job", "name", "state", "status", "reason", "dir", "title")


def typed_columns(frame, pandas):
    """A column whose values are numbers or None becomes numeric (None -> NaN; int64 when every
    value is a whole number and none is missing), not object; so does one with no value at all
    (a one-particle run's min_gap), except the text columns (TEXT_COLUMNS)."""
    for column in frame.columns:
        values = [v for v in frame[column] if v is not None]
        numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values)
        if values and numbers:
            frame[column] = pandas.to_numeric(frame[column], errors="coerce")
        elif not values and column not in TEXT_COLUMNS:
            frame[column] = pandas.to_numeric(frame[column], errors="coerce").astype("float64")
    return frame


def as_table(rows, frame=None):
    """rows as a pandas DataFrame when frame is True, or None and pandas imports; else the list.
    Numeric columns with missing values are float64 with NaN (typed_columns)."""
    if frame is False:
        return rows
    try:
        import pandas
    except ImportError:
        if frame:
            raise
        return rows
    return typed_columns(pandas.DataFrame(rows), pandas)
