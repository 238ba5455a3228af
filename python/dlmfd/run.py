"""A results directory as a scientist reads it (docs/python.md, docs/results.md): ``dlmfd.open``.

    run = dlmfd.open("runs/pair")
    run.summary            # summary.json as a dict
    run.scene              # scene.toml (the scene as run) as a dict; run.scene_text its text
    run.diagnostics        # diagnostics.csv as a DataFrame, numeric columns as floats
    run.particles          # particles.h5 as a long-form DataFrame: one row per record and particle
    run.fields             # the snapshots as an xarray Dataset over (time, y, x), the disks at each
                           # snapshot's own time as (time, particle) variables
    run.snapshot(-1)       # one snapshot as an xarray Dataset

Every variable carries the file's ``units`` (dimensions in the scene's units: L, M, T; the
paper's cases are CGS) and ``description`` attributes. A snapshot written before results format 2
holds no particles: its disks are interpolated linearly in time between the particle records
around it, and the Dataset's ``particles_source`` attribute says so. Files of a newer format than
this package reads raise ``FormatError`` naming the version.
"""

import builtins
import json
import os
import tomllib

import numpy as np

from . import results, study_table

FORMAT_VERSION = 2  # the newest results format this package reads (results_format.h)


class FormatError(ValueError):
    """A results file of a format version this package does not read."""


def _pandas():
    try:
        import pandas
    except ImportError as error:  # pragma: no cover - a declared dependency
        raise ImportError("dlmfd.open needs pandas (Debian: python3-pandas)") from error
    return pandas


def _xarray():
    try:
        import xarray
    except ImportError as error:  # pragma: no cover - a declared dependency
        raise ImportError("dlmfd.open needs xarray (Debian: python3-xarray)") from error
    return xarray


def _check_version(path, attrs):
    version = int(attrs.get("format_version", 1))
    if version > FORMAT_VERSION:
        raise FormatError(f"{path} is of results format version {version}; this dlmfd package "
                          f"reads versions 1 to {FORMAT_VERSION} (a newer dlmfd wrote it)")
    return version


def _read(path):
    with builtins.open(path) as f:
        return f.read()


def _text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def _meaning(dataset):
    """units and description attributes of an h5py dataset, as str."""
    return {k: _text(dataset.attrs[k]) for k in ("units", "description") if k in dataset.attrs}


class Run:
    """One results directory (``dlmfd.open(path)``); each part is read when first asked for."""

    def __init__(self, path):
        self.path = os.fspath(path)
        if not os.path.exists(self.path):
            raise FileNotFoundError(f"no results directory {self.path}: it does not exist")
        if not os.path.isdir(self.path):
            raise NotADirectoryError(f"{self.path} is not a directory (a results directory of "
                                     "dlmfd-solve --out or dlmfd fetch)")
        known = ("scene.toml", "summary.json", "particles.h5", "fields", "diagnostics.csv")
        if not any(os.path.exists(os.path.join(self.path, name)) for name in known):
            raise FileNotFoundError(f"{self.path} is not a results directory: it holds none of "
                                    f"{', '.join(known)}")
        self._cache = {}

    def __repr__(self):
        return f"dlmfd.Run({self.path!r})"

    def _file(self, name):
        path = os.path.join(self.path, name)
        if not os.path.exists(path):
            raise FileNotFoundError(f"{self.path} has no {name}")
        return path

    def _cached(self, key, make):
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    @property
    def summary(self):
        """summary.json as a dict (written when the run ends; FileNotFoundError before)."""
        return self._cached("summary", lambda: json.loads(_read(self._file("summary.json"))))

    @property
    def scene_text(self):
        """The scene as run (scene.toml: every default filled in)."""
        return self._cached("scene_text", lambda: _read(self._file("scene.toml")))

    @property
    def scene(self):
        """The scene as run, as a dict (tomllib)."""
        return self._cached("scene", lambda: tomllib.loads(self.scene_text))

    @property
    def diagnostics(self):
        """diagnostics.csv, one row per step, as a DataFrame; every column but text is float64
        (``nan`` where a step has nothing to measure)."""
        def read():
            pandas = _pandas()
            frame = pandas.read_csv(self._file("diagnostics.csv"), na_values=["nan", "-nan"])
            return frame.apply(lambda c: pandas.to_numeric(c, errors="ignore"))
        return self._cached("diagnostics", read)

    @property
    def particles(self):
        """particles.h5 in long form: one row per record and particle, columns time, step,
        particle (the id), radius, x, y, u, v, omega, angle (NaN in a file of format 1), fx, fy,
        torque. ``frame.attrs['units']`` maps each column to its units."""
        return self._cached("particles", self._read_particles)

    def _read_particles(self):
        pandas = _pandas()
        path = self._file("particles.h5")
        with results._open(path) as f:
            _check_version(path, f.attrs)
            units = {}
            arrays = {}
            for name in ("time", "step", "position", "velocity", "angular_velocity", "force",
                         "torque", "id", "radius", "angle"):
                if name in f:
                    arrays[name] = f[name][()]
                    units[name] = _meaning(f[name]).get("units", "")
        nt, n = len(arrays["time"]), len(arrays["id"])
        angle = arrays.get("angle", np.full((nt, n), np.nan))
        frame = pandas.DataFrame({
            "time": np.repeat(arrays["time"], n),
            "step": np.repeat(arrays["step"], n),
            "particle": np.tile(arrays["id"], nt),
            "radius": np.tile(arrays["radius"], nt),
            "x": arrays["position"][..., 0].ravel() if n else np.zeros(0),
            "y": arrays["position"][..., 1].ravel() if n else np.zeros(0),
            "u": arrays["velocity"][..., 0].ravel() if n else np.zeros(0),
            "v": arrays["velocity"][..., 1].ravel() if n else np.zeros(0),
            "omega": arrays["angular_velocity"].ravel(),
            "angle": np.asarray(angle, dtype=float).ravel(),
            "fx": arrays["force"][..., 0].ravel() if n else np.zeros(0),
            "fy": arrays["force"][..., 1].ravel() if n else np.zeros(0),
            "torque": arrays["torque"].ravel(),
        })
        frame.attrs["units"] = {
            "time": units.get("time", "T"), "radius": units.get("radius", "L"), "x": "L",
            "y": "L", "u": "L T-1", "v": "L T-1", "omega": "T-1", "angle": "rad",
            "fx": "M T-2", "fy": "M T-2", "torque": "M L T-2"}
        return frame

    def snapshot_paths(self):
        """The snapshot files, by ascending step."""
        return results.snapshot_paths(self.path)

    def snapshot(self, index=-1):
        """One snapshot as an xarray Dataset: index into snapshot_paths() (-1: the latest)."""
        paths = self.snapshot_paths()
        if not paths:
            raise FileNotFoundError(f"{self.path} has no field snapshots in fields/ "
                                    "(output.fields_every = 0 writes none)")
        return self._snapshot_dataset(paths[index])

    @property
    def fields(self):
        """Every snapshot as one xarray Dataset over time (loaded into memory)."""
        def read():
            xarray = _xarray()
            paths = self.snapshot_paths()
            if not paths:
                raise FileNotFoundError(f"{self.path} has no field snapshots in fields/ "
                                        "(output.fields_every = 0 writes none)")
            frames = [self._snapshot_dataset(p) for p in paths]
            sources = sorted({d.attrs.get("particles_source", "") for d in frames} - {""})
            merged = xarray.concat(frames, dim="time", combine_attrs="drop_conflicts")
            if sources:
                merged.attrs["particles_source"] = "; ".join(sources)
            return merged
        return self._cached("fields", read)

    def _snapshot_dataset(self, path):
        xarray = _xarray()
        with results._open(path) as f:
            version = _check_version(path, f.attrs)
            attrs = f.attrs
            time, step = float(attrs["time"]), int(attrs["step"])
            h, x0, y0 = float(attrs["h"]), float(attrs["x0"]), float(attrs["y0"])
            ny1, nx1 = f["u"].shape
            coords = {"x": ("x", x0 + h * np.arange(nx1)), "y": ("y", y0 + h * np.arange(ny1))}
            if "p" in f:
                pny, pnx = f["p"].shape
                coords["x_pressure"] = ("x_pressure", x0 + 2 * h * np.arange(pnx))
                coords["y_pressure"] = ("y_pressure", y0 + 2 * h * np.arange(pny))
            data = {}
            for name in ("u", "v", "p", "trA", "A11", "A12", "A22"):
                if name not in f:
                    continue
                dims = ("y_pressure", "x_pressure") if name == "p" else ("y", "x")
                meaning = _meaning(f[name]) or _V1_MEANINGS.get(name, {})
                data[name] = (("time",) + dims, f[name][()][np.newaxis], meaning)
            particles = None
            if "particles" in f:
                g = f["particles"]
                particles = {k: g[k][()] for k in g.keys()}
                particles["_units"] = {k: _meaning(g[k]).get("units", "") for k in g.keys()}
            scene = _text(f["scene"][()]) if "scene" in f else None
        ds = xarray.Dataset(data, coords=coords)
        for axis in ("x", "y", "x_pressure", "y_pressure"):
            if axis in ds.coords:
                ds[axis].attrs.update(units="L", description=f"{axis} of the nodes")
        ds = ds.assign_coords(time=("time", [time]), step=("time", [step]))
        ds["time"].attrs.update(units="T", description="simulated time of the snapshot")
        ds.attrs.update(format_version=version, h=h, source=path)
        if scene is not None:
            ds.attrs["scene"] = scene
        ds = self._add_particles(ds, particles, time, step)
        return ds

    def _add_particles(self, ds, particles, time, step):
        """The disks at the snapshot's time as (time, particle) variables."""
        if particles is None:  # format 1: interpolate particles.h5 in time, and say so
            if not os.path.exists(os.path.join(self.path, "particles.h5")):
                return ds
            table = self.particles
            if table.empty:
                return ds
            particles, note = _interpolated(table, time, step)
            ds.attrs["particles_source"] = note
        else:
            ds.attrs["particles_source"] = "the snapshot's own step"
        ids = np.asarray(particles["id"])
        ds = ds.assign_coords(particle=("particle", ids))
        position = np.asarray(particles["position"]).reshape(len(ids), 2)
        velocity = np.asarray(particles["velocity"]).reshape(len(ids), 2)
        angle = np.asarray(particles.get("angle", np.full(len(ids), np.nan)), dtype=float)
        columns = {
            "particle_x": (position[:, 0], "L", "particle centre x"),
            "particle_y": (position[:, 1], "L", "particle centre y"),
            "particle_u": (velocity[:, 0], "L T-1", "particle velocity x"),
            "particle_v": (velocity[:, 1], "L T-1", "particle velocity y"),
            "particle_omega": (particles["angular_velocity"], "T-1", "particle angular velocity"),
            "particle_angle": (angle, "rad", "particle rotation since t = 0, counter-clockwise"),
            "particle_radius": (particles["radius"], "L", "particle radius"),
        }
        for name, (values, units, description) in columns.items():
            ds[name] = (("time", "particle"), np.asarray(values, dtype=float)[np.newaxis])
            ds[name].attrs.update(units=units, description=description)
        return ds


def _interpolated(table, time, step):
    """The particles of particles.h5 at `time`: the record of `step`, else linear between the
    records around it, else the nearest; and a note saying which."""
    times = np.unique(table["time"].to_numpy())
    at_step = table[table["step"] == step]
    if not at_step.empty:
        rows, note = at_step, "particles.h5's record of the snapshot's step"
    else:
        before, after = times[times <= time], times[times > time]
        if len(before) and len(after):
            a = table[table["time"] == before[-1]].reset_index(drop=True)
            b = table[table["time"] == after[0]].reset_index(drop=True)
            w = (time - before[-1]) / (after[0] - before[-1])
            rows = a.copy()
            for c in ("x", "y", "u", "v", "omega", "angle"):
                rows[c] = a[c] + w * (b[c] - a[c])
            note = (f"interpolated linearly between particles.h5's records at t = {before[-1]:.6g} "
                    f"and {after[0]:.6g} (a snapshot of results format 1 holds no particles)")
        else:
            nearest = times[np.argmin(np.abs(times - time))]
            rows = table[table["time"] == nearest]
            note = f"particles.h5's nearest record, t = {nearest:.6g}"
    return ({"id": rows["particle"].to_numpy(), "radius": rows["radius"].to_numpy(),
             "position": rows[["x", "y"]].to_numpy(), "velocity": rows[["u", "v"]].to_numpy(),
             "angular_velocity": rows["omega"].to_numpy(), "angle": rows["angle"].to_numpy()},
            note)


# What format 1 files (no attributes) hold, for the variables' attributes.
_V1_MEANINGS = {
    "u": {"units": "L T-1", "description": "x component of the fluid velocity at the nodes"},
    "v": {"units": "L T-1", "description": "y component of the fluid velocity at the nodes"},
    "p": {"units": "M L-1 T-2", "description": "pressure at the nodes of the 2h mesh"},
    "trA": {"units": "1", "description": "trace of the conformation tensor A"},
    "A11": {"units": "1", "description": "conformation tensor component A_xx"},
    "A12": {"units": "1", "description": "conformation tensor component A_xy"},
    "A22": {"units": "1", "description": "conformation tensor component A_yy"},
}


def open(path):  # noqa: A001 - dlmfd.open, as xarray.open_dataset
    """The results directory at ``path`` as a ``Run``; FileNotFoundError naming the path when it
    does not exist or holds no results files."""
    return Run(path)


# The summary's columns of a local table, as the daemon's Table rpc names them (table.py).
_SUMMARY_KEYS = (("status", "status"), ("reason", "reason"), ("steps", "steps"), ("time", "time"),
                 ("wall_seconds", "wall_seconds"), ("fall_speed", "fall_speed"),
                 ("min_gap", "min_gap"), ("min_wall_gap", "min_wall_gap"),
                 ("max_trA", "max_trA"), ("min_eig_A", "min_eig_A"), ("Re", "reynolds"),
                 ("De", "deborah"), ("E", "elasticity"), ("M", "mach"))
_PARTICLE_KEYS = (("radius", "radius"), ("x", "position", 0), ("y", "position", 1),
                  ("angle", "angle"), ("u", "velocity", 0), ("v", "velocity", 1),
                  ("omega", "angular_velocity"), ("fx", "force", 0), ("fy", "force", 1),
                  ("torque", "torque"), ("fall_speed", "fall_speed"))


def _flatten(value, prefix, out):
    if isinstance(value, dict):
        for key, item in value.items():
            _flatten(item, f"{prefix}.{key}" if prefix else key, out)
    elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
        for k, item in enumerate(value):
            _flatten(item, f"{prefix}.{k}", out)
    else:
        out[prefix] = tuple(value) if isinstance(value, list) else value


def table(run_dirs, frame=None):
    """One row per results directory, with no daemon: ``dir``, ``title``, the scene keys in
    which the runs differ (dotted, typed as TOML reads them), then the columns of ``dlmfd table``
    from each summary.json (None where a run has none: still running, or failed before it) and
    per particle N ``pN.radius``, ``pN.x`` ... ``pN.fall_speed``. A DataFrame when pandas
    imports (frame=None), frame=False for a list of dicts."""
    runs = [Run(d) for d in run_dirs]
    scenes = []
    for run in runs:
        flat = {}
        try:
            _flatten(run.scene, "", flat)
        except FileNotFoundError:
            pass
        scenes.append(flat)
    keys = sorted({k for s in scenes for k in s} - {"title"})
    differing = [k for k in keys if len({repr(s.get(k)) for s in scenes}) > 1]
    rows = []
    for run, scene in zip(runs, scenes):
        row = {"dir": run.path, "title": scene.get("title")}
        for key in differing:
            value = scene.get(key)
            row[key] = list(value) if isinstance(value, tuple) else value
        try:
            summary = run.summary
        except FileNotFoundError:
            summary = {}
        for column, key in _SUMMARY_KEYS:
            row[column] = summary.get(key)
        for n, particle in enumerate(summary.get("particles") or []):
            for column, key, *index in _PARTICLE_KEYS:
                value = particle.get(key)
                if index and value is not None:
                    value = value[index[0]]
                row[f"p{n}.{column}"] = value
        rows.append(row)
    columns = []
    for row in rows:
        columns += [c for c in row if c not in columns]
    rows = [{c: row.get(c) for c in columns} for row in rows]
    if frame is False:
        return rows
    try:
        pandas = _pandas()
    except ImportError:
        if frame:
            raise
        return rows
    return study_table.typed_columns(pandas.DataFrame(rows, columns=columns), pandas)
