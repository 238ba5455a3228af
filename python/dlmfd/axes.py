"""The axes of a study (SubmitStudy, docs/cli.md "study"), from Python values.

``axes`` maps a dotted scene key (``*`` for every index of an array: ``particles.*.density``) to a
list of values (TOML value texts of scene_input.toml_value) or to a ``Range``; together they form a
full grid. ``zip`` maps keys to lists of equal length that step together, one axis of that grid.
"""

import dataclasses

from . import scene_input
from .v1 import jobs_pb2


@dataclasses.dataclass(frozen=True)
class Range:
    """``count`` values from ``start`` to ``stop``, both included: evenly spaced, or with
    ``log=True`` in geometric progression (start and stop of one sign, neither zero)."""
    start: float
    stop: float
    count: int
    log: bool = False


def _axis(key, values, zip_name=""):
    if isinstance(values, Range):
        return jobs_pb2.StudyAxis(key=key, zip=zip_name, range=jobs_pb2.AxisRange(
            start=values.start, stop=values.stop, count=values.count, logarithmic=values.log))
    if isinstance(values, (str, bytes)) or not hasattr(values, "__iter__"):
        raise TypeError(f"axis {key}: expected a list of values or a dlmfd.Range, "
                        f"got {type(values).__name__}")
    return jobs_pb2.StudyAxis(key=key, zip=zip_name,
                              values=[scene_input.toml_value(v) for v in values])


def study_axes(axes=None, zip=None):
    """The StudyAxis messages of grid axes and of one group of zipped axes."""
    out = [_axis(key, values) for key, values in (axes or {}).items()]
    out += [_axis(key, values, "zip") for key, values in (zip or {}).items()]
    return out
