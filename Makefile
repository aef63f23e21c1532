# Two entry points, each sets itself up from nothing:
#   make run   - create .venv, install reportgen, run the lecture pack configs/ -> output/
#   make test  - create .venv, install reportgen with test extras, run the test suite
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin

.PHONY: run test setup setup-test clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/pip install --quiet --upgrade pip

setup: $(BIN)/python
	$(BIN)/pip install --quiet -e .

setup-test: $(BIN)/python
	$(BIN)/pip install --quiet -e ".[test]"

run: setup
	$(BIN)/reportgen run configs/ --out output

test: setup-test
	$(BIN)/python -m pytest -q

clean:
	rm -rf $(VENV) output/*/ output/index.html
