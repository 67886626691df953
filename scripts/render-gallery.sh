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
# BoxAnimated with both materials made alphaMode BLEND (alpha 0.5 inner,
# 0.35 outer) in a temporary copy: stochastic transparency, motion blur and
# depth of field together (64 spp: the transparency is noise at 32).
blend=$(mktemp --suffix=.gltf)
python3 -c "import json, sys; d = json.load(open(sys.argv[1])); [m.update(alphaMode='BLEND') or m['pbrMetallicRoughness']['baseColorFactor'].__setitem__(3, a) for m, a in zip(d['materials'], (0.5, 0.35))]; json.dump(d, open(sys.argv[2], 'w'))" $k/BoxAnimated.gltf "$blend"
"$blurcull" render --scene "$blend" --shutter 1.5,1.9 --lens-radius 0.5 --backend cpu --size 320x240 --spp 64 -q -o $out/gallery-boxanimated-blend.png
rm -f "$blend"
