"""Tables in and out at the speed of the formats' libraries, with bounded memory.

Readers (``read_table_file``) take a path and return a DataFrame of the file's columns:

* CSV/TSV: the dialect (separator, decimal mark) is guessed from the first lines only
  (``sniff``), then pandas' C parser reads straight from the file, so a big recording is
  never held as one Python string (nor as the 4-byte-per-character copy ``io.StringIO``
  makes of it); ``usecols`` keeps only the columns asked for.
* Parquet (``.parquet``, ``.pq``; optional extra ``pyarrow``): only the columns asked for
  are read.
* MATLAB ``.mat`` (``scipy.io.loadmat``, files up to v7; v7.3 is HDF5 and is refused with a
  note): every numeric vector of the file's common length becomes a column, named as the
  variable (``struct.field`` for fields of a struct, ``name_1``, ``name_2``, … for the columns
  of a matrix).

Writers (``write_table``) take named columns of equal length: CSV in ``%.10g`` (the format the
command line has always written), a block of rows at a time, by a compiled formatter
(``identify.csvformat``) for float columns, else by one C-level string format of the block
instead of one Python call per value; Parquet through pyarrow.

Every problem a user can cause is a ``DataError`` naming the file.
"""

from __future__ import annotations

import re
from pathlib import Path
from typing import Callable, Iterable

import numpy as np

from .errors import DataError

PARQUET_SUFFIXES = (".parquet", ".pq")
MAT_SUFFIXES = (".mat",)
SNIFF_BYTES = 1 << 16
SNIFF_ROWS = 20  # data lines the decimal mark is guessed from
CSV_FORMAT = "%.10g"
CSV_BLOCK_ROWS = 65536


def table_format(path) -> str:
    """'parquet', 'mat' or 'csv', from the file name's suffix."""
    suffix = Path(path).suffix.lower()
    if suffix in PARQUET_SUFFIXES:
        return "parquet"
    if suffix in MAT_SUFFIXES:
        return "mat"
    return "csv"


# ---------------------------------------------------------------- CSV dialect
def sniff(lines: Iterable[str]) -> tuple[str, str]:
    """(separator, decimal mark) from the first lines of a table: the separator is the most
    frequent of tab, semicolon and comma in the header (the first line that is not blank or a
    ``#`` comment), else whitespace; a semicolon table with a digit, comma, digit in its
    first SNIFF_ROWS data lines uses the decimal comma (European CSV), and
    so does a tab- or whitespace-separated one whose first data lines have a digit, comma,
    digits (other than exactly three, which may group thousands) and no digit, point, digit
    (where a comma cannot separate columns)."""
    rows = [ln for ln in lines if ln.strip() and not ln.lstrip().startswith("#")]
    first = rows[0] if rows else ""
    counts = {"\t": first.count("\t"), ";": first.count(";"), ",": first.count(",")}
    sep = max(counts, key=counts.get) if max(counts.values()) > 0 else r"\s+"
    decimal = "."
    data = "\n".join(rows[1:SNIFF_ROWS + 1])  # a first row of whole numbers says nothing: look at a few
    if sep == ";" and re.search(r"\d,\d", data):
        decimal = ","
    elif (sep in ("\t", r"\s+") and not re.search(r"\d\.\d", data)
          and re.search(r"\d,(\d{1,2}|\d{4,})(?!\d)", data)):
        # a comma followed by exactly three digits everywhere may group thousands ("1,234"):
        # only other counts of digits make it a decimal mark
        decimal = ","
    return sep, decimal


def _names_columns(fields: list[str]) -> bool:
    """Whether a row's fields read as a header: one of them at least is no number (in either
    decimal mark) and not empty; a data row's "2.5e-05" has a letter too."""
    def number(f: str) -> bool:
        try:
            float(f.strip().replace(",", "."))
            return True
        except ValueError:
            return False

    return any(f.strip() and not number(f) for f in fields)


PREAMBLE_TAIL = 20  # rows at the end of a sniffed block that set a table's number of fields (``preamble_lines``)


def preamble_lines(lines: list[str]) -> int:
    """How many lines at the start of a delimited table precede its header: an instrument's
    export opens with notes of its own ("Instrument: …", "Load: 10 N", a blank line) before the
    names of its columns, none of them ``#`` comments (a tribometer's export made apart was
    refused with "line 2 has 4 fields, the header 2", its first note read as the header).
    The table's shape is the number of tab, semicolon or comma separators shared by at least
    80 % of the last PREAMBLE_TAIL rows of the block (the last line, which may be cut, left
    to the caller); the header is the first row with that many, where every row before it has
    another number and the PREAMBLE_TAIL rows after it all have it. 0 where the first row is
    the header, or no separator gives such a shape (the reader then goes on as before)."""
    rows = [(i, ln) for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith("#")]
    if len(rows) < 4:
        return 0
    tail = [ln for _, ln in rows[-PREAMBLE_TAIL:]]
    for sep in ("\t", ";", ","):
        counts = [ln.count(sep) for _, ln in rows]
        m = max(set(c for c in (ln.count(sep) for ln in tail)), key=[ln.count(sep) for ln in tail].count)
        if m == 0 or sum(ln.count(sep) == m for ln in tail) < 0.8 * len(tail):
            continue
        k = next((j for j, c in enumerate(counts) if c == m), None)
        if k is None or k == 0:
            return 0  # the first row has the table's shape: it is the header (or this separator is not the table's)
        if all(c == m for c in counts[k + 1:k + 1 + PREAMBLE_TAIL]) and _names_columns(rows[k][1].split(sep)):
            return rows[k][0]
        return 0
    return 0


WORKBOOKS = ((b"PK\x03\x04", "a zip archive (an Excel .xlsx or OpenDocument .ods workbook is one)"),
             (b"\xd0\xcf\x11\xe0\xa1\xb1\x1a\xe1", "an Excel 97–2003 .xls workbook"))


def refuse_workbook(head: bytes, label) -> None:
    """A spreadsheet workbook given as a recording is refused saying what to do, before its
    bytes are read as text (they decode to a column named 'PK…')."""
    for magic, what in WORKBOOKS:
        if head.startswith(magic):
            raise DataError(f"{label}: {what}, not a text table: save the sheet as CSV (UTF-8) from the "
                            f"spreadsheet program and give that file")


def decode_text(raw: bytes, label) -> tuple[str, str]:
    """(text, encoding) of a table's bytes: UTF-8 (with or without a byte-order mark), else
    Windows-1252, which many lab programs on Windows still write (µ, °, ä as one byte each)."""
    refuse_workbook(raw[:16], label)
    if b"\0" in raw[:SNIFF_BYTES]:
        # a picture, an archive or a program's own format: Windows-1252 decodes nearly any bytes,
        # and a PNG uploaded by mistake had been read as a table of one column named '‰PNG'
        raise DataError(f"{label}: not a text file (it contains NUL bytes)")
    try:
        return raw.decode("utf-8-sig"), "utf-8-sig"
    except UnicodeDecodeError:
        pass
    try:
        return raw.decode(LEGACY_ENCODING), LEGACY_ENCODING
    except UnicodeDecodeError:
        raise DataError(f"{label}: not a text file (could not decode as UTF-8 or Windows-1252)") from None


LEGACY_ENCODING = "cp1252"


def _head_text(path: Path) -> tuple[str, str]:
    try:
        with open(path, "rb") as fh:
            head = fh.read(SNIFF_BYTES)
    except OSError as e:
        raise DataError(f"{path}: cannot read ({e.strerror})") from None
    refuse_workbook(head, path)
    if b"\0" in head:
        raise DataError(f"{path}: not a text file (it contains NUL bytes)")
    try:
        return head.decode("utf-8-sig"), "utf-8-sig"
    except UnicodeDecodeError as e:
        if e.start >= len(head) - 4:  # only a character cut at the end of the sniffed block
            return head[: e.start].decode("utf-8-sig"), "utf-8-sig"
    return decode_text(head, path)


RAGGED_BLOCK = 1 << 23  # bytes ``ragged_line`` counts at once (its memory: a few times this)


def ragged_line(path: Path, sep: str, preamble: int = 0) -> tuple[int, int, int] | None:
    """(line number, fields, fields of the header) of the first line of a delimited table with
    more fields than its header, or None. Reading only some columns, pandas drops such a
    line's extra field silently (and with one more field on every line it would take the first
    column for an index); fewer fields leave a gap, which the reader of each used column
    reports. Counted on the bytes, block by block (a separator is one byte in UTF-8 and
    Windows-1252 alike); a file with quotes, or with a comment after values, is not checked, as
    those may hold the separator. The first ``preamble`` lines (``preamble_lines``) are no rows."""
    if sep == r"\s+":
        return None
    header, before = None, 0
    with open(path, "rb") as fh:
        head = fh.read(3)
        carry = b"" if head == b"\xef\xbb\xbf" else head  # the byte-order mark is not in the first line
        while True:
            block = fh.read(RAGGED_BLOCK)
            data = carry + block
            if not data:
                return None
            if block:  # the unfinished last line waits for the next block
                cut = data.rfind(b"\n") + 1
                data, carry = data[:cut], data[cut:]
                if not data:
                    continue
            else:
                carry = b""
            buf = np.frombuffer(data, dtype=np.uint8)
            if np.any(buf == ord('"')):
                return None
            nl = np.flatnonzero(buf == ord("\n"))
            starts = np.concatenate([[0], nl + 1])
            starts = starts[starts < len(buf)]
            hashes = np.flatnonzero(buf == ord("#"))
            if np.any(buf[hashes[hashes > 0] - 1] != ord("\n")):
                return None
            fields = np.bincount(np.searchsorted(nl, np.flatnonzero(buf == ord(sep))), minlength=len(starts))
            fields = fields[:len(starts)] + 1
            first = buf[starts]
            nxt = np.concatenate([starts[1:], [len(buf)]])
            # a row: not a # comment, not blank (a lone \r, or whitespace without separators
            # counts as one field and cannot outnumber a header)
            row = (first != ord("#")) & ~((nxt - starts <= 2) & ((first == ord("\r")) | (first == ord("\n"))))
            idx = np.flatnonzero(row)
            idx = idx[before + idx >= preamble]
            if header is None:
                # the header: the first row with more than whitespace on it
                for i in idx:
                    if data[starts[i]:nxt[i]].strip():
                        header, idx = int(fields[i]), idx[idx > i]
                        break
            if header is not None:
                over = idx[fields[idx] > header]
                if len(over):
                    return before + int(over[0]) + 1, int(fields[over[0]]), header
            before += len(starts)
            if not block:
                return None


def line_of_row(lines: Iterable[str], index: int, preamble: int = 0) -> int | None:
    """The line of a text table (1-based, as an editor or a spreadsheet numbers it) that holds
    its data row ``index`` (0-based) as the reader takes them: the ``preamble`` lines
    (``preamble_lines``), blank lines and ``#`` comment lines are skipped, and the first other
    line is the header. None past the last row."""
    header = False
    row = -1
    for number, line in enumerate(lines, 1):
        if number <= preamble:
            continue
        text = line.strip().lstrip("\ufeff")
        if not text or text.startswith("#"):
            continue
        if not header:
            header = True
            continue
        row += 1
        if row == index:
            return number
    return None


def file_line_of_row(path: Path, index: int, preamble: int = 0) -> int | None:
    """``line_of_row`` of a CSV/TSV file, read line by line (only where a message needs it)."""
    with open(path, encoding="utf-8", errors="replace", newline=None) as f:
        return line_of_row(f, index, preamble)


TAIL_BYTES = 1 << 13  # bytes of a file's end ``last_cell_cut`` reads


def last_cell_cut(tail: str, sep: str, decimal: str) -> bool:
    """Whether a delimited table's text ending in ``tail`` was cut inside its last cell: no
    line end after it (a file written to the end closes its last line; a logger stopped or a
    copy interrupted mid-write does not), and that cell shorter after its decimal mark (or,
    without one, in all) than the same cell of every one of the up to ``SNIFF_ROWS`` lines
    before it with as many fields. Only the last cell can be cut: the cells before it on the
    line were written whole. A format whose digits vary from line to line leaves the minimum
    over those lines low, so a cell written whole is rarely taken for cut (and one row left
    out costs a fit nothing)."""
    if not tail or tail.endswith(("\n", "\r")):
        return False
    lines = [ln for ln in tail.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if len(lines) < 3:
        return False

    def fields(line: str) -> list[str]:
        return line.split() if sep == r"\s+" else [c.strip() for c in line.split(sep)]

    def size(cell: str) -> int:
        return len(cell.split(decimal, 1)[1]) if decimal in cell else len(cell)

    last = fields(lines[-1])
    before = [f for f in map(fields, lines[-SNIFF_ROWS - 1:-1]) if len(f) == len(last)]
    # (the tail's first line may itself be cut at the block's start: it is among ``before`` only
    # where it has all its fields, and a short cell there lowers the minimum, which errs on keeping)
    return len(before) >= 2 and size(last[-1]) < min(size(f[-1]) for f in before)


def file_tail(path: Path, encoding: str) -> str:
    """The last ``TAIL_BYTES`` of a text file, decoded (a character cut at the block's start
    is replaced)."""
    with open(path, "rb") as fh:
        fh.seek(0, 2)
        fh.seek(max(fh.tell() - TAIL_BYTES, 0))
        return fh.read().decode(encoding, errors="replace")


def csv_options(sep: str, decimal: str, preamble: int = 0) -> dict:
    """``pandas.read_csv``'s options for a table ``sniff`` read as ``sep``, ``decimal``: the
    reader of files and of text alike. low_memory off: a column is typed once, over the whole
    file (chunk by chunk, a word in one chunk made pandas warn of mixed types on the console,
    before the one-line error that names it); the python engine of whitespace has no such option."""
    c = sep != r"\s+"
    return dict(sep=sep, engine="c" if c else "python", comment="#", skip_blank_lines=True, decimal=decimal,
                skiprows=range(preamble), **({"low_memory": False} if c else {}))


def read_csv_file(path: Path, usecols: Callable[[str], bool] | None = None):
    import pandas as pd

    text, encoding = _head_text(path)
    if not text.strip():
        raise DataError(f"{path}: the file is empty")
    lines = text.splitlines()
    if len(text) == SNIFF_BYTES and len(lines) > 1:
        lines = lines[:-1]  # the last line of the block may be cut
    skip = preamble_lines(lines)
    sep, decimal = sniff(lines[skip:])
    opts = csv_options(sep, decimal, skip)

    def read(enc):
        if usecols is None:
            return pd.read_csv(path, encoding=enc, **opts)
        names = [str(c) for c in pd.read_csv(path, nrows=0, encoding=enc, **opts).columns]
        df = pd.read_csv(path, usecols=lambda c: usecols(str(c)), encoding=enc, **opts)
        df.attrs["columns_in_file"] = names
        return df

    try:
        try:
            df = read(encoding)
        except UnicodeDecodeError:
            if encoding == LEGACY_ENCODING:
                raise
            # UTF-8 as far as the sniffed head went, not beyond it
            encoding = LEGACY_ENCODING
            df = read(encoding)
        if usecols is not None:
            bad = ragged_line(path, sep, skip)
            if bad is not None:
                raise DataError(f"{path}: line {bad[0]} has {bad[1]} fields, the header {bad[2]}")
        df.attrs["encoding"] = encoding
        df.attrs["decimal"] = decimal  # a column holding a word is read as text: its numbers keep their commas
        df.attrs["last_cell_cut"] = last_cell_cut(file_tail(path, encoding), sep, decimal)
        df.attrs["preamble"] = skip
        return df
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as e:
        msg = str(e).splitlines()[0] if str(e) else type(e).__name__
        raise DataError(f"{path}: not a readable CSV/TSV table ({msg})") from None
    except OSError as e:
        raise DataError(f"{path}: cannot read ({e.strerror})") from None


# ---------------------------------------------------------------- Parquet
def require_pyarrow(what: str):
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        raise DataError(f"{what}: Parquet needs the optional dependency pyarrow "
                        "(pip install 'leuven-friction[parquet]')") from None
    return pa, pq


def read_parquet_file(path: Path, usecols: Callable[[str], bool] | None = None):
    pa, pq = require_pyarrow(str(path))
    try:
        schema = pq.read_schema(path)
        names = [n for n in schema.names if usecols is None or usecols(n)]
        table = pq.read_table(path, columns=names)
        df = table.to_pandas()
    except OSError as e:
        raise DataError(f"{path}: cannot read ({getattr(e, 'strerror', None) or str(e).splitlines()[0]})") from None
    except (pa.ArrowInvalid, pa.ArrowNotImplementedError) as e:
        raise DataError(f"{path}: not a readable Parquet file ({str(e).splitlines()[0]})") from None
    df.attrs["columns_in_file"] = list(schema.names)
    return df


# ---------------------------------------------------------------- MATLAB
def read_mat_file(path: Path, usecols: Callable[[str], bool] | None = None):
    import pandas as pd
    import scipy.io

    try:
        data = scipy.io.loadmat(path, squeeze_me=True, struct_as_record=False)
    except NotImplementedError:
        raise DataError(f"{path}: a MATLAB v7.3 (HDF5) file; save it with -v7 or export a CSV") from None
    except (ValueError, TypeError, OSError, scipy.io.matlab.MatReadError) as e:
        # scipy's reader says why in its own words (truncated, not a .mat at all, …)
        reason = (str(e).splitlines() or [type(e).__name__])[0]
        raise DataError(f"{path}: not a readable MATLAB .mat file ({reason})") from None
    columns: dict[str, np.ndarray] = {}

    def add(name: str, value) -> None:
        if hasattr(value, "_fieldnames"):  # a struct: its fields, dotted
            for f in value._fieldnames:
                add(f"{name}.{f}", getattr(value, f))
            return
        a = np.asarray(value)
        if a.dtype.kind not in "fiub" or a.size < 2:
            return
        if a.ndim == 1:
            columns[name] = a.astype(np.float64)
        elif a.ndim == 2:  # one column per signal (a row-per-sample matrix) or per sample
            m = a if a.shape[0] >= a.shape[1] else a.T
            for j in range(m.shape[1]):
                columns[f"{name}_{j + 1}"] = m[:, j].astype(np.float64)

    for name, value in data.items():
        if not name.startswith("__"):
            add(name, value)
    if not columns:
        raise DataError(f"{path}: no numeric vectors in the .mat file")
    lengths = {}
    for name, a in columns.items():
        lengths.setdefault(len(a), []).append(name)
    n = max(lengths, key=lambda k: (len(lengths[k]), k))  # the length most vectors share
    same = [k for k, v in columns.items() if len(v) == n]
    df = pd.DataFrame({k: columns[k] for k in same if usecols is None or usecols(k)}, index=pd.RangeIndex(n))
    df.attrs["columns_in_file"] = same
    return df


def read_table_file(path, usecols: Callable[[str], bool] | None = None):
    """The table in ``path`` as a DataFrame (CSV/TSV, Parquet or .mat by suffix); ``usecols``
    keeps only the columns for which it is true (the names of all the file's columns are then
    in ``df.attrs["columns_in_file"]``)."""
    path = Path(path)
    if not path.exists():
        raise DataError(f"{path}: cannot read (No such file or directory)")
    if path.is_dir():
        raise DataError(f"{path}: is a directory, not a recording")
    fmt = table_format(path)
    if fmt == "parquet":
        return read_parquet_file(path, usecols)
    if fmt == "mat":
        return read_mat_file(path, usecols)
    return read_csv_file(path, usecols)


# ---------------------------------------------------------------- writers
def _columns(columns: dict) -> tuple[list[str], list[np.ndarray], int]:
    names = list(columns)
    arrays = [np.asarray(columns[c]) for c in names]
    n = len(arrays[0]) if arrays else 0
    for c, a in zip(names, arrays):
        if a.ndim != 1 or len(a) != n:
            raise ValueError(f"column {c!r}: expected {n} values in one dimension, got shape {a.shape}")
    return names, arrays, n


def csv_blocks(columns: dict, fmt: str = CSV_FORMAT, block_rows: int = CSV_BLOCK_ROWS):
    """The CSV text of ``columns`` (header first) in encoded blocks of ``block_rows`` rows.

    Floats are written with ``fmt`` (the bytes ``'%.10g' % value`` gives, as pandas'
    ``float_format`` does), strings as they are. Each block is one ``%`` formatting of a
    row template repeated over the block, which runs in C: no Python call per value."""
    names, arrays, n = _columns(columns)
    yield (",".join(names) + "\n").encode()
    kinds = ["s" if a.dtype.kind in "OUS" else "f" for a in arrays]
    if fmt == CSV_FORMAT and "s" not in kinds:
        from .csvformat import rows_bytes  # compiled, the same bytes

        for a0 in range(0, n, block_rows):
            yield rows_bytes(np.column_stack([a[a0 : a0 + block_rows] for a in arrays]))
        return
    row = ",".join("%s" if k == "s" else fmt for k in kinds) + "\n"
    for a0 in range(0, n, block_rows):
        a1 = min(n, a0 + block_rows)
        m = a1 - a0
        cols = []
        for a, k in zip(arrays, kinds):
            part = a[a0:a1]
            cols.append(part.astype(str) if k == "s" else part.astype(np.float64, copy=False))
        if all(k == "f" for k in kinds):
            flat = np.column_stack(cols).ravel().tolist()
        else:
            obj = np.empty((m, len(cols)), dtype=object)
            for j, c in enumerate(cols):
                obj[:, j] = c.tolist()
            flat = obj.ravel().tolist()
        yield ((row * m) % tuple(flat)).encode()


def write_csv(columns: dict, path) -> None:
    with open(path, "wb") as fh:
        for block in csv_blocks(columns):
            fh.write(block)


def write_parquet(columns: dict, path) -> None:
    pa, pq = require_pyarrow(str(path))
    names, arrays, _ = _columns(columns)
    # no dictionary encoding: measured floats rarely repeat, and trying costs 4× the write
    pq.write_table(pa.table({c: a for c, a in zip(names, arrays)}), path, use_dictionary=False)


def write_table(columns: dict, path, fmt: str | None = None) -> None:
    """Write ``columns`` to ``path`` as CSV or Parquet (``fmt``, else by the file's suffix)."""
    fmt = fmt or table_format(path)
    if fmt == "parquet":
        write_parquet(columns, path)
    elif fmt == "csv":
        write_csv(columns, path)
    else:
        raise DataError(f"{path}: cannot write {fmt} files; use .csv or .parquet")
