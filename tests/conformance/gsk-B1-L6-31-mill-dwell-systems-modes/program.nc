(gsk B.1 L6-7, L21-31: G04 dwell, G09 exact stop, G52 local and G53 machine coordinates,)
(G54-G59 work systems, G61/G64 exact-stop and cutting modes, in the mill dialect)
G90 G00 X10 Y10 Z10
G04 X1.5
G04 P250
G09 G01 X20 F300
G55 G00 X0 Y0 Z0
G52 X5 Y-5
G00 X0 Y0
G53 X1 Y2 Z3
G52 X0 Y0
G61 G01 X10 Y10
G64 X20
G54 G00 X0 Y0
M30
