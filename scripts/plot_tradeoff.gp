# The speed/accuracy trade study's plots (docs/trade-off.md), from the gnuplot data that
# `octomotion bench` and bench/tradeoff_bench write (one block per curve, the block's first line
# is its title):
#   kind='tradeoff': mean check time vs false-positive rate, one curve per checker (the points of
#                    a curve are the resolutions, coarse at the right);
#   kind='planning': median planning time vs resolution, one curve per planner x checker.
# Usage: gnuplot -e "dat='DIR/bookshelf_tradeoff.dat'; png='x.png'; kind='tradeoff'; name='bookshelf'" \
#          scripts/plot_tradeoff.gp        (scripts/plot_tradeoff.sh DIR does every scene)
if (!exists("kind")) kind = 'tradeoff'
if (!exists("name")) name = ''
if (!exists("png")) png = kind . '.png'

set terminal pngcairo size 1000,700 font ",11"
set output png
set grid
set key outside right top
set logscale y
stats dat using 2 nooutput
blocks = STATS_blocks

if (kind eq 'tradeoff') {
  # FP = 0 cannot sit on a log axis: such points are drawn at 0.01 %.
  set logscale x
  set xrange [0.005:200]
  set xlabel 'false positives (% of the states FCL finds free; 0 drawn at 0.01 %)'
  set ylabel 'mean time per full check (microseconds, FK included)'
  set title name . ': check time vs false-positive rate (points: resolutions)'
  plot for [i=0:blocks-1] dat index i using ($1 > 0.01 ? $1 : 0.01):2 \
       with linespoints pt (i+4) lw 2 title columnheader(1)
} else {
  set logscale x
  set xlabel 'resolution (cm)'
  set ylabel 'median planning time (s; unsolved runs count the limit)'
  set title name . ': planning time vs resolution'
  plot for [i=0:blocks-1] dat index i using 1:2 with linespoints pt (i+4) lw 2 \
       title columnheader(1)
}
