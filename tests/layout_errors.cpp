// Layouts that cannot work must not compile, and must say why. CTest compiles this file once per CASE
// and looks for the sentence; CASE 0 must compile, so a broken file cannot pass as a "failure".
#include <dstrans/gbuffer.hpp>

using namespace dstrans;

#if CASE == 0
using ok = layout<surface, target<format::rgba8, field::diffuse, field::alpha>>;
#elif CASE == 1  // a field stored twice
using bad = layout<surface, target<format::rgba8, field::diffuse, field::alpha>, target<format::r8, field::alpha>>;
#elif CASE == 2  // more channels than the format has
using bad = layout<surface, target<format::rg8, field::diffuse>>;
#elif CASE == 3  // alpha in the 2-bit channel of RGB10A2
using bad = layout<surface, target<format::rgb10a2, unused<3>, field::alpha>>;
#elif CASE == 4  // depth in 8 bits
using bad = layout<surface, target<format::rgba8, field::diffuse, field::depth>>;
#elif CASE == 5  // more than 8 targets
using t = target<format::r8, unused<1>>;
using bad = layout<surface, t, t, t, t, t, t, t, t, t>;
#elif CASE == 6  // a light-buffer field in a G-buffer
using bad = layout<surface, target<format::rgba8, field::light, field::specular>>;
#elif CASE == 7  // a technique that needs normals, given the shadow map
static_assert(requires_fields<thesis_shadow_map, field::depth, field::normal>());
#elif CASE == 8  // no targets at all
using bad = layout<surface>;
#endif

#if CASE == 0
int touch = ok::bytes_per_pixel;
#elif CASE != 7
int touch = bad::bytes_per_pixel;
#endif
