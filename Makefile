# SoftPad: `make demo` runs the main job on the simulated box, `make test` runs the checks.
# Both create the virtual environment in .venv and install everything on first use.
PYTHON ?= python3
VENV ?= .venv
BIN := $(VENV)/bin

.PHONY: demo test bench lint typecheck venv clean

$(VENV)/.installed: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip
	$(BIN)/python -m pip install -q -e '.[dev]'
	touch $@

venv: $(VENV)/.installed

demo: venv
	MPLBACKEND=Agg $(BIN)/softpad demo --out report

lint: venv
	$(BIN)/ruff check src tests examples
	$(BIN)/ruff format --check src tests examples

typecheck: venv
	$(BIN)/mypy

test: lint typecheck
	MPLBACKEND=Agg $(BIN)/pytest -n 2 -q

bench: venv
	MPLBACKEND=Agg $(BIN)/softpad bench

clean:
	rm -rf $(VENV) build src/*.egg-info .pytest_cache .mypy_cache .ruff_cache report
