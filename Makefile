# Glint: `make demo` and `make test` do all the set-up on a fresh Debian machine.
BUILD ?= build
JOBS  ?= 2

# Debian packages the build and the tests need; `make deps` installs the missing ones
# (gnuplot-nox draws glint accuracy's plot).
DEPS := cmake g++ make pkg-config libglm-dev nlohmann-json3-dev libtinyobjloader-dev \
        libstb-dev libcli11-dev libgtest-dev libgmock-dev \
        libflatbuffers-dev flatbuffers-compiler libssl-dev libasio-dev libosmesa6-dev \
        libegl-dev libglfw3-dev libgl1-mesa-dri xvfb xauth x11-utils x11-apps xdotool netpbm openssl iproute2 \
        libopenexr-dev libassimp-dev libjpeg-dev zlib1g-dev assimp-testmodels \
        gnuplot-nox
# The benchmark also compares against POV-Ray 3.7 and Embree 3.
BENCH_DEPS := povray libembree-dev blender
# The fuzzers are built with clang and its libFuzzer.
FUZZ_DEPS := clang libclang-rt-14-dev
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60

SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)

.PHONY: all deps bench-deps fuzz-deps configure build test demo install bench accuracy fuzz fuzz-seeds clean

all: build

define install_missing
	@missing=$$(for p in $(1); do \
	  dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q 'install ok installed' || echo $$p; \
	done); \
	if [ -n "$$missing" ]; then \
	  echo "installing:" $$missing; \
	  $(SUDO) apt-get update -qq && \
	  DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq --no-install-recommends $$missing; \
	fi
endef

deps:
	$(call install_missing,$(DEPS))

bench-deps: deps
	$(call install_missing,$(BENCH_DEPS))

configure: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: configure
	cmake --build $(BUILD) -j$(JOBS)

test: build
	tests/run_suite.sh $(BUILD) $(JOBS)

# The demo needs only the two programs (the tests build in `make test`).
demo: configure
	cmake --build $(BUILD) -j$(JOBS) --target glint glintd
	deploy/local-demo.sh $(BUILD) out

# glint, glintd, glint-certs and deploy/glintd@.service under /usr/local
# (PREFIX=... elsewhere: the installed unit then names PREFIX/bin/glintd).
# Builds only the two programs.
PREFIX ?= /usr/local
install: configure
	cmake --build $(BUILD) -j$(JOBS) --target glint glintd
	$(SUDO) cmake --install $(BUILD) --prefix $(PREFIX)

bench: bench-deps build
	$(BUILD)/bin/glint-bench --scenes scenes

# The default accuracy sweep on the thesis's scenes 1 and 2, the mask rules
# and the perceptual threshold on three more, an area light's samples on
# soft-shadows.json: out/accuracy/, and
# docs/accuracy.md with its plots in docs/images/.
RULE_SWEEP = --vary mask_rule=auto,perceptual --vary perceptual_threshold=0.1,0.2,0.3,0.5,0.8
accuracy: build
	$(BUILD)/bin/glint accuracy scenes/room.json -o out/accuracy/room
	$(BUILD)/bin/glint accuracy scenes/room-gl-floor.json -o out/accuracy/room-gl-floor
	for s in glass bunny room-bright; do $(BUILD)/bin/glint accuracy scenes/$$s.json -o out/accuracy/$$s $(RULE_SWEEP) || exit 1; done
	$(BUILD)/bin/glint accuracy scenes/soft-shadows.json -o out/accuracy/soft-shadows --vary light_samples=1,4,16,64
	tests/bench/accuracy_doc.sh out/accuracy docs room room-gl-floor glass bunny room-bright soft-shadows

fuzz-deps: deps
	$(call install_missing,$(FUZZ_DEPS))

# Every fuzz target for FUZZ_SECONDS each (make fuzz FUZZ_SECONDS=600).
fuzz: fuzz-deps
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ -DGLINT_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j$(JOBS)
	tests/fuzz/run.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

# Rewrites the seed corpora in tests/fuzz/corpus with the project's encoders.
fuzz-seeds: build
	$(BUILD)/bin/glint-fuzz-seeds .

clean:
	rm -rf $(BUILD) $(FUZZ_BUILD) out
