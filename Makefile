# Glint: `make demo` and `make test` do all the set-up on a fresh Debian machine.
BUILD ?= build
JOBS  ?= 2

# Debian packages the build and the tests need; `make deps` installs the missing ones.
DEPS := cmake g++ make pkg-config libglm-dev nlohmann-json3-dev libtinyobjloader-dev \
        libstb-dev libcli11-dev libgtest-dev libgmock-dev \
        libflatbuffers-dev flatbuffers-compiler libssl-dev libasio-dev libosmesa6-dev \
        libglfw3-dev libgl1-mesa-dri xvfb xauth
# The benchmark also compares against POV-Ray 3.7.
BENCH_DEPS := povray

SUDO := $(shell [ "$$(id -u)" -eq 0 ] || echo sudo)

.PHONY: all deps bench-deps configure build test demo bench clean

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
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)

demo: build
	deploy/local-demo.sh $(BUILD) out

bench: bench-deps build
	$(BUILD)/bin/glint-bench --scenes scenes

clean:
	rm -rf $(BUILD) out
