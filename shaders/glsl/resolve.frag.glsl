// The resolve pass (S1): the k nearest fragments of the pixel's list stay in registers (the core), sorted
// by depth (ties by their packed tangent and colour, so equal fragments resolve the same way every time);
// the rest are blended out of order (the tail) with the capture pass's overflow. The core is shaded fully
// (Eq. 2) unless DST_LAYERS_CHEAP; the tail cheaply and once for all its fragments from their gathered
// inputs (DST_LAYERS_GATHERED), not at all with DST_LAYERS_TAILLESS (its opacity still counts), or each
// fragment fully with DST_LAYERS_FORWARD (the reference, whose core holds every fragment anyway).
// Written premultiplied over the frame: colour + frame * alpha (alpha = what the frame keeps); around the
// glass (DST_AROUND_GLASS) into the glass layers, what lies behind the glass apart from what lies in front.
layout(location = 0) out vec4 colour;
#ifdef DST_AROUND_GLASS
layout(location = 1) out vec4 colour_front;
#endif
layout(binding = DST_SLOT_KBUFFER_TAIL) uniform sampler2D dst_tail;
layout(binding = DST_SLOT_KBUFFER_TAIL + 1) uniform sampler2D dst_tail_optical_depth;

vec3 dst_shade_node(ivec2 p, uvec4 node, bool full) {
  return dst_hair_lit(dst_world_position(p, uintBitsToFloat(node.x)), dst_unpack_tangent(node.y), dst_unpack_colour(node.z), full);
}

void main() {
  ivec2 p = dst_pixel();
  uint head = imageLoad(dst_heads, p).x;
  vec4 tail = texelFetch(dst_tail, p, 0);
  float transmittance = exp(-texelFetch(dst_tail_optical_depth, p, 0).x);
  if (head == dst_no_node && !(tail.w > 0.0f)) discard;
  uvec4 core[DST_K];
  for (int i = 0; i < DST_K; ++i) core[i] = uvec4(dst_no_node);  // Mesa warns of reads it cannot prove written
  int n = 0;
  uint at = head;
  // The cheap tail's inputs, gathered to be shaded once (dst_hair_lit_mean): alpha and count, then the sums
  // of depth, colour and T T^T (its diagonal and its xy, xz, yz), each weighted by alpha.
  vec2 gathered = vec2(0.0f);
  float gathered_depth = 0.0f;
  vec3 gathered_colour = vec3(0.0f), diag = vec3(0.0f), off = vec3(0.0f);
  for (uint steps = 0u; at != dst_no_node && steps < kbuffer.capacity; ++steps) {
    uvec4 node = kbuffer.nodes[at];
    at = node.w;
    uvec4 out_node = node;  // what leaves for the tail: this node, or the core's farthest
    bool to_tail = true;
    if (n < DST_K || dst_nearer(node, core[DST_K - 1])) {
      // Shift the farther ones back (the farthest leaves when the core is full) and put it in the gap.
      // Written without `i > 0 && f(core[i - 1])`: Mesa's GL compiler read core[-1] there.
      int last = n < DST_K ? n : DST_K - 1;
      if (n == DST_K) out_node = core[last];
      to_tail = n == DST_K;
      int i = last;
      for (; i > 0; --i) {
        if (!dst_nearer(node, core[i - 1])) break;
        core[i] = core[i - 1];
      }
      core[i] = node;
      if (n < DST_K) ++n;
    }
    if (to_tail) {
      vec4 c = dst_unpack_colour(out_node.z);
      transmittance *= 1.0f - c.w;
#ifdef DST_LAYERS_FORWARD
      tail = dst_tail_add(tail, vec4(dst_shade_node(p, out_node, true), c.w));
#endif
#ifdef DST_LAYERS_TAILLESS
      tail.w += c.w;
#endif
#ifdef DST_LAYERS_GATHERED
      vec3 t = dst_unpack_tangent(out_node.y);
      gathered += vec2(c.w, 1.0f);
      gathered_depth += c.w * uintBitsToFloat(out_node.x);
      gathered_colour += c.w * c.xyz;
      diag += c.w * t * t;
      off += c.w * vec3(t.x * t.y, t.x * t.z, t.y * t.z);
#endif
    }
  }
#ifdef DST_LAYERS_GATHERED
  if (gathered.x > 0.0f) {
    vec3 world = dst_world_position(p, gathered_depth / gathered.x);
    tail += vec4(dst_hair_lit_mean(world, diag / gathered.x, off / gathered.x, gathered_colour, gathered.x / gathered.y), gathered.x);
  }
#endif
  // Around the glass (DST_AROUND_GLASS), the core splits at the glass's depth, and the tail goes with the
  // core's farthest fragment (every list fragment in it lies farther still); elsewhere all lies behind.
  float glass = dst_glass_and_opaque(p).x;
  bool tail_behind = true;
  if (n > 0) tail_behind = dst_behind_glass(uintBitsToFloat(core[n - 1].x), glass);
  vec4 none = vec4(0.0f, 0.0f, 0.0f, 1.0f), tail_layer = vec4(dst_tail_over(vec3(0.0f), tail, transmittance), transmittance);
  vec4 behind = tail_behind ? tail_layer : none, front = tail_behind ? none : tail_layer;
  for (int i = n - 1; i >= 0; --i) {
    vec4 c = dst_unpack_colour(core[i].z);
#ifdef DST_LAYERS_CHEAP
    vec3 shaded = dst_shade_node(p, core[i], false);
#else
    vec3 shaded = dst_shade_node(p, core[i], true);
#endif
    if (dst_behind_glass(uintBitsToFloat(core[i].x), glass)) behind = vec4(dst_over(behind.xyz, vec4(shaded, c.w)), behind.w * (1.0f - c.w));
    else front = vec4(dst_over(front.xyz, vec4(shaded, c.w)), front.w * (1.0f - c.w));
  }
  colour = behind;
#ifdef DST_AROUND_GLASS
  colour_front = front;
#endif
}
