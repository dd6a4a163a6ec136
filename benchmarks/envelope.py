"""Envelope benchmark (issue 22, item 5): auto across a fixed random sample of realistic lines.

Run: ``python benchmarks/envelope.py [--points 200] [--workers 2] [--out out/envelope]``
(about 7 minutes for 200 points on 2 cores; not part of the test suite). The sample and
its generator: ``envelope_sample.py``. ``--material board`` (or ``--index 57 86``) solves and
reports only those of the first ``--points``. Each point is solved with ``webfem.solve(case)``
(auto, the default options) in its own forked process (one BLAS thread), killed after
``--timeout`` s (60) or above ``--memory`` GB; its time is the solve's wall time, its memory
the process's peak resident set (``wait4``'s ru_maxrss, the interpreter and webfem
included). Each result is appended to ``OUT/envelope.csv`` as it arrives; a second run with
the same folder solves only the points not yet there (``--replace`` starts over).

Prints the answered fraction of the physically possible points (the refusals no model could
answer are listed apart, with why, see ``envelope_sample.IMPOSSIBLE``), the refusals grouped
by reason, the failures ("did not converge", crash, timeout) one by one, time median, p90
and max, peak memory, and each figure beside issue 22's target, met or not.
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import resource
import select
import signal
import statistics
import sys
import time
from collections import Counter
from pathlib import Path

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

from common import target  # noqa: E402
from envelope_sample import IMPOSSIBLE, MATERIALS, PARAMS, case_of, category, draw  # noqa: E402

RESULTS = ("status", "category", "seconds", "peak_mb", "model_used", "h_min", "mu",
           "n_dofs", "message")
FIELDS = PARAMS + RESULTS


def solve_point(p: dict) -> dict:
    """Solve point ``p`` with auto (runs in the child): status, time, the answer's keys."""
    import warnings
    import webfem
    from webfem.errors import ConvergenceError, InputError
    warnings.simplefilter("ignore")
    out = {"model_used": "", "h_min": "", "mu": "", "n_dofs": "", "message": ""}
    try:
        case = case_of(p)
    except InputError as err:
        return {**out, "status": "refused", "seconds": 0.0, "message": str(err)}
    t0 = time.perf_counter()
    try:
        r = webfem.solve(case)
        out.update(status="answered", model_used=r["model_used"], h_min=r["h_min"],
                   mu=r["mu"], n_dofs=r["n_dofs"])
    except InputError as err:
        out.update(status="refused", message=str(err))
    except ConvergenceError as err:
        out.update(status="did not converge", message=str(err))
    except Exception as err:  # noqa: BLE001 - a crash is a result here
        out.update(status="crash", message=f"{type(err).__name__}: {err}")
    out["seconds"] = time.perf_counter() - t0
    return out


def _child(p: dict, fd: int) -> None:
    try:
        text = json.dumps(solve_point(p))
    except BaseException as err:  # noqa: BLE001
        text = json.dumps({"status": "crash", "seconds": 0.0,
                           "message": f"{type(err).__name__}: {err}"})
    with os.fdopen(fd, "w") as f:
        f.write(text)
    os._exit(0)


class Running:
    """A point being solved in a forked child: its pipe, start time and collected output."""

    def __init__(self, p: dict):
        self.p, self.t0, self.chunks = p, time.perf_counter(), []
        r, w = os.pipe()
        self.pid = os.fork()
        if self.pid == 0:
            os.close(r)
            _child(p, w)
        os.close(w)
        self.fd, self.killed = r, ""

    def rss_mb(self) -> float:
        try:
            for line in Path(f"/proc/{self.pid}/status").read_text().splitlines():
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024.0
        except OSError:
            pass
        return 0.0

    def kill(self, why: str) -> None:
        self.killed = why
        os.kill(self.pid, signal.SIGKILL)

    def finish(self, limit: float) -> dict:
        """Reap the child; its row (status from its report, or why it was killed)."""
        _, status, usage = os.wait4(self.pid, 0)
        os.close(self.fd)
        text = b"".join(self.chunks).decode()
        out = {"model_used": "", "h_min": "", "mu": "", "n_dofs": "", "message": ""}
        if self.killed == "timeout":
            out.update(status="timeout", seconds=limit, message=f"killed after {limit:g} s")
        elif self.killed:
            out.update(status="crash", seconds=time.perf_counter() - self.t0,
                       message=self.killed)
        elif text:
            out.update(json.loads(text))
        else:
            out.update(status="crash", seconds=time.perf_counter() - self.t0,
                       message=f"the worker died (wait status {status})")
        out["peak_mb"] = usage.ru_maxrss / 1024.0
        out["category"] = (category(out["status"], out["message"])
                           if out["status"] != "answered" else "")
        return {**self.p, **out}


def run(points: list[dict], workers: int, limit: float, memory_gb: float, csv_path: Path,
        done: list[dict]) -> list[dict]:
    """Solve ``points`` on ``workers`` forked processes, appending each row to the CSV."""
    rows, todo, running = list(done), list(points), {}
    total = len(points) + len(done)
    new = not csv_path.exists() or csv_path.stat().st_size == 0
    with csv_path.open("a", newline="") as f:
        writer = csv.DictWriter(f, FIELDS)
        if new:
            writer.writeheader()
        try:
            _loop(todo, running, workers, limit, memory_gb, writer, f, rows, total)
        finally:
            for job in running.values():
                os.kill(job.pid, signal.SIGKILL)
                os.waitpid(job.pid, 0)
    print(file=sys.stderr)
    return sorted(rows, key=lambda r: int(r["index"]))


def _loop(todo, running, workers, limit, memory_gb, writer, f, rows, total) -> None:
    """Start children up to ``workers``, collect their output, kill the overdue ones."""
    while todo or running:
        while todo and len(running) < workers:
            job = Running(todo.pop(0))
            running[job.fd] = job
        ready, _, _ = select.select(list(running), [], [], 0.2)
        for fd in ready:
            chunk = os.read(fd, 65536)
            if chunk:
                running[fd].chunks.append(chunk)
                continue
            row = running.pop(fd).finish(limit)
            writer.writerow(row)
            f.flush()
            rows.append(row)
            _progress(rows, row, total)
        for job in running.values():
            if job.killed:
                continue
            if time.perf_counter() - job.t0 > limit:
                job.kill("timeout")
            elif job.rss_mb() > memory_gb * 1024.0:
                job.kill(f"killed above {memory_gb:g} GB resident")


def _progress(rows, row, total) -> None:
    counts = Counter(r["status"] for r in rows)
    text = (f"[{len(rows):4d}/{total}] " + ", ".join(f"{k} {v}" for k, v in
                                                      sorted(counts.items()))
            + f" | #{row['index']} {row['material']} {row['mode']}"
            f"{' grooved' if str(row['grooved']) == 'True' else ''}: {row['status']} "
            f"{float(row['seconds']):.1f} s {float(row['peak_mb']):.0f} MB")
    end = "\r" if sys.stderr.isatty() else "\n"
    print(f"{text:<110}", end=end, file=sys.stderr, flush=True)


def load(csv_path: Path, points: list[dict]) -> list[dict]:
    """The rows of an earlier run of the same sample (refused if it is another sample)."""
    if not csv_path.exists():
        return []
    by_index = {p["index"]: p for p in points}
    rows = list(csv.DictReader(csv_path.open()))
    for row in rows:
        p = by_index.get(int(row["index"]))
        if p is not None and any(str(p[k]) != row[k] for k in PARAMS if k != "index"):
            sys.exit(f"{csv_path} holds another sample (point {row['index']}): use --replace "
                     "or another --out")
    return [r for r in rows if int(r["index"]) in by_index]


def percentile(values, q: float) -> float:
    values = sorted(values)
    k = (len(values) - 1) * q
    lo, hi = int(k), min(int(k) + 1, len(values) - 1)
    return values[lo] + (values[hi] - values[lo]) * (k - lo)


def report(rows: list[dict], limit: float) -> None:
    impossible = [r for r in rows if r["category"] in IMPOSSIBLE]
    possible = [r for r in rows if r["category"] not in IMPOSSIBLE]
    answered = [r for r in possible if r["status"] == "answered"]
    frac = len(answered) / max(len(possible), 1)
    print(f"envelope: {len(rows)} points (seed 22), {len(impossible)} not physically "
          f"possible, {len(possible)} possible, {len(answered)} answered ({frac:.1%})")
    for name, why in IMPOSSIBLE.items():
        n = sum(r["category"] == name for r in impossible)
        print(f"  not possible: {n:3d} {name}: {why}")
    used = Counter(r["model_used"] for r in answered)
    print("  answered by: " + ", ".join(f"{k} {v}" for k, v in used.most_common()))
    refused = [r for r in possible if r["status"] == "refused"]
    print(f"refusals of possible points: {len(refused)}")
    for name, n in Counter(r["category"] for r in refused).most_common():
        sample = next(r for r in refused if r["category"] == name)
        print(f"  {n:3d} {name}  (e.g. #{sample['index']}: {sample['message'][:160]})")
    failed = [r for r in possible if r["status"] not in ("answered", "refused")]
    print(f"failures: {len(failed)} (" + ", ".join(
        f"{k} {v}" for k, v in Counter(r["status"] for r in failed).most_common()) + ")")
    for (status, name), n in Counter((r["status"], r["category"]) for r in failed).most_common():
        print(f"  {n:3d} {status}: {name}")
    for r in failed:
        print(f"  #{r['index']} {r['material']} {r['mode']} "
              f"{'grooved ' if str(r['grooved']) == 'True' else ''}R {float(r['radius']):.3g} "
              f"T {float(r['tension']):.3g} B {float(r['wrap_deg']):.3g} L "
              f"{float(r['width']):.3g} U_r {float(r['U_r']):.3g} U_w {float(r['U_w']):.3g}: "
              f"{r['status']} after {float(r['seconds']):.1f} s: {r['message'][:200]}")
    times = [float(r["seconds"]) for r in possible]
    peak = max(float(r["peak_mb"]) for r in rows) / 1024.0
    med, p90, tmax = statistics.median(times), percentile(times, 0.9), max(times)
    mem = statistics.median(float(r["peak_mb"]) for r in rows)
    base = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"time per possible point: median {med:.2f} s, p90 {p90:.2f} s, max {tmax:.1f} s; "
          f"peak memory {peak:.2f} GB (a worker's resident peak; median {mem:.0f} MB, the "
          f"parent it forks from {base:.0f} MB)")
    slow = sorted(possible, key=lambda r: -float(r["seconds"]))[:5]
    print("  slowest: " + "; ".join(f"#{r['index']} {float(r['seconds']):.1f} s "
                                    f"({r['status']})" for r in slow))
    ok = frac >= 0.99
    print(f"  target answered fraction: {frac:.3g} >= 0.99 -> {'met' if ok else 'NOT met'}")
    print(target("'did not converge'", sum(r["status"] == "did not converge" for r in failed),
                 0, "points"))
    print(target(f"over {limit:g} s", sum(r["status"] == "timeout" for r in failed), 0,
                 "points"))
    print(target("time p90", p90, 3.0))
    print(target("peak memory", peak, 2.5, "GB"))


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, default=200)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--out", type=Path, default=Path("out/envelope"))
    ap.add_argument("--timeout", type=float, default=60.0, help="seconds per point (60)")
    ap.add_argument("--memory", type=float, default=6.0,
                    help="GB resident at which a point is killed as a crash (6)")
    ap.add_argument("--replace", action="store_true", help="start the CSV over")
    ap.add_argument("--material", choices=sorted(MATERIALS),
                    help="only the points of this material (among the first --points)")
    ap.add_argument("--index", type=int, nargs="+",
                    help="only these points (their numbers in the sample)")
    args = ap.parse_args(argv)
    import webfem  # noqa: F401 - imported once, before the children fork
    import webfem.models.fe2d  # noqa: F401
    args.out.mkdir(parents=True, exist_ok=True)
    csv_path = args.out / "envelope.csv"
    if args.replace and csv_path.exists():
        csv_path.unlink()
    points = [draw(i) for i in range(args.points)]
    if args.material:
        points = [p for p in points if p["material"] == args.material]
    if args.index:
        points = [p for p in points if p["index"] in set(args.index)]
    done = load(csv_path, points)
    seen = {int(r["index"]) for r in done}
    todo = [p for p in points if p["index"] not in seen]
    print(f"envelope: {len(points)} points, {len(done)} already in {csv_path}, solving "
          f"{len(todo)} on {args.workers} processes", file=sys.stderr)
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    rows = run(todo, args.workers, args.timeout, args.memory, csv_path, done)
    report([r for r in rows if int(r["index"]) < args.points], args.timeout)


if __name__ == "__main__":
    main()
