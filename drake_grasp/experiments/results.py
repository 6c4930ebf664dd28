"""Results files that survive interruption: append-only CSV, resumed by row key.

A sweep writes each finished piece of work at once (one `write` per batch of rows, flushed and
fsynced), so `kill -9` loses at most the batch being written. On the next run the file is read back:
a torn last line is dropped, rows are keyed by their key fields, and the sweep computes only the keys
that are missing, so no row is lost or duplicated.
"""

import csv
import io
import math
import os
import pathlib
from collections.abc import Iterable, Sequence


class ResultsTable:
    """An append-only CSV file of rows with a unique key.

    Args:
        path: the CSV file (created with a header if missing).
        fieldnames: the columns, in order.
        key_fields: the columns that identify a row (a subset of fieldnames).
    """

    def __init__(self, path: str | os.PathLike, fieldnames: Sequence[str], key_fields: Sequence[str]):
        self.path = pathlib.Path(path)
        self.fieldnames = list(fieldnames)
        self.key_fields = list(key_fields)
        missing = set(self.key_fields) - set(self.fieldnames)
        if missing:
            raise ValueError(f"key fields {sorted(missing)} are not columns")
        self._rows: dict[tuple, dict] = {}
        self._load()

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

    def append(self, rows: Iterable[dict]) -> int:
        """Writes the rows whose keys are new, in one write; returns how many were written."""
        new = []
        for row in rows:
            key = self.key(row)
            if key in self._rows:
                continue
            new.append(row)
            self._rows[key] = {k: _normalise(row.get(k, "")) for k in self.fieldnames}
        if not new:
            return 0
        buffer = io.StringIO()
        writer = csv.DictWriter(buffer, fieldnames=self.fieldnames, extrasaction="ignore", lineterminator="\n")
        for row in new:
            writer.writerow({k: _format(row.get(k, "")) for k in self.fieldnames})
        with open(self.path, "a", newline="") as f:
            f.write(buffer.getvalue())
            f.flush()
            os.fsync(f.fileno())
        return len(new)

    def _load(self) -> None:
        if not self.path.exists() or self.path.stat().st_size == 0:
            self.path.parent.mkdir(parents=True, exist_ok=True)
            with open(self.path, "w", newline="") as f:
                f.write(",".join(self.fieldnames) + "\n")
            return
        text = self.path.read_text()
        if not text.endswith("\n"):
            # A torn last line from an interrupted write: drop it, and rewrite the file without it.
            text = text[: text.rfind("\n") + 1]
            tmp = self.path.with_suffix(self.path.suffix + ".tmp")
            tmp.write_text(text)
            tmp.replace(self.path)
        reader = csv.DictReader(io.StringIO(text))
        if reader.fieldnames != self.fieldnames:
            raise ValueError(
                f"{self.path}: columns do not match this run's (another version of the sweep?); "
                "move the file away or choose another --out"
            )
        for row in reader:
            self._rows[self.key(row)] = row


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
        tmp = path.with_name(path.stem + ".tmp" + path.suffix)
        fig.savefig(tmp, dpi=dpi)
        tmp.replace(path)
    return paths


def _format(value) -> str:
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        return repr(float(value))  # float(): numpy scalars print as np.float64(...)
    if isinstance(value, bool):
        return "1" if value else "0"
    return str(value)


def _normalise(value) -> str:
    """Keys and values compare as the text written to the file: 0.1 and '0.1' are the same key."""
    return value if isinstance(value, str) else _format(value)
