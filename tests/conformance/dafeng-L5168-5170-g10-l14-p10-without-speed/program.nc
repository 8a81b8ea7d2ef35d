O1003 (spec L5168-5170: torque mode needs a motor speed, of G10 L14 P11 or param 5521; without either P10 is alarm 1152 and nothing moves)
G98 G00 X0 Z10
G10 L14 P10 B50
G01 Z0 F100
M30
