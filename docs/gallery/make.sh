#!/bin/sh
# Regenerates the README gallery from examples/. Run from the repository root.
set -eu
cargo build --release --quiet
B=target/release/stlc
G=docs/gallery
$B render examples/2dtree.od --show-layout --size 360x384 -o $G/2dtree.png
$B render examples/fig9.od --growth bfs --show-layout --size 300x316 -o $G/fig9-bfs.png
$B render examples/fig9.od --growth dfs --show-layout --size 300x316 -o $G/fig10-dfs.png
$B render examples/holes.od --show-layout --size 300x300 -o $G/holes.png
$B render examples/polygon.od --show-layout --size 300x300 -o $G/polygon.png
$B render examples/decrement.od --size 300x300 -o $G/decrement.png
for n in abop-1.24a abop-1.24b abop-1.24c abop-1.24d abop-1.24e abop-1.24f \
         koch-snowflake sierpinski-arrowhead stl-003-fig4; do
  $B render examples/$n.lsys --size 240x240 -o $G/$n.png
done
# The book's parametric and context-sensitive L-systems (docs/lsys.md).
for n in abop-1.31a abop-2.6a abop-2.7a abop-2.8a param-willow abop-5.5a; do
  $B render examples/$n.lsys --size 240x240 -o $G/$n.png
done
# Leaves, flowers and colours (docs/lsys.md, *Colours, widths and organs*).
$B render examples/abop-1.26.lsys --size 360x360 -o $G/abop-1.26.png
$B render examples/abop-3.2.lsys --size 240x240 -o $G/abop-3.2.png
$B render examples/crown.od --show-layout --size 300x300 -o $G/crown.png
$B render examples/successors.od --show-layout --size 300x300 -o $G/successors.png
$B render examples/pentagon.od --show-layout --size 300x300 -o $G/pentagon.png
# The tutorial's pictures (docs/tutorial.md).
T=docs/tutorial
for i in 1 2; do
  $B render examples/tutorial/step$i.od --size 240x240 -o $T/step$i.png
done
for i in 3 4; do
  $B render examples/tutorial/step$i.od --show-layout --size 240x240 -o $T/step$i.png
done
$B render examples/tutorial/step4.od --growth dfs --show-layout --size 240x240 -o $T/step5.png
for s in 1 2; do
  $B render examples/tutorial/step6.od --seed $s --show-layout --size 240x240 -o $T/step6-seed$s.png
done
$B render examples/tutorial/step7.od --show-layout --size 240x240 -o $T/step7.png
$B render examples/tutorial/step7.od --view 0,90 --show-layout --size 240x240 -o $T/step7-above.png
# 3D (docs/3d.md): two views each.
$B render examples/hilbert3d.lsys --depth 3 --size 240x240 -o $G/hilbert3d-30-20.png
$B render examples/hilbert3d.lsys --depth 3 --view -60,35 --size 240x240 -o $G/hilbert3d-m60-35.png
$B render examples/plant3d.lsys --size 240x240 -o $G/plant3d-30-20.png
$B render examples/plant3d.lsys --view 120,60 --size 240x240 -o $G/plant3d-120-60.png
$B render examples/oak3d.od --show-layout --size 320x320 -o $G/oak3d-layout.png
$B render examples/oak3d.od --view 120,50 --size 320x320 -o $G/oak3d-120-50.png
$B render examples/oak3d.od -o $G/oak3d.glb
$B render examples/forest3d.od --view 30,35 --show-layout --size 320x320 -o $G/forest3d-layout.png
$B render examples/forest3d.od --view -40,10 --size 320x320 -o $G/forest3d-m40-10.png
# Depth 7 is a solid grey square at thumbnail size.
$B render examples/hilbert.lsys --depth 5 --size 240x240 -o $G/hilbert.png
# Variation (docs/language.md): alternatives under bfs and dfs, and a grove
# of four roots in one outline under two seeds and both growth orders.
$B render examples/alternatives.od --show-layout --size 240x300 -o $G/alternatives-bfs.png
$B render examples/alternatives.od --growth dfs --show-layout --size 240x300 -o $G/alternatives-dfs.png
$B render examples/grove.od --seed 7 --show-layout --size 300x300 -o $G/grove-seed7.png
$B render examples/grove.od --seed 8 --show-layout --size 300x300 -o $G/grove-seed8.png
$B render examples/grove.od --seed 7 --growth dfs --show-layout --size 300x300 -o $G/grove-seed7-dfs.png
# ABOP Fig. 1.27, the stochastic plant, with five seeds.
for s in 1 2 3 4 5; do
  $B render examples/abop-1.27.lsys --seed $s --size 160x240 -o $G/abop-1.27-seed$s.png
done
# Space-first growth beside bfs and dfs (docs/growth.md): every gallery OD
# grown whole, and the coverage cases at a third of bfs's stems.
S=$G/space
mkdir -p $S
for n in 2dtree fig9 holes polygon decrement crown successors pentagon \
         alternatives grove; do
  for o in bfs dfs space; do
    $B render examples/$n.od --growth $o --show-layout --size 240x240 -o $S/$n-$o.png
  done
done
for n in oak3d forest3d; do
  for o in bfs dfs space; do
    $B render examples/$n.od --growth $o --show-layout --size 240x240 -o $S/$n-$o.png
  done
done
for f in benches/space/box-hole.od examples/holes.od benches/space/l-shape.od \
         examples/crown.od; do
  n=$(basename $f .od)
  third=$(( $($B check $f | sed -n 's/.*grows *\([0-9]*\) stems.*/\1/p') / 3 ))
  for o in bfs dfs space; do
    $B render $f --growth $o --max-stems $third --show-layout --size 240x240 \
      -o $S/$n-third-$o.png 2>/dev/null
  done
done
