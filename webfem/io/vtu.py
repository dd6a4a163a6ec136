"""VTU files for ParaView (meshio): the web as a polyline, the film as quadrilaterals.

Arrays are named with their units (``"h [m]"``, ``"p-p_a [Pa]"``, :data:`ARRAY_NAMES`);
``regime`` (0 boundary, 1 mixed, 2 fluid) and ``in_wrap`` (1 on the roller) are integers;
the field data name the regime codes, the coordinates and the headline numbers with units.
A half-width film is mirrored, so the file shows the full width.

Files appear whole or not at all (hidden temporary file, renamed) with the user's umask.
A sweep's files (:class:`SweepVtu`) are named by series and point index, carry their series
label and swept value as field data, and are tied together per series by ``.pvd``
collections indexed by the swept value.
"""

from __future__ import annotations

import os
import re
from pathlib import Path
from xml.etree import ElementTree
from xml.sax.saxutils import escape, quoteattr

import meshio
import numpy as np

from ..errors import InputError
from ..files import remove_stale_temps, replacing, write_text

__all__ = ["ARRAY_NAMES", "WEB_FIELDS", "FILM_FIELDS", "MEANING", "H_MIN_KEYS", "H_MIN_NOTE",
           "web_mesh", "film_mesh", "write_mesh", "write_result", "write_pvd", "SweepVtu"]

#: Result field -> VTU array name: the unit in brackets, so ParaView's colour bars carry it.
ARRAY_NAMES = {"w": "w [m]", "h": "h [m]", "p_rel": "p-p_a [Pa]", "p": "p [Pa]",
               "p_contact": "p_contact [Pa]", "chi_c": "chi_c [-]", "mu": "mu [-]",
               "mu_c": "mu_c [-]", "mu_f": "mu_f [-]", "regime": "regime", "in_wrap": "in_wrap"}
#: Point data of the web polyline (array names).
WEB_FIELDS = tuple(ARRAY_NAMES[k] for k in ("w", "h", "p_rel", "p", "p_contact", "chi_c", "mu",
                                            "regime", "in_wrap"))
#: Point data of the film surface (2-D models; array names).
FILM_FIELDS = tuple(ARRAY_NAMES[k] for k in ("p", "p_rel", "h", "p_contact", "chi_c", "mu",
                                             "regime", "in_wrap"))
#: Integer arrays: the regime codes and the in-wrap flag.
_INTEGER = ("regime", "in_wrap")
#: Field data every result file carries: the regime codes' names and the coordinates'
#: meaning (names are text, values numbers: meshio cannot read VTK string arrays).
MEANING = {"regime 0 = boundary (h < h_c)": 0.0, "regime 1 = mixed (h_c <= h <= 3 sigma)": 1.0,
           "regime 2 = fluid (h > 3 sigma)": 2.0,
           "X = arc from the wrap centre [m], air dragged to +X": 0.0,
           "Y = across the width from the centre line [m] (film)": 0.0,
           "in_wrap = 1 on the roller (|X| <= R B / 2), 0 in the free spans": 0.0,
           "mu = local traction over the wrap load T_eff/R, its wrap average the summary's "
           "mu; above mu_cc where the asperities carry more than T_eff/R": 0.0}


#: The film's Y where a grooved roller's periodic cell answered: mirrored about its land
#: centre, the file shows one groove pitch, not the web's width.
CELL_Y = ("Y = across one groove pitch from a land centre [m] (film: the periodic cell, land "
          "centre to groove centre, mirrored; the web's edges left out)")


def _field_data(values: dict) -> bytes:
    """A VTK ``<FieldData>`` block of Float64 arrays (text is kept out of the values: meshio
    cannot read VTK string arrays)."""
    lines = ["<FieldData>"]
    for name, value in values.items():
        lines.append(f'<DataArray type="Float64" Name={quoteattr(name)} '
                     f'NumberOfTuples="1" format="ascii">{float(value)!r}</DataArray>')
    lines.append("</FieldData>\n")
    return "\n".join(lines).encode("utf-8")


def write_mesh(mesh: meshio.Mesh, path: Path, field_data: dict | None = None) -> Path:
    """Write ``mesh`` to VTU file ``path`` atomically, with ``field_data`` (name -> number,
    read back by :func:`read_field_data`) in the file; returns ``path``."""
    with replacing(path) as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
        if field_data:   # meshio's VTU writer drops field data: add it after the grid tag
            data = tmp.read_bytes()
            tag = b"<UnstructuredGrid>\n"
            at = data.index(tag) + len(tag)
            tmp.write_bytes(data[:at] + _field_data(field_data) + data[at:])
    return path


def read_field_data(path: str | Path) -> dict:
    """The field data :func:`write_result` stored in a VTU file (name -> number)."""
    head = Path(path).read_bytes()[:65536].decode("utf-8", errors="replace")
    block = re.search(r"<FieldData>.*?</FieldData>", head, re.S)
    return {array.get("Name"): float(array.text)
            for array in ElementTree.fromstring(block.group(0) if block else "<FieldData/>")}


def _arrays(values: dict, keys) -> dict:
    return {ARRAY_NAMES[k]: np.asarray(values[k], np.int32 if k in _INTEGER else float)
            for k in keys if k in values}


def web_mesh(result) -> meshio.Mesh:
    """The web as a polyline along x [m] with its fields (width-averaged film pressure),
    arrays named with their units (:data:`ARRAY_NAMES`)."""
    f = result.fields
    x = np.asarray(f["x"], float)
    pts = np.column_stack([x, np.zeros_like(x), np.zeros_like(x)])
    cells = [("line", np.column_stack([np.arange(x.size - 1), np.arange(1, x.size)]))]
    data = _arrays(f, ARRAY_NAMES)
    if "in_wrap" not in data:   # the closed form solves the wrap only
        data["in_wrap"] = np.ones(x.size, np.int32)
    return meshio.Mesh(pts, cells, point_data=data)


def film_mesh(result, full: bool = True) -> meshio.Mesh:
    """The film surface (x, y = z) [m] with its vertex fields and the in-wrap flag; with
    ``full`` a half-width solve is mirrored about the centre line, so the file shows the
    whole web."""
    film = result.film
    pts = np.asarray(film["points"], float)
    quads = np.asarray(film["quads"], int)
    values = {k: np.asarray(film[k]) for k in ARRAY_NAMES if k in film}
    half = result.case.roller.radius * result.case.B / 2
    values["in_wrap"] = (np.abs(pts[:, 0]) <= half * (1 + 1e-12)).astype(np.int32)
    if full and pts[:, 1].min() >= 0.0 and pts[:, 1].max() > 0.0:
        off = np.flatnonzero(pts[:, 1] > 0.0)   # the centre line's vertices stay shared
        image = np.arange(len(pts))
        image[off] = len(pts) + np.arange(off.size)
        pts = np.vstack([pts, pts[off] * [1.0, -1.0, 1.0]])
        quads = np.vstack([quads, image[quads][:, ::-1]])   # reversed: still counter-clockwise
        values = {k: np.concatenate([v, v[off]]) for k, v in values.items()}
    return meshio.Mesh(pts, [("quad", quads)], point_data=_arrays(values, ARRAY_NAMES))


#: Field data naming where the reported minimum gap lies and how it compares with the
#: smallest gap at the file's nodes (:func:`_minimum_data`).
H_MIN_KEYS = ("h_min [m]", "x_min [m]", "h_min of the nodes in this file [m]",
              "h_min of the nodes / reported h_min - 1 [-]")
#: The sentence a ParaView user reads (as a field name: VTK field values are numbers).
H_MIN_NOTE = ("note: h_min [m] is the reported smallest gap, at x_min [m] between nodes "
              "(the finite element solution there); the h array is at the nodes, whose "
              "smallest value is larger by the ratio given")


def _summary_data(result) -> dict:
    """The headline numbers, named with their units, for every file of a result."""
    s, c = result.summary, result.case
    data = {"roller.speed [m/s]": c.roller.speed, "web.tension [N/m]": c.web.tension,
            "wrap.angle_deg [deg]": c.wrap.angle_deg, "web.width [m]": c.web.width,
            "roller.radius [m]": c.roller.radius, "mu (wrap average) [-]": s.mu,
            "h_min [m]": s.h_min, "x_min [m]": s.x_min, "h_c [m]": s.h_c,
            "3 sigma [m]": 3 * s.sigma, "converged": float(bool(s.converged))}
    return {k: v for k, v in data.items() if v is not None and np.isfinite(v)}


def _minimum_data(result, h_nodes) -> dict:
    """The smallest gap at the nodes of one file beside the reported h_min, and a note when
    they differ: the solution's minimum lies between nodes (3.30 um at x_min on the base
    case, 3.35 um at the nearest node), so the file's h array alone would not show it."""
    h_min = result.summary.h_min
    h = np.asarray(h_nodes, float)
    h = h[np.isfinite(h)]
    if h_min is None or not np.isfinite(h_min) or h.size == 0:
        return {}
    nodes = float(h.min())
    data = {H_MIN_KEYS[2]: nodes}
    if h_min > 0.0:
        data[H_MIN_KEYS[3]] = nodes / h_min - 1.0
    if not np.isclose(nodes, h_min, rtol=1e-9, atol=0.0):
        data[H_MIN_NOTE] = 1.0
    return data


def write_result(result, folder, stem: str | None = None, field_data: dict | None = None
                 ) -> list[Path]:
    """Write ``STEM_web.vtu`` (and ``STEM_film.vtu`` for 2-D models); returns the paths.

    Arrays carry their units in their names (``"h [m]"``, ``"p-p_a [Pa]"``); ``regime`` is
    an integer whose names, with the coordinates' meaning and the headline numbers, are in
    the field data (:data:`MEANING`); the film covers the full width (a grooved roller's
    periodic cell: one groove pitch, :data:`CELL_Y`). The field data also
    hold the reported ``h_min [m]`` and ``x_min [m]``, the smallest gap at the file's
    nodes and, where the two differ (the minimum lies between nodes), a note saying so
    (:data:`H_MIN_KEYS`, :data:`H_MIN_NOTE`). An unconverged result
    is written with ``_NOT_CONVERGED`` in the names, for inspection. ``field_data`` (name ->
    number) is added to every file. The film is written before the web, so a web file
    implies its film file is complete.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    stem = stem or result["model"]
    if not result["converged"]:
        stem += "_NOT_CONVERGED"
    data = MEANING | _summary_data(result) | dict(field_data or {})
    if result.summary.periodic_cell:
        data = {(CELL_Y if k.startswith("Y =") else k): v for k, v in data.items()}
    paths = []
    if result.film is not None:
        film = film_mesh(result)
        paths.append(write_mesh(film, folder / f"{stem}_film.vtu", data | _minimum_data(
            result, film.point_data.get(ARRAY_NAMES["h"], ()))))
    web = web_mesh(result)
    paths.insert(0, write_mesh(web, folder / f"{stem}_web.vtu", data | _minimum_data(
        result, web.point_data.get(ARRAY_NAMES["h"], ()))))
    return paths


def write_pvd(entries, path, comment: str = "", parameter: str = "") -> Path:
    """A ParaView collection: ``entries`` are ``(value, file)`` or ``(value, file, name)``
    (files relative to the .pvd's folder or absolute); the swept value becomes the
    collection's time, and ``parameter`` (its name) is stated in the file's first comment
    and as an attribute of the collection, which ParaView ignores but a reader can see."""
    path = Path(path)
    lines = ['<?xml version="1.0"?>']
    if parameter:
        lines.append(f"<!-- time (timestep) = {escape(parameter).replace('--', '- -')} -->")
    lines.append('<VTKFile type="Collection" version="0.1" byte_order="LittleEndian"'
                 + (f" parameter={quoteattr(parameter)}" if parameter else "") + ">")
    if comment:
        lines.append(f"  <!-- {escape(comment).replace('--', '- -')} -->")
    lines.append("  <Collection>")
    for value, file, *name in entries:
        rel = os.path.relpath(Path(file), path.parent)
        named = f" name={quoteattr(name[0])}" if name else ""
        lines.append(f'    <DataSet timestep="{float(value)!r}" part="0"{named} '
                     f'file={quoteattr(rel)}/>')
    lines += ["  </Collection>", "</VTKFile>", ""]
    path.parent.mkdir(parents=True, exist_ok=True)
    return write_text(path, "\n".join(lines))


_LABEL = "series: "


def _tag(label: str) -> str:
    return "".join(ch if ch.isalnum() else "_" for ch in label).strip("_")[:40]


class SweepVtu:
    """The VTU files of a sweep: ``STEM_sSS_pPPP_web.vtu`` (and ``_film.vtu``) per point,
    numbered from 1 by series and point, and ``STEM_sSS_TAG_web.pvd`` per series and part.

    Each file holds as field data the swept ``value`` (also under the parameter's name),
    ``series`` and ``point`` (numbers from 1), ``converged`` (1 or 0) and the series label
    as the name of an array ``"series: LABEL"`` holding the series number (VTK string
    arrays would make the files unreadable to meshio); the ``.pvd`` names each data set by
    its label. For :func:`webfem.sweeps.run`'s ``vtu`` argument: ``missing`` tells which
    points need files (a resumed sweep solves those again), ``write`` writes one point,
    ``close`` the collections (once; later calls return the same paths).

    Raises InputError at creation if ``folder`` cannot be written, before anything is solved.
    """

    def __init__(self, folder, stem: str, parameter: str):
        self.folder, self.stem, self.parameter = Path(folder), stem, parameter
        if self.folder.exists() and not self.folder.is_dir():
            raise InputError(f"VTU folder {self.folder} is a file; it must be a folder")
        try:
            self.folder.mkdir(parents=True, exist_ok=True)
        except (FileExistsError, NotADirectoryError):
            raise InputError(f"cannot create the VTU folder {self.folder}: a file is in the "
                             "way") from None
        except PermissionError:
            raise InputError(f"cannot create the VTU folder {self.folder}: permission denied") \
                from None
        if not os.access(self.folder, os.W_OK | os.X_OK):
            raise InputError(f"cannot write in the VTU folder {self.folder}: permission denied")
        remove_stale_temps(self.folder, stem)
        # (series, part) -> point -> (value, path, label)
        self._entries: dict[tuple[int, str], dict[int, tuple]] = {}
        self._closed: list[Path] | None = None

    def path(self, series: int, point: int, part: str = "web", converged: bool = True
             ) -> Path:
        """The file of one point (indices from 0 as :func:`~webfem.sweeps.run` passes them;
        the names count from 1)."""
        flag = "" if converged else "_NOT_CONVERGED"
        return self.folder / f"{self._stem(series, point)}{flag}_{part}.vtu"

    def _stem(self, series: int, point: int) -> str:
        return f"{self.stem}_s{series + 1:02d}_p{point + 1:03d}"

    def missing(self, series_index: int, point_index: int) -> bool:
        """True unless this point's converged files are there (and readable)."""
        web = self.path(series_index, point_index, "web")
        try:
            data = read_field_data(web)
            value = data["value"]
            label = next(k[len(_LABEL):] for k in data if k.startswith(_LABEL))
        except (OSError, KeyError, ValueError, TypeError, StopIteration,
                ElementTree.ParseError):
            return True
        film = self.path(series_index, point_index, "film")
        for part, path in (("web", web), ("film", film)):
            if path.exists():
                self._entries.setdefault((series_index, part), {})[point_index] = (
                    value, path, label)
        return False

    def write(self, series_index: int, point_index: int, label: str, value: float, result
              ) -> list[Path]:
        """Write one point's files; returns their paths."""
        data = {"value": float(value), self.parameter: float(value),
                "series": series_index + 1, _LABEL + str(label): series_index + 1,
                "point": point_index + 1, "converged": float(bool(result["converged"]))}
        paths = write_result(result, self.folder, self._stem(series_index, point_index), data)
        for part in ("web", "film"):   # the other outcome's files of this point are stale
            self.path(series_index, point_index, part,
                      not result["converged"]).unlink(missing_ok=True)
        for path in paths:
            part = "film" if path.stem.endswith("_film") else "web"
            self._entries.setdefault((series_index, part), {})[point_index] = (
                float(value), path, str(label))
        return paths

    def close(self) -> list[Path]:
        """Write one ``.pvd`` per series and part; returns their paths."""
        if self._closed is None:
            self._closed = []
            for (series, part), points in sorted(self._entries.items()):
                entries = [points[p] for p in sorted(points)]
                label = entries[0][2]
                tag = _tag(label)
                name = f"{self.stem}_s{series + 1:02d}{'_' + tag if tag else ''}_{part}.pvd"
                self._closed.append(write_pvd(
                    entries, self.folder / name,
                    comment=f"webfem sweep {self.stem}: series {series + 1} ({label}); "
                            f"timestep = swept parameter {self.parameter}",
                    parameter=self.parameter))
        return list(self._closed)
