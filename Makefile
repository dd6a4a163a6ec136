# Two commands on a fresh machine: `make run` (main job) and `make test` (test suite).
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed-stamp
OUT ?= out

.PHONY: run test test-slow bench envelope clean meshes figures studies

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

# main job: the base case with the most complete model (2-D film + 1-D web) with its VTU
# files, picture and report, what each effect beyond the paper does, then the speed sweep
# with the 1-D FE model beside the closed form
run: $(STAMP)
	mkdir -p $(OUT)/base
	$(VENV)/bin/webfem solve cases/base.toml --model fe2d --json --vtu $(OUT)/base --plot > $(OUT)/base/solve.json
	$(VENV)/bin/webfem solve cases/base.toml
	$(VENV)/bin/webfem effects cases/base.toml --model fe2d --quiet
	$(VENV)/bin/webfem report cases/base.toml --model fe2d --out $(OUT)/base
	$(VENV)/bin/webfem sweep cases/base.toml --model closed-form --out $(OUT)/base --quiet
	$(VENV)/bin/webfem sweep cases/base.toml --model fe1d --out $(OUT)/base --quiet

# the stored meshes of meshes/ (what the FE models start from for the cases)
meshes: $(STAMP)
	for c in cases/*.toml; do $(VENV)/bin/webfem mesh $$c --out meshes; done

test: $(STAMP)
	$(PY) -m pytest -q

test-slow: $(STAMP)
	$(PY) -m pytest -q -m slow

# time, iterations, unknowns, error against the converged mesh and the Newton floor of each
# model, with issue 14's targets beside them (met / not met); issue 23's six speed figures on
# real cases (bench_speed.py, about 4 more minutes: its 32-design groove map alone takes 2-3);
# about 8 minutes on 2 cores
# (bench_figures.py alone runs `make figures` into a temporary folder: about 2.5)
bench: $(STAMP)
	$(PY) benchmarks/bench_closed_form.py
	$(PY) benchmarks/bench_fe1d.py
	$(PY) benchmarks/bench_fe2d.py
	$(PY) benchmarks/bench_sweeps.py
	$(PY) benchmarks/bench_speed.py
	$(PY) benchmarks/bench_calibration.py
	$(PY) benchmarks/bench_fitted.py speed
	$(PY) benchmarks/bench_figures.py

# auto across 200 random operating points of real lines (issue 22's targets; about 7 minutes
# on 2 processes, resumable: per-point rows in $(OUT)/envelope/envelope.csv)
envelope: $(STAMP)
	cd benchmarks && $(abspath $(PY)) envelope.py --points 200 --workers 2 --out $(abspath $(OUT))/envelope

clean:
	rm -rf $(OUT) .pytest_cache

# the paper's four figure families (closed form beside the 2-D FE model), the traction-loss
# chart and the friction-model variants, into docs/figures (FIG_DIR; the searches and curves on
# 2 processes)
FIG_MODEL ?= fe2d
FIG_DIR ?= docs/figures
figures: $(STAMP)
	for f in fig10_wrap fig11_tension fig12_width fig13_radius; do \
	  $(VENV)/bin/webfem sweep cases/$$f.toml --model $(FIG_MODEL) --num 24 --log --workers 2 \
	    --out $(FIG_DIR) --quiet || exit 1; done
	$(VENV)/bin/webfem traction-loss cases/base.toml --mu-min 0.1 --model $(FIG_MODEL) \
	  --set model.physics=paper --chart $(FIG_DIR) --points 4 --workers 2 --quiet
	$(VENV)/bin/webfem study variants cases/base.toml --set model.physics=paper \
	  --out $(FIG_DIR) --model $(FIG_MODEL) --workers 2

# the three studies and docs/studies.md from their numbers, then Eq. 21 over lambda
# (docs/lambda_table.md), all with the paper's physics (about 20 minutes on 2 cores)
studies: $(STAMP)
	$(VENV)/bin/webfem study report cases/base.toml --set model.physics=paper --out docs
	$(VENV)/bin/webfem study lambda-table cases/base.toml --set model.physics=paper --out docs
