# Every target creates and uses .venv on a fresh machine.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python
BASE := $(VENV)/.installed-base
STAMP := $(VENV)/.installed

.PHONY: demo test bench validate lint docs clean

# the package and its core dependencies only (what the demo needs)
$(BASE): pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e .
	touch $(BASE)

# plus the test and co-simulation tools
$(STAMP): $(BASE)
	$(PY) -m pip install --quiet -e ".[test]"
	touch $(STAMP)

# the modules' bytecode, as pip writes it for an install: where the environment sets
# PYTHONDONTWRITEBYTECODE, Python would otherwise compile every module of bearingsim in
# every process that imports it (0.5-0.6 s of each command; only what changed is compiled)
BYTECODE = $(PY) -m compileall -q bearingsim bench tests tools

demo: $(BASE)
	$(BYTECODE)
	$(PY) -m bearingsim.cli demo --out demo_output --overwrite

# (components' Variables and Connectors sections are not numpydoc's: its warnings about them are muted)
DOCSTRINGS = $(PY) -W ignore::UserWarning -m numpydoc lint $$(find bearingsim -name '*.py' | sort)

test: $(STAMP)
	$(PY) -m ruff check bearingsim tests bench examples tools
	$(DOCSTRINGS)
	$(BYTECODE)
	$(PY) -m pytest -q -n 2 tests

bench: $(STAMP)
	$(BYTECODE)
	$(PY) -m bench.run_all --out docs/benchmarks.md

validate: $(STAMP)
	$(BYTECODE)
	$(PY) -m tools.validation_report docs/validation.md

docs: $(STAMP)
	$(PY) -m bearingsim.reference docs/components.md

lint: $(STAMP)
	$(PY) -m ruff check bearingsim tests bench examples tools
	$(DOCSTRINGS)

clean:
	rm -rf $(VENV) demo_output build *.egg-info
