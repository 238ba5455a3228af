"""``python -m dlmfd VERB ...`` (also the ``dlmfd-py`` script): the job verbs of the ``dlmfd`` CLI
(docs/cli.md) through this package, for a machine with Python but no C++ build, and ``open``, a
summary of a local results directory.

    python -m dlmfd --server 127.0.0.1:7443 submit scene.toml --set time.end=1 --wait
    python -m dlmfd list --state running
    python -m dlmfd table --study s-3f2a          # the daemon's table, as CSV
    python -m dlmfd table runs/a runs/b           # a local table of results directories

Exit codes follow the CLI's (docs/cli.md): 2 usage or INVALID_ARGUMENT, 3 NOT_FOUND, 4
UNAUTHENTICATED, 5 UNAVAILABLE, 6 FAILED_PRECONDITION, 7 RESOURCE_EXHAUSTED, 8 other, 1 a job that
ended FAILED or CANCELLED.
"""

import argparse
import json
import os
import sys

import grpc
from google.protobuf import json_format

from . import errors
from .client import Client, state_name
from .run import open as open_run
from .run import table as local_table

_EXIT = {errors.InvalidArgument: 2, errors.NotFound: 3, errors.Unauthenticated: 4,
         errors.Unavailable: 5, errors.FailedPrecondition: 6, errors.ResourceExhausted: 7}


def _job_line(job):
    return f"{job.id}  {job.name or '-'}  {state_name(job.state)}  step {job.progress.step}"


def _json(message):
    return json_format.MessageToJson(message, preserving_proto_field_name=True, indent=None)


def _parser():
    p = argparse.ArgumentParser(prog="python -m dlmfd", description=__doc__.split("\n\n")[0])
    p.add_argument("--server", help="HOST:PORT (default $DLMFD_SERVER, else 127.0.0.1:7443)")
    p.add_argument("--token", help="bearer token (default $DLMFD_TOKEN)")
    p.add_argument("--timeout", type=float, default=30.0, help="seconds per rpc (default 30)")
    p.add_argument("--version", action="store_true", help="print the package's version")
    verbs = p.add_subparsers(dest="verb")
    s = verbs.add_parser("submit", help="queue a scene file")
    s.add_argument("scene")
    s.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    s.add_argument("--name", default="")
    s.add_argument("--tag", action="append", default=[])
    s.add_argument("--priority", type=int, default=0)
    s.add_argument("--wait", action="store_true", help="watch to the end; exit 1 unless completed")
    s = verbs.add_parser("study", help="queue a study: --grid KEY=V1,V2 (repeatable)")
    s.add_argument("scene")
    s.add_argument("--grid", action="append", default=[], metavar="KEY=V1,V2,...")
    s.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    s.add_argument("--name", default="")
    s.add_argument("--tag", action="append", default=[])
    s.add_argument("--max-running", type=int, default=0)
    verbs.add_parser("studies", help="your studies").add_argument("--tag", default="")
    s = verbs.add_parser("list", help="your jobs, newest first")
    s.add_argument("--state", action="append", default=[])
    s.add_argument("--tag", default="")
    s.add_argument("--study", default="")
    s = verbs.add_parser("show", help="one job, or a study with --study")
    s.add_argument("job", nargs="?")
    s.add_argument("--study", default="")
    verbs.add_parser("watch", help="a job's events to its end").add_argument("job")
    s = verbs.add_parser("cancel", help="jobs, or a study's unfinished jobs")
    s.add_argument("jobs", nargs="*")
    s.add_argument("--study", default="")
    s = verbs.add_parser("retry", help="rerun finished jobs")
    s.add_argument("jobs", nargs="*")
    s.add_argument("--study", default="")
    s.add_argument("--state", action="append", default=[])
    s.add_argument("--set", action="append", default=[], metavar="KEY=VALUE")
    s = verbs.add_parser("fetch", help="a job's results, or every job of a study")
    s.add_argument("job", nargs="?")
    s.add_argument("--study", default="")
    s.add_argument("--out")
    s.add_argument("--path", action="append", default=[])
    s = verbs.add_parser("logs", help="a job's solver log")
    s.add_argument("job")
    s.add_argument("--follow", action="store_true")
    s = verbs.add_parser("inputs", help="a job's scene as submitted (or --as-run)")
    s.add_argument("job")
    s.add_argument("--as-run", action="store_true")
    s = verbs.add_parser("table", help="a study's table (--study), or of local results dirs")
    s.add_argument("dirs", nargs="*")
    s.add_argument("--study", default="")
    s = verbs.add_parser("delete", help="jobs' records and results")
    s.add_argument("jobs", nargs="*")
    s.add_argument("--study", default="")
    s.add_argument("--force", action="store_true")
    s = verbs.add_parser("priority", help="a queued job's priority, -1000..1000")
    s.add_argument("job")
    s.add_argument("priority", type=int)
    verbs.add_parser("hold", help="keep a queued job from starting").add_argument("job")
    verbs.add_parser("release", help="let a held job start").add_argument("job")
    verbs.add_parser("health", help="whether the daemon serves")
    verbs.add_parser("open", help="a local results directory's summary").add_argument("dir")
    return p


def _grid(texts):
    axes = {}
    for text in texts:
        key, _, values = text.partition("=")
        if not key or not values:
            raise SystemExit(f"python -m dlmfd study: --grid {text}: expected KEY=V1,V2,...")
        axes[key] = values.split(",")
    return axes


def _run(args, client):
    verb = args.verb
    if verb == "submit":
        job = client.submit(args.scene, args.set, name=args.name, tags=args.tag,
                            priority=args.priority)
        print(job.id)
        if args.wait:
            job = client.wait(job.id)
            print(_job_line(job), file=sys.stderr)
            return 0 if state_name(job.state) == "COMPLETED" else 1
    elif verb == "study":
        study_id, jobs = client.submit_study(args.scene, _grid(args.grid), overrides=args.set,
                                      name=args.name, tags=args.tag, max_running=args.max_running)
        print(study_id)
        for job in jobs:
            print(_job_line(job))
    elif verb == "studies":
        for study in client.studies(tag=args.tag):
            print(_json(study))
    elif verb == "list":
        for job in client.jobs(states=[s.upper() for s in args.state], tag=args.tag,
                               study_id=args.study):
            print(_job_line(job))
    elif verb == "show":
        print(_json(client.study(args.study) if args.study else client.job(args.job)))
    elif verb == "watch":
        for event in client.watch(args.job):
            print(_json(event))
        return 0 if state_name(client.job(args.job).state) == "COMPLETED" else 1
    elif verb == "cancel":
        jobs = client.cancel_study(args.study) if args.study else [client.cancel(j)
                                                                   for j in args.jobs]
        for job in jobs:
            print(_job_line(job))
    elif verb == "retry":
        for job in client.retry(args.jobs, study_id=args.study,
                                states=[s.upper() for s in args.state], overrides=args.set):
            print(_job_line(job))
    elif verb == "fetch":
        if args.study:
            for folder, job in client.fetch_study(args.study, args.out, args.path).items():
                print(f"{folder}  {job.id}  {state_name(job.state)}")
        else:
            print(client.fetch(args.job, args.out, args.path))
    elif verb == "logs":
        sys.stdout.write(client.logs(args.job, follow=args.follow))
    elif verb == "inputs":
        inputs = client.inputs(args.job)
        if args.as_run:
            if not inputs.scene_as_run:
                raise errors.NotFound(grpc.StatusCode.NOT_FOUND,
                                      f"job {args.job} has no scene as run yet", "GetInputs")
            sys.stdout.write(inputs.scene_as_run)
        else:
            for override in inputs.overrides:
                print(f"# --set {override}")
            sys.stdout.write(inputs.scene)
    elif verb == "table":
        frame = local_table(args.dirs) if args.dirs else client.table(study_id=args.study)
        sys.stdout.write(frame.to_csv(index=False))
    elif verb == "delete":
        deleted, freed = client.delete(args.jobs, study_id=args.study, force=args.force)
        print("\n".join(deleted))
        print(f"deleted {len(deleted)} jobs, {freed} bytes freed", file=sys.stderr)
    elif verb == "priority":
        print(_job_line(client.set_priority(args.job, args.priority)))
    elif verb in ("hold", "release"):
        print(_job_line(getattr(client, verb)(args.job)))
    elif verb == "health":
        status = client.health()
        print(f"{status} {client.server}")
        return 0 if status == "SERVING" else 5
    return 0


def main(argv=None):
    args = _parser().parse_args(argv)
    if args.version:
        from . import __version__
        print(__version__)
        return 0
    if args.verb is None:
        _parser().print_help()
        return 2
    if args.verb == "open":
        run = open_run(args.dir)
        summary = run.summary if os.path.exists(os.path.join(run.path, "summary.json")) else {}
        print(json.dumps({k: summary.get(k) for k in ("status", "steps", "time", "fall_speed",
                                                       "max_trA", "min_gap")}))
        return 0
    try:
        with Client(args.server, args.token, args.timeout) as client:
            return _run(args, client)
    except errors.DlmfdError as error:
        print(f"python -m dlmfd {args.verb}: {error.message}", file=sys.stderr)
        return _EXIT.get(type(error), 8)
    except (FileNotFoundError, NotADirectoryError) as error:
        print(f"python -m dlmfd {args.verb}: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
