# Time per step vs cube count for the N-objects octree broad phase (N = 5, 10, 30, 50), the
# exhaustive all-pairs test and FCL's dynamic AABB tree, from the CSV printed by
#   build/bench/broadphase_bench --csv > broadphase.csv
# Usage: gnuplot -e "csv='broadphase.csv'; png='broadphase.png'" scripts/plot_broadphase.gp
# Log-log axes: a slope of 1 is linear growth, 2 is quadratic (dashed guides).
if (!exists("csv")) csv = 'broadphase.csv'
if (!exists("png")) png = 'broadphase.png'

set terminal pngcairo size 1000,700 font ",11"
set output png
set datafile separator ','
set datafile missing 'nan'
set key top left
set logscale xy
set grid
set xlabel 'cubes'
set ylabel 'CPU time per step (microseconds, median)'
set title 'Colliding planes of cubes, 200 steps: broad phase + exact narrow phase'

# Guides anchored at the exhaustive time of the 882-cube set (t10).
stats csv using 2 every ::11::11 nooutput
anchor_x = STATS_min
stats csv using 7 every ::11::11 nooutput
anchor_y = STATS_min
linear(x) = anchor_y * (x / anchor_x)
quadratic(x) = anchor_y * (x / anchor_x)**2

plot csv using 2:3 skip 1 with linespoints title 'octree N=5', \
     csv using 2:4 skip 1 with linespoints title 'octree N=10', \
     csv using 2:5 skip 1 with linespoints title 'octree N=30', \
     csv using 2:6 skip 1 with linespoints title 'octree N=50', \
     csv using 2:7 skip 1 with linespoints lw 2 title 'exhaustive (N = infinity)', \
     csv using 2:8 skip 1 with linespoints lw 2 title 'FCL DynamicAABBTree', \
     quadratic(x) dashtype 2 lc rgb 'gray40' title 'slope 2 (quadratic)', \
     linear(x) dashtype 3 lc rgb 'gray40' title 'slope 1 (linear)'
