#!/bin/sh
# Records the regression images: the final image of every example scene (JSON and glTF) under every technique, of
# glass_room under the example post chain and of its sun and lamp variants with 5 x 5 soft shadows, at
# 160x90 with 256^2 shadow maps on both backends, as `dstrans render` makes them.
# render_test.cpp's [regression] case renders the same frames and compares them with these files.
#   tests/regression/record.sh build/tools/dstrans
set -eu
tool=$1
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$here/images"
record() {  # record NAME ARGS...: renders and keeps final.png as images/NAME.png
  name=$1
  shift
  "$tool" render "$@" --width 160 --height 90 --shadow-size 256 --out "$work/$name" >/dev/null
  cp "$work/$name/final.png" "$here/images/$name.png"
}
for backend in gl vk; do
  for scene in "$root"/examples/scenes/*.json "$root"/examples/scenes/*.gltf; do
    s=$(basename "$scene"); s=${s%.*}
    for technique in interlaced peeling forward forward-depth; do
      record "${backend}_${s}_${technique}" "$scene" --backend $backend --technique $technique
    done
  done
  record "${backend}_glass_room_post" "$root/examples/scenes/glass_room.json" --backend $backend \
    --post "$root/examples/post_chain.json"
  for s in glass_room_sun glass_room_lamp; do
    record "${backend}_${s}_soft" "$root/examples/scenes/$s.json" --backend $backend --shadow-filter 5
  done
done
