# Two commands on a fresh machine: `make run` (set up, run the bundled study, draw its map)
# and `make test` (set up, run the tests).  Everything is installed into .venv from PyPI.
VENV   := .venv
PY     := $(VENV)/bin/python
STAMP  := $(VENV)/.installed
export OMPI_MCA_rmaps_base_oversubscribe := 1

.PHONY: install run scenes test test-nojit test-cudasim ptx validate bench bench-gpu figures \
  rate-study clean

$(STAMP): pyproject.toml
	python3 -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	# the editable install's notice (folders named like the package) is about this very layout
	PYTHONWARNINGS=ignore::UserWarning $(PY) -m pip install --quiet -e '.[mpi,test]'
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
	for f in studies/fig0[345][a-g]_*.yaml; do \
	  $(PY) -m sweep.scene $$f --plot figures/scenes/$$(basename $$f .yaml).png || exit 1; done

test: install
	$(PY) -m pytest -m "not slow" -q

test-nojit: $(STAMP)
	NUMBA_DISABLE_JIT=1 $(PY) -m pytest -m "not slow and not mpi" -q tests/kernels/test_impact.py

# The CUDA kernel without a GPU (docs/gpu.md): installs the cuda extra into the venv
test-cudasim: install
	$(PY) -m pip install --quiet -e '.[cuda]'
	$(PY) -m pytest -m "slow or not slow" -q tests/kernels/test_cuda_batch.py tests/kernels/test_ptx.py

# The kernel's PTX for sm_90 and its figures (ptxas -v: registers, spills), no GPU needed
ptx: install
	$(PY) -m pip install --quiet -e '.[cuda]'
	mkdir -p results
	$(PY) -m benchmarks.gpu --ptx results/kernel_sm90.ptx

validate: install
	$(PY) -m pytest -m slow -q

bench: install
	$(PY) -m benchmarks

# On a machine with an NVIDIA GPU: the GPU against every CPU core, and scaling by rank count
bench-gpu: install
	$(PY) -m pip install --quiet -e '.[cuda]'
	$(PY) -m benchmarks.gpu
	$(PY) -m benchmarks.scaling --levels 160

# The paper's figures from our own simulations: Figs 3-5 (scenes), 8-16 (frequency sweeps),
# 17 (closed forms), 18-21 (records), the rocking spectrum and fragility figures (one MPI job
# on 2 ranks), the estimate examples (deterministic, and with an ensemble of records) and
# the risk examples (docs/risk.md).
figures: install
	mkdir -p figures
	$(VENV)/bin/mpiexec -n 2 $(PY) -m sweep.figures -o figures
	$(PY) -m sweep.estimate studies/bodies_example.yaml | tee figures/bodies_example.txt
	$(PY) -m sweep.estimate studies/tombstones_estimate.yaml -o figures/site_estimate.png \
	  > figures/tombstones_estimate.txt
	$(PY) -m sweep.risk studies/risk_example.yaml -o figures/risk_example.png \
	  > figures/risk_example.txt
	$(PY) -m sweep.risk studies/risk_map_example.yaml --map figures/risk_map_example.png \
	  > figures/risk_map_example.txt

# Sweep rate against curves a and c (docs/reproduction.md): 2,304 sweeps, ~1,300 s CPU,
# ~15 min on 2 ranks; tables into figures/rate_study.md, figure figures/rate_study.png
RATE_STUDIES := fig09_acceleration fig08_acceleration fig09_velocity fig08_velocity fig09_displacement
rate-study: install
	mkdir -p figures
	for s in $(RATE_STUDIES); do \
	  $(VENV)/bin/mpiexec -n 2 $(PY) -m sweep.run studies/rate_study_$$s.yaml --force || exit 1; done
	$(PY) -m sweep.paper.rates $(RATE_STUDIES:%=results/rate_study_%.nc) > figures/rate_study.md
	$(PY) -m sweep.plot $(RATE_STUDIES:%=results/rate_study_%.nc) --figure rates -o figures/rate_study.png

clean:
	rm -rf out results figures
