# Two commands: `make demo` and `make test`. Each installs what is missing, configures, builds,
# then runs. PRESET picks a CMakePresets.json configuration (CI uses "ci": warnings are errors).
PRESET ?= $(if $(CI),ci,default)
BUILD := $(if $(filter asan,$(PRESET)),build-asan,build)
JOBS ?= $(shell nproc)

.PHONY: demo test build deps clean

deps:
	@scripts/install-deps

build: deps
	cmake --preset $(PRESET) >/dev/null
	cmake --build $(BUILD) -j$(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS) --timeout 600

# The twin-turret part transfer on simulated drives at real-time pace, with the operator HMI
# (its address and token are printed) and the run report in $(BUILD)/demo-report. Paced
# lockstep by default: the realtime clock needs more than two cores for this machine
# (docs/decisions.md 21); DEMO_CLOCK="--clock realtime" where there are.
DEMO_CLOCK ?= --pace
demo: build
	$(BUILD)/bin/mcnc run launch/machines/twin_turret.yaml \
	  --program CH1=launch/programs/part_transfer_ch1.nc \
	  --program CH2=launch/programs/part_transfer_ch2.nc $(DEMO_CLOCK) --hmi \
	  --trace $(BUILD)/demo-trace.jsonl --report $(BUILD)/demo-report

clean:
	rm -rf build build-asan
