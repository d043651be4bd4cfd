// Where deferred depth peeling keeps the layer behind a pixel: at the same pixel of the second G-buffer
// and light buffer (the nearest opaque surface behind the first layer).
dst_surface dst_other(ivec2 pixel) { return dst_gbuffer2_read(pixel); }
dst_light_sample dst_other_light(ivec2 pixel) { return dst_light2_read(pixel); }
