#!/bin/sh
# Plots every scene of a trade-study result directory (the output of bench/tradeoff_bench or
# `octomotion bench --out-dir DIR`): DIR/SCENE_tradeoff.png and DIR/SCENE_planning.png.
# Usage: scripts/plot_tradeoff.sh DIR
# Study directories are not kept in git (docs/trade-off.md, "Commands", regenerates them); the
# plots docs/trade-off.md shows are copies of a default run's, in docs/img/trade-off/.
set -eu
dir=${1:?usage: scripts/plot_tradeoff.sh DIR}
script=$(dirname "$0")/plot_tradeoff.gp
for dat in "$dir"/*_tradeoff.dat "$dir"/*_planning.dat; do
  [ -f "$dat" ] || continue
  base=${dat%.dat}
  file=$(basename "$base")
  case "$file" in
    *_tradeoff) kind=tradeoff; name=${file%_tradeoff} ;;
    *) kind=planning; name=${file%_planning} ;;
  esac
  gnuplot -e "dat='$dat'; png='$base.png'; kind='$kind'; name='$name'" "$script"
  echo "$base.png"
done
