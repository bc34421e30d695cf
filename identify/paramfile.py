"""Parameter files: YAML in and out, validated, written atomically."""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import yaml

from ..model import FrictionParams, ParameterError


def load_params(path: str | os.PathLike) -> FrictionParams:
    """Read and validate a parameter file; every problem is one line naming the file and field."""
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as e:
        raise ParameterError(f"{path}: cannot read ({e.strerror})") from None
    try:
        data = yaml.safe_load(text)
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = f" line {mark.line + 1}" if mark is not None else ""
        raise ParameterError(f"{path}:{where} not valid YAML ({getattr(e, 'problem', e)})") from None
    try:
        return FrictionParams.from_dict(data)
    except ParameterError as e:
        raise ParameterError(f"{path}: {e}") from None


def params_to_yaml(params: FrictionParams) -> str:
    return yaml.safe_dump(params.to_dict(), sort_keys=False, default_flow_style=None, width=100)


def save_params(params: FrictionParams, path: str | os.PathLike) -> None:
    """Write via a temporary file and rename, so a failure never leaves half a file."""
    write_atomic(path, params_to_yaml(params.validate()))


def write_atomic(path: str | os.PathLike, text: str) -> None:
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent if str(path.parent) else ".")
    try:
        with os.fdopen(fd, "w") as fh:
            fh.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; a user's output file gets the usual mode
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
