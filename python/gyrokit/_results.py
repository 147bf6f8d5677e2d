"""What every result carries besides its arrays: the tables the CLI prints for it and
the figure it draws, built by the library (so the two front ends cannot drift apart),
saved in the CLI's formats and read back, and drawn with matplotlib or gnuplot."""
from __future__ import annotations

import csv as _csv
import json as _json
import os as _os

import numpy as _np

from ._core import InputError
from . import _core

UNITS = {"rad/s": 1.0, "Hz": 1.0 / (2 * _np.pi), "rpm": 30.0 / _np.pi}   # from rad/s
_FORMATS = {".csv": "csv", ".json": "json", ".txt": "table"}


def factor(unit):
    """rad/s -> unit; InputError naming the unit and the allowed ones."""
    if unit not in UNITS:
        raise InputError(f"unit = {unit!r} is unknown; allowed: rad/s, Hz, rpm")   # the library's words
    return UNITS[unit]


class Table:
    """One table of a result as the CLI prints it: `key` (its --table name), `title`, `columns` and `rows`
    (lists of float, int, bool or str; `inf` for an undamped peak)."""

    def __init__(self, key, title, columns, rows):
        self.key, self.title, self.columns, self.rows = key, title, list(columns), [list(r) for r in rows]

    def column(self, name):
        """The values of one column, in row order."""
        if name not in self.columns:
            raise InputError(f"column {name!r}; allowed: {', '.join(self.columns)}")
        k = self.columns.index(name)
        return [r[k] for r in self.rows]

    def to_pandas(self):
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("to_pandas() needs pandas (Debian: python3-pandas)") from e
        return pd.DataFrame(self.rows, columns=self.columns)

    def _dict(self):
        return {"key": self.key, "title": self.title, "columns": self.columns, "rows": self.rows}

    def __str__(self):
        return _core.format_tables([self._dict()], "table")

    def __repr__(self):
        return f"<gyrokit.Table {self.key!r}: {len(self.rows)} rows x {len(self.columns)} columns>"

    def __eq__(self, other):
        return isinstance(other, Table) and self._dict() == other._dict()


def _tables(d):
    return [Table(t["key"], t["title"], t["columns"], t["rows"]) for t in d.get("tables", [])]


def _cell(text):
    """A CSV cell back to the value the library wrote (%.12g numbers, true/false, inf)."""
    if text in ("true", "false"):
        return text == "true"
    try:
        return int(text)
    except ValueError:
        pass
    try:
        return float(text)
    except ValueError:
        return text


def load_tables(path):
    """The tables of a result file written by `save()` or by the CLI's --format json / csv: JSON gives every
    table at full precision, CSV its one table (numbers to 12 digits, as written)."""
    ext = _os.path.splitext(str(path))[1].lower()
    if ext == ".json":
        with open(path) as f:
            data = _json.load(f)
        if isinstance(data, list):   # one table: an array of row objects
            data = {_os.path.splitext(_os.path.basename(str(path)))[0]: data}
        out = []
        for key, rows in data.items():
            columns = list(rows[0].keys()) if rows else []
            out.append(Table(key, "", columns,
                             [[float(v) if v in ("inf", "-inf") else v for v in r.values()] for r in rows]))
        return out
    if ext == ".csv":
        with open(path, newline="") as f:
            lines = [row for row in _csv.reader(f) if row and not row[0].startswith("#")]
        if not lines:
            raise InputError(f"{path}: no table in it")
        key = _os.path.splitext(_os.path.basename(str(path)))[0]
        return [Table(key, "", lines[0], [[_cell(c) for c in r] for r in lines[1:]])]
    raise InputError(f"{path}: extension {ext!r}; allowed: .json, .csv")


_LINE = {"lines": "-", "dashed": "--", "dotted": ":", "points": "none", "linespoints": "-"}


def draw(figure, axes=None):
    """A library figure (panels of series) drawn with matplotlib: one axes per panel, stacked; returns the
    matplotlib Figure. `axes`: your own axes, one per panel."""
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:  # pragma: no cover - depends on the machine
        raise ImportError("plot() needs matplotlib (Debian: python3-matplotlib)") from e
    panels = figure["panels"]
    if axes is None:
        fig, axes = plt.subplots(len(panels), 1, squeeze=False,
                                 figsize=(figure["width"] / 100, figure["height_per_panel"] * len(panels) / 100))
        axes = list(axes[:, 0])
    else:
        axes = list(_np.atleast_1d(axes))
        if len(axes) != len(panels):
            raise InputError(f"axes: {len(axes)} given; allowed: one per panel of this figure ({len(panels)})")
        fig = axes[0].figure
    for ax, p in zip(axes, panels):
        for s in p["series"]:
            if not s["x"]:
                continue
            x, y = _np.asarray(s["x"], float), _np.asarray(s["y"], float)
            style = s["style"]
            kw = {"linestyle": _LINE.get(style, "-"), "label": s["label"] or None}
            if style in ("points", "linespoints"):
                kw["marker"] = "o"
                kw["markersize"] = 3
            if s["color"]:
                kw["color"] = s["color"]
            line, = ax.plot(x, y, **kw)
            for xi, yi, text in zip(x, y, s.get("point_labels") or ()):   # speed marks: a ring and its text
                if text and _np.isfinite(xi) and _np.isfinite(yi):
                    ax.plot([xi], [yi], marker="o", markersize=5, fillstyle="none", color=line.get_color())
                    ax.annotate(text, (xi, yi), xytext=(4, 4), textcoords="offset points", fontsize=8,
                                color=line.get_color())
        ax.set_xlabel(p["xlabel"])
        ax.set_ylabel(p["ylabel"])
        if p["title"]:
            ax.set_title(p["title"])
        if p["logx"]:
            ax.set_xscale("log")
        if p["logy"]:
            ax.set_yscale("log")
        ax.set_xlim(p["xmin"], p["xmax"])
        ax.set_ylim(p["ymin"], p["ymax"])
        if p["equal_axes"]:
            ax.set_aspect("equal", adjustable="datalim")
        if any(s["label"] for s in p["series"]):
            ax.legend(fontsize="small")
    if figure["title"]:
        fig.suptitle(figure["title"])
    return fig


class Result:
    """Base of the result objects: `tables` (what the CLI prints), `save()`, `plot()`."""

    tables: tuple = ()   # a result's own tables replace it (a list)
    _figure = None
    _inputs = ()   # the files the result was computed from: save() and plot(path) never write onto one

    def _take_reports(self, d):
        self.tables = _tables(d)
        self._figure = d.get("figure")

    def _frame(self, columns):
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("to_pandas() needs pandas (Debian: python3-pandas)") from e
        return pd.DataFrame(columns)

    @staticmethod
    def _pyplot():
        try:
            import matplotlib.pyplot as plt
        except ImportError as e:  # pragma: no cover - depends on the machine
            raise ImportError("plot() needs matplotlib (Debian: python3-matplotlib)") from e
        return plt

    def table(self, key):
        """The table of this key (the CLI's --table name)."""
        for t in self.tables:
            if t.key == key:
                return t
        raise InputError(f"table {key!r}; allowed: {', '.join(t.key for t in self.tables)}")

    def save(self, path, table=None):
        """The result's tables written to `path` as the CLI writes them: .json (every table, full precision),
        .csv (one table: `table`, default the first), .txt (the text tables). Replaced whole, never half written."""
        ext = _os.path.splitext(str(path))[1].lower()
        if ext not in _FORMATS:
            raise InputError(f"{path}: extension {ext!r}; allowed: .json, .csv, .txt")
        if not self.tables:
            raise InputError(f"{type(self).__name__} has no tables to save")
        chosen = [self.table(table)] if table is not None else list(self.tables)
        if ext == ".csv":
            chosen = chosen[:1]
        _core.write_tables([t._dict() for t in chosen], str(path), _FORMATS[ext], list(self._inputs))
        return path

    def _draw_figure(self, figure, path, axes):
        if figure is None:
            raise InputError(f"{type(self).__name__} has no figure")
        if path is not None:
            _core.render_figure(figure, str(path), list(self._inputs))   # gnuplot: the CLI's --plot picture
            return path
        return draw(figure, axes)

    def plot(self, path=None, axes=None):
        """The CLI's figure of this result: into `path` (.png or .svg, drawn by gnuplot as the CLI's --plot),
        or with matplotlib (returns its Figure; `axes`: one per panel)."""
        return self._draw_figure(self._figure, path, axes)

    def __repr__(self):
        fields = ", ".join(f"{k}" for k in self.__dict__ if not k.startswith("_"))
        return f"<gyrokit.{type(self).__name__}: {fields}>"
