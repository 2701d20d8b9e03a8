# Two commands on a fresh machine: `make run` (set up, run the bundled study, draw its map)
# and `make test` (set up, run the tests).  Everything is installed into .venv from PyPI.
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed
# numba's cache misses edits in files a kernel calls: key the cache on the kernel sources
KERNEL_HASH := $(shell cat kernels/*.py | sha1sum | cut -c1-12)
export NUMBA_CACHE_DIR ?= $(CURDIR)/.numba_cache/$(KERNEL_HASH)
export OMPI_MCA_rmaps_base_oversubscribe := 1

.PHONY: install run scenes test test-nojit validate bench figures clean

$(STAMP): pyproject.toml
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[mpi,test]'
	touch $(STAMP)

install: $(STAMP)

run: $(STAMP)
	mkdir -p figures
	$(VENV)/bin/mpiexec -n 2 $(PY) -m sweep.run studies/smoke.yaml --force
	$(PY) -m sweep.plot results/smoke.nc --figure map -o figures/smoke_map.png
	@echo "wrote results/smoke.nc and figures/smoke_map.png"

scenes: $(STAMP)
	mkdir -p figures/scenes
	for f in studies/fig0[345]*.yaml; do \
	  $(PY) -m sweep.scene $$f --plot figures/scenes/$$(basename $$f .yaml).png || exit 1; done

test: $(STAMP)
	$(PY) -m pytest -m "not slow" -q

test-nojit: $(STAMP)
	NUMBA_DISABLE_JIT=1 $(PY) -m pytest -m "not slow and not mpi" -q tests/kernels/test_impact.py

validate: $(STAMP)
	$(PY) -m pytest -m slow -q

clean:
	rm -rf .numba_cache out results figures
