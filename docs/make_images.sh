#!/bin/bash
# Renders the pictures of docs/integration.md with `dstrans render` (run from the repository's root after
# a build): docs/make_images.sh [build/tools/dstrans]
set -e
tool=${1:-build/tools/dstrans}
scene=examples/scenes/pane.json
work=$(mktemp -d)
render() { "$tool" render "$scene" --backend gl --width 480 --height 270 --out "$work/$1" "${@:2}" >/dev/null; }
render thesis
render no_refraction --refraction 0
render opaque_shadows --shadows opaque
render peeling --technique peeling
"$tool" render examples/scenes/glass_room.json --backend gl --width 960 --height 540 --out "$work/demo" >/dev/null
cp "$work/demo/final.png" docs/images/demo_final.png
cp "$work/thesis/final.png" docs/images/final.png
cp "$work/thesis/diffuse.png" docs/images/gbuffer_diffuse.png
cp "$work/thesis/light.png" docs/images/light_buffer.png
cp "$work/thesis/shadow_colour.png" docs/images/shadow_colour.png
cp "$work/no_refraction/final.png" docs/images/final_no_refraction.png
cp "$work/opaque_shadows/final.png" docs/images/final_opaque_shadows.png
cp "$work/peeling/final.png" docs/images/final_peeling.png
rm -rf "$work"
echo "docs/images: written"
