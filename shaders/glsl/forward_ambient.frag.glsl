// The forward ambient pass: depth test and write on; the ambient colour and the material's alpha, the
// normal for refraction, and (with DST_FORWARD_DEPTH) the depth for its rejection.
layout(location = 0) out vec4 colour;
layout(location = 1) out vec4 encoded_normal;
#ifdef DST_FORWARD_DEPTH
layout(location = 2) out float depth;
#endif

void main() {
  dst_surface s;
  if (!dst_forward_surface(s)) discard;
  colour = vec4(dst_shade(s, dst_light_sample_zero(), frame.ambient.xyz), s.alpha);
  encoded_normal = vec4(dst_encode_normal(s.normal), 0.0f);
#ifdef DST_FORWARD_DEPTH
  depth = s.depth;
#endif
}
