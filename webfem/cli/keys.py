"""``webfem keys``: the case TOML keys with their defaults, units and meaning, and the tables
a sweep reads ([sweep], [[series]])."""

from __future__ import annotations

import dataclasses


def add_parser(subparsers) -> None:
    subparsers.add_parser("keys", help="list the case TOML keys with units and defaults, and "
                                       "the [sweep] and [[series]] tables")


def _case_lines() -> list[str]:
    from ..case import Case
    from ..keys import key_range
    from ..sections import ALIASES, SECTIONS
    from ..units import examples

    def line(name, key, default, meta):
        if meta["kind"] == "choice":
            extra = " one of " + ", ".join(meta["choices"])
            valid = ""
        else:
            e1, e2 = examples(key, meta["unit"])
            extra = f" [{meta['unit']}] or e.g. '{e1}', '{e2}'"
            # the range every value is checked against (sections.py), in the key's SI unit
            valid = f" ({key_range(key).replace('must be', 'valid:')} {meta['unit']})"
        return f"  {name:<18} = {default!r:<12}{extra}  {meta.get('doc', '')}{valid}"

    default = Case()
    lines = []
    for name, cls in SECTIONS.items():
        lines.append(f"[{name}]")
        for f in dataclasses.fields(cls):
            key = f"{name}.{f.name}"
            lines.append(line(f.name, key, getattr(getattr(default, name), f.name), f.metadata))
            for alias, (stored, _, meta) in ALIASES.items():
                if stored == key:
                    lines.append(line(alias.split(".", 1)[1], alias, None, meta))
    return lines


def _sweep_lines() -> list[str]:
    from ..sweepspec import MAX_POINTS, MAX_SERIES, MAX_VALUES

    row = "  {:<18}   {}"
    return [
        "[sweep]             (read by `webfem sweep`; without it the sweep is the paper's "
        "roller speed range)",
        row.format("parameter", "the swept numeric case key, e.g. \"roller.speed\" (the "
                                "default; moves the roller alone) or \"web.tension\"; or "
                                "\"line.speed\" [m/s] (e.g. \"600 m/min\"): roller and web "
                                "together at the case's U_w/U_r, as an idler's line moves "
                                "(`webfem sweep --parameter` on the command line)"),
        row.format("values", f"the swept values, e.g. [1.0, 2.5, 5.0]: 1 to {MAX_VALUES} "
                             "distinct finite numbers, SI or text with a unit of the "
                             "swept key (\"600 m/min\"); or instead:"),
        row.format("start, stop", "the ends of an evenly spaced range (SI or with a unit)"),
        row.format("num", f"number of values in the range (an integer, 1 to {MAX_VALUES})"),
        row.format("spacing", "one of linear, log (log needs start and stop > 0)"),
        f"[[series]]          (repeatable, at most {MAX_SERIES}; at most {MAX_POINTS} points "
        "in all; without it one series 'base')",
        row.format("label", "the curve family's name in the CSV and the chart: non-empty "
                            "text, unique"),
        row.format("SECTION.KEY", "any case key this family changes from the file's case, "
                                  "e.g. wrap = { angle_deg = 20 }"),
    ]


#: After the tables: how units are read.
UNITS_NOTE = ("Numbers are in the SI unit shown in brackets, within the range shown (generous "
              "limits no real line reaches: a value beyond them is refused by name); text "
              "with a unit is read too "
              "(TOML: speed = \"1200 m/min\"; command line: --set 'roller.speed=1200 m/min'). "
              "US: pli (lbf/in), ft/min or fpm, in, mil (0.001 in), psi.")


def run(args) -> int:
    print("\n".join(_case_lines() + _sweep_lines() + ["", UNITS_NOTE]))
    return 0
