"""dlmfd: a Python client of the dlmfdd job daemon, and readers of its results (docs/python.md).

    import dlmfd
    client = dlmfd.Client("127.0.0.1:7443", token=None)
    job = client.submit("cases/lid_driven_cavity.toml", {"time.end": 0.5})
    for event in client.watch(job.id): ...
    client.fetch(job.id, "runs/cavity")
    run = dlmfd.open("runs/cavity")      # summary, scene, diagnostics, particles, fields (xarray)
    dlmfd.table(["runs/a", "runs/b"])    # one row per run, no daemon
"""

from ._version import __version__
from .axes import Range
from .errors import (DlmfdError, FailedPrecondition, InvalidArgument, NotFound, ResourceExhausted,
                     Unauthenticated, Unavailable)
from .results import (Particles, Snapshot, read_particles, read_snapshot, read_snapshots,
                      snapshot_paths)
from .run import FormatError, Run, open, table

from .client import FINISHED_STATES, Client, state_name
from .v1 import events_pb2, jobs_pb2

__all__ = [
    "__version__", "Client", "Range", "state_name", "FINISHED_STATES", "DlmfdError",
    "InvalidArgument", "NotFound", "Unauthenticated", "ResourceExhausted", "FailedPrecondition",
    "Unavailable", "Particles", "Snapshot", "read_particles", "read_snapshot", "read_snapshots",
    "snapshot_paths", "events_pb2", "jobs_pb2", "open", "table", "Run", "FormatError",
]
