// A program that takes dstrans the way an engine would; exits 0 when the core works.
#include <cstdio>

#include <dstrans/dstrans.hpp>

int main() {
  dstrans::glsl::source src;
  dstrans::glsl::add_layout<dstrans::thesis_gbuffer>(src, "gbuffer");
  const bool ok = dstrans::thesis_gbuffer::bytes_per_pixel == 16 &&
                  src.str().find("dst_gbuffer_write") != std::string::npos &&
                  dstrans::interlace::rows::keep({0, 1}, {2, 2});
  std::puts(ok ? "dstrans consumer: ok" : "dstrans consumer: WRONG");
  return ok ? 0 : 1;
}
