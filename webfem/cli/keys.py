"""``webfem keys``: the case TOML keys with their defaults, units and meaning, and the tables
a sweep reads ([sweep], [[series]])."""

from __future__ import annotations

import dataclasses


def add_parser(subparsers) -> None:
    subparsers.add_parser("keys", help="list the case TOML keys with units and defaults, and "
                                       "the [sweep] and [[series]] tables")


def _case_lines() -> list[str]:
    from ..case import _SECTIONS, Case

    default = Case()
    lines = []
    for name, cls in _SECTIONS.items():
        lines.append(f"[{name}]")
        for f in dataclasses.fields(cls):
            meta = f.metadata
            extra = (" one of " + ", ".join(meta["choices"]) if "choices" in meta
                     else f" [{meta.get('unit', '')}]")
            lines.append(f"  {f.name:<18} = {getattr(getattr(default, name), f.name)!r:<12}"
                         f"{extra}  {meta.get('doc', '')}")
    return lines


def _sweep_lines() -> list[str]:
    from ..sweepspec import MAX_POINTS, MAX_SERIES, MAX_VALUES

    row = "  {:<18}   {}"
    return [
        "[sweep]             (read by `webfem sweep`; without it the sweep is the paper's "
        "roller speed range)",
        row.format("parameter", "the swept numeric case key, e.g. \"roller.speed\" (the "
                                "default) or \"web.tension\""),
        row.format("values", f"the swept values, e.g. [1.0, 2.5, 5.0]: 1 to {MAX_VALUES} "
                             "distinct finite numbers; or instead:"),
        row.format("start, stop", "the ends of an evenly spaced range"),
        row.format("num", f"number of values in the range (an integer, 1 to {MAX_VALUES})"),
        row.format("spacing", "one of linear, log (log needs start and stop > 0)"),
        f"[[series]]          (repeatable, at most {MAX_SERIES}; at most {MAX_POINTS} points "
        "in all; without it one series 'base')",
        row.format("label", "the curve family's name in the CSV and the chart: non-empty "
                            "text, unique"),
        row.format("SECTION.KEY", "any case key this family changes from the file's case, "
                                  "e.g. wrap = { angle_deg = 20 }"),
    ]


def run(args) -> int:
    print("\n".join(_case_lines() + _sweep_lines()))
    return 0
