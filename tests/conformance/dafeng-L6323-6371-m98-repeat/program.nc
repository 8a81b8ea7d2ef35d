O0001
G00 X0 Z0
M98 P31234 (spec L6326 writes P30001234 for 3 times; by the FANUC rule it cites that is 3000: docs/dialect.md)
G00 Z10
M30
O1234
G01 U2 F100
M99
