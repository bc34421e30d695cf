"""The files a command writes: checked before the work starts, written all or none.

A command names its outputs first (``Outputs({"--out": path, "--json": other})``): each path is
checked at once (its directory exists and is writable, it is not a directory, an existing file
is not read-only), so that a mistake is a one-line error before a long fit, not a traceback
after it. Inside the ``with`` block the command stages its outputs (``write_text``/``write_bytes``
write temporary files beside their targets); leaving the block normally renames them all into
place, leaving it by an exception removes them all. A failing command therefore leaves nothing
behind, and a reader never sees half a file.
"""

from __future__ import annotations

import json
import math
import os
import stat
import tempfile
from pathlib import Path

from ..model.errors import FrictionError


class OutputError(FrictionError):
    """An output path that cannot be written; names the option and the path."""


def check_output_path(path: str | os.PathLike, option: str = "output") -> Path:
    """The path, or an OutputError saying in one line why it cannot be written."""
    p = Path(path)
    if not str(path).strip():
        raise OutputError(f"{option}: empty path")
    if p.is_dir():
        raise OutputError(f"{option} {path}: is a directory; give a file name")
    parent = p.parent
    if not parent.exists():
        raise OutputError(f"{option} {path}: directory {parent} does not exist")
    if not parent.is_dir():
        raise OutputError(f"{option} {path}: {parent} is not a directory")
    if p.exists():
        if not p.is_file():
            raise OutputError(f"{option} {path}: exists and is not a regular file")
        # the mode bits, not os.access: a read-only file stays read-only for root as well
        if not p.stat().st_mode & (stat.S_IWUSR | stat.S_IWGRP | stat.S_IWOTH):
            raise OutputError(f"{option} {path}: the file is read-only")
    try:  # the only sure test of a writable directory is to write in it
        fd, probe = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".probe", dir=parent)
        os.close(fd)
        os.unlink(probe)
    except OSError as e:
        raise OutputError(f"{option} {path}: cannot write in {parent} ({e.strerror})") from None
    return p


class Outputs:
    """All the output files of one command; see the module docstring."""

    def __init__(self, paths):
        """``paths``: {option name: path or None} (or (option, path) pairs, when one option
        names several files); the None ones are not asked for."""
        self._option = {}
        seen = {}
        for option, path in (paths.items() if isinstance(paths, dict) else paths):
            if path is None:
                continue
            p = check_output_path(path, option)
            key = os.path.realpath(p)
            if key in seen:
                raise OutputError(f"{option} {path}: the same file as {seen[key]}")
            seen[key] = option
            self._option[key] = option
        self._staged: list[tuple[str, Path]] = []

    def __enter__(self) -> "Outputs":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        if exc_type is None:
            self.commit()
        else:
            self.discard()

    def stage(self, path: str | os.PathLike) -> Path:
        """An empty temporary file beside ``path`` for a writer that streams (a big CSV, a
        Parquet file); renamed into place with the others on leaving the block."""
        p = Path(path)
        option = self._option.get(os.path.realpath(p))
        if option is None:
            raise RuntimeError(f"{path}: not declared as an output of this command")  # a bug, not a user error
        try:
            fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".part", dir=p.parent)
            os.close(fd)
        except OSError as e:
            raise OutputError(f"{option} {path}: cannot write ({e.strerror})") from None
        self._staged.append((tmp, p))
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; an output file gets the usual mode
        return Path(tmp)

    def write_text(self, path: str | os.PathLike, text: str) -> None:
        self.write_bytes(path, text.encode("utf-8"))

    def write_bytes(self, path: str | os.PathLike, data: bytes) -> None:
        p = Path(path)
        key = os.path.realpath(p)
        option = self._option.get(key)
        if option is None:
            raise RuntimeError(f"{path}: not declared as an output of this command")  # a bug, not a user error
        try:
            fd, tmp = tempfile.mkstemp(prefix=f".{p.name}.", suffix=".part", dir=p.parent)
        except OSError as e:
            raise OutputError(f"{option} {path}: cannot write ({e.strerror})") from None
        self._staged.append((tmp, p))
        try:
            with os.fdopen(fd, "wb") as fh:
                fh.write(data)
            umask = os.umask(0)
            os.umask(umask)
            os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; an output file gets the usual mode
        except OSError as e:
            raise OutputError(f"{option} {path}: cannot write ({e.strerror})") from None

    def commit(self) -> None:
        """Rename every staged file into place (renames within a directory do not fail
        half-way like a write can)."""
        staged, self._staged = self._staged, []
        try:
            for i, (tmp, target) in enumerate(staged):
                os.replace(tmp, target)
        except OSError as e:
            for tmp, _ in staged[i:]:
                _remove(tmp)
            raise OutputError(f"{self._option[os.path.realpath(target)]} {target}: cannot write ({e.strerror})") from None

    def discard(self) -> None:
        for tmp, _ in self._staged:
            _remove(tmp)
        self._staged = []


def json_text(obj) -> str:
    """``obj`` as JSON that any reader parses: a value that is not a finite number (a regime
    too short for its noise floor: NaN) written as null, where ``json.dumps`` writes a bare
    ``NaN`` that JavaScript's and strict parsers refuse."""

    def finite(o):
        if isinstance(o, float):
            return o if math.isfinite(o) else None
        if isinstance(o, dict):
            return {k: finite(v) for k, v in o.items()}
        if isinstance(o, (list, tuple)):
            return [finite(v) for v in o]
        return o

    return json.dumps(finite(obj), indent=2, allow_nan=False) + "\n"


def _remove(path: str) -> None:
    try:
        os.unlink(path)
    except FileNotFoundError:
        pass


def write_outputs(files: dict) -> None:
    """Check and write several files at once, all or none: {option: (path, text)}."""
    with Outputs({opt: path for opt, (path, _) in files.items()}) as out:
        for path, text in files.values():
            out.write_text(path, text)
