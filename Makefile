# The README's two commands. Both install the Debian packages dstrans needs when some are missing
# (apt-get update only then), configure once, build incrementally in build/, then do their job.
#   make demo   writes what dstrans generates for the thesis's layouts into out/demo/
#   make test   builds and runs every test (ctest)

BUILD ?= build
OUT ?= out/demo
JOBS ?= $(shell nproc)

# Debian 12 packages: compiler and build, the core's GLM, glslang and SPIRV-Cross for shader checks,
# Catch2 for the tests; ccache keeps rebuilds cheap.
PACKAGES := g++ make cmake ccache libglm-dev glslang-dev glslang-tools spirv-tools spirv-cross catch2

SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

.PHONY: demo test deps configure build clean

deps:
	@missing=$$(for p in $(PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages: $$missing"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  $$(command -v ccache >/dev/null && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)

configure: $(BUILD)/CMakeCache.txt

build: deps configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

demo: build
	@mkdir -p $(OUT)
	$(BUILD)/tools/dstrans gen gbuffer thesis > $(OUT)/gbuffer_thesis.glsl
	$(BUILD)/tools/dstrans gen gbuffer light > $(OUT)/light_buffer.glsl
	$(BUILD)/tools/dstrans gen gbuffer shadow > $(OUT)/shadow_map.glsl
	$(BUILD)/tools/dstrans gen interlace rows > $(OUT)/interlace_rows.glsl
	@for f in $(OUT)/*.glsl; do glslangValidator -S frag $$f >/dev/null || { echo "glslangValidator rejects $$f"; exit 1; }; done
	@echo "make demo: wrote $$(ls $(OUT)/*.glsl | wc -l) GLSL files to $(OUT)/, each accepted by glslangValidator"

clean:
	rm -rf $(BUILD) out
