"""Results files that survive interruption and damage: append-only CSV, one record per line.

A sweep writes each finished piece of work at once (one `write` per batch of rows, flushed and
fsynced), so `kill -9` loses at most the batch being written. Every line ends with a checksum of its
own text (column `check`, CRC-32), and every field must parse as its column's type, so a record is
whole or absent: on the next run the file is read back line by line, a damaged line anywhere (torn
by a kill, cut, edited, a field that is not a number) is reported once as ``FILE:LINE: damaged
record, recomputing``, the file is rewritten without it (atomically), and the sweep computes again
the keys that are missing. A key that appears twice keeps its first record.

A row's key normally includes its `fingerprint` (`sweeps.fingerprint`): rows of other inputs
stay in the file and are never mistaken for this run's.
"""

import csv
import io
import json
import math
import os
import pathlib
import sys
import tempfile
import zlib
from collections.abc import Iterable, Sequence

CHECK = "check"  # the last column: the CRC-32 of the line's text before it, 8 hex digits
FINGERPRINT = "fingerprint"


class ResultsFileError(ValueError):
    """A results file this version cannot use (another version's columns): one line, exit code 2."""


def _is_float(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return text.strip() == text and text != ""


def _is_int(text: str) -> bool:
    try:
        int(text)
    except ValueError:
        return False
    return text.strip() == text and text != ""


def _is_json(text: str) -> bool:
    try:
        json.loads(text)
    except ValueError:
        return False
    return True


def _is_hex(text: str) -> bool:
    return text != "" and all(c in "0123456789abcdef" for c in text)


# Column types: the check each field of the column must pass for its line to be whole.
PARSERS = {
    "str": lambda text: True,
    "float": _is_float,
    "int": _is_int,
    "bool": lambda text: text in ("0", "1"),
    "json": _is_json,
    "hex": _is_hex,
}


def line_check(fields_text: str) -> str:
    """The checksum written at the end of a line: CRC-32 of the line's text before it, 8 hex digits."""
    return f"{zlib.crc32(fields_text.encode()):08x}"


def format_line(values: Sequence[str]) -> str:
    """One record as one CSV line (with its checksum and the newline)."""
    buffer = io.StringIO()
    csv.writer(buffer, lineterminator="").writerow(values)
    text = buffer.getvalue()
    return f"{text},{line_check(text)}\n"


def parse_line(line: str, fieldnames: Sequence[str], types: dict[str, str]) -> dict | None:
    """The record of one line (without its newline), or None if the line is damaged: not valid CSV,
    the wrong number of fields, a checksum that does not match, or a field that does not parse as
    its column's type. Pure."""
    text, sep, check = line.rpartition(",")
    if not sep or check != line_check(text):
        return None
    try:
        values = next(csv.reader([text]))
    except (csv.Error, StopIteration):
        return None
    if len(values) != len(fieldnames):
        return None
    row = dict(zip(fieldnames, values))
    if not all(PARSERS[types.get(name, "str")](value) for name, value in row.items()):
        return None
    return row


class ResultsTable:
    """An append-only CSV file of rows with a unique key, every line checked when read back.

    Args:
        path: the CSV file (created with a header if missing).
        fieldnames: the columns, in order (the file adds `check` after them).
        key_fields: the columns that identify a row (a subset of fieldnames).
        types: column name -> "str" | "float" | "int" | "bool" | "json" | "hex" (default "str"): a
            line whose field does not parse as its column's type is damaged.
        read_only: only read (a results file of another folder, e.g. Fig. 6's reused by Fig. 7):
            damaged lines are skipped and reported, the file is neither created nor repaired.
        report: where damaged lines are reported.
    """

    def __init__(self, path: str | os.PathLike, fieldnames: Sequence[str], key_fields: Sequence[str],
                 types: dict[str, str] | None = None, read_only: bool = False, report=None):
        self.path = pathlib.Path(path)
        self.fieldnames = list(fieldnames)
        self.key_fields = list(key_fields)
        self.types = dict(types or {})
        self.read_only = read_only
        self.report = report if report is not None else sys.stderr
        missing = (set(self.key_fields) | set(self.types)) - set(self.fieldnames)
        if missing:
            raise ValueError(f"columns {sorted(missing)} are not in fieldnames")
        unknown = set(self.types.values()) - set(PARSERS)
        if unknown:
            raise ValueError(f"unknown column types {sorted(unknown)}")
        self.damaged: list[int] = []  # line numbers (1-based) found damaged when the file was read
        self._rows: dict[tuple, dict] = {}
        self._load()

    @property
    def header(self) -> str:
        return ",".join(self.fieldnames + [CHECK]) + "\n"

    def key(self, row: dict) -> tuple:
        """The key of a row, normalised so that a row read back from the file has the same key."""
        return tuple(_normalise(row[k]) for k in self.key_fields)

    def __contains__(self, key: tuple) -> bool:
        return tuple(_normalise(k) for k in key) in self._rows

    def __len__(self) -> int:
        return len(self._rows)

    def rows(self) -> list[dict]:
        """All rows, as read back (strings), in file order."""
        return list(self._rows.values())

    def rows_of(self, fingerprint: str) -> list[dict]:
        """The rows of one fingerprint (the current inputs), in file order."""
        return [r for r in self._rows.values() if r.get(FINGERPRINT) == fingerprint]

    def append(self, rows: Iterable[dict]) -> int:
        """Writes the rows whose keys are new, in one write; returns how many were written."""
        if self.read_only:
            raise ValueError(f"{self.path}: opened read-only")
        lines = []
        for row in rows:
            values = {k: _normalise(row.get(k, "")) for k in self.fieldnames}
            key = self.key(values)
            if key in self._rows:
                continue
            line = format_line([values[k] for k in self.fieldnames])
            if parse_line(line[:-1], self.fieldnames, self.types) is None:
                # A record this table would reject when read back (and compute again, forever).
                bad = [k for k in self.fieldnames if not PARSERS[self.types.get(k, "str")](values[k])]
                raise RuntimeError(f"{self.path}: a record's {', '.join(bad) or 'text'} does not match its "
                                   "column type (a bug)")
            lines.append(line)
            self._rows[key] = values
        if not lines:
            return 0
        fd = os.open(self.path, os.O_WRONLY | os.O_APPEND)
        try:
            os.write(fd, "".join(lines).encode())
            os.fsync(fd)
        finally:
            os.close(fd)
        return len(lines)

    def _load(self) -> None:
        if not self.path.exists() or self.path.stat().st_size == 0:
            if not self.read_only:
                self.path.parent.mkdir(parents=True, exist_ok=True)
                write_atomically(self.path, self.header)
            return
        if self.path.is_dir():
            raise ResultsFileError(f"{self.path}: is a directory, not a results file")
        data = self.path.read_bytes()
        lines = data.split(b"\n")
        # The last piece is empty when the file ends with a newline; otherwise it is a torn line.
        header = lines[0].decode(errors="replace") + "\n"
        if header != self.header:
            self._reject_header(header)
        kept = [header]
        for number, raw in enumerate(lines[1:], start=2):
            if number == len(lines) and raw == b"":
                break
            row = None
            if number < len(lines) or raw == b"":  # a line that ended with its newline
                try:
                    row = parse_line(raw.decode(), self.fieldnames, self.types)
                except UnicodeDecodeError:
                    row = None
            if row is None:
                self.damaged.append(number)
                what = "ignored" if self.read_only else "recomputing"
                print(f"{self.path}:{number}: damaged record, {what}", file=self.report, flush=True)
                continue
            key = self.key(row)
            if key in self._rows:  # a second record of a key (e.g. two writers before the lock)
                self.damaged.append(number)
                print(f"{self.path}:{number}: duplicate record, dropped", file=self.report, flush=True)
                continue
            self._rows[key] = row
            kept.append(raw.decode() + "\n")
        if self.damaged and not self.read_only:
            write_atomically(self.path, "".join(kept))

    def _reject_header(self, header: str) -> None:
        _reject_header(self.path, header, self.fieldnames)


def check_results_file(path: str | os.PathLike, fieldnames: Sequence[str]) -> None:
    """Raises ResultsFileError (one line) if a results file exists but this version cannot use it (a
    folder, or other columns): a sweep calls it for every file it will use before any work starts."""
    path = pathlib.Path(path)
    if path.is_dir():
        raise ResultsFileError(f"{path}: is a directory, not a results file")
    if not path.is_file() or path.stat().st_size == 0:
        return
    with open(path, "rb") as f:
        header = f.readline().decode(errors="replace")
    if header != ",".join(list(fieldnames) + [CHECK]) + "\n":
        _reject_header(path, header, fieldnames)


def _reject_header(path: pathlib.Path, header: str, fieldnames: Sequence[str]) -> None:
    columns = header.strip().split(",")
    if FINGERPRINT in fieldnames and (FINGERPRINT not in columns or CHECK not in columns):
        raise ResultsFileError(
            f"{path}: written by an older version of drake-grasp (records without a fingerprint "
            "of their inputs); move it away or choose another --out to start fresh")
    raise ResultsFileError(
        f"{path}: its columns do not match this version's; move it away or choose another --out "
        "to start fresh")


def write_atomically(path: pathlib.Path, text: str) -> None:
    """Writes text to path through a uniquely named temporary file in the same folder (fsynced, then
    renamed over path): readers see the old file or the new one, never part of one, and two writers
    never share a temporary file."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        os.fchmod(fd, _file_mode(path))
        with os.fdopen(fd, "w", newline="") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with _suppress_os_error():
            os.unlink(tmp)
        raise


def _file_mode(path: pathlib.Path) -> int:
    """The permissions a rewritten file keeps: its own if it exists, else those of a new file."""
    try:
        return path.stat().st_mode & 0o777
    except OSError:
        umask = os.umask(0)
        os.umask(umask)
        return 0o666 & ~umask


class _suppress_os_error:
    def __enter__(self):
        return self

    def __exit__(self, kind, value, traceback):
        return kind is not None and issubclass(kind, OSError)


def axis_label(obj: str) -> str:
    """An object's name as a plot's tick label: a mesh file by its stem, words on separate lines
    (a primitive such as "sphere:0.12" as it is)."""
    if ":" not in obj and ("/" in obj or pathlib.Path(obj).suffix):
        obj = pathlib.Path(obj).stem
    return obj.replace("_", "\n")


def save_figure(fig, out_dir: pathlib.Path, stem: str, dpi: int = 120) -> list[pathlib.Path]:
    """Writes a matplotlib figure as out_dir/stem.png and .svg, each atomically (no half-written
    figure if the run is interrupted); returns the two paths."""
    paths = [out_dir / f"{stem}.png", out_dir / f"{stem}.svg"]
    for path in paths:
        fd, tmp = tempfile.mkstemp(dir=out_dir, prefix=f".{path.name}.", suffix=path.suffix)
        os.fchmod(fd, _file_mode(path))
        os.close(fd)
        try:
            fig.savefig(tmp, dpi=dpi, format=path.suffix[1:])
            os.replace(tmp, path)
        except BaseException:
            with _suppress_os_error():
                os.unlink(tmp)
            raise
    return paths


def _format(value) -> str:
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        return repr(float(value))  # float(): numpy scalars print as np.float64(...)
    if isinstance(value, bool):
        return "1" if value else "0"
    if hasattr(value, "item") and not isinstance(value, str):  # numpy scalars
        return _format(value.item())
    # One record is one line: line breaks inside a text field become spaces.
    return str(value).replace("\r", " ").replace("\n", " ")


def _normalise(value) -> str:
    """Keys and values compare as the text written to the file: 0.1 and '0.1' are the same key."""
    return _format(value)


def json_finite(value):
    """`value` with NaN and inf floats as None (at any depth of dicts, lists and tuples), so that
    the JSON cells of a results file are standard JSON."""
    if isinstance(value, float):
        return value if math.isfinite(value) else None
    if isinstance(value, dict):
        return {k: json_finite(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [json_finite(v) for v in value]
    return value


def ensure_generated(directory: pathlib.Path, generate, expected: int, seeds: tuple) -> list[dict]:
    """Generated object files in `directory` with their manifest: reused when the manifest lists
    `expected` rows, each of a seed in `seeds`, whose files all exist; else `generate(staging)`
    (a deterministic generator writing its files, manifest.csv and manifest.json into `staging`,
    returning the manifest rows) runs in a private folder and the files are moved into place one by
    one, the manifest last: an interrupted generation leaves no torn file and no manifest that
    promises a missing one. A row's "assets" (files its "file" names, such as a URDF's mesh) move
    with it. Returns the manifest rows, "file" as a path in `directory`."""
    import shutil

    directory.mkdir(parents=True, exist_ok=True)
    manifest = directory / "manifest.json"
    rows = json.loads(manifest.read_text()) if manifest.is_file() else None
    fresh = (rows is not None and len(rows) == expected and all(r["seed"] in seeds for r in rows)
             and all((directory / f).is_file() for r in rows for f in [r["file"], *r.get("assets", ())]))
    if not fresh:
        staging = pathlib.Path(tempfile.mkdtemp(dir=directory, prefix=".generating."))
        try:
            rows = generate(staging)
            for name in [f for r in rows for f in [*r.get("assets", ()), r["file"]]] + ["manifest.csv"]:
                (staging / name).replace(directory / name)
            write_atomically(manifest, (staging / "manifest.json").read_text())
        finally:
            shutil.rmtree(staging, ignore_errors=True)
    return [{**row, "file": str(directory / row["file"])} for row in rows]
