"""Builds the package's protobuf and gRPC stubs (dlmfd/v1) from ../proto before setuptools
reads the package (pyproject.toml holds everything else): at every setup.py run, since the
metadata step already lists dlmfd.v1.

The stubs come from protoc with grpc_python_plugin (Debian's protobuf-compiler and
protobuf-compiler-grpc, the versions of python3-protobuf and python3-grpcio), else from
grpcio-tools (`python -m grpc_tools.protoc`); a source tree that already holds them (an sdist)
needs neither. A missing generator is an error that names both.
"""

import pathlib
import shutil
import subprocess
import sys

from setuptools import setup

HERE = pathlib.Path(__file__).resolve().parent
PROTO = HERE.parent / "proto"
STUBS = HERE / "dlmfd" / "v1"
NAMES = ("events_pb2.py", "jobs_pb2.py", "jobs_pb2_grpc.py")


def generate_stubs():
    if all((STUBS / name).exists() for name in NAMES) and not PROTO.is_dir():
        return  # an sdist: the stubs came with it
    if not PROTO.is_dir():
        raise SystemExit(f"dlmfd: {PROTO} is missing: build the package from the repository "
                         "(pip install ./python)")
    sources = [str(PROTO / "dlmfd" / "v1" / "events.proto"), str(PROTO / "dlmfd" / "v1" / "jobs.proto")]
    protoc, plugin = shutil.which("protoc"), shutil.which("grpc_python_plugin")
    if protoc and plugin:
        commands = [[protoc, f"--python_out={HERE}", "-I", str(PROTO), *sources],
                    [protoc, f"--grpc_python_out={HERE}", f"--plugin=protoc-gen-grpc_python={plugin}",
                     "-I", str(PROTO), sources[1]]]
    else:
        try:
            import grpc_tools  # noqa: F401
        except ImportError:
            raise SystemExit("dlmfd: cannot generate the gRPC stubs: install protoc and "
                             "grpc_python_plugin (Debian: protobuf-compiler protobuf-compiler-grpc) "
                             "or grpcio-tools") from None
        commands = [[sys.executable, "-m", "grpc_tools.protoc", f"--python_out={HERE}",
                     f"--grpc_python_out={HERE}", "-I", str(PROTO), *sources]]
    STUBS.mkdir(parents=True, exist_ok=True)
    for command in commands:
        subprocess.run(command, check=True)
    (STUBS / "__init__.py").touch()


generate_stubs()
setup()
