// Where the single-layer interlaced G-buffer keeps the layer behind (or in front of) a pixel: on the
// pixel's interlace partner, in the same G-buffer and light buffer.
dst_surface dst_other(ivec2 pixel) { return dst_gbuffer_read(dst_interlace_partner(pixel, frame.size.xy)); }
dst_light_sample dst_other_light(ivec2 pixel) { return dst_light_read(dst_interlace_partner(pixel, frame.size.xy)); }
