// dstrans: deferred shading of transparent surfaces, as a header-only toolkit. This header includes
// every public header; include the one you need instead to take only that piece.
//
//   #include <dstrans/dstrans.hpp>
//   dstrans::glsl::source src;
//   dstrans::glsl::add_layout<dstrans::thesis_gbuffer>(src, "gbuffer");
//   dstrans::glsl::add_interlace<dstrans::interlace::rows>(src);
//   std::puts(src.str().c_str());
#pragma once

#include "closed_surface.hpp"
#include "format.hpp"
#include "frame/blocks.hpp"
#include "frame/culling.hpp"
#include "frame/passes.hpp"
#include "frame/plan.hpp"
#include "frame/schedule.hpp"
#include "frame/slots.hpp"
#include "formula.hpp"
#include "fullscreen.hpp"
#include "gbuffer.hpp"
#include "glsl.hpp"
#include "interlace.hpp"
#include "kbuffer.hpp"
#include "layout.hpp"
#include "light_basis.hpp"
#include "light_mesh.hpp"
#include "light_volume.hpp"
#include "material_textures.hpp"
#include "particles.hpp"
#include "pass_shaders.hpp"
#include "phong.hpp"
#include "pipeline.hpp"
#include "refraction.hpp"
#include "result.hpp"
#include "scene.hpp"
#include "scene_features.hpp"
#include "surface.hpp"
#include "transparent_shadow.hpp"
