# The two commands: `make run` and `make test`. Both create .venv with the machine's
# python3 when it is missing and install the package with its test extra first.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: run test serve bench lint clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(STAMP): $(BIN)/python pyproject.toml
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

# The package's own bytecode, brought up to date before each command: an editable install does
# not write it (pip compiles only the dependencies it installs), and where PYTHONDONTWRITEBYTECODE
# is set every process (each test worker, service, Dask worker and command the tests start)
# would compile the package's 44 000 lines again (0.43 s a process, benchmarks/bench_bytecode.py;
# 17 % of the command-line tests' time).
BYTECODE := $(BIN)/python -m compileall -q engine service >/dev/null

# The main job: start the study service (LocalCluster, data in ./data), submit
# studies/paper-comparison.yaml, show progress, print CEMA vs Non-Lin, stop the service.
run: $(STAMP)
	$(BYTECODE)
	$(BIN)/beltstudy demo

# The study service on http://127.0.0.1:8000 (docs at /docs) until Ctrl-C.
serve: $(STAMP)
	$(BYTECODE)
	$(BIN)/beltstudy serve

# The tests on TEST_WORKERS processes (pytest-xdist); the live services, clusters and the
# browser one after another on one of them (tests/conftest.py).
TEST_WORKERS ?= 2
test: $(STAMP)
	$(BIN)/ruff check .
	$(BYTECODE)
	$(BIN)/python -m pytest -q -n $(TEST_WORKERS) --dist loadgroup

bench: $(STAMP)
	$(BIN)/python benchmarks/bench_statics.py
	$(BIN)/python benchmarks/bench_dynamics.py
	$(BIN)/python benchmarks/bench_study.py
	$(BIN)/python benchmarks/bench_load.py

lint: $(STAMP)
	$(BIN)/ruff check .

clean:
	rm -rf $(VENV) build *.egg-info
