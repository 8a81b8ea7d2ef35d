O1001 (shared variables, channel 2: reads channel 1's after a mark, writes one back)
G04.1 P1 Q12
G01 X[-10*#20000] Z[#500] F600
#501=#500+2*#20000
G04.1 P2 Q12
M30
