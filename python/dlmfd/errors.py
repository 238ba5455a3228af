"""Errors of the job API as Python exceptions.

Every rpc failure of dlmfdd (proto/dlmfd/v1/jobs.proto, docs/api.md) is raised as a subclass of
DlmfdError, chosen by its gRPC status code, so a notebook can catch exactly what it expects:
``except dlmfd.InvalidArgument as e: print(e.key)``. The daemon's message for an invalid scene
starts with the dotted scene key (``fluid.viscosity = -1 is not allowed: expected > 0``, the text
of the engine's InvalidParameter); InvalidArgument splits it into ``key``, ``value`` and
``allowed``.
"""

import re

import grpc


class DlmfdError(Exception):
    """An rpc of dlmfdd failed. ``code`` is the grpc.StatusCode, ``message`` the daemon's text."""

    def __init__(self, code, message, rpc=""):
        self.code = code
        self.message = message
        self.rpc = rpc
        name = code.name.lower().replace("_", " ") if code is not None else "error"
        super().__init__(f"{rpc}: {name}: {message}" if rpc else f"{name}: {message}")


class InvalidArgument(DlmfdError):
    """INVALID_ARGUMENT: a bad scene, override or request field.

    ``key``, ``value`` and ``allowed`` are the parts of "KEY = VALUE is not allowed: expected
    ALLOWED" when the message has that shape (else None); ``key`` is the dotted scene key.
    """

    _SHAPE = re.compile(r"^(?P<key>[^\s=]+) = (?P<value>.*?) is not allowed: expected (?P<allowed>.*)$",
                        re.DOTALL)

    def __init__(self, code, message, rpc=""):
        super().__init__(code, message, rpc)
        match = self._SHAPE.match(message)
        self.key = match.group("key") if match else None
        self.value = match.group("value") if match else None
        self.allowed = match.group("allowed") if match else None


class NotFound(DlmfdError):
    """NOT_FOUND: no such job, study or file for this user."""


class Unauthenticated(DlmfdError):
    """UNAUTHENTICATED or PERMISSION_DENIED: a missing or unknown token."""


class ResourceExhausted(DlmfdError):
    """RESOURCE_EXHAUSTED: scene or grid too large, or the queue is full."""


class FailedPrecondition(DlmfdError):
    """FAILED_PRECONDITION, ALREADY_EXISTS or ABORTED: e.g. cancelling a finished job."""


class Unavailable(DlmfdError):
    """UNAVAILABLE or DEADLINE_EXCEEDED: no daemon answering at that address."""


_BY_CODE = {
    grpc.StatusCode.INVALID_ARGUMENT: InvalidArgument,
    grpc.StatusCode.OUT_OF_RANGE: InvalidArgument,
    grpc.StatusCode.NOT_FOUND: NotFound,
    grpc.StatusCode.UNAUTHENTICATED: Unauthenticated,
    grpc.StatusCode.PERMISSION_DENIED: Unauthenticated,
    grpc.StatusCode.RESOURCE_EXHAUSTED: ResourceExhausted,
    grpc.StatusCode.FAILED_PRECONDITION: FailedPrecondition,
    grpc.StatusCode.ALREADY_EXISTS: FailedPrecondition,
    grpc.StatusCode.ABORTED: FailedPrecondition,
    grpc.StatusCode.UNAVAILABLE: Unavailable,
    grpc.StatusCode.DEADLINE_EXCEEDED: Unavailable,
}


def from_rpc_error(error, rpc=""):
    """The DlmfdError subclass for a grpc.RpcError raised by a stub call."""
    code = error.code() if hasattr(error, "code") else None
    message = error.details() if hasattr(error, "details") else str(error)
    return _BY_CODE.get(code, DlmfdError)(code, message or "", rpc)
