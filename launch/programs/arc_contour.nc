%
O0200 (finish a contour: arcs, blended G64 corners, an exact stop, a rapid out)
N10 G00 X20. Z2.
N20 G01 Z0. F600
N30 G03 X30. Z-5. R5.
N40 G01 Z-20.
N50 G02 X40. Z-25. R5.
N60 G01 X50. F300
N70 G09 W-5.
N80 G00 X60. Z10.
N90 M30
%
