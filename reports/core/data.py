"""Reading the committed data: CSV files as dict rows or typed columns, and each run's meta.json;
and writing what the studies derive from it (digests, records) whole or not at all.

Paths are relative to the repository root passed in (so a check can run on a copy of the data).
Numbers are parsed with float(); an empty field is None."""

import csv
import json
import math
import os


class DataError(Exception):
    """A committed file that a check needs is missing or unusable (one line, naming the file)."""


def path(root, *parts):
    return os.path.join(root, *parts)


def read_rows(root, relpath):
    """All rows of a CSV as dicts of strings."""
    full = path(root, relpath)
    try:
        with open(full, newline="", encoding="utf-8") as f:
            return list(csv.DictReader(f))
    except OSError as error:
        raise DataError(f"{relpath}: {error.strerror}") from None


def number(text):
    """float of a CSV field; None for an empty field."""
    if text is None or text == "":
        return None
    try:
        return float(text)
    except ValueError:
        raise DataError(f"not a number: {text!r}") from None


def num(row, column):
    """The number in a row's column (None when empty); a missing column is an error."""
    if column not in row:
        raise DataError(f"no column '{column}'")
    return number(row[column])


def select(rows, **where):
    """Rows whose columns equal the given values (numbers compared as numbers)."""
    out = []
    for r in rows:
        ok = True
        for k, v in where.items():
            cell = r.get(k)
            if isinstance(v, (int, float)) and not isinstance(v, bool):
                x = number(cell) if cell not in (None, "") else None
                ok = x is not None and math.isclose(x, v, rel_tol=1e-9, abs_tol=1e-12)
            else:
                ok = cell == v
            if not ok:
                break
        if ok:
            out.append(r)
    return out


def one(rows, what="row", **where):
    """The single row matching where (an error naming what otherwise)."""
    found = select(rows, **where)
    if len(found) != 1:
        raise DataError(f"{what}: {len(found)} rows match {where}")
    return found[0]


def read_meta(root, folder):
    full = path(root, folder, "meta.json")
    try:
        with open(full, encoding="utf-8") as f:
            return json.load(f)
    except OSError as error:
        raise DataError(f"{folder}/meta.json: {error.strerror}") from None
    except json.JSONDecodeError as error:
        raise DataError(f"{folder}/meta.json: not JSON ({error.msg}, line {error.lineno})") from None


def write_text(path, text):
    """path holds text, or (on a failure) what it held before: written beside it, then renamed."""
    tmp = path + ".tmp"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)
    return path


def write_csv(path, header, rows):
    """A CSV of header and rows, written as write_text writes; returns the path."""
    tmp = path + ".tmp"
    with open(tmp, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(header)
        w.writerows(rows)
    os.replace(tmp, path)
    return path
