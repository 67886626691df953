#!/usr/bin/env bash
# Renders the gallery of docs/scenes.md: the Khronos sample models in
# ../shared/scenes/khronos at 320x240 on the cpu backend, into docs/images/.
# Each line below is the command the page shows beside its image.
#
#   bash scripts/render-gallery.sh [path/to/blurcull]   (default: build/frontend/blurcull)
set -euo pipefail
cd "$(dirname "$0")/.."
blurcull=${1:-build/frontend/blurcull}
k=../shared/scenes/khronos
out=${GALLERY_OUT:-docs/images}
common=(--backend cpu --size 320x240 --spp 32 -q)

"$blurcull" render --scene $k/BoxAnimated.gltf --shutter 1.5,1.9 "${common[@]}" -o $out/gallery-boxanimated.png
"$blurcull" render --scene $k/BoxAnimated.gltf --frames 24:72:24 --fps 24 --shutter-angle 180 "${common[@]}" -o $out/gallery-boxanimated-%04d.png
"$blurcull" render --scene $k/AnimatedTriangle.gltf --shutter 0.1,0.3 "${common[@]}" -o $out/gallery-animatedtriangle.png
"$blurcull" render --scene $k/RiggedSimple.gltf --shutter 0.6,1.0 "${common[@]}" -o $out/gallery-riggedsimple.png
"$blurcull" render --scene $k/RiggedFigure.gltf --shutter 0.3,0.5 "${common[@]}" -o $out/gallery-riggedfigure.png
"$blurcull" render --scene $k/Cameras.gltf --lens-radius 0.05 "${common[@]}" -o $out/gallery-cameras.png
"$blurcull" render --scene $k/Cube/Cube.gltf --lens-radius 0.1 "${common[@]}" -o $out/gallery-cube.png
"$blurcull" render --scene $k/SparseMorphCube/singleBlendshapeCube_sparse.glb "${common[@]}" -o $out/gallery-sparsemorphcube.png
