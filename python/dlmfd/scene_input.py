"""What a notebook hands to submit and study: scene text, overrides and axis values.

A scene is TOML text, or a path (a pathlib.Path, or a str naming an existing file and holding no
newline) whose text is sent. Overrides are the ``key=value`` texts of ``dlmfd-solve --set``
(docs/scenes.md), given as a list of such strings or as a dict ``{"fluid.relaxation_time": 1.4}``.
A Python value becomes TOML value text: bool -> true/false, int and float -> their shortest repr,
list/tuple -> an array; a str is taken as TOML text already (``"\\"wave\\""`` for a TOML string).
"""

import os
import pathlib


def _looks_like_a_path(text):
    """One line with no "=": no scene (every TOML key-value line has one) but a file name."""
    return "\n" not in text and "=" not in text and text.strip() != ""


def scene_text(scene):
    """The TOML text of a scene given as text or as a path. A path (a PathLike, or one line
    without "=") that names no file raises FileNotFoundError naming it."""
    if isinstance(scene, os.PathLike) or (isinstance(scene, str) and _looks_like_a_path(scene)):
        path = pathlib.Path(scene)
        if not path.is_file():
            raise FileNotFoundError(f"scene file {path} does not exist" if not path.exists()
                                    else f"scene file {path} is not a file")
        return path.read_text()
    if isinstance(scene, str) and "\n" not in scene and os.path.isfile(scene):
        return pathlib.Path(scene).read_text()
    if not isinstance(scene, str):
        raise TypeError(f"scene: expected TOML text or a path, got {type(scene).__name__}")
    return scene


def toml_value(value):
    """TOML value text of a Python value (a str is taken as TOML text already)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(toml_value(v) for v in value) + "]"
    if isinstance(value, str):
        return value
    raise TypeError(f"cannot write {type(value).__name__} {value!r} as a TOML value")


def override_texts(overrides):
    """["key=value", ...] from None, a dict or an iterable of "key=value" strings."""
    if overrides is None:
        return []
    if isinstance(overrides, dict):
        return [f"{key}={toml_value(value)}" for key, value in overrides.items()]
    if isinstance(overrides, str):
        raise TypeError("overrides: expected a dict or a list of \"key=value\" strings, got a str")
    return [str(o) for o in overrides]
