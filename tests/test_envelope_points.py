"""The hardest points of the envelope benchmark (``benchmarks/envelope.py``, seed 22): each must
answer with auto, the default.

Points are the benchmark's, numbered as there, at full precision (rounded to 4 digits, #120
answers in 3 s instead of 17-29 s: the solver's path is that sensitive): a material's case file
(its web, friction and roller roughness) at another radius, tension, wrap, width and speeds,
grooved or not. The fast set was refused before issue 22 (webs resting on the roller; board,
whose bending stiffness, Dn in the hundreds, puts the residual's rounding floor above the
absolute tolerance); what still fails is ``xfail(strict=True)`` with its cause, so each test
flips (XPASS, a failure to act on) when it is mended. The fast set runs in about 20 s; the slow set
(``make test-slow``) holds the points that take 10-60 s or longer, each solved in a child
process killed after 60 s (the issue's limit).
"""

from __future__ import annotations

import multiprocessing
import warnings

import pytest

import webfem
from conftest import CASE_DIR

pytestmark = pytest.mark.filterwarnings("ignore::webfem.errors.ValidityWarning")

MATERIALS = {"newsprint": "base", "PET": "pet_idler", "foil": "foil_roller", "board": "board"}
LIMIT = 60.0


def point(material: str, R: float, T: float, B: float, L: float, U_r: float, U_w: float,
          pitch: float = 0.0, width: float = 0.0, depth: float = 0.0) -> webfem.Case:
    """A point as the benchmark builds it (``envelope_sample.case_of``)."""
    return webfem.load_case(CASE_DIR / f"{MATERIALS[material]}.toml").updated({
        "roller.radius": R, "web.tension": T, "wrap.angle_deg": B, "web.width": L,
        "roller.speed": U_r, "web.speed": U_w, "roller.drag_torque": 0.0,
        "roller.inertia": 0.0, "web.acceleration": 0.0, "roller.groove_pitch": pitch,
        "roller.groove_width": width, "roller.groove_depth": depth})


FAST = [
    pytest.param(point("newsprint", 0.026657924755901088, 241.61511997181137, 64.80715484176389,
                       1.8300893130692903, 0.8695904538025763, 0.0),
                 id="140-newsprint-held-lands"),
    pytest.param(point("newsprint", 0.0218531600309185, 382.9409885011614, 156.41933868866155,
                       0.21498326520794775, 0.5737444169951277, 0.5737444169951277),
                 id="56-newsprint-idler-lands"),
    pytest.param(point("newsprint", 0.035397008634778133, 150.78674690464047, 43.97945566007834,
                       0.08582802354891242, 10.54938748425151, 6.983451499474462),
                 id="148-newsprint-driven-suction"),
    pytest.param(point("newsprint", 0.04174162164757434, 178.16627440095363, 30.095367703047792,
                       0.2864999799219784, 2.877467299904675, 1.8381601106650391,
                       0.0019775925655030994, 0.0004642236535616499, 0.0003661589424012588),
                 id="23-newsprint-driven-grooved-pressed"),
    pytest.param(point("newsprint", 0.028013710557563284, 156.4157533609509, 11.890595196647327,
                       2.6864671336790074, 24.18289323730403, 0.0, 0.0006381036257750444,
                       0.00016607866946254568, 3.2012199620591715e-05),
                 id="47-newsprint-held-grooved-lands"),
    pytest.param(point("board", 0.19638134790289602, 339.30551464822264, 99.251208809302,
                       0.02636511040680687, 4.339051775982415, 0.0),
                 id="89-board-held-suction"),
    pytest.param(point("board", 0.03246484348705017, 37.77475581630491, 42.10957092039589,
                       0.07406089309492707, 42.85423708729113, 0.0),
                 id="1-board-held-stiff"),
    pytest.param(point("board", 0.030713671672867444, 135.25952178193708, 71.68529300085973,
                       0.8437486605279162, 1.8866915070069905, 3.1277134805523525),
                 id="134-board-driven-stiff"),
    pytest.param(point("board", 0.11127428835501674, 38.74472178236612, 10.957953244889985,
                       1.9203743075671362, 1.3969513958209825, 1.3969513958209825),
                 id="117-board-idler-stiff"),
    # past the flying branch's fold (Dn 640): the Eshel-Elrod path ends with the absolute film
    # pressure below 0, the film strength's path rests the web (over 60 s before it)
    pytest.param(point("board", 0.049130085295654304, 136.21272609428226, 21.582978900383086,
                       1.232876233589238, 2.89440563032965, 2.0471734411643236),
                 id="86-board-driven-past-the-fold"),
    # Dn 2300: Newton's iterates reach the residual's rounding floor (1e-3) with a correction
    # of 1e-9-1e-6 that no step lowers (accepted at the floor; was "line search failed" on
    # every path, then 60 s of fe2d)
    pytest.param(point("board", 0.022870793425287805, 48.03214406339539, 23.298022785291085,
                       1.0570783652655031, 8.621917941139357, 8.621917941139357),
                 id="57-board-idler-at-the-rounding-floor"),
    pytest.param(point("board", 0.06022614488371616, 246.37427321720466, 13.30501278689511,
                       0.012320407854979261, 12.61228954262293, 15.4485795560439),
                 id="60-board-driven-narrow"),
    pytest.param(point("PET", 0.2863032196076981, 235.50821579385448, 10.5293662570822,
                       0.031442702680865534, 14.584018132802168, 0.0, 0.0011595980923180503,
                       0.000532761046914414, 8.119547301217023e-05),
                 id="147-PET-held-grooved-narrow"),
    pytest.param(point("PET", 0.18059101043960907, 102.78943906054803, 106.50730517389044,
                       0.01485196611087133, 12.224630036674535, 0.0),
                 id="162-PET-held-narrow"),
]


@pytest.mark.parametrize("case", FAST)
def test_hard_point_answers(case):
    r = webfem.solve(case)
    assert r.summary.converged and r["h_min"] > -case.web.thickness and 0.0 <= r["mu"] < 5.0


def _solve_in_child(case, queue) -> None:
    warnings.simplefilter("ignore")
    try:
        r = webfem.solve(case)
        queue.put(f"answered converged={r.summary.converged}")
    except Exception as err:  # noqa: BLE001 - reported to the parent
        queue.put(f"{type(err).__name__}: {err}")


def answer_within(case, limit: float = LIMIT) -> str:
    """What auto says for ``case`` in a child process, or 'timeout' past ``limit`` s."""
    ctx = multiprocessing.get_context("fork")
    queue = ctx.Queue()
    child = ctx.Process(target=_solve_in_child, args=(case, queue))
    child.start()
    child.join(limit)
    if child.is_alive():
        child.kill()
        child.join()
        return f"timeout: no answer within {limit:g} s"
    return queue.get(timeout=5) if not queue.empty() else f"died ({child.exitcode})"


SLOW = [
    pytest.param(point("newsprint", 0.07928832162301212, 275.0477313669829, 175.68854107634505,
                       0.023007897046516648, 46.78751422867414, 46.78751422867414,
                       0.0025600018619533565, 0.0005998136144476655, 0.00042746171007085337),
                 id="39-newsprint-idler-grooved-narrow-fast"),
    pytest.param(point("foil", 0.13835512815918824, 113.08653534109646, 167.05998496281953,
                       0.030327718615621842, 34.788077504227594, 0.0, 0.0008521736914234697,
                       0.00023476213304638447, 0.0007296430246532562),
                 # 46.9 s alone on one process (the strict xfail XPASSed on main and here)
                 id="191-foil-held-grooved-narrow"),
    pytest.param(point("board", 0.09322702927739941, 39.888123256518746, 42.24623437101128,
                       0.01990908307497629, 24.494259403758267, 0.0, 0.0007008183524727319,
                       0.0002852014280292631, 0.00015068353529605068),
                 # answers (mu 0.41, the web resting 1.7 um deep) since the depth
                 # continuation's first step may shrink: 92-120 s on the loaded machine
                 # then, 24.6 s alone on one process now (XPASSed on main and here)
                 id="143-board-held-grooved-narrow"),
    pytest.param(point("newsprint", 0.06114512740899566, 181.56246933001026, 14.475138014112687,
                       0.3401409238960507, 9.736536174424273, 9.736536174424273,
                       0.0006895281140219222, 0.00033097577968699103, 0.0007459527643714616),
                 id="179-newsprint-idler-grooved-inadmissible"),
    pytest.param(point("PET", 0.07268047090000081, 239.5257106181927, 129.97582458695916,
                       1.709635318231127, 0.6521185056353574, 0.0, 0.002635619488070767,
                       0.0005978264242576499, 0.00011723228193553134),
                 id="139-PET-held-grooved-wide-most-memory"),
    pytest.param(point("board", 0.07548056354088023, 143.0057322363517, 101.19779652111428,
                       0.5176197219412062, 14.103384655618617, 10.572950077521561,
                       0.0009239460856883392, 0.00021085408103354715, 4.086125989958569e-05),
                 # the edge strip starts from the solved cell and rests 3.8 nm deep, no
                 # longer re-checked by the safe start (the cell's branch is its): 37 s in
                 # the envelope run on a quiet machine (2 processes), 60 s alone at load 3,
                 # 76-220 s at load 3-7 (was 157-455 s): near the limit on a loaded machine
                 id="67-board-driven-grooved-strip"),
    pytest.param(point("board", 0.022352705672172523, 21.975361980738843, 88.36551805943071,
                       0.031040909084778016, 26.81332812593722, 0.0, 0.0006259409199144019,
                       0.00024959128238976366, 0.0001119517501406904),
                 # Dn 1800, narrow (issue 22's <= 20 s figure). Held at the zones' ends it
                 # took over 60 s: Newton on the cell's refined meshes stalled (the stiff web
                 # rests 6-8 sigma into its asperities, the lands' film Jacobian diagonal
                 # 6e-9 against 2.7e5 elsewhere) and the safe start repeated the cell's
                 # depth continuation. Held through its spans (the default) it answers
                 # from an edge strip on 156,871 unknowns, the film accepting Newton's
                 # floor noise there as the 1-D line does (~21 s on a loaded machine).
                 id="171-board-held-grooved-narrow-stiff"),
    pytest.param(point("board", 0.06686807687794044, 386.1665317432179, 165.64374446882212,
                       0.19033965274252743, 38.48716843305741, 26.054261896851166),
                 id="120-board-driven-slowest-answer"),
]


@pytest.mark.slow
@pytest.mark.parametrize("case", SLOW)
def test_slow_hard_point_answers_within_60_s(case):
    assert answer_within(case).startswith("answered converged=True")
