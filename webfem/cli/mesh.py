"""``webfem mesh``: the graded web and film meshes a case's FE solve starts from, as VTU."""

from __future__ import annotations

from pathlib import Path

from ..errors import InputError
from ..models.start_mesh import film_domain, start_meshes
from .common import (HELP_FORMATTER, add_case_arguments, case_from, model_options,
                     options_epilog, output_folder)


def add_parser(subparsers) -> None:
    p = subparsers.add_parser(
        "mesh", help="write the graded web and film meshes of a case (VTU, metres) as the FE "
                     "models start from them",
        description="Write CASE_web.vtu (x nodes along the web) and CASE_film.vtu (x times "
                    "the width nodes), in metres, before the models refine where the film is "
                    "thin. On a grooved roller the film mesh spans the domain fe2d solves: "
                    "the periodic groove cell (land centre to groove centre) under grooves = "
                    "auto, which solves it first, else the domain grooves names. "
                    "The meshes follow fe2d's options entry, level, symmetry and "
                    "width_fine (--model fe2d or auto, the default); --model fe1d writes its "
                    "own web mesh alone (options entry, level: it solves no film across the "
                    "width). The closed form and the fitted model solve no mesh: refused.",
        formatter_class=HELP_FORMATTER, epilog=options_epilog(["fe2d", "fe1d"]))
    add_case_arguments(p, default_model="fe2d")
    p.add_argument("--out", required=True, help="output folder")


#: Models without a mesh: what they evaluate instead (the refusal says it).
NO_MESH = {"closed-form": "Eq. 21 and its friction in closed form",
           "fitted": "a fit of fe2d's answers"}


def run(args) -> int:
    # imported here: meshio took ~0.1 s of every command's start (each builds all parsers)
    from ..io.meshes import write_meshes, write_web_mesh

    if args.model in NO_MESH:
        # it used to write fe2d's meshes under any --model: files no solve of it uses
        raise InputError(f"--model {args.model} solves no mesh ({NO_MESH[args.model]}): "
                         "`webfem mesh` writes the FE models' starting meshes, --model fe2d "
                         "(web and film) or fe1d (the web)")
    case = case_from(args)
    model = "fe1d" if args.model == "fe1d" else "fe2d"   # auto's finest model is fe2d
    options = model_options(args, model)
    folder = output_folder(args.out, "--out")
    x, z = start_meshes(case, options)
    stem = Path(args.case).stem
    domain = film_domain(case, options) if model == "fe2d" else None
    paths = (write_meshes(x, z, folder, stem, cell=domain.startswith("the periodic"))
             if model == "fe2d" else [write_web_mesh(x, folder, stem)])
    for path in paths:
        print(f"wrote {path}")
    if domain is not None:
        print(f"film mesh across: {domain}")
    return 0
