O0001 (spec L3991-4021 without its polar square: X in radius after G10.9 X0, G53 not switched)
G00 X100 Z0
G10.9 X0
G00 X50
G01 X40 F500
G01 U-10
G53 X100
G10.9 X1
G00 X200
U-10
M30
