"""Readers of a results directory (docs/results.md) into numpy arrays, through h5py.

particles.h5: /time (nt), /step (nt), /position (nt, np, 2), /velocity (nt, np, 2),
/angular_velocity (nt, np), /force (nt, np, 2), /torque (nt, np), /id (np), /radius (np).
fields/snap_NNNNNN.h5: node values /u, /v, /velocity (ny+1, nx+1, 3), and /trA, /A11, /A12, /A22
for a viscoelastic run, of shape (ny+1, nx+1), x fastest (row j is y = y0 + j h); /p of shape
(ny/2+1, nx/2+1) on the 2h mesh; attributes time, step, h, x0, y0; in results format 2 also the
coordinates /x, /y, /x_pressure, /y_pressure, /scene and the group /particles.
run.py (dlmfd.open) reads them into pandas and xarray with their units.
The files are opened without HDF5's file lock, so they can be read while the solver writes them
(it writes snapshots by rename and flushes particles.h5 record by record).
"""

import dataclasses
import os
import re

import h5py
import numpy as np

_PARTICLE_SETS = ("time", "step", "position", "velocity", "angular_velocity", "force", "torque",
                  "id", "radius")
_SNAPSHOT_NAME = re.compile(r"^snap_(\d+)\.h5$")


def _open(path):
    try:
        return h5py.File(path, "r", locking=False)
    except TypeError:  # an h5py without the locking argument
        os.environ.setdefault("HDF5_USE_FILE_LOCKING", "FALSE")
        return h5py.File(path, "r")


@dataclasses.dataclass
class Particles:
    """particles.h5: one record per output time; np = 0 without particles."""

    time: np.ndarray
    step: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray
    force: np.ndarray
    torque: np.ndarray
    id: np.ndarray
    radius: np.ndarray


def _existing(path, what):
    if not os.path.exists(path):
        raise FileNotFoundError(f"no {what} {path}: it does not exist")
    return path


def read_particles(path):
    """Particles of a particles.h5 file, or of the particles.h5 in a results directory."""
    _existing(path, "particles.h5 or results directory")
    if os.path.isdir(path):
        path = _existing(os.path.join(path, "particles.h5"), "file")
    with _open(path) as f:
        return Particles(**{name: f[name][()] for name in _PARTICLE_SETS})


@dataclasses.dataclass
class Snapshot:
    """One field snapshot: ``fields[name]`` as stored, and the node coordinates ``x``, ``y``."""

    time: float
    step: int
    h: float
    x0: float
    y0: float
    fields: dict

    def __getitem__(self, name):
        return self.fields[name]

    @property
    def x(self):
        """x of the velocity-mesh nodes, (nx+1,)."""
        return self.x0 + self.h * np.arange(self.fields["u"].shape[1])

    @property
    def y(self):
        """y of the velocity-mesh nodes, (ny+1,)."""
        return self.y0 + self.h * np.arange(self.fields["u"].shape[0])


def read_snapshot(path):
    """Every dataset and attribute of one fields/snap_NNNNNN.h5 (the node fields, the coordinates
    and, in results format 2, the scene text and the group ``particles``, as a dict)."""
    with _open(_existing(path, "snapshot file")) as f:
        attrs = f.attrs
        fields = {}
        for name in f.keys():
            item = f[name]
            if hasattr(item, "keys"):  # a group: particles
                fields[name] = {k: item[k][()] for k in item.keys()}
            else:
                fields[name] = item[()]
        return Snapshot(time=float(attrs["time"]), step=int(attrs["step"]), h=float(attrs["h"]),
                        x0=float(attrs["x0"]), y0=float(attrs["y0"]), fields=fields)


def snapshot_paths(results_dir):
    """Paths of the snapshots of a results directory, by ascending step ([] when it has no
    fields/ folder: output.fields_every = 0). FileNotFoundError when results_dir does not
    exist."""
    if not os.path.isdir(_existing(results_dir, "results directory")):
        raise NotADirectoryError(f"{results_dir} is not a directory")
    folder = os.path.join(results_dir, "fields")
    if not os.path.isdir(folder):
        return []
    steps = sorted((int(m.group(1)), name) for name in os.listdir(folder)
                   if (m := _SNAPSHOT_NAME.match(name)))
    return [os.path.join(folder, name) for _, name in steps]


def read_snapshots(results_dir):
    """The snapshots of a results directory, by ascending step (an iterator: one file at a time)."""
    for path in snapshot_paths(results_dir):
        yield read_snapshot(path)
