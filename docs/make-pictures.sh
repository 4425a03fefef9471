#!/usr/bin/env bash
# Regenerates the pictures the README shows, from the demo and the examples.
# Run from the repository root: bash docs/make-pictures.sh (the examples need ../shared).
set -euo pipefail
work=target/docs-pictures
rm -rf "$work" && mkdir -p "$work"
cargo build --release -p sweepffd-cli --examples --bin sweepffd
./target/release/sweepffd demo --out "$work/demo" --quiet
./target/release/sweepffd render --mesh "$work/demo/rest.obj" --rig "$work/demo/rig.json" \
  --pose "$work/demo/pose.json" --compare --show-sweeps --size 480x360 --view 90,15 --out docs/demo.png
for example in teapot bunny armadillo_leg chair; do
  ./target/release/examples/$example "$work/$example" > /dev/null
done
cp "$work/teapot/handle-edit.png" docs/teapot-handle.png
cp "$work/teapot/body-edit-no-hierarchy.png" docs/teapot-no-hierarchy.png
cp "$work/bunny/ears-bent.png" docs/bunny-ears.png
cp "$work/armadillo_leg/step0.png" docs/armadillo-rough.png
cp "$work/armadillo_leg/step4.png" docs/armadillo-fitted.png 2>/dev/null || cp "$work/armadillo_leg/step3.png" docs/armadillo-fitted.png
cp "$work/chair/chair.png" docs/chair.png
# Each shared mesh rigged by autorig, its sweeps drawn.
mkdir -p docs/autorig
for spec in spot_triangulated.obj:spot:110,10 bunny_closed.obj:bunny:20,15 chair.off:chair:30,20 \
  teapot_newell.obj:teapot-newell:30,20 teapot_mcguire/teapot.obj:teapot-mcguire:30,20 dino.off:dino:150,-30 \
  characters/blocky_man.obj:blocky-man:30,10 characters/wuson.obj:wuson:60,15 characters/at-at.obj:at-at:120,60 \
  characters/faerie.obj:faerie:90,10; do
  IFS=: read -r mesh name view <<< "$spec"
  ./target/release/sweepffd autorig --mesh "../shared/meshes/$mesh" --out "$work/$name-rig.json" --quiet > /dev/null
  ./target/release/sweepffd render --mesh "../shared/meshes/$mesh" --rig "$work/$name-rig.json" --show-sweeps \
    --size 640x480 --view "$view" --out "docs/autorig/$name.png" --quiet
done
# Sydney, the game man (BCN_Epileptic) and Mr. Fixit, game characters kept with the tests.
./target/release/sweepffd autorig --mesh tests/meshes/sydney.obj --out "$work/sydney-rig.json" --quiet > /dev/null
./target/release/sweepffd render --mesh tests/meshes/sydney.obj --rig "$work/sydney-rig.json" --show-sweeps \
  --size 640x480 --view 60,10 --out docs/autorig/sydney.png --quiet
./target/release/sweepffd autorig --mesh tests/meshes/bcn_epileptic.obj --out "$work/game-man-rig.json" --quiet > /dev/null
./target/release/sweepffd render --mesh tests/meshes/bcn_epileptic.obj --rig "$work/game-man-rig.json" --show-sweeps \
  --size 640x480 --view 30,10 --out docs/autorig/game-man.png --quiet
./target/release/sweepffd autorig --mesh tests/meshes/mrfixit.obj --out "$work/mrfixit-rig.json" --quiet > /dev/null
./target/release/sweepffd render --mesh tests/meshes/mrfixit.obj --rig "$work/mrfixit-rig.json" --show-sweeps \
  --size 640x480 --view 60,10 --out docs/autorig/mrfixit.png --quiet
./target/release/sweepffd autorig --mesh ../shared/meshes/armadillo_50k.obj --out "$work/armadillo-rig.json" --quiet > /dev/null
./target/release/sweepffd render --mesh ../shared/meshes/armadillo_50k.obj --rig "$work/armadillo-rig.json" \
  --show-sweeps --size 1200x900 --out docs/autorig-armadillo.png --quiet
# The faerie, the dino, wuson, Sydney, the game man, Mr. Fixit and the star at rest and with
# every sweep bent 45° at its middle key: the autorig pipeline test's poses
# (tests/fitting/autorig_pipeline.rs).
mkdir -p "$work/pipeline"
SWEEPFFD_PICTURES_DIR="$work/pipeline" cargo test --release --test fitting meshes_no_constant --quiet > /dev/null
SWEEPFFD_PICTURES_DIR="$work/pipeline" cargo test --release --test fitting the_star_bends --quiet > /dev/null
./target/release/sweepffd render --mesh "$work/pipeline/star.obj" --rig "$work/pipeline/star-rig.json" --show-sweeps \
  --size 640x480 --view 30,20 --out docs/autorig/star.png --quiet
SWEEPFFD_PICTURES_DIR="$work/pipeline" cargo test --release --test fitting sydney_bends --quiet > /dev/null
SWEEPFFD_PICTURES_DIR="$work/pipeline" cargo test --release --test fitting game_man_bends --quiet > /dev/null
SWEEPFFD_PICTURES_DIR="$work/pipeline" cargo test --release --test fitting mr_fixit_bends --quiet > /dev/null
# Wuson's with its sweeps drawn.
for spec in characters-faerie.obj:faerie:90,10: dino.off:dino:150,-30: characters-wuson.obj:wuson:60,15:--show-sweeps \
  sydney:sydney:60,10: bcn_epileptic:game-man:30,10: mrfixit:mrfixit:60,10: star:star:30,20:; do
  IFS=: read -r mesh name view sweeps <<< "$spec"
  ./target/release/sweepffd render --mesh "$work/pipeline/$mesh.obj" --rig "$work/pipeline/$mesh-rig.json" \
    --pose "$work/pipeline/$mesh-pose.json" --compare $sweeps --view "$view" --size 450x400 \
    --out "docs/autorig/$name-bent.png" --quiet
done
# Bends over a fifth of a limb against the same turn given to one key (docs/method.md): the
# poses the bend test writes, drawn close up where they bend.
mkdir -p docs/pose "$work/pose"
SWEEPFFD_PICTURES_DIR="$work/pose" cargo test --release --test fitting a_bend_over --quiet > /dev/null
for spec in armadillo_50k:limb0:armadillo-leg:60,10 bunny_stanford_zipper:limb0:bunny-ear:100,10; do
  IFS=: read -r mesh limb name view <<< "$spec"
  for pose in bend one-key; do
    ./target/release/sweepffd render --mesh "../shared/meshes/$mesh.obj" --rig "$work/pose/$mesh-rig.json" \
      --pose "$work/pose/$mesh-$limb-$pose.json" --view "$view" --zoom 3 \
      --look-at "$(cat "$work/pose/$mesh-$limb-look-at.txt")" --out "docs/pose/$name-$pose.png" --quiet
  done
done
# The viewer, scripted in a virtual display (Debian's xvfb): the bunny's ear dragged (§4).
cp docs/viewer-session.json "$work/bunny/"
xvfb-run -a -s "-screen 0 1600x1000x24" ./target/release/sweepffd view \
  --mesh ../shared/meshes/bunny_stanford_zipper.obj --rig "$work/bunny/ears-rig.json" \
  --script "$work/bunny/viewer-session.json" --size 1280x800 > /dev/null
cp "$work/bunny/viewer.png" docs/viewer.png
ls -l docs/*.png docs/autorig/*.png docs/pose/*.png
