# The README's two commands. Both install the Debian packages dstrans needs when some are missing
# (apt-get update only then), configure, build incrementally, then do their job.
#   make demo       builds the dstrans command alone and renders glass_room and the glTF glass_shelf on OpenGL
#                   and Vulkan into out/demo/
#   make test       builds and runs every test (ctest) in build/, then the suite under the sanitizers; one test
#                   checks that every Debian package the build found is one this Makefile installs
#   make sanitize   the suite alone under AddressSanitizer, LeakSanitizer and UBSan, in build-sanitize/: every
#                   test that draws no frame, and of those that do, the ones that draw the same frames on both
#                   backends and through the renderers' engine API (tests/CMakeLists.txt says why)

BUILD ?= build
SANITIZE_BUILD ?= build-sanitize
OUT ?= out/demo
JOBS ?= $(shell nproc)

# CMake runs make below make: its "Entering directory" lines say nothing here.
MAKEFLAGS += --no-print-directory

# Debian 12 packages: compiler and build, the core's GLM, glslang, SPIRV-Tools and SPIRV-Cross (with its CMake
# packages) for shaders, Catch2 for the tests; ccache keeps rebuilds cheap.
# GL through EGL and Vulkan on Mesa (llvmpipe, lavapipe) with the Khronos validation layer, and
# nlohmann-json for the command line, stb for PNG files, matplotlib for the benchmark's plot, GLFW and
# Xvfb for the viewer and its test, tinygltf for glTF scenes. `make test` fails when CMake finds a package
# these lists do not install.
PACKAGES := g++ make cmake ccache libglm-dev glslang-dev glslang-tools spirv-tools spirv-cross \
            libspirv-cross-c-shared-dev catch2 \
            libegl-dev libgl-dev libopengl-dev libegl-mesa0 libgl1-mesa-dri mesa-vulkan-drivers libvulkan-dev \
            vulkan-validationlayers nlohmann-json3-dev libstb-dev python3-matplotlib libglfw3-dev xvfb xauth \
            libtinygltf-dev
# For the tests alone (74 MB that `make demo` does not need): assimp's valid and broken glTF models.
TEST_PACKAGES := assimp-testmodels

SUDO := $(if $(filter 0,$(shell id -u)),,sudo)

CMAKE_FLAGS = $$(command -v ccache >/dev/null && echo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# ccache rewrites the paths under this clone to relative ones before it hashes a compile, so that a clone in
# another folder (CI's, a second checkout) finds what this one compiled; -ffile-prefix-map (CMakeLists.txt)
# keeps the objects themselves free of the folder.
export CCACHE_BASEDIR := $(CURDIR)
SANITIZE_ENV := ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
                LSAN_OPTIONS=suppressions=$(CURDIR)/tests/sanitizers.supp:print_suppressions=0

# Configuring runs every time: CMake is idempotent and fast when nothing changed, and a configure that failed
# or was interrupted (which still leaves a CMakeCache.txt) is simply done again. Its output goes to a log that
# is shown when it fails.
configure_in = @mkdir -p $(1) && cmake -S . -B $(1) $(2) $(CMAKE_FLAGS) > $(1)/configure.log 2>&1 \
               || { cat $(1)/configure.log; echo "make: configuring $(1) failed (log: $(1)/configure.log)"; exit 1; }

.PHONY: demo test sanitize deps test-deps configure build print-packages clean

# install_missing: installs those of the packages $(1) that are not installed.
install_missing = @missing=$$(for p in $(1); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -n "$$missing" ]; then \
	  echo "Installing Debian packages:" $$missing; \
	  $(SUDO) apt-get update -qq && DEBIAN_FRONTEND=noninteractive $(SUDO) apt-get install -y -qq $$missing; \
	fi

deps:
	$(call install_missing,$(PACKAGES))

test-deps:
	$(call install_missing,$(PACKAGES) $(TEST_PACKAGES))

configure: deps
	@echo "Configuring $(BUILD)/ (cmake)"
	$(call configure_in,$(BUILD),-DCMAKE_BUILD_TYPE=RelWithDebInfo)

build: configure
	cmake --build $(BUILD) -j $(JOBS)

test: test-deps build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)
	$(MAKE) --no-print-directory sanitize

sanitize: test-deps
	@echo "Configuring $(SANITIZE_BUILD)/ (cmake, sanitizers)"
	$(call configure_in,$(SANITIZE_BUILD),-DCMAKE_BUILD_TYPE=Debug -DDSTRANS_SANITIZE=ON)
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	$(SANITIZE_ENV) ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS)

# The list, for the test that every package CMake found is one of these or a dependency of one
# (tests/check_packages.sh).
print-packages:
	@echo $(PACKAGES) $(TEST_PACKAGES)

demo: configure
	@echo "Building the dstrans command ($(BUILD)/tools/dstrans)"
	@cmake --build $(BUILD) --target dstrans_cli -j $(JOBS)
	@echo "Rendering examples/scenes/glass_room.json on OpenGL (llvmpipe) into $(OUT)/"
	@$(BUILD)/tools/dstrans render examples/scenes/glass_room.json --backend gl --out $(OUT) --width 960 --height 540
	@echo "Rendering it on Vulkan (lavapipe) into $(OUT)/vk/"
	@$(BUILD)/tools/dstrans render examples/scenes/glass_room.json --backend vk --out $(OUT)/vk --width 960 --height 540
	@echo "Rendering examples/scenes/glass_shelf.gltf (glTF glass) on OpenGL and Vulkan into $(OUT)/glass_shelf/"
	@$(BUILD)/tools/dstrans render examples/scenes/glass_shelf.gltf --backend gl --out $(OUT)/glass_shelf --width 960 --height 540 --rough-refraction on
	@$(BUILD)/tools/dstrans render examples/scenes/glass_shelf.gltf --backend vk --out $(OUT)/glass_shelf/vk --width 960 --height 540 --rough-refraction on
	@echo "Writing the generated GLSL into $(OUT)/glsl/ and checking it with glslangValidator"
	@mkdir -p $(OUT)/glsl
	@$(BUILD)/tools/dstrans gen gbuffer thesis > $(OUT)/glsl/gbuffer_thesis.glsl
	@$(BUILD)/tools/dstrans gen gbuffer light > $(OUT)/glsl/light_buffer.glsl
	@$(BUILD)/tools/dstrans gen gbuffer shadow > $(OUT)/glsl/shadow_map.glsl
	@$(BUILD)/tools/dstrans gen interlace rows > $(OUT)/glsl/interlace_rows.glsl
	@for f in $(OUT)/glsl/*.glsl; do glslangValidator -S frag $$f >/dev/null || { echo "glslangValidator rejects $$f"; exit 1; }; done
	@echo "make demo: $(OUT)/final.png (OpenGL) and $(OUT)/vk/final.png (Vulkan) with their buffers, glass_shelf.gltf's in $(OUT)/glass_shelf/, and the generated GLSL in $(OUT)/glsl/"

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) out
