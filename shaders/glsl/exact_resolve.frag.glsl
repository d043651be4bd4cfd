// The exact reference's resolve: every fragment of the pixel's list, shaded already, blended front to back
// in depth order and laid over the frame (colour + frame * alpha, alpha being what the frame keeps). Each
// round takes the nearest fragments after the last round's (dst_nearer's order; equal ones together), so
// no register array bounds how many a pixel holds. What went to the tail lies behind them all.
layout(location = 0) out vec4 colour;
layout(binding = DST_SLOT_KBUFFER_TAIL) uniform sampler2D dst_tail;
layout(binding = DST_SLOT_KBUFFER_TAIL + 1) uniform sampler2D dst_tail_optical_depth;

void main() {
  ivec2 p = dst_pixel();
  uint head = imageLoad(dst_heads, p).x;
  vec4 tail = texelFetch(dst_tail, p, 0);
  float tail_kept = exp(-texelFetch(dst_tail_optical_depth, p, 0).x);
  if (head == dst_no_node && !(tail.w > 0.0f)) discard;
  vec3 sum = vec3(0.0f);
  float kept = 1.0f;
  uvec4 last = uvec4(0u);
  bool first = true;
  for (uint taken = 0u; taken < kbuffer.capacity;) {
    uvec4 best = uvec4(dst_no_node);
    uint copies = 0u;
    uint at = head;
    for (uint steps = 0u; at != dst_no_node && steps < kbuffer.capacity; ++steps) {
      uvec4 node = kbuffer.nodes[at];
      at = node.w;
      if (!first && !dst_nearer(last, node)) continue;
      if (copies == 0u || dst_nearer(node, best)) {
        best = node;
        copies = 1u;
      } else if (node.xyz == best.xyz) {
        ++copies;
      }
    }
    if (copies == 0u) break;
    vec4 c = dst_shaded_colour(best);
    for (uint k = 0u; k < copies; ++k) {
      sum += kept * c.w * c.xyz;
      kept *= 1.0f - c.w;
    }
    taken += copies;
    last = best;
    first = false;
  }
  colour = vec4(sum + kept * dst_tail_over(vec3(0.0f), tail, tail_kept), kept * tail_kept);
}
