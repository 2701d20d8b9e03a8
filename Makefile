# Two commands on a fresh machine: `make run` (set up, run the bundled study, draw its map)
# and `make test` (set up, run the tests).  Everything is installed into .venv from PyPI.
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed
export OMPI_MCA_rmaps_base_oversubscribe := 1

.PHONY: install run scenes test test-nojit validate bench figures clean

$(STAMP): pyproject.toml
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e '.[mpi,test]'
	touch $(STAMP)

# Compiles the kernel once into its cache folder (kernels/_jit.py), or finds it there
install: $(STAMP)
	$(PY) -c "from sweep.runner.cells import warm_up; warm_up()"

run: install
	mkdir -p figures
	$(VENV)/bin/mpiexec -n 2 $(PY) -m sweep.run studies/smoke.yaml --force
	$(PY) -m sweep.plot results/smoke.nc --figure map -o figures/smoke_map.png
	@echo "wrote results/smoke.nc and figures/smoke_map.png"

scenes: install
	mkdir -p figures/scenes
	for f in studies/fig0[345]*.yaml; do \
	  $(PY) -m sweep.scene $$f --plot figures/scenes/$$(basename $$f .yaml).png || exit 1; done

test: install
	$(PY) -m pytest -m "not slow" -q

test-nojit: $(STAMP)
	NUMBA_DISABLE_JIT=1 $(PY) -m pytest -m "not slow and not mpi" -q tests/kernels/test_impact.py

validate: install
	$(PY) -m pytest -m slow -q

bench: install
	$(PY) -m benchmarks

# The paper's figures from our own simulations: Figs 3-5 (scenes), 8-16 (frequency sweeps),
# 17 (closed forms), 18-21 (records), and the estimate example.  Each study runs on 2 ranks.
SWEEP_STUDIES  := $(basename $(notdir $(wildcard studies/fig08_*.yaml studies/fig09_*.yaml \
                                                    studies/fig10_*.yaml)))
RECORD_STUDIES := fig18_elcentro_ns fig19_taft_ew fig20_elcentro_ew fig21_summary
R := results

figures: $(STAMP) scenes
	mkdir -p figures
	for s in $(SWEEP_STUDIES) $(RECORD_STUDIES); do \
	  $(VENV)/bin/mpiexec -n 2 $(PY) -m sweep.run studies/$$s.yaml --force --quiet || exit 1; done
	for n in 08 09 10; do $(PY) -m sweep.plot $(R)/fig$${n}_acceleration.nc \
	  $(R)/fig$${n}_velocity.nc $(R)/fig$${n}_displacement.nc --figure fig$$n \
	  -o figures/fig$$n.png || exit 1; done
	for s in variants_acceleration variants_velocity bodies_acceleration bodies_velocity \
	         rate_acceleration rate_velocity; do $(PY) -m sweep.plot $(R)/fig09_$$s.nc \
	  --figure fig09 -o figures/fig09_$$s.png || exit 1; done
	$(PY) -m sweep.plot $(R)/fig08_acceleration.nc $(R)/fig08_velocity.nc \
	  $(R)/fig08_displacement.nc $(R)/fig09_acceleration.nc $(R)/fig09_velocity.nc \
	  $(R)/fig09_displacement.nc $(R)/fig10_acceleration.nc --figure fig11 -o figures/fig11.png
	$(PY) -m sweep.plot $(R)/fig08_acceleration.nc $(R)/fig09_acceleration.nc \
	  $(R)/fig09_velocity.nc $(R)/fig09_displacement.nc --figure fig12 -o figures/fig12.png
	$(PY) -m sweep.plot $(R)/fig09_acceleration.nc --figure fig13 -o figures/fig13.png
	$(PY) -m sweep.plot $(R)/fig08_acceleration.nc $(R)/fig09_acceleration.nc --figure fig14 \
	  -o figures/fig14.png
	$(PY) -m sweep.plot $(R)/fig09_velocity.nc --figure fig15 -o figures/fig15.png
	$(PY) -m sweep.plot $(R)/fig09_displacement.nc --figure fig16 -o figures/fig16.png
	$(PY) -m sweep.plot --figure fig17 -o figures/fig17.png
	for n in 18 19 20 21; do s=$$(echo $(RECORD_STUDIES) | tr ' ' '\n' | grep fig$$n); \
	  $(PY) -m sweep.plot $(R)/$$s.nc --figure fig$$n -o figures/fig$$n.png || exit 1; done
	$(PY) -m sweep.estimate studies/bodies_example.yaml | tee figures/bodies_example.txt

clean:
	rm -rf out results figures
