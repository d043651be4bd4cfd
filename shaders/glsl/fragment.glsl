// What every dstrans fragment shader knows besides frame.glsl.

// The pixel a fragment covers, rows from the top on both APIs.
ivec2 dst_pixel() { return ivec2(gl_FragCoord.xy); }
