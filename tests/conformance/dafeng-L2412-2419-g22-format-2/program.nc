O0001 (format 2: the + limit X100 and the - limit X20, Z unlimited)
G00 X150 Z0
G22 X100 P1
G22 X20 P2
G00 Z-200
G00 X120
G01 X80 F100
M30
