O0001 (inclined-axis control, the spec's positioning example: machine X Z in the table's right column)
G53 X0 Z0
G53 X-100 Z-50
T0001
G00 X10 Z0
G00 X-10 Z5
T0002
G00 X10 Z0
G00 X-10 Z5
G01 X20 Z-10 F100
M30
