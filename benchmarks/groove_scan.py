"""Grooved-roller scan (issue 22, item 4): a fixed random sample of groove designs and
operating points, each solved with the default options (``webfem solve CASE``: auto, which
uses fe2d on a grooved roller) in its own process with a time and a memory limit.

Run (on demand, not in the tests; serial: the machines are shared)::

    .venv/bin/python benchmarks/groove_scan.py --n 90 --seed 22 --out /tmp/groove_scan.jsonl

The generator (seeded, so the same sample every time): one of three webs in turn (newsprint,
``cases/base_grooved.toml``; PET film, ``cases/pet_idler_grooved.toml``; aluminium foil,
``cases/foil_roller.toml`` with grooves added), pitch log-uniform 0.5-6 mm, land fraction
uniform 50-95 % (a draw whose groove width falls outside 0.1-1 mm is drawn again), depth
log-uniform 25 um-1 mm, roller speed log-uniform 1-60 m/s (the web's speed scaled with it:
still for newsprint, equal for the PET idler, 0.2/8.2 slower for the foil), web width
log-uniform 5 mm-3 m. Everything else is the bundled case's.

Each point is recorded as ``answered``, ``refused`` (webfem's NoAdmissibleSolution or
InputError: the problem has no admissible answer, said with the reason), ``impossible`` (the
case itself is refused: a web too fast to be held on the roller, T_eff <= 0; left out of the
answered fraction) or ``failed`` (did not
converge, a crash, over the time limit or over the memory limit), with its wall time and its
peak resident memory (the child's ru_maxrss). Results are appended to ``--out`` as JSON lines;
a second run with the same file skips the points already there (``--fresh`` starts over).
``--only i,j`` solves the given indices; ``--report`` only prints the figures of ``--out``.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import signal
import statistics
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WEBS = {
    # name: (case file, web speed / roller speed)
    "newsprint": ("base_grooved.toml", 0.0),
    "pet": ("pet_idler_grooved.toml", 1.0),
    "foil": ("foil_roller.toml", 8.0 / 8.2),
}


def draw(n: int, seed: int, family: str = "random") -> list[dict]:
    """``n`` designs and operating points from the generator of the module text.

    ``family``: "random" (the envelope of issue 22), "narrow" (the same, but web widths
    log-uniform from 5 mm to 10 pitches: the full-width solves) or "fast" (roller speeds
    38-60 m/s, the web held still or at its case's speed ratio, drawn in turn: the moving
    foil and PET webs cannot be held on the roller that fast)."""
    import numpy as np

    rng = np.random.default_rng(seed + {"random": 0, "narrow": 1000, "fast": 2000}[family])
    names = list(WEBS)
    out = []
    while len(out) < n:
        pitch = math.exp(rng.uniform(math.log(0.5e-3), math.log(6e-3)))
        land = rng.uniform(0.5, 0.95)
        depth = math.exp(rng.uniform(math.log(25e-6), math.log(1e-3)))
        lo, hi = (38.0, 60.0) if family == "fast" else (1.0, 60.0)
        speed = math.exp(rng.uniform(math.log(lo), math.log(hi)))
        top = 10.0 * pitch if family == "narrow" else 3.0
        width = math.exp(rng.uniform(math.log(5e-3), math.log(top)))
        groove = pitch * (1.0 - land)
        if not 0.1e-3 <= groove <= 1e-3:
            continue
        web = names[len(out) % len(names)]
        ratio = WEBS[web][1] if family != "fast" or (len(out) // 3) % 2 else 0.0
        out.append({"index": len(out), "family": family, "web": web, "pitch": pitch,
                    "land": land, "groove_width": groove, "depth": depth, "speed": speed,
                    "width": width, "web_speed_ratio": ratio})
    return out


def values_of(point: dict) -> dict:
    """The case keys a point sets on its web's bundled case."""
    ratio = point.get("web_speed_ratio", WEBS[point["web"]][1])
    return {"roller.groove_pitch": point["pitch"], "roller.groove_width": point["groove_width"],
            "roller.groove_depth": point["depth"], "roller.speed": point["speed"],
            "web.speed": ratio * point["speed"], "web.width": point["width"]}


def solve_one(point: dict) -> dict:
    """Solve one point here (the child process) and return what the scan records."""
    import warnings

    import webfem
    from webfem.errors import ConvergenceError, InputError

    t0 = time.perf_counter()
    try:
        case = webfem.load_case(ROOT / "cases" / WEBS[point["web"]][0], values_of(point))
    except InputError as err:          # e.g. T_eff <= 0: no such line exists
        return {"status": "impossible", "reason": str(err), "time": time.perf_counter() - t0}
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            r = webfem.solve(case)
    except InputError as err:          # NoAdmissibleSolution included: no answer exists
        return {"status": "refused", "reason": str(err), "time": time.perf_counter() - t0}
    except ConvergenceError as err:
        return {"status": "failed", "reason": str(err), "time": time.perf_counter() - t0}
    s = r.summary
    return {"status": "answered", "time": time.perf_counter() - t0,
            "model_used": s.get("model_used"), "groove_domain": s.get("groove_domain"),
            "h_center": s.get("h_center"), "h_min": s.get("h_min"), "mu": s.get("mu"),
            "n_dofs": s.get("n_dofs"), "lambda": s.get("lambda_"),
            "error_h_center": s.get("error_h_center"), "error_h_min": s.get("error_h_min"),
            "error_mu": s.get("error_mu"), "estimated_error": s.get("estimated_error"),
            "warnings": list(s.get("warnings") or ())}


def _rss_kb(pid: int) -> int:
    try:
        for line in Path(f"/proc/{pid}/status").read_text().splitlines():
            if line.startswith("VmRSS:"):
                return int(line.split()[1])
    except OSError:
        pass
    return 0


def run_point(point: dict, timeout: float, mem_gb: float) -> dict:
    """Solve ``point`` in a child process; kill it past ``timeout`` s or ``mem_gb`` GB."""
    env = dict(os.environ, OMP_NUM_THREADS="1", OPENBLAS_NUM_THREADS="1", MKL_NUM_THREADS="1")
    t0 = time.perf_counter()
    child = subprocess.Popen([sys.executable, __file__, "--child", json.dumps(point)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, env=env,
                             cwd=ROOT, start_new_session=True)
    killed = None
    while True:
        pid, status, usage = os.wait4(child.pid, os.WNOHANG)
        if pid:
            break
        if time.perf_counter() - t0 > timeout:
            killed = f"over the time limit of {timeout:g} s"
        elif _rss_kb(child.pid) > mem_gb * 1024 ** 2:
            killed = f"over the memory limit of {mem_gb:g} GB"
        if killed:
            os.killpg(child.pid, signal.SIGKILL)
            pid, status, usage = os.wait4(child.pid, 0)
            break
        time.sleep(0.05)
    wall = time.perf_counter() - t0
    child.returncode = os.waitstatus_to_exitcode(status)
    out, err = child.stdout.read().decode(), child.stderr.read().decode()
    child.stdout.close()
    child.stderr.close()
    peak = usage.ru_maxrss / 1024 ** 2      # kB -> GB
    if killed:
        rec = {"status": "failed", "reason": killed, "time": wall}
    else:
        lines = [ln for ln in out.splitlines() if ln.startswith("{")]
        rec = json.loads(lines[-1]) if lines else {
            "status": "failed", "time": wall,
            "reason": "crash: " + (err.strip().splitlines() or ["no output"])[-1]}
    return {**point, **rec, "wall": wall, "peak_gb": peak}


def reason_class(rec: dict) -> str:
    """A short class of a refusal's or failure's reason, for grouping."""
    text = rec.get("reason", "")
    for key, label in [("time limit", "time limit"), ("memory limit", "memory limit"),
                       ("groove depth continuation", "groove depth continuation failed"),
                       ("width continuation", "width continuation failed"),
                       ("through its asperities", "suction pulls the web through"),
                       ("negative", "negative gap"), ("absolute pressure", "negative pressure"),
                       ("thicker than", "film too thick"), ("did not converge", "no convergence"),
                       ("crash", "crash")]:
        if key in text:
            return label
    return text[:80]


def report(records: list[dict]) -> str:
    """The scan's figures: answered fraction, refusals and failures by reason, times, memory."""
    by = Counter(r["status"] for r in records)
    n = len(records) - by["impossible"]
    lines = [f"{len(records)} points, {by['impossible']} impossible (T_eff <= 0), {n} possible: "
             f"answered {by['answered']} ({100 * by['answered'] / max(n, 1):.1f} %), "
             f"refused {by['refused']}, failed {by['failed']}"]
    for status in ("refused", "failed"):
        groups = Counter(reason_class(r) for r in records if r["status"] == status)
        for reason, k in groups.most_common():
            lines.append(f"  {status}: {k} x {reason}")
    solved = [r for r in records if r["status"] != "impossible"]
    times = sorted(r["wall"] for r in solved)
    mems = sorted(r["peak_gb"] for r in solved)

    def pct(v, q):
        return v[min(len(v) - 1, int(math.ceil(q * len(v))) - 1)]

    if times:
        lines.append(f"time (wall, incl. ~1 s of process start): median {statistics.median(times):.2f} s, "
                     f"p90 {pct(times, 0.9):.2f} s, max {times[-1]:.2f} s")
        lines.append(f"peak memory: median {statistics.median(mems):.2f} GB, p90 "
                     f"{pct(mems, 0.9):.2f} GB, max {mems[-1]:.2f} GB")
    domains = Counter((r.get("groove_domain") or "").split(":")[0] for r in records
                      if r["status"] == "answered")
    lines.append("answered on: " + ", ".join(f"{k or '?'} {v}" for k, v in domains.items()))
    return "\n".join(lines)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=90)
    ap.add_argument("--seed", type=int, default=22)
    ap.add_argument("--family", default="random", choices=("random", "narrow", "fast"))
    ap.add_argument("--out", default=None, help="default /tmp/groove_scan_FAMILY.jsonl")
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--mem-gb", type=float, default=6.0)
    ap.add_argument("--only", default="")
    ap.add_argument("--fresh", action="store_true")
    ap.add_argument("--report", action="store_true")
    ap.add_argument("--child", default=None, help=argparse.SUPPRESS)
    a = ap.parse_args(argv)
    if a.child is not None:
        print(json.dumps(solve_one(json.loads(a.child))))
        return
    out = Path(a.out or f"/tmp/groove_scan_{a.family}.jsonl")
    if a.fresh and out.exists():
        out.unlink()
    done = {}
    if out.exists():
        for line in out.read_text().splitlines():
            rec = json.loads(line)
            done[rec["index"]] = rec
    points = draw(a.n, a.seed, a.family)
    if a.only:
        want = {int(i) for i in a.only.split(",")}
        points = [p for p in points if p["index"] in want]
    if not a.report:
        for p in points:
            if p["index"] in done and not a.only:
                continue
            rec = run_point(p, a.timeout, a.mem_gb)
            done[p["index"]] = rec
            with out.open("a") as f:
                f.write(json.dumps(rec) + "\n")
            print(f"{p['index']:3d} {p['web']:9s} pitch {p['pitch'] * 1e3:.2f} mm land "
                  f"{p['land']:.2f} depth {p['depth'] * 1e6:.0f} um {p['speed']:.1f} m/s width "
                  f"{p['width'] * 1e3:.0f} mm -> {rec['status']} {rec['wall']:.1f} s "
                  f"{rec['peak_gb']:.2f} GB {rec.get('reason', '')[:100]}", flush=True)
    print(report([done[p["index"]] for p in points if p["index"] in done]))


if __name__ == "__main__":
    main()
