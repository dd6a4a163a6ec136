# Two commands on a fresh machine: `make run` (main job) and `make test` (test suite).
PYTHON ?= python3
VENV ?= .venv
PY := $(VENV)/bin/python
STAMP := $(VENV)/.installed-stamp
OUT ?= out

.PHONY: run test test-slow bench clean

$(STAMP): pyproject.toml
	test -x $(PY) || $(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[test]'
	touch $(STAMP)

# main job: the base case with the most complete model (1-D FE for now), then the speed
# sweep with the FE model beside the paper's closed form
run: $(STAMP)
	mkdir -p $(OUT)/base
	$(VENV)/bin/webfem solve cases/base.toml --model fe1d --json > $(OUT)/base/solve.json
	$(VENV)/bin/webfem solve cases/base.toml --model fe1d
	$(VENV)/bin/webfem sweep cases/base.toml --out $(OUT)/base
	$(VENV)/bin/webfem sweep cases/base.toml --model fe1d --out $(OUT)/base

test: $(STAMP)
	$(PY) -m pytest -q

test-slow: $(STAMP)
	$(PY) -m pytest -q -m slow

bench: $(STAMP)
	$(PY) benchmarks/bench_closed_form.py
	$(PY) benchmarks/bench_fe1d.py

clean:
	rm -rf $(OUT) .pytest_cache
