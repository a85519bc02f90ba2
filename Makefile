# Two commands a user needs: `make run` and `make test`. Both set up .venv when it is missing.
PYTHON ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: run desk test bench docs proto clean bytecode

# The protobuf modules are generated at install (setup.py), so a changed .proto reinstalls.
# pip's own output goes to $(VENV)/install.log, shown only when the install fails: `make run` prints the run.
$(STAMP): pyproject.toml setup.py $(wildcard proto/coopdrive/v1/*.proto)
	@test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	@echo "installing coopdrive and its dependencies into $(VENV) (log: $(VENV)/install.log)"
	@{ $(BIN)/python -m pip install --upgrade pip && $(BIN)/python -m pip install -e '.[test]'; } \
		> $(VENV)/install.log 2>&1 || { tail -40 $(VENV)/install.log; exit 1; }
	@touch $(STAMP)

## bytecode: compiled modules of the source tree. An editable install compiles none, and where PYTHONDONTWRITEBYTECODE
## is set (CI, many images) every process a run or a test starts would compile each module it imports again: a tenth
## of a subprocess-heavy test's CPU. Up-to-date files are skipped, so this costs about 0.05 s.
bytecode: $(STAMP)
	@$(BIN)/python -m compileall -q coopdrive services bench tests

## run: the follow scenario with the full stack (the simulator and the stack, a process each); prints the summary
run: $(STAMP) bytecode
	@$(BIN)/coopdrive run follow --record out/follow.mcap

## desk: the deployed stack without the car or Docker: docker-compose.yml's desk profile as local processes
## (simulated follow world, one stack, gateway on :8080, Foxglove on ws://localhost:8765) until Ctrl-C
desk: $(STAMP) bytecode
	$(BIN)/python -m coopdrive.launch.compose_processes --profile desk

## test: the whole test suite, a test file at a time on each worker (pytest-xdist: a file's module fixtures run once),
## in the order tests/conftest.py gives them: the files that start whole runs first; TEST_WORKERS=N runs N files at
## a time. The default is one more worker than cores: a test that waits (a real-time run, a timeout, a process
## starting) leaves its core to another; on a quiet 2-core machine 3 workers took 533 s where 2 took 650 s.
## The Debian packages some tests use are installed first, once (tools/system_packages.sh: where this user may not
## install them, it names the tests that will skip).
TEST_WORKERS ?= $(shell $(PYTHON) -c 'import os; print(len(os.sched_getaffinity(0)) + 1)')
test: $(STAMP) bytecode
	@tools/system_packages.sh
	@tools/peer_env.sh
	$(BIN)/python -m pytest -n $(TEST_WORKERS) --dist loadfile --no-loadscope-reorder

## bench: benchmarks, each against a baseline measured in the same run
bench: $(STAMP) bytecode
	$(BIN)/python -m bench

## docs: the documentation site from docs/ into site/ (open site/index.html); --strict: a broken link, a missing page
## or a reference page that cannot be generated fails the build
docs: $(STAMP)
	NO_MKDOCS_2_WARNING=1 $(BIN)/python -m mkdocs build --strict --site-dir site

## proto: regenerate coopdrive/v1/*_pb2.py from proto/ (any install does it; this one forces it)
proto:
	rm -f $(STAMP)
	$(MAKE) $(STAMP)

clean:
	rm -rf $(VENV) .venv-peers out build site *.egg-info
