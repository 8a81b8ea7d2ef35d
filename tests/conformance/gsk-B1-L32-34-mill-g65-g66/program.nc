O0001
(gsk B.1 L32-34: G65 calls O9100 once; G66 calls it after every block that moves, G04 not;)
(G67 ends the modal call)
G65 P9100 A1.
G66 P9100 A2.
G00 X10
G04 P100
G01 Z5 F100
G67
G00 X0
M30
O9100
G01 Y#1 F100
M99
