# The README's two commands. Both install the Debian packages dstrans needs when some are missing
# (apt-get update only then), configure once, build incrementally, then do their job.
#   make demo       renders glass_room on OpenGL and Vulkan into out/demo/, with every buffer
#   make test       builds and runs every test (ctest) in build/, then again under the sanitizers
#   make sanitize   the suite alone under AddressSanitizer, LeakSanitizer and UBSan, in build-sanitize/

BUILD ?= build
SANITIZE_BUILD ?= build-sanitize
OUT ?= out/demo
JOBS ?= $(shell nproc)

# Debian 12 packages: compiler and build, the core's GLM, glslang and SPIRV-Cross for shader checks,
# Catch2 for the tests; ccache keeps rebuilds cheap.
# GL through EGL and Vulkan on Mesa (llvmpipe, lavapipe) with the Khronos validation layer, and
# nlohmann-json for the command line, stb for PNG files, matplotlib for the benchmark's plot, GLFW and
# Xvfb for the viewer and its test.
PACKAGES := g++ make cmake ccache libglm-dev glslang-dev glslang-tools spirv-tools spirv-cross catch2 \
            libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri mesa-vulkan-drivers libvulkan-dev \
            vulkan-validationlayers nlohmann-json3-dev libstb-dev python3-matplotlib libglfw3-dev xvfb xauth

SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

LAUNCHER = $$(command -v ccache >/dev/null && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
SANITIZE_ENV := ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
                LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers.supp:print_suppressions=0

.PHONY: demo test sanitize deps configure build clean

deps:
	@missing=$$(for p in $(PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages: $$missing"; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo $(LAUNCHER)

$(SANITIZE_BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=Debug -DDSTRANS_SANITIZE=ON $(LAUNCHER)

configure: $(BUILD)/CMakeCache.txt

build: deps configure
	cmake --build $(BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)
	$(MAKE) --no-print-directory sanitize

sanitize: deps $(SANITIZE_BUILD)/CMakeCache.txt
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	$(SANITIZE_ENV) ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS)

demo: build
	$(BUILD)/tools/dstrans render examples/scenes/glass_room.json --backend gl --out $(OUT) --width 960 --height 540
	$(BUILD)/tools/dstrans render examples/scenes/glass_room.json --backend vk --out $(OUT)/vk --width 960 --height 540
	@mkdir -p $(OUT)/glsl
	$(BUILD)/tools/dstrans gen gbuffer thesis > $(OUT)/glsl/gbuffer_thesis.glsl
	$(BUILD)/tools/dstrans gen gbuffer light > $(OUT)/glsl/light_buffer.glsl
	$(BUILD)/tools/dstrans gen gbuffer shadow > $(OUT)/glsl/shadow_map.glsl
	$(BUILD)/tools/dstrans gen interlace rows > $(OUT)/glsl/interlace_rows.glsl
	@for f in $(OUT)/glsl/*.glsl; do glslangValidator -S frag $$f >/dev/null || { echo "glslangValidator rejects $$f"; exit 1; }; done
	@echo "make demo: $(OUT)/final.png (OpenGL) and $(OUT)/vk/final.png (Vulkan) with their buffers, and the generated GLSL in $(OUT)/glsl/"

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) out
