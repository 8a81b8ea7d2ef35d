%
O0001 (walking skeleton: X and Z, rapid, feed, dwell)
N10 G00 X40. Z5.
N20 G01 Z-20. F600
N30 X50. W-5. F300 (incremental Z)
N40 G04 P200
N50 G00 X60. Z10.
N60 M30
%
