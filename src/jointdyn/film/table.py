"""Film forces for a CSV table of bearing states, streamed in blocks (bounded memory).

The required columns are the parameters of :func:`jointdyn.film.models.film_forces`
(after ``model``), read from its signature; their units from its docstring. Rows are numbered
from 1 (the first data row after the header), as in every message.
"""

from __future__ import annotations

import contextlib
import csv
import inspect
import math
import re
import sys
from functools import partial
from pathlib import Path

import numpy as np

from jointdyn.core import atomic, interrupts
from jointdyn.film.models import FILM_MODELS, film_forces

BLOCK = 4096  # rows per evaluation: memory stays O(BLOCK) whatever the file size
OUT_COLUMNS = ("Fr", "Ft", "Fx", "Fy")


def columns() -> tuple[str, ...]:
    """The input columns, in the order of ``film_forces``'s parameters."""
    return tuple(p for p in inspect.signature(film_forces).parameters if p != "model")


def units() -> dict[str, str]:
    """Unit of each input column, from ``film_forces``'s docstring lines ``name ... [unit]``."""
    doc = film_forces.__doc__ or ""
    found = {m.group(1): m.group(2) for m in re.finditer(r"^\s*(\w+)\s.*\[([^\]]+)\]\s*$", doc, re.M)}
    return {c: found.get(c, "SI") for c in columns()}


def _header(reader, src) -> list[str]:
    try:
        head = next(reader)
    except StopIteration:
        raise ValueError(
            f"{src}: empty file; the first line must name the columns {list(columns())}"
        ) from None
    head = [h.strip() for h in head]
    dup = sorted({h for h in head if head.count(h) > 1})
    if dup:
        raise ValueError(f"{src}: duplicate column(s) {dup} in the header")
    missing = [c for c in columns() if c not in head]
    if missing:
        raise ValueError(f"{src}: missing column(s) {missing}; required: {list(columns())}")
    return head


def _parse(rows, head, start: int, src) -> np.ndarray:
    """Rows -> (len(rows), n_columns) array; row numbers from ``start`` (1-based)."""
    idx = [head.index(c) for c in columns()]
    out = np.empty((len(rows), len(idx)))
    for r, row in enumerate(rows):
        n = start + r
        if len(row) != len(head):
            raise ValueError(f"{src}: row {n} has {len(row)} fields, the header has {len(head)}")
        for k, j in enumerate(idx):
            try:
                v = float(row[j])
            except ValueError:
                raise ValueError(f"{src}: row {n}, column {head[j]!r}: {row[j]!r} is not a number") from None
            if not math.isfinite(v):
                raise ValueError(f"{src}: row {n}, column {head[j]!r}: non-finite value {v!r}")
            out[r, k] = v
    return out


def _forces(model, data: np.ndarray, start: int, src) -> dict:
    c, r = data[:, columns().index("clearance")], data[:, columns().index("radius")]
    bad = np.flatnonzero(c >= r)  # a state table is dimensional: c < R [T284]
    if bad.size:
        i = bad[0]
        ci, ri = float(c[i]), float(r[i])
        raise ValueError(f"{src}: row {start + i}: clearance = {ci!r} [m] must be < radius = {ri!r} (c < R)")
    from jointdyn.film.jfo_states import SteadyJFO

    forces = model.forces if isinstance(model, SteadyJFO) else partial(film_forces, model)
    try:
        return forces(*data.T)
    except ValueError:
        pass
    for r in range(data.shape[0]):  # find the 1-based row of the first bad state
        try:
            forces(*data[r : r + 1].T)
        except ValueError as err:
            raise ValueError(f"{src}: row {start + r}: {str(err).replace(' at index 0', '')}") from None
    raise AssertionError("unreachable")  # pragma: no cover


def film_force_table(src, model, out=None) -> int:
    """Read states from CSV ``src``, write them with ``Fr, Ft, Fx, Fy`` [N] appended to ``out``
    (a path, written atomically; None = stdout). ``model``: a film model (name or instance) or
    the steady mass-conserving film :class:`~jointdyn.film.jfo_states.SteadyJFO` [T343]. Returns
    the number of rows."""
    from jointdyn.film.jfo_states import SteadyJFO  # the 2-D solver (scipy.sparse) only when used

    known = type(model) in FILM_MODELS.values() or isinstance(model, SteadyJFO)
    if not known and (not isinstance(model, str) or model not in FILM_MODELS):
        raise ValueError(f"--model {model!r} is unknown; valid: {', '.join(FILM_MODELS)}")
    src = Path(src)
    if src.is_dir():
        raise ValueError(f"{src}: is a directory, not a CSV file")
    with contextlib.ExitStack() as stack:
        try:
            atomic.regular_input(src, "STATES")  # a FIFO would block
            fin = stack.enter_context(open(src, newline="", encoding="utf-8-sig"))  # a BOM is not a name
        except FileNotFoundError:
            raise ValueError(f"{src}: no such file") from None
        if out is None:
            fout = sys.stdout
        else:
            tmp = stack.enter_context(atomic.replacing(Path(out), devices=True))
            fout = stack.enter_context(open(tmp, "w", newline="", encoding="utf-8"))
        reader, writer = csv.reader(fin), csv.writer(fout)
        n = 0
        try:
            head = _header(reader, src)
            while True:
                block = [row for _, row in zip(range(BLOCK), reader) if row]
                if not block:
                    break
                F = _forces(model, _parse(block, head, n + 1, src), n + 1, src)
                if n == 0:  # the header only once the first block computed: an error comes first
                    writer.writerow(head + list(OUT_COLUMNS))
                for i, row in enumerate(block):
                    writer.writerow(row + [f"{F[k][i]:.10g}" for k in OUT_COLUMNS])
                n += len(block)
                interrupts.check()
        except UnicodeDecodeError as err:
            _mark_incomplete(fout, out, n)
            raise ValueError(f"{src}: not a UTF-8 text file ({err.reason})") from None
        except csv.Error as err:
            _mark_incomplete(fout, out, n)
            raise ValueError(f"{src}: line {reader.line_num}: malformed CSV ({err})") from None
        except BaseException:
            _mark_incomplete(fout, out, n)
            raise
        if n == 0:
            raise ValueError(f"{src}: no data rows")
    return n


def _mark_incomplete(fout, out, n: int) -> None:
    """Streaming to stdout, a failure after ``n`` rows were written (blocks of ``BLOCK`` rows)
    leaves a partial table: end it with a line that is not a row (one field, starting with ``#``),
    so the output is plainly not a whole table (a file ``out`` is written atomically and never
    appears)."""
    if out is None and n:
        fout.write(f"# INCOMPLETE: film-force stopped after {n} rows (the error is on stderr)\n")
        fout.flush()
