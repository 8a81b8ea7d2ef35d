%
O0400 (calls O2001 twice from the program directory, then ends at X60 Z10)
N10 G00 X40. Z5.
N20 M98 P22001
N30 G00 X60. Z10.
N40 M30
%
