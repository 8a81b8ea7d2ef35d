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

demo: build
	$(BUILD)/bin/mcnc run launch/machines/small_lathe.yaml \
	  --program CH1=launch/programs/demo_turn.nc --clock realtime \
	  --trace $(BUILD)/demo-trace.jsonl --report $(BUILD)/demo-report

clean:
	rm -rf build build-asan
