"""Parameter files: YAML in and out, validated, written atomically.

The YAML shape is ``FrictionParams.to_dict``/``from_dict`` (driven by the parameter schema of
``model.params``). A parameter file is a few kilobytes; a file larger than ``MAX_FILE_BYTES``
or a transition curve with more than ``model.params.MAX_KNOTS`` knots is refused before it
can stall anything.
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import yaml

from ..model import FrictionParams, ParameterError

MAX_FILE_BYTES = 1_000_000

_Loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


def load_params(path: str | os.PathLike) -> FrictionParams:
    """Read and validate a parameter file; every problem is one line naming the file and field."""
    path = Path(path)
    try:
        if path.is_dir():
            raise ParameterError(f"{path}: is a directory, not a parameter file")
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise ParameterError(f"{path}: {size} bytes; a parameter file is at most {MAX_FILE_BYTES} bytes")
        text = path.read_text(encoding="utf-8")
    except OSError as e:
        raise ParameterError(f"{path}: cannot read ({e.strerror})") from None
    except UnicodeDecodeError as e:
        raise ParameterError(f"{path}: not a UTF-8 text file (byte {e.start})") from None
    return params_from_yaml(text, str(path))


def params_from_yaml(text: str, name: str = "<yaml>") -> FrictionParams:
    """Parse and validate YAML text (an upload, a file's content); errors are prefixed by ``name``."""
    if len(text) > MAX_FILE_BYTES:
        raise ParameterError(f"{name}: {len(text)} characters; a parameter file is at most {MAX_FILE_BYTES}")
    try:
        data = yaml.load(text, Loader=_Loader)  # noqa: S506 - a safe loader
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = f" line {mark.line + 1}" if mark is not None else ""
        problem = str(getattr(e, "problem", None) or e).splitlines()[0]
        raise ParameterError(f"{name}:{where} not valid YAML ({problem})") from None
    except (ValueError, OverflowError, RecursionError) as e:
        # the YAML constructors raise these for values they cannot build (a timestamp with
        # month 13, an integer beyond Python's digit limit, nesting too deep)
        msg = str(e).splitlines()[0] if str(e) else type(e).__name__
        raise ParameterError(f"{name}: a value YAML cannot read ({msg[:120]})") from None
    if data is None:
        raise ParameterError(f"{name}: the file is empty (a parameter file holds stribeck:, transition_curve: "
                             "and the other fields; `leuven-friction fit` writes one)")
    try:
        return FrictionParams.from_dict(data)
    except ParameterError as e:
        raise ParameterError(f"{name}: {e}") from None
    except RecursionError:
        raise ParameterError(f"{name}: nested too deeply") from None


def params_to_yaml(params: FrictionParams) -> str:
    # allow_unicode: the provenance's words (ζ, √, σ, "Savitzky–Golay") as written, not as
    # \u escapes continued over lines with backslashes; the text is UTF-8 wherever it goes
    return yaml.safe_dump(params.to_dict(), sort_keys=False, default_flow_style=None, width=100, allow_unicode=True)


def save_params(params: FrictionParams, path: str | os.PathLike) -> None:
    """Write via a temporary file and rename, so a failure never leaves half a file."""
    write_atomic(path, params_to_yaml(params.validate()))


def write_atomic(path: str | os.PathLike, text: str) -> None:
    path = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent if str(path.parent) else ".")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as fh:
            fh.write(text)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; a user's output file gets the usual mode
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise
