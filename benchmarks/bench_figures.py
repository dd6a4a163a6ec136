"""`make figures` timed (issue 14's target: <= 3 minutes), into a temporary folder.

Run: ``python benchmarks/bench_figures.py`` (from the repository root; about 12 minutes on
2 cores). It runs the Makefile's own ``figures`` target with ``FIG_DIR`` set to a temporary
folder, so docs/figures is left as it is, and prints the wall time beside the target.
"""

import subprocess
import sys
import tempfile
import time

from common import target


def main():
    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        subprocess.run(["make", "--no-print-directory", "figures", f"FIG_DIR={tmp}",
                        f"PYTHON={sys.executable}"], check=True, capture_output=True)
        t = time.perf_counter() - t0
    print(f"make figures (4 families x 24 fe2d points on 2 processes, traction-loss chart, "
          f"friction variants): {t / 60:.1f} min")
    print(target("make figures", t / 60, 3.0, "min"))


if __name__ == "__main__":
    main()
