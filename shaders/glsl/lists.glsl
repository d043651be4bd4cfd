// Per-pixel lists of fragments (the k-buffer's, S1, and the exact reference's): a head per pixel and a pool
// of 16-byte nodes (depth bits, two words of the fragment, the next node), shared by the passes that fill
// and resolve them.
layout(binding = DST_SLOT_KBUFFER_HEADS, r32ui) uniform coherent uimage2D dst_heads;
layout(std430, binding = DST_SLOT_KBUFFER_NODES) coherent buffer dst_kbuffer {
  uint count;     // nodes asked for; past the capacity, fragments went to the tail targets instead
  uint overflow;  // fragments that found no node
  uint capacity;
  uint unused;
  uvec4 nodes[];
} kbuffer;
const uint dst_no_node = 0xffffffffu;

// `node` (depth bits first) at the head of pixel p's list; false, and counted as overflow, where the pool
// is used up.
bool dst_list_push(ivec2 p, uvec3 node) {
  uint at = atomicAdd(kbuffer.count, 1u);
  if (at >= kbuffer.capacity) {
    atomicAdd(kbuffer.overflow, 1u);
    return false;
  }
  kbuffer.nodes[at] = uvec4(node, imageAtomicExchange(dst_heads, p, at));
  return true;
}

// Whether node a lies nearer than b: depths are positive floats, whose bits order as uints; equal depths
// by the fragment's words, so that equal fragments resolve the same way every time.
bool dst_nearer(uvec4 a, uvec4 b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// The exact reference's nodes hold fragments already shaded: colour and alpha in half floats (colour
// clamped to half's finite range, alpha to [0, 1]).
uvec3 dst_shaded_node(float depth, vec4 shaded) {
  vec4 c = vec4(min(max(shaded.xyz, vec3(0.0f)), vec3(65504.0f)), clamp(shaded.w, 0.0f, 1.0f));
  return uvec3(floatBitsToUint(depth), packHalf2x16(c.xy), packHalf2x16(c.zw));
}
vec4 dst_shaded_colour(uvec4 node) { return vec4(unpackHalf2x16(node.y), unpackHalf2x16(node.z)); }

// A shaded fragment at window depth `depth` into pixel p's list; where the pool is used up, it goes to the
// tail targets instead (out of order): what it adds to them (colour and alpha, and optical depth).
vec4 dst_push_shaded(ivec2 p, float depth, vec4 shaded, out float optical_depth) {
  optical_depth = 0.0f;
  if (dst_list_push(p, dst_shaded_node(depth, shaded))) return vec4(0.0f);
  optical_depth = -log(max(1.0f - shaded.w, 1.0f / 1024.0f));
  return dst_tail_add(vec4(0.0f), shaded);
}
