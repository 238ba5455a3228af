"""The package's version (pyproject.toml reads it)."""

__version__ = "0.3.0"
