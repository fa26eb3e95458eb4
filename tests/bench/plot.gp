# The plot of docs/performance.md: TX bus utilisation and RX loss against
# bit rate, both drivers on both chips.  tests/bench/report.py runs it with
# data (its plot.dat: one block per driver and chip), out (the SVG) and
# scale (mcp2510-sim.ko's time_scale) set.
set terminal svg size 900,420 dynamic font "sans,11"
set output out
set multiplot layout 1,2 title sprintf("make bench: Debian 6.1 in QEMU, simulated chips, time\\_scale=%d", scale)
set logscale x
set xlabel "bit rate (bit/s)"
set format x "%.0s%c"
set grid
set key bottom left
set yrange [0:105]

titles = "mcp2510.ko/MCP2510 mcp2510.ko/MCP2515 mcp251x/MCP2510 mcp251x/MCP2515"
set title "TX: bus utilisation, can-flood send"
set ylabel "% of the most the bus carries"
plot for [i=0:3] data index i using 1:2 with linespoints lw 2 title word(titles, i + 1)

set title "RX: frames lost from a back-to-back flood"
set ylabel "% lost"
set key top left
plot for [i=0:3] data index i using 1:3 with linespoints lw 2 title word(titles, i + 1)
unset multiplot
