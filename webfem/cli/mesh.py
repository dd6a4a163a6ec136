"""``webfem mesh``: the graded web and film meshes a case's FE solve starts from, as VTU."""

from __future__ import annotations

from pathlib import Path

from ..models.start_mesh import start_meshes
from .common import (HELP_FORMATTER, add_case_arguments, case_from, model_options,
                     options_epilog, output_folder)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "mesh", help="write the graded web and film meshes of a case (VTU, metres) as the FE "
                     "models start from them",
        description="Write CASE_web.vtu (x nodes along the web) and CASE_film.vtu (x times "
                    "the width nodes), in metres, before the models refine where the film is "
                    "thin. The meshes follow fe2d's options entry, level, symmetry and "
                    "width_fine.",
        formatter_class=HELP_FORMATTER, epilog=options_epilog(["fe2d"]))
    # --model is accepted for old scripts; the meshes are fe2d's
    add_case_arguments(p, default_model="fe2d")
    p.add_argument("--out", required=True, help="output folder")


def run(args) -> int:
    # imported here: meshio took ~0.1 s of every command's start (each builds all parsers)
    from ..io.meshes import write_meshes

    case = case_from(args)
    options = model_options(args, "fe2d")
    folder = output_folder(args.out, "--out")
    x, z = start_meshes(case, options)
    for path in write_meshes(x, z, folder, Path(args.case).stem):
        print(f"wrote {path}")
    return 0
