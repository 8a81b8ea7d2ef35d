O1000 (shared variables, channel 1: written before a mark, read after one)
G01 X40 Z20 F600
#500=12.5 (retained range)
#20000=-4 (the range that starts null)
G04.1 P1 Q12 (channel 2 sees both from here)
G04.1 P2 Q12 (channel 2 has written #501)
G01 Z[#501] F600
M30
