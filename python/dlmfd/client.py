"""The job API of dlmfdd (proto/dlmfd/v1/jobs.proto, docs/api.md) for notebooks and scripts.

``Client(server, token)`` opens a plaintext gRPC channel (tunnel it to reach another machine, as
for the CLI: docs/cli.md) and sends the token as ``authorization: Bearer TOKEN``. Each method is one
rpc or a short composition of them; a failed rpc raises a DlmfdError subclass (errors.py). Jobs
and events are the generated protobuf messages (``job.id``, ``job.state``, ``event.progress``);
``state_name(job.state)`` gives "COMPLETED". The stubs are generated from proto/ at build time
(python/CMakeLists.txt), into the build tree beside this package.
"""

import os
import pathlib
import re
import time

import grpc
from google.protobuf import json_format

from . import errors, scene_input, study_table
from .axes import study_axes
from .v1 import jobs_pb2, jobs_pb2_grpc

FINISHED_STATES = (jobs_pb2.COMPLETED, jobs_pb2.FAILED, jobs_pb2.CANCELLED)


def state_name(state):
    """"COMPLETED" for jobs_pb2.COMPLETED."""
    return jobs_pb2.JobState.Name(state)


class Client:
    """A connection to dlmfdd. server: "HOST:PORT" ($DLMFD_SERVER, else 127.0.0.1:7443); token:
    the bearer token ($DLMFD_TOKEN, else none); timeout: seconds per unary rpc."""

    def __init__(self, server=None, token=None, timeout=30.0):
        self.server = server or os.environ.get("DLMFD_SERVER") or "127.0.0.1:7443"
        self.token = token if token is not None else os.environ.get("DLMFD_TOKEN") or None
        self.timeout = timeout
        self._channel = grpc.insecure_channel(self.server)
        self._stub = jobs_pb2_grpc.JobsStub(self._channel)

    def close(self):
        self._channel.close()

    def __enter__(self):
        return self

    def __exit__(self, *_):
        self.close()

    def _metadata(self):
        return (("authorization", f"Bearer {self.token}"),) if self.token else ()

    def _unary(self, rpc, request):
        try:
            return getattr(self._stub, rpc)(request, metadata=self._metadata(),
                                            timeout=self.timeout)
        except grpc.RpcError as error:
            raise errors.from_rpc_error(error, rpc) from None

    def _stream(self, rpc, request):
        try:
            yield from getattr(self._stub, rpc)(request, metadata=self._metadata())
        except grpc.RpcError as error:
            raise errors.from_rpc_error(error, rpc) from None

    def submit(self, scene, overrides=None, name="", tags=(), priority=0, request_id="",
               labels=None, time_limit_seconds=0, after=()):
        """Queues one job (Submit); returns the Job. scene: TOML text or a path; labels: a dict
        of key=value labels; time_limit_seconds: the wall time one run may take (0: the
        daemon's limit; under Slurm its --time); after: job ids (or Jobs) that must COMPLETE
        before this one starts (one that fails or is cancelled cancels it)."""
        request = jobs_pb2.SubmitRequest(scene=scene_input.scene_text(scene),
                                         overrides=scene_input.override_texts(overrides),
                                         name=name, tags=list(tags), priority=priority,
                                         client_request_id=request_id, labels=labels or {},
                                         time_limit_seconds=time_limit_seconds,
                                         after=_job_ids(after))
        return self._unary("Submit", request)

    def submit_study(self, scene, axes=None, overrides=None, name="", tags=(), priority=0,
                     request_id="", zip=None, labels=None, max_running=0, time_limit_seconds=0,
                     after=()):
        """Queues a study, one job per point (SubmitStudy); returns (study_id, [Job, ...]).

        axes: {"fluid.relaxation_time": [0.5, 1.4], "time.dt": dlmfd.Range(1e-3, 1e-2, 3,
        log=True), "particles.*.density": [...]}, a full grid; zip: {key: [values], ...} of equal
        lengths, stepping together as one axis of the grid (axes.py); labels: a dict;
        max_running: at most this many of its jobs run at once (0: no limit);
        time_limit_seconds, after: each job's, as submit's."""
        request = jobs_pb2.SubmitStudyRequest(
            scene=scene_input.scene_text(scene), overrides=scene_input.override_texts(overrides),
            axes=study_axes(axes, zip), name=name, tags=list(tags), priority=priority,
            client_request_id=request_id, labels=labels or {}, max_running=max_running,
            time_limit_seconds=time_limit_seconds, after=_job_ids(after))
        response = self._unary("SubmitStudy", request)
        return response.study_id, list(response.jobs)

    def studies(self, tag=""):
        """The caller's studies (Study messages: axes, counts per state, progress), newest first."""
        found, token = [], ""
        while True:
            page = self._unary("ListStudies", jobs_pb2.ListStudiesRequest(
                tag=tag, page_size=1000, page_token=token))
            found.extend(page.studies)
            token = page.next_page_token
            if not token:
                return found

    def study(self, study_id):
        """One study (GetStudy): its axes, labels, limit on running jobs and counts per state."""
        return self._unary("GetStudy", jobs_pb2.GetStudyRequest(study_id=study_id))

    def retry(self, job_ids=(), study_id="", states=(), overrides=None):
        """Reruns finished jobs (Retry): the ones named, or the study's in `states` (default
        FAILED and CANCELLED); overrides replace or add to each job's. Returns the requeued jobs."""
        request = jobs_pb2.RetryRequest(job_ids=list(job_ids), study_id=study_id,
                                        states=_state_values(states),
                                        overrides=scene_input.override_texts(overrides))
        return list(self._unary("Retry", request).jobs)

    def usage(self):
        """What you use (GetUsage): disk_bytes against disk_quota_bytes (0: no quota), your jobs
        per state (queued, running, completed, failed, cancelled) and the queue's room
        (queue_unfinished of queue_limit, every user's)."""
        return self._unary("GetUsage", jobs_pb2.GetUsageRequest())

    def job(self, job_id):
        """One job (Get)."""
        return self._unary("Get", jobs_pb2.GetRequest(job_id=job_id))

    def jobs(self, states=(), tag="", study_id="", tags=(), labels=None, where=None):
        """The caller's jobs, newest first, every page of List; every filter given must hold.
        states: JobState values or names; tags: jobs carrying each; labels: a dict; where: the
        effective scene's values, a dict {"particles.*.density": 1.01} or texts "KEY=VALUE",
        "KEY!=VALUE", "KEY<NUMBER" (also <=, >, >=: only numbers meet a range)."""
        request = jobs_pb2.ListRequest(states=_state_values(states), tag=tag, study_id=study_id,
                                       tags=list(tags), labels=labels or {},
                                       where=scene_input.override_texts(where), page_size=1000)
        found = []
        while True:
            page = self._unary("List", request)
            found.extend(page.jobs)
            request.page_token = page.next_page_token
            if not request.page_token:
                return found

    def cancel(self, job_id):
        """Cancels a job (Cancel); returns the Job."""
        return self._unary("Cancel", jobs_pb2.CancelRequest(job_id=job_id))

    def cancel_study(self, study_id):
        """Cancels every unfinished job of a study (CancelStudy); returns the jobs."""
        return list(self._unary("CancelStudy", jobs_pb2.CancelStudyRequest(study_id=study_id)).jobs)

    def watch(self, job_id, from_seq=0, snapshots=False, snapshot_max_width=0,
              snapshot_max_height=0):
        """The job's events (WatchEvent messages) as they come; ends after its final state."""
        request = jobs_pb2.WatchRequest(job_id=job_id, from_seq=from_seq,
                                        include_snapshots=snapshots,
                                        snapshot_max_width=snapshot_max_width,
                                        snapshot_max_height=snapshot_max_height)
        return self._stream("Watch", request)

    def wait(self, job_id):
        """Watches the job to its end; returns the finished Job."""
        for _ in self.watch(job_id):
            pass
        return self.job(job_id)

    def files(self, job_id):
        """The files of the job's results directory with their sizes (ListFiles)."""
        return list(self._unary("ListFiles", jobs_pb2.ListFilesRequest(job_id=job_id)).files)

    def read(self, job_id, path):
        """The bytes of one result file (Fetch of one path)."""
        data = bytearray()
        for chunk in self._stream("Fetch", jobs_pb2.FetchRequest(job_id=job_id, path=path)):
            data += chunk.data
        return bytes(data)

    def fetch(self, job_id, out=None, paths=()):
        """Writes the job's result files (all, or the given relative paths) under out (default
        ./JOB_ID); each file goes to a hidden temporary name and is renamed when complete. Then
        out/job.json records the job as `dlmfd fetch` does (docs/results.md), so that `dlmfd plot
        DIR` captions the directory with the job's name and overrides. Returns out as a
        pathlib.Path."""
        out = pathlib.Path(out if out is not None else job_id)
        requests = [jobs_pb2.FetchRequest(job_id=job_id, path=p) for p in paths] or [
            jobs_pb2.FetchRequest(job_id=job_id)]
        for request in requests:
            handle, temporary = None, None
            try:
                for chunk in self._stream("Fetch", request):
                    if handle is None:
                        final = out / chunk.path
                        final.parent.mkdir(parents=True, exist_ok=True)
                        temporary = final.with_name(f".{final.name}.part")
                        handle = open(temporary, "wb")
                    handle.write(chunk.data)
                    if chunk.last:
                        handle.close()
                        os.replace(temporary, final)
                        handle = None
            finally:
                if handle is not None:  # the stream broke inside a file: no truncated file kept
                    handle.close()
                    os.remove(temporary)
        out.mkdir(parents=True, exist_ok=True)
        _write_job_json(out, self.job(job_id))
        return out

    def fetch_study(self, study_id, out=None, paths=()):
        """Fetches every job of a study (as `dlmfd fetch --study`): each into out/FOLDER, FOLDER
        its point's "key=value,..." in the order of the axes (its name without parameters),
        characters other than letters, digits and ._=,+*- made "_", a name taken twice getting
        the job id appended; default out ./STUDY_ID. Returns {folder path: Job}, oldest first."""
        out = pathlib.Path(out if out is not None else study_id)
        jobs = sorted(self.jobs(study_id=study_id), key=lambda j: (j.created_time, j.id))
        if not jobs:
            raise errors.NotFound(grpc.StatusCode.NOT_FOUND, f"study {study_id} has no jobs", "List")
        fetched, taken = {}, set()
        for job in jobs:
            folder = point_folder(job)
            if folder in taken:
                folder += "." + job.id
            taken.add(folder)
            fetched[self.fetch(job.id, out / folder, paths)] = job
        return fetched

    def log(self, job_id, offset=0, max_bytes=0):
        """One piece of the job's solver log (ReadLog): a LogChunk (data, offset, size,
        finished)."""
        return self._unary("ReadLog", jobs_pb2.ReadLogRequest(job_id=job_id, offset=offset,
                                                              max_bytes=max_bytes))

    def logs(self, job_id, follow=False, poll_seconds=1.0):
        """The job's solver log as text (`dlmfd logs`); with follow=True, waits for what the
        solver adds until the job has ended."""
        text, offset = bytearray(), 0
        while True:
            chunk = self.log(job_id, offset)
            text += chunk.data
            offset = chunk.offset + len(chunk.data)
            if offset < chunk.size:
                continue
            if not follow or chunk.finished:
                return text.decode(errors="replace")
            time.sleep(poll_seconds)

    def inputs(self, job_id):
        """The job's inputs (GetInputs): scene as submitted, overrides, scene_as_run (empty
        before the solver wrote it)."""
        return self._unary("GetInputs", jobs_pb2.GetInputsRequest(job_id=job_id))

    def delete(self, job_ids=(), study_id="", force=False):
        """Deletes jobs' records and results (Delete; force: running ones too, cancelled
        first). Returns (deleted job ids, freed bytes)."""
        if isinstance(job_ids, str):
            job_ids = [job_ids]
        response = self._unary("Delete", jobs_pb2.DeleteRequest(job_ids=list(job_ids),
                                                                study_id=study_id, force=force))
        return list(response.deleted), response.freed_bytes

    def set_priority(self, job_id, priority):
        """Sets a job's priority, -1000..1000, higher first (SetPriority); returns the Job."""
        return self._unary("SetPriority", jobs_pb2.SetPriorityRequest(job_id=job_id,
                                                                      priority=priority))

    def hold(self, job_id):
        """Keeps a queued job from starting (Hold); returns the Job."""
        return self._unary("Hold", jobs_pb2.HoldRequest(job_id=job_id))

    def release(self, job_id):
        """Lets a held job start again (Release); returns the Job."""
        return self._unary("Release", jobs_pb2.HoldRequest(job_id=job_id))

    def health(self, timeout=None):
        """The daemon's grpc.health.v1 status ("SERVING", "NOT_SERVING", ...), as `dlmfd
        health`; Unavailable when nothing answers. Needs no token."""
        check = self._channel.unary_unary("/grpc.health.v1.Health/Check",
                                          request_serializer=lambda _: b"",
                                          response_deserializer=_health_status)
        try:
            return check(None, timeout=timeout or self.timeout)
        except grpc.RpcError as error:
            raise errors.from_rpc_error(error, "Health/Check") from None

    def table(self, study_id="", jobs=None, tag="", states=(), frame=None):
        """One row per job, from the Table rpc (the columns of `dlmfd table`, table.py): the
        study's jobs, oldest first; or `jobs` (ids or Job messages), in that order; or the jobs
        with the tag, states (and study) given, oldest first.

        frame: True for a pandas DataFrame, False for a list of dicts, None for a DataFrame when
        pandas imports."""
        if jobs is None and study_id and not tag and not states:
            rows = list(self._unary("Table", jobs_pb2.TableRequest(study_id=study_id)).rows)
        else:
            if jobs is None:
                jobs = sorted(self.jobs(states=states, tag=tag, study_id=study_id),
                              key=lambda j: (j.created_time, j.id))
            ids = [j if isinstance(j, str) else j.id for j in jobs]
            rows = []
            for start in range(0, len(ids), _TABLE_IDS):
                request = jobs_pb2.TableRequest(job_ids=ids[start:start + _TABLE_IDS])
                rows.extend(self._unary("Table", request).rows)
        return study_table.as_table(study_table.rows_of(rows), frame)


_TABLE_IDS = 1000  # the most job ids one Table rpc takes

_HEALTH = {0: "UNKNOWN", 1: "SERVING", 2: "NOT_SERVING", 3: "SERVICE_UNKNOWN"}


def _health_status(data):
    """The status of a grpc.health.v1.HealthCheckResponse: its one field, 1, a varint enum (the
    message is decoded by hand: Debian has no grpc_health package)."""
    status, shift, k = 0, 0, 0
    if data[:1] == b"\x08":
        k = 1
        while k < len(data):
            status |= (data[k] & 0x7F) << shift
            shift += 7
            k += 1
            if not data[k - 1] & 0x80:
                break
    return _HEALTH.get(status, str(status))


def point_folder(job):
    """The folder name of a study's job, as `dlmfd fetch --study` names it."""
    name = ",".join(f"{p.key}={p.text}" for p in job.parameters) or job.name or job.id
    name = re.sub(r"[^A-Za-z0-9._=,+*\-]", "_", name)
    return (job.id if name in (".", "..") else name)[:200]


def _write_job_json(out, job):
    job_json = json_format.MessageToJson(job, preserving_proto_field_name=True,
                                         including_default_value_fields=True, indent=None)
    temporary = out / ".job.json.part"
    temporary.write_text(job_json + "\n")
    os.replace(temporary, out / "job.json")


def _state_values(states):
    """JobState values from values or names ("RUNNING")."""
    return [jobs_pb2.JobState.Value(s) if isinstance(s, str) else s for s in states]


def _job_ids(jobs):
    """Job ids from ids or Job messages; one id alone is a list of one."""
    if isinstance(jobs, str):
        return [jobs]
    return [job if isinstance(job, str) else job.id for job in jobs]
