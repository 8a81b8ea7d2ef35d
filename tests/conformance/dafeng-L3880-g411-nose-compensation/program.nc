O1001 (spec L3880: with G42 the axis follows the offset path. Z10 X10 is an outside corner:)
(the corner arc turns A; Z0 X0 an inside one: A turns at the offset lines' intersection)
(Z9 X1. G40.1 leaves A where the last move of the control leaves it; the G40 move carries it)
T0101
G00 X20 Z30
G41.1
G42 G01 Z20 F300
G01 Z10
G01 X0
G01 Z0
G02 X-20 Z-10 R10
G40.1
G40 G00 X40 Z40
G00 A0
M30
